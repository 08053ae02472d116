//! Binary STL through `stl_io`.

use std::io::Write;

use stl_io::{Normal, Triangle, Vertex};

use super::{ExportError, FieldMesh};

/// Writes binary STL: one facet per triangle with its flat normal (the geometry only).
pub fn write_stl(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    if m.mesh.triangles.len() > u32::MAX as usize {
        return Err(ExportError::Unsupported(
            "STL holds at most 2³² − 1 triangles".into(),
        ));
    }
    let p = &m.mesh.positions;
    let facets = m.mesh.triangles.iter().map(|t| {
        let [a, b, c] = t.map(|k| p[k as usize]);
        let n = (b - a)
            .cross(&(c - a))
            .try_normalize(0.0)
            .unwrap_or_default();
        let v = |x: nalgebra::Vector3<f64>| Vertex::new([x.x as f32, x.y as f32, x.z as f32]);
        Triangle {
            normal: Normal::new([n.x as f32, n.y as f32, n.z as f32]),
            vertices: [v(a), v(b), v(c)],
        }
    });
    let mut w = w;
    stl_io::write_stl(&mut w, facets)?;
    Ok(())
}
