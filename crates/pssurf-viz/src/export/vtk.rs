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

/// Writes binary legacy VTK: POINTS (double), POLYGONS, LINES (the polylines, whose points
/// follow the mesh's), and as POINT_DATA the NORMALS, the colours (COLOR_SCALARS) and one
/// SCALARS array (double) per field (zero normals, black and NaN on the lines' points).
pub fn write_vtk(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    let (mesh_points, t) = (m.mesh.positions.len(), m.mesh.triangles.len());
    let extra = m.line_points();
    let n = mesh_points + extra;
    if 4 * t > i32::MAX as usize || n + m.lines.len() > i32::MAX as usize {
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
        m.mesh
            .positions
            .iter()
            .chain(m.lines.iter().flatten())
            .flat_map(|p| [p.x, p.y, p.z]),
    )?;
    write!(w, "\nPOLYGONS {t} {}\n", 4 * t)?;
    for tri in &m.mesh.triangles {
        w.write_all(&3i32.to_be_bytes())?;
        for &k in tri {
            w.write_all(&(k as i32).to_be_bytes())?;
        }
    }
    if !m.lines.is_empty() {
        let runs = m.line_indices();
        let size: usize = runs.iter().map(|r| 1 + r.len()).sum();
        write!(w, "\nLINES {} {size}\n", runs.len())?;
        for r in runs {
            w.write_all(&(r.len() as i32).to_be_bytes())?;
            for k in r {
                w.write_all(&(k as i32).to_be_bytes())?;
            }
        }
    }
    write!(w, "\nPOINT_DATA {n}\nNORMALS normals double\n")?;
    doubles(
        &mut w,
        m.mesh
            .normals
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .chain(std::iter::repeat_n(0.0, 3 * extra)),
    )?;
    if let Some(colors) = m.colors {
        // Binary COLOR_SCALARS are unsigned chars.
        write!(w, "\nCOLOR_SCALARS colors 3\n")?;
        for c in colors {
            w.write_all(c)?;
        }
        w.write_all(&vec![0u8; 3 * extra])?;
    }
    for (name, values) in m.fields {
        write!(
            w,
            "\nSCALARS {} double 1\nLOOKUP_TABLE default\n",
            token(name)
        )?;
        doubles(
            &mut w,
            values
                .iter()
                .copied()
                .chain(std::iter::repeat_n(f64::NAN, extra)),
        )?;
    }
    writeln!(w)?;
    w.flush()?;
    Ok(())
}
