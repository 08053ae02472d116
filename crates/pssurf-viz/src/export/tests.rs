//! Every format is read back with a reader that shares no code with its writer: hand-written
//! parsers for PLY and STL, `tobj` for OBJ, `gltf` (validating) for GLB, `vtkio` for VTK.

use std::sync::Arc;

use nalgebra::Point2;
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::ps::{Hermite, PsBasis, PsSpline};
use pssurf::surface::Surface;
use pssurf::triangulation::Triangulation;

use super::*;

fn surface() -> Surface {
    let pts: Vec<Point2<f64>> = (0..25)
        .map(|k| {
            Point2::new(
                (k % 5) as f64 * 0.25 + 0.01 * (k / 5) as f64,
                (k / 5) as f64 * 0.25,
            )
        })
        .collect();
    let basis = Arc::new(PsBasis::optimal(Triangulation::delaunay(pts).unwrap()).unwrap());
    Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: (2.0 * p.x).sin() * p.y + 0.3 * p.x * p.x,
            dx: 2.0 * (2.0 * p.x).cos() * p.y + 0.6 * p.x,
            dy: (2.0 * p.x).sin(),
        })
        .unwrap(),
    )
}

struct Data {
    mesh: pssurf::mesh::TriMesh,
    fields: Vec<(String, Vec<f64>)>,
    colors: Vec<[u8; 3]>,
}

fn data() -> Data {
    let s = sample_patches(&surface(), 1, true);
    let fields = CurvatureQuantity::ALL
        .iter()
        .map(|&q| (q.short_name().to_string(), s.quantity(q)))
        .collect();
    let colors = (0..s.mesh.positions.len())
        .map(|k| [(k % 256) as u8, (k * 7 % 256) as u8, 200])
        .collect();
    Data {
        mesh: s.mesh,
        fields,
        colors,
    }
}

fn export(d: &Data, format: MeshFormat) -> Vec<u8> {
    let mut out = Vec::new();
    let m = FieldMesh {
        mesh: &d.mesh,
        fields: &d.fields,
        colors: Some(&d.colors),
        lines: &[],
    };
    write_mesh(&mut out, format, &m).unwrap();
    out
}

/// Two polylines of 3 and 4 points.
fn lines() -> Vec<Vec<nalgebra::Vector3<f64>>> {
    let p = |x: f64, y: f64| nalgebra::Vector3::new(x, y, 0.5);
    vec![
        vec![p(0.0, 0.0), p(0.1, 0.0), p(0.2, 0.1)],
        vec![p(0.3, 0.3), p(0.4, 0.3), p(0.5, 0.4), p(0.6, 0.6)],
    ]
}

fn export_with_lines(d: &Data, format: MeshFormat) -> Result<Vec<u8>, ExportError> {
    let mut out = Vec::new();
    let lines = lines();
    let m = FieldMesh {
        mesh: &d.mesh,
        fields: &d.fields,
        colors: Some(&d.colors),
        lines: &lines,
    };
    write_mesh(&mut out, format, &m).map(|_| out)
}

#[test]
fn polylines_go_into_ply_edges_vtk_lines_and_obj_line_elements() {
    let d = data();
    let n = d.mesh.positions.len();
    // PLY: 7 more vertices, then 2 + 3 edges between consecutive ones, at the end.
    let ply = export_with_lines(&d, MeshFormat::Ply).unwrap();
    let end = ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let header = std::str::from_utf8(&ply[..end]).unwrap();
    assert!(
        header.contains(&format!("element vertex {}\n", n + 7)),
        "{header}"
    );
    assert!(header.contains("element edge 5\nproperty int vertex1\nproperty int vertex2\n"));
    let tail = &ply[ply.len() - 40..];
    let ints: Vec<i32> = tail
        .chunks(4)
        .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    let m = n as i32;
    assert_eq!(
        ints,
        [
            m,
            m + 1,
            m + 1,
            m + 2,
            m + 3,
            m + 4,
            m + 4,
            m + 5,
            m + 5,
            m + 6
        ]
    );
    // VTK: LINES 2 9 with the runs n..n+3 and n+3..n+7.
    let vtk = export_with_lines(&d, MeshFormat::Vtk).unwrap();
    let tag = b"\nLINES 2 9\n";
    let at = vtk.windows(tag.len()).position(|w| w == tag).unwrap() + tag.len();
    let ints: Vec<i32> = vtk[at..at + 36]
        .chunks(4)
        .map(|c| i32::from_be_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(ints, [3, m, m + 1, m + 2, 4, m + 3, m + 4, m + 5, m + 6]);
    let points = format!("POINTS {} double\n", n + 7);
    assert!(vtk.windows(points.len()).any(|w| w == points.as_bytes()));
    // OBJ: l elements over the points after the mesh's (1-based).
    let obj = String::from_utf8(export_with_lines(&d, MeshFormat::Obj).unwrap()).unwrap();
    assert!(obj.contains(&format!("\nl {} {} {}\n", n + 1, n + 2, n + 3)));
    assert!(obj.contains(&format!("\nl {} {} {} {}\n", n + 4, n + 5, n + 6, n + 7)));
    // STL and glTF cannot hold lines: an error, not a silent drop.
    for f in [MeshFormat::Stl, MeshFormat::Glb] {
        assert!(matches!(
            export_with_lines(&d, f),
            Err(ExportError::Unsupported(_))
        ));
    }
}

fn close32(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn ply_reads_back_with_an_independent_parser() {
    let d = data();
    let bytes = export(&d, MeshFormat::Ply);
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    let header = std::str::from_utf8(&bytes[..end]).unwrap();
    assert!(header.starts_with("ply\nformat binary_little_endian 1.0\n"));
    let mut props = Vec::new();
    let (mut nv, mut nf) = (0, 0);
    for line in header.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["element", "vertex", n] => nv = n.parse().unwrap(),
            ["element", "face", n] => nf = n.parse().unwrap(),
            ["property", t, name] => props.push((t.to_string(), name.to_string())),
            _ => {}
        }
    }
    assert_eq!((nv, nf), (d.mesh.positions.len(), d.mesh.triangles.len()));
    let names: Vec<&str> = props.iter().map(|p| p.1.as_str()).collect();
    assert_eq!(
        names,
        [
            "x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "K", "H", "k1", "k2", "kabs"
        ]
    );
    let mut at = end;
    let f32_at = |at: &mut usize| {
        let v = f32::from_le_bytes(bytes[*at..*at + 4].try_into().unwrap());
        *at += 4;
        v as f64
    };
    for k in 0..nv {
        let p = d.mesh.positions[k];
        let xyz = [f32_at(&mut at), f32_at(&mut at), f32_at(&mut at)];
        assert!(close32(xyz[0], p.x) && close32(xyz[1], p.y) && close32(xyz[2], p.z));
        at += 12; // normals
        assert_eq!(bytes[at..at + 3], d.colors[k]);
        at += 3;
        for (_, f) in &d.fields {
            let v = f32_at(&mut at);
            assert!(close32(v, f[k]), "{v} vs {}", f[k]);
        }
    }
    for t in &d.mesh.triangles {
        assert_eq!(bytes[at], 3);
        at += 1;
        for &k in t {
            assert_eq!(
                i32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()),
                k as i32
            );
            at += 4;
        }
    }
    assert_eq!(at, bytes.len());
}

#[test]
fn stl_reads_back_with_an_independent_parser() {
    let d = data();
    let bytes = export(&d, MeshFormat::Stl);
    let n = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert_eq!(n, d.mesh.triangles.len());
    assert_eq!(bytes.len(), 84 + 50 * n);
    for (k, t) in d.mesh.triangles.iter().enumerate().step_by(13) {
        let rec = &bytes[84 + 50 * k..];
        for v in 0..3 {
            let p = d.mesh.positions[t[v] as usize];
            for c in 0..3 {
                let off = 12 + 12 * v + 4 * c;
                let x = f32::from_le_bytes(rec[off..off + 4].try_into().unwrap()) as f64;
                assert!(close32(x, p[c]));
            }
        }
    }
}

#[test]
fn obj_reads_back_with_tobj() {
    let d = data();
    let bytes = export(&d, MeshFormat::Obj);
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut std::io::Cursor::new(&bytes), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .unwrap();
    let m = &models[0].mesh;
    assert_eq!(m.positions.len(), 3 * d.mesh.positions.len());
    assert_eq!(m.indices.len(), 3 * d.mesh.triangles.len());
    assert_eq!(m.vertex_color.len(), 3 * d.mesh.positions.len());
    for (k, t) in d.mesh.triangles.iter().enumerate() {
        for v in 0..3 {
            let i = m.indices[3 * k + v] as usize;
            let p = d.mesh.positions[t[v] as usize];
            for c in 0..3 {
                assert!(close32(m.positions[3 * i + c], p[c]));
                assert!(close32(
                    m.normals[3 * i + c],
                    d.mesh.normals[t[v] as usize][c]
                ));
            }
        }
    }
}

#[test]
fn glb_validates_and_reads_back_with_gltf() {
    let d = data();
    let bytes = export(&d, MeshFormat::Glb);
    let g = gltf::Gltf::from_slice(&bytes).expect("a valid glTF");
    let blob = g.blob.as_ref().unwrap();
    let prim = g.meshes().next().unwrap().primitives().next().unwrap();
    let read_f32 = |a: &gltf::Accessor| -> Vec<f32> {
        let v = a.view().unwrap();
        let start = v.offset() + a.offset();
        let n = a.count() * a.dimensions().multiplicity();
        (0..n)
            .map(|k| f32::from_le_bytes(blob[start + 4 * k..start + 4 * k + 4].try_into().unwrap()))
            .collect()
    };
    let mut seen = Vec::new();
    for (sem, acc) in prim.attributes() {
        assert_eq!(acc.count(), d.mesh.positions.len());
        match sem {
            gltf::Semantic::Positions => {
                let v = read_f32(&acc);
                for (k, p) in d.mesh.positions.iter().enumerate() {
                    assert!(close32(v[3 * k] as f64, p.x) && close32(v[3 * k + 2] as f64, p.z));
                }
            }
            gltf::Semantic::Extras(name) => {
                let field = d
                    .fields
                    .iter()
                    .find(|f| glb::attribute_name(&f.0)[1..] == name)
                    .unwrap();
                let v = read_f32(&acc);
                for k in 0..v.len() {
                    assert!(close32(v[k] as f64, field.1[k]));
                }
                seen.push(name);
            }
            _ => {}
        }
    }
    seen.sort();
    assert_eq!(seen, ["H", "K", "K1", "K2", "KABS"]);
    let idx = prim.indices().unwrap();
    assert_eq!(idx.count(), 3 * d.mesh.triangles.len());
}

#[test]
fn vtk_reads_back_with_vtkio() {
    use vtkio::model::{Attribute, DataSet, IOBuffer, Piece};
    let d = data();
    let bytes = export(&d, MeshFormat::Vtk);
    let vtk = vtkio::Vtk::parse_legacy_be(&bytes[..]).expect("valid legacy VTK");
    let DataSet::PolyData { pieces, .. } = vtk.data else {
        panic!("not polydata")
    };
    let Piece::Inline(p) = &pieces[0] else {
        panic!()
    };
    let IOBuffer::F64(points) = &p.points else {
        panic!("points are doubles")
    };
    assert_eq!(points.len(), 3 * d.mesh.positions.len());
    for (k, q) in d.mesh.positions.iter().enumerate() {
        assert_eq!(
            [points[3 * k], points[3 * k + 1], points[3 * k + 2]],
            [q.x, q.y, q.z]
        );
    }
    let polys = p.polys.as_ref().unwrap();
    assert_eq!(polys.num_cells(), d.mesh.triangles.len());
    let mut found = 0;
    for a in &p.data.point {
        if let Attribute::DataArray(arr) = a
            && let Some(f) = d.fields.iter().find(|f| f.0 == arr.name)
        {
            let IOBuffer::F64(v) = &arr.data else {
                panic!()
            };
            assert_eq!(v, &f.1, "{}", f.0);
            found += 1;
        }
    }
    assert_eq!(found, d.fields.len());
}

#[test]
fn fields_of_the_wrong_length_are_refused() {
    let d = data();
    let bad = vec![("K".to_string(), vec![0.0; 3])];
    let m = FieldMesh {
        mesh: &d.mesh,
        fields: &bad,
        colors: None,
        lines: &[],
    };
    let e = write_mesh(&mut Vec::new(), MeshFormat::Ply, &m).unwrap_err();
    assert!(e.to_string().contains("field 'K' has 3 values"), "{e}");
}
