//! Wavefront OBJ: `v x y z [r g b]`, `vn`, `f a//a b//b c//c`, and polylines as `l` elements
//! over their own `v` points (after the mesh's).

use std::io::Write;

use super::{ExportError, FieldMesh};

/// Writes OBJ text: points (with colours in [0, 1] when given), normals and triangles.
/// Scalar fields are not representable in OBJ and are left out.
pub fn write_obj(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    let mut w = std::io::BufWriter::new(w);
    writeln!(
        w,
        "# pssurf mesh: {} vertices, {} triangles",
        m.mesh.positions.len(),
        m.mesh.triangles.len()
    )?;
    for (k, p) in m.mesh.positions.iter().enumerate() {
        match m.colors {
            Some(c) => {
                let c = c[k].map(|x| x as f64 / 255.0);
                writeln!(
                    w,
                    "v {:?} {:?} {:?} {:.4} {:.4} {:.4}",
                    p.x, p.y, p.z, c[0], c[1], c[2]
                )?
            }
            None => writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?,
        }
    }
    for n in &m.mesh.normals {
        writeln!(w, "vn {:?} {:?} {:?}", n.x, n.y, n.z)?;
    }
    for t in &m.mesh.triangles {
        let [a, b, c] = t.map(|k| k as u64 + 1);
        writeln!(w, "f {a}//{a} {b}//{b} {c}//{c}")?;
    }
    for p in m.lines.iter().flatten() {
        writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
    }
    for run in m.line_indices().into_iter().filter(|r| r.len() >= 2) {
        let ids: Vec<String> = run.map(|k| (k + 1).to_string()).collect();
        writeln!(w, "l {}", ids.join(" "))?;
    }
    w.flush()?;
    Ok(())
}
