//! Display of UPS surfaces by repeated subdivision (thesis section 4.6): after L steps, each
//! real vertex gives the surface point s(V) = (c1 + c2 + c3)/3 (α = 1/3, (4.6)) and the normal
//! of its control triangle, which is the tangent plane there (Property 2.3, Theorem 3.2).

use nalgebra::{Point2, Vector3};
use rayon::prelude::*;

use super::spline::Ups;
use crate::mesh::{MeshBuilder, MeshVertex, plane_normal};
use crate::ps::net::{Combine, Weighted};

/// Control values that are points in R³ (plain or weighted).
pub trait ControlPoint3: Combine + Default {
    /// The Euclidean point.
    fn point3(&self) -> Vector3<f64>;
}

impl ControlPoint3 for Vector3<f64> {
    fn point3(&self) -> Vector3<f64> {
        *self
    }
}

impl ControlPoint3 for Weighted<Vector3<f64>> {
    fn point3(&self) -> Vector3<f64> {
        self.point
    }
}

impl<T: ControlPoint3> Ups<T> {
    /// The surface as an indexed triangle mesh after `level` subdivision steps: one vertex per
    /// real vertex of D^{−level}Δ (point and normal on the surface, exactly), four times as many
    /// triangles per step. Vertices and triangles are produced in block-matrix order, without
    /// any search. For a rational UPS the point is the projected (stable) combination.
    pub fn tessellate(&self, level: usize, out: &mut impl MeshBuilder) {
        let fine = self.subdivide_times(level);
        let grid = fine.grid();
        let lattice = *grid.lattice();
        let blocks = fine.blocks();
        let third = 1.0 / 3.0;
        let verts: Vec<Option<MeshVertex>> = (0..grid.slots())
            .into_par_iter()
            .with_min_len(4096)
            .map(|s| {
                if !grid.is_real(s) {
                    return None;
                }
                let c = blocks[s];
                let position = T::combine3([third; 3], c).point3();
                let normal = plane_normal(c[0].point3(), c[1].point3(), c[2].point3());
                let uv: Point2<f64> = lattice.point(grid.lattice_point(s));
                Some(MeshVertex {
                    position,
                    normal,
                    uv,
                })
            })
            .collect();
        let triangles = grid.triangle_slots();
        out.reserve(grid.vertex_count(), triangles.len());
        let mut index = vec![u32::MAX; grid.slots()];
        for (s, v) in verts.into_iter().enumerate() {
            if let Some(v) = v {
                index[s] = out.add_vertex(v);
            }
        }
        for t in triangles {
            out.add_triangle(index[t[0]], index[t[1]], index[t[2]]);
        }
    }
}
