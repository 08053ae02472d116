//! Legacy VTK (`# vtk DataFile Version 3.0`), binary big-endian POLYDATA: readable by
//! ParaView and VisIt, with the fields as point data.

use std::io::Write;

use super::{ExportError, FieldMesh};

fn doubles(w: &mut dyn Write, values: impl Iterator<Item = f64>) -> std::io::Result<()> {
    for v in values {
        w.write_all(&v.to_be_bytes())?;
    }
    Ok(())
}

/// A field name without whitespace (VTK names are single tokens).
fn token(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_whitespace() { '_' } else { c })
        .collect()
}

/// Writes binary legacy VTK: POINTS (double), POLYGONS, and as POINT_DATA the NORMALS, the
/// colours (COLOR_SCALARS) and one SCALARS array (double) per field.
pub fn write_vtk(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    let (n, t) = (m.mesh.positions.len(), m.mesh.triangles.len());
    if 4 * t > i32::MAX as usize {
        return Err(ExportError::Unsupported(
            "too many triangles for legacy VTK".into(),
        ));
    }
    let mut w = std::io::BufWriter::new(w);
    write!(
        w,
        "# vtk DataFile Version 3.0\npssurf surface\nBINARY\nDATASET POLYDATA\nPOINTS {n} double\n"
    )?;
    doubles(
        &mut w,
        m.mesh.positions.iter().flat_map(|p| [p.x, p.y, p.z]),
    )?;
    write!(w, "\nPOLYGONS {t} {}\n", 4 * t)?;
    for tri in &m.mesh.triangles {
        w.write_all(&3i32.to_be_bytes())?;
        for &k in tri {
            w.write_all(&(k as i32).to_be_bytes())?;
        }
    }
    write!(w, "\nPOINT_DATA {n}\nNORMALS normals double\n")?;
    doubles(&mut w, m.mesh.normals.iter().flat_map(|p| [p.x, p.y, p.z]))?;
    if let Some(colors) = m.colors {
        // Binary COLOR_SCALARS are unsigned chars.
        write!(w, "\nCOLOR_SCALARS colors 3\n")?;
        for c in colors {
            w.write_all(c)?;
        }
    }
    for (name, values) in m.fields {
        write!(
            w,
            "\nSCALARS {} double 1\nLOOKUP_TABLE default\n",
            token(name)
        )?;
        doubles(&mut w, values.iter().copied())?;
    }
    writeln!(w)?;
    w.flush()?;
    Ok(())
}
