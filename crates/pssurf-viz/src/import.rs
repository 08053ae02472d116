//! Reading triangle meshes from OBJ (tobj), PLY (ply-rs-bw) and STL (stl_io) files, for the
//! subdivision surface schemes. Polygons are split into fans of triangles.

use std::path::Path;

use nalgebra::Vector3;
use pssurf::subdivision::Mesh;
use thiserror::Error;

/// Why a mesh file cannot be read.
#[derive(Debug, Error)]
pub enum ImportError {
    /// The extension names no mesh format.
    #[error("{0}: not a mesh file (use .obj, .ply or .stl)")]
    Format(String),
    /// The reader failed.
    #[error("{path}: {message}")]
    Read {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
}

/// An I/O error in words, without the OS error number.
fn cause(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file or folder".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        k => k.to_string(),
    }
}

/// The triangles of a polygon with vertex indices `face` (a fan from its first vertex).
fn fan(face: &[u32], out: &mut Vec<[u32; 3]>) {
    for k in 1..face.len().saturating_sub(1) {
        out.push([face[0], face[k], face[k + 1]]);
    }
}

/// Reads a mesh file, the format chosen by the extension.
pub fn read_mesh(path: &Path) -> Result<Mesh, ImportError> {
    let name = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    let fail = |message: String| ImportError::Read {
        path: name.clone(),
        message,
    };
    match ext.as_str() {
        "obj" => read_obj(path).map_err(fail),
        "ply" => read_ply(path).map_err(fail),
        "stl" => read_stl(path).map_err(fail),
        _ => Err(ImportError::Format(name)),
    }
}

fn read_obj(path: &Path) -> Result<Mesh, String> {
    // Positions in file order (no merging with texture or normal indices), read as f64.
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj(path, &options).map_err(|e| e.to_string())?;
    let mut mesh = Mesh::default();
    for m in models {
        let base = mesh.positions.len() as u32;
        let pos = &m.mesh.positions;
        mesh.positions
            .extend(pos.chunks_exact(3).map(|c| Vector3::new(c[0], c[1], c[2])));
        let indices: Vec<u32> = m.mesh.indices.iter().map(|&i| base + i).collect();
        if m.mesh.face_arities.is_empty() {
            for t in indices.chunks_exact(3) {
                mesh.triangles.push([t[0], t[1], t[2]]);
            }
        } else {
            let mut at = 0;
            for &n in &m.mesh.face_arities {
                let n = n as usize;
                let face = indices
                    .get(at..at + n)
                    .ok_or("a face runs past the index list")?;
                fan(face, &mut mesh.triangles);
                at += n;
            }
        }
    }
    Ok(mesh)
}

/// Why an STL file ended before its triangles did (stl_io says "failed to fill whole
/// buffer"): for a binary file, the triangles its header promises and the bytes they need.
fn truncated_stl(path: &Path) -> String {
    let bytes = std::fs::metadata(path).map_or(0, |m| m.len());
    let promised = std::fs::File::open(path).ok().and_then(|mut f| {
        use std::io::Read as _;
        let mut header = [0u8; 84];
        f.read_exact(&mut header).ok()?;
        Some(u32::from_le_bytes(header[80..84].try_into().ok()?))
    });
    match promised {
        Some(n) if !is_ascii_stl(path) => format!(
            "the file ends early: its header promises {n} triangles, {} bytes, and it has {bytes}",
            84 + 50 * u64::from(n)
        ),
        _ => "the file ends early, in the middle of a triangle".to_string(),
    }
}

/// Whether the file starts like an ASCII STL ("solid").
fn is_ascii_stl(path: &Path) -> bool {
    use std::io::Read as _;
    let mut start = [0u8; 5];
    std::fs::File::open(path).is_ok_and(|mut f| f.read_exact(&mut start).is_ok())
        && &start == b"solid"
}

fn read_stl(path: &Path) -> Result<Mesh, String> {
    let mut file = std::fs::File::open(path).map_err(|e| cause(&e))?;
    let indexed = stl_io::read_stl(&mut file).map_err(|e| match e.kind() {
        std::io::ErrorKind::UnexpectedEof => truncated_stl(path),
        _ => e.to_string(),
    })?;
    Ok(Mesh {
        positions: indexed
            .vertices
            .iter()
            .map(|v| Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64))
            .collect(),
        triangles: indexed
            .faces
            .iter()
            .map(|f| f.vertices.map(|i| i as u32))
            .collect(),
    })
}

fn read_ply(path: &Path) -> Result<Mesh, String> {
    use ply_rs_bw::parser::Parser;
    use ply_rs_bw::ply::{DefaultElement, Property};
    let file = std::fs::File::open(path).map_err(|e| cause(&e))?;
    let mut reader = std::io::BufReader::new(file);
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut reader)
        .map_err(|e| e.to_string())?;
    let number = |p: Option<&Property>| -> Option<f64> {
        Some(match p? {
            Property::Float(x) => *x as f64,
            Property::Double(x) => *x,
            Property::Int(x) => *x as f64,
            Property::UInt(x) => *x as f64,
            Property::Short(x) => *x as f64,
            Property::UShort(x) => *x as f64,
            Property::Char(x) => *x as f64,
            Property::UChar(x) => *x as f64,
            _ => return None,
        })
    };
    let vertices = ply.payload.get("vertex").ok_or("no vertex element")?;
    let positions = vertices
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let c = |n: &str| number(v.get(n)).ok_or(format!("vertex {k} has no number {n}"));
            Ok(Vector3::new(c("x")?, c("y")?, c("z")?))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let mut triangles = Vec::new();
    for (k, f) in ply
        .payload
        .get("face")
        .map(|v| v.as_slice())
        .unwrap_or_default()
        .iter()
        .enumerate()
    {
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .ok_or(format!("face {k} has no vertex_indices"))?;
        let face: Vec<u32> = match list {
            Property::ListInt(v) => v.iter().map(|&i| i as u32).collect(),
            Property::ListUInt(v) => v.clone(),
            Property::ListShort(v) => v.iter().map(|&i| i as u32).collect(),
            Property::ListUShort(v) => v.iter().map(|&i| i as u32).collect(),
            Property::ListUChar(v) => v.iter().map(|&i| i as u32).collect(),
            Property::ListChar(v) => v.iter().map(|&i| i as u32).collect(),
            _ => {
                return Err(format!(
                    "face {k}: vertex_indices is not a list of integers"
                ));
            }
        };
        fan(&face, &mut triangles);
    }
    Ok(Mesh {
        positions,
        triangles,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// OBJ coordinates come back as written, to the last bit (tobj renumbers the vertices in
    /// the order the faces use them); polygons become fans.
    #[test]
    fn obj_positions_are_exact() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.obj");
        let xs = [0.1, 1.0 / 3.0, 2f64.sqrt(), -7.25e-9];
        let mut text = String::new();
        for (k, x) in xs.iter().enumerate() {
            text.push_str(&format!("v {x} {} {}\n", k as f64 * 0.7, -x));
        }
        text.push_str("vt 0 0\nf 4/1 2/1 1/1 3/1\n");
        std::fs::write(&path, text).unwrap();
        let m = read_mesh(&path).unwrap();
        let written = |k: usize| Vector3::new(xs[k], k as f64 * 0.7, -xs[k]);
        let fan = [[3, 1, 0], [3, 0, 2]];
        assert_eq!(m.triangles.len(), 2);
        for (t, f) in m.triangles.iter().zip(fan) {
            for (v, k) in t.iter().zip(f) {
                assert_eq!(m.positions[*v as usize], written(k));
            }
        }
    }

    /// A binary STL cut short is named as such, with the size its header promises (stl_io
    /// said "failed to fill whole buffer").
    #[test]
    fn a_truncated_binary_stl_says_so() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.stl");
        let mut bytes = vec![0u8; 80];
        bytes.extend(2u32.to_le_bytes());
        bytes.extend([0u8; 60]);
        std::fs::write(&path, bytes).unwrap();
        let e = read_mesh(&path).unwrap_err().to_string();
        assert!(
            e.contains("ends early: its header promises 2 triangles, 184 bytes, and it has 144"),
            "{e}"
        );
    }
}
