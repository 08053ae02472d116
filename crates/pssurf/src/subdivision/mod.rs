//! The classic subdivision schemes of seed 004 (issue 20): curves (Chaikin, cubic B-spline,
//! the four-point scheme) and surfaces on triangle meshes (Loop, √3, butterfly).

pub mod curves;
pub mod mesh;
pub mod refined;
pub mod surfaces;

pub use curves::{CurveScheme, SubdivisionError, limit_points, subdivide_curve};
pub use mesh::{Mesh, MeshError, Topology};
pub use refined::RefinedMesh;
pub use surfaces::{SurfaceScheme, loop_limit_normals, loop_limit_positions};

#[cfg(test)]
mod surface_tests;
