//! Mesh export with curvature fields: PLY (binary), OBJ, STL (binary), glTF 2.0 binary (.glb)
//! and legacy VTK (binary), each written to any `Write` (callers write files atomically).
//!
//! | format | points, triangles | normals | colours | scalar fields |
//! | --- | --- | --- | --- | --- |
//! | PLY | float | `nx ny nz` | `red green blue` (uchar) | one float property each (`K`, `H`, …) |
//! | OBJ | `v`, `f` (1-based) | `vn` | `v x y z r g b` (the common extension) | — |
//! | STL | facets | facet normals | — | — |
//! | GLB | POSITION, indices (u32) | NORMAL | COLOR_0 (normalised u8 RGBA) | `_K`, `_H`, `_K1`, `_K2`, `_KABS`, … (float) |
//! | VTK | POINTS double, POLYGONS | NORMALS double | COLOR_SCALARS | SCALARS double |
//!
//! Polylines (curves traced on the surface) go into PLY as an `edge` element, into VTK as
//! `LINES` and into OBJ as `l` elements; STL and glTF refuse them.

pub(crate) mod glb;
mod obj;
mod ply;
mod stl;
mod vtk;

use std::io::Write;

use nalgebra::Vector3;

use pssurf::mesh::TriMesh;
use thiserror::Error;

pub use glb::write_glb;
pub use obj::write_obj;
pub use ply::write_ply;
pub use stl::write_stl;
pub use vtk::write_vtk;

/// A mesh with per-vertex fields to export.
#[derive(Clone, Copy, Debug)]
pub struct FieldMesh<'a> {
    /// Points, normals, triangles.
    pub mesh: &'a TriMesh,
    /// Named scalar fields, one value per vertex (NaN where undefined).
    pub fields: &'a [(String, Vec<f64>)],
    /// Optional per-vertex colours.
    pub colors: Option<&'a [[u8; 3]]>,
    /// Polylines to write with the mesh (curves traced on the surface): PLY edges, VTK
    /// lines, OBJ line elements; STL and glTF refuse them.
    pub lines: &'a [Vec<Vector3<f64>>],
}

/// The export formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Stanford PLY, binary little-endian.
    Ply,
    /// Wavefront OBJ.
    Obj,
    /// Binary STL.
    Stl,
    /// glTF 2.0 binary.
    Glb,
    /// Legacy VTK, binary (ParaView, VisIt).
    Vtk,
}

impl MeshFormat {
    /// The format of a name or file extension (`ply`, `obj`, `stl`, `glb`, `vtk`).
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s.to_ascii_lowercase().as_str() {
            "ply" => MeshFormat::Ply,
            "obj" => MeshFormat::Obj,
            "stl" => MeshFormat::Stl,
            "glb" | "gltf" => MeshFormat::Glb,
            "vtk" => MeshFormat::Vtk,
            _ => return None,
        })
    }

    /// Whether the format stores named scalar fields.
    pub fn carries_fields(self) -> bool {
        matches!(self, MeshFormat::Ply | MeshFormat::Glb | MeshFormat::Vtk)
    }

    /// Whether the format stores polylines.
    pub fn carries_lines(self) -> bool {
        matches!(self, MeshFormat::Ply | MeshFormat::Obj | MeshFormat::Vtk)
    }

    /// Whether the format stores vertex colours.
    pub fn carries_colors(self) -> bool {
        !matches!(self, MeshFormat::Stl)
    }
}

/// An export failed.
#[derive(Debug, Error)]
pub enum ExportError {
    /// Writing failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The mesh does not fit the format.
    #[error("{0}")]
    Unsupported(String),
    /// A field's length differs from the number of vertices.
    #[error("field '{name}' has {found} values for {expected} vertices")]
    FieldLength {
        /// The field.
        name: String,
        /// Vertices.
        expected: usize,
        /// Values.
        found: usize,
    },
}

impl FieldMesh<'_> {
    /// The number of points of all lines.
    pub fn line_points(&self) -> usize {
        self.lines.iter().map(Vec::len).sum()
    }

    /// Each line as a run of point indices, counting after the mesh's vertices.
    pub fn line_indices(&self) -> Vec<std::ops::Range<usize>> {
        let mut next = self.mesh.positions.len();
        self.lines
            .iter()
            .map(|l| {
                let r = next..next + l.len();
                next += l.len();
                r
            })
            .collect()
    }

    /// Checks that every field and the colours have one entry per vertex.
    pub fn validate(&self) -> Result<(), ExportError> {
        let n = self.mesh.positions.len();
        for (name, v) in self.fields {
            if v.len() != n {
                return Err(ExportError::FieldLength {
                    name: name.clone(),
                    expected: n,
                    found: v.len(),
                });
            }
        }
        if let Some(c) = self.colors
            && c.len() != n
        {
            return Err(ExportError::FieldLength {
                name: "colors".into(),
                expected: n,
                found: c.len(),
            });
        }
        Ok(())
    }
}

/// Writes `mesh` in `format`.
pub fn write_mesh(
    w: &mut dyn Write,
    format: MeshFormat,
    mesh: &FieldMesh<'_>,
) -> Result<(), ExportError> {
    mesh.validate()?;
    if !mesh.lines.is_empty() && !format.carries_lines() {
        return Err(ExportError::Unsupported(
            "this format cannot hold lines: use ply, vtk or obj".into(),
        ));
    }
    match format {
        MeshFormat::Ply => write_ply(w, mesh),
        MeshFormat::Obj => write_obj(w, mesh),
        MeshFormat::Stl => write_stl(w, mesh),
        MeshFormat::Glb => write_glb(w, mesh),
        MeshFormat::Vtk => write_vtk(w, mesh),
    }
}

#[cfg(test)]
mod tests;
