//! UPS-splines: PS-splines on uniform triangulations with the fixed PS-triangles t(6)
//! (thesis sections 4.2.2–4.3).

use std::sync::Arc;

use nalgebra::Point2;
use rayon::prelude::*;

use super::UpsError;
use super::grid::UpsGrid;
use super::lattice::{Lattice, SQRT3_2};
use crate::geometry::Triangle2;
use crate::ps::net::{Combine, Weighted};
use crate::ps::{Hermite, Nurps, PsBasis, PsRefinement, PsSpline, PsTriangleChoice, SplitRule};
use crate::vector::Vector;

/// The fixed PS-triangle t(6) of a vertex V (Property 4.1): equilateral, centred at V, with
/// corners halfway to three alternate neighbours,
/// Q1 = V − (B/2, 0), Q2 = V + (B/4, −√3B/4), Q3 = V + (B/4, √3B/4) (counter-clockwise).
/// These give the triplets (α, β, γ) of (4.6)–(4.8).
pub fn fixed_ps_triangle(lattice: &Lattice, v: Point2<f64>) -> Triangle2 {
    let b = lattice.base;
    Triangle2::new(
        Point2::new(v.x - 0.5 * b, v.y),
        Point2::new(v.x + 0.25 * b, v.y - 0.5 * SQRT3_2 * b),
        Point2::new(v.x + 0.25 * b, v.y + 0.5 * SQRT3_2 * b),
    )
}

/// A UPS-spline: three control values per vertex of a uniform triangulation, in the slots of
/// its block matrix (pseudo-vertices hold `T::default()`). `T` is `f64` (functional), a point
/// such as `Vector3<f64>` (parametric), or a [`Weighted`] point (rational UPS).
///
/// Control value k (0-based) belongs to the corner Q_{k+1} of t(6): k = 0 at −x, k = 1 at
/// −60°, k = 2 at +60° from the vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct Ups<T> {
    grid: UpsGrid,
    blocks: Vec<[T; 3]>,
}

impl<T: Combine + Default> Ups<T> {
    /// A UPS-spline from one control triple per slot of `grid`.
    pub fn new(grid: UpsGrid, blocks: Vec<[T; 3]>) -> Result<Self, UpsError> {
        if blocks.len() != grid.slots() {
            return Err(UpsError::WrongBlockCount {
                expected: grid.slots(),
                found: blocks.len(),
            });
        }
        Ok(Ups { grid, blocks })
    }

    /// A UPS-spline from one control triple per real vertex, in slot order.
    pub fn from_vertices(grid: UpsGrid, values: Vec<[T; 3]>) -> Result<Self, UpsError> {
        let slots = grid.real_slots();
        if values.len() != slots.len() {
            return Err(UpsError::WrongBlockCount {
                expected: slots.len(),
                found: values.len(),
            });
        }
        let mut blocks = vec![[T::default(); 3]; grid.slots()];
        for (&s, v) in slots.iter().zip(values) {
            blocks[s] = v;
        }
        Ok(Ups { grid, blocks })
    }

    /// The triangulation.
    pub fn grid(&self) -> &UpsGrid {
        &self.grid
    }

    /// The control triples of all slots.
    pub fn blocks(&self) -> &[[T; 3]] {
        &self.blocks
    }

    /// Mutable control triples (keep pseudo-vertices at their default).
    pub fn blocks_mut(&mut self) -> &mut [[T; 3]] {
        &mut self.blocks
    }

    /// The control triples of the real vertices, in slot order.
    pub fn vertex_values(&self) -> Vec<[T; 3]> {
        self.grid
            .real_slots()
            .iter()
            .map(|&s| self.blocks[s])
            .collect()
    }

    /// Replaces the grid and blocks (used by subdivision and the wavelet transform).
    pub(crate) fn from_parts(grid: UpsGrid, blocks: Vec<[T; 3]>) -> Self {
        debug_assert_eq!(grid.slots(), blocks.len());
        Ups { grid, blocks }
    }

    /// The general PS basis of this triangulation: the UPS-refinement (angle bisectors, i.e.
    /// incentres, Definition 4.3) and the fixed PS-triangles t(6).
    pub fn basis(&self) -> Result<PsBasis, UpsError> {
        let tri = self.grid.triangulation().map_err(UpsError::Triangulation)?;
        let refinement = PsRefinement::new(&tri, SplitRule::Incenter).map_err(UpsError::Ps)?;
        let lattice = *self.grid.lattice();
        let tris = tri
            .vertices()
            .iter()
            .map(|&v| fixed_ps_triangle(&lattice, v))
            .collect();
        PsBasis::with_refinement(tri, refinement, &PsTriangleChoice::Given(tris))
            .map_err(UpsError::Ps)
    }
}

impl<V: Vector + Default> Ups<V> {
    /// The Hermite interpolant (4.9): c1 = f − (B/2) f_x, c2 = f + (B/4) f_x − (√3B/4) f_y,
    /// c3 = f + (B/4) f_x + (√3B/4) f_y at every vertex.
    pub fn hermite(grid: UpsGrid, f: impl Fn(Point2<f64>) -> Hermite<V> + Sync) -> Self {
        let lattice = *grid.lattice();
        let b = lattice.base;
        let blocks = (0..grid.slots())
            .into_par_iter()
            .with_min_len(1024)
            .map(|s| {
                if !grid.is_real(s) {
                    return [V::default(); 3];
                }
                let h = f(lattice.point(grid.lattice_point(s)));
                [
                    h.value - h.dx * (0.5 * b),
                    h.value + h.dx * (0.25 * b) - h.dy * (0.5 * SQRT3_2 * b),
                    h.value + h.dx * (0.25 * b) + h.dy * (0.5 * SQRT3_2 * b),
                ]
            })
            .collect();
        Ups { grid, blocks }
    }

    /// The same spline as a general PS-spline (for evaluation, curvature, export).
    pub fn to_ps(&self) -> Result<PsSpline<V>, UpsError> {
        let basis = Arc::new(self.basis()?);
        PsSpline::new(basis, self.vertex_values()).map_err(UpsError::Ps)
    }

    /// ∫_Ω s (4.22): Σ_i Σ_j w_ij c_ij with w_ij = A · Σ over the triangles of M_i of the
    /// weight of Q_ij relative to that triangle — 7/36 when Q_ij lies on the sector's bounding
    /// ray, 1/9 when it lies beyond the sector's other ray, 1/36 when opposite ((4.17)–(4.21));
    /// A = √3B²/4 is the area of a triangle.
    pub fn integral(&self) -> V {
        let area = 0.5 * SQRT3_2 * self.grid.lattice().base.powi(2);
        let mut sum = V::zero();
        for s in 0..self.grid.slots() {
            if !self.grid.is_real(s) {
                continue;
            }
            let w = integration_weights(&self.grid.sectors(s));
            for k in 0..3 {
                sum += self.blocks[s][k] * (w[k] * area);
            }
        }
        sum
    }
}

/// The directions of the corners of t(6) as [`super::grid::NEIGHBORS`] indices:
/// Q1 at 180° (3), Q2 at 300° (5), Q3 at 60° (1).
pub const CORNER_DIRECTIONS: [usize; 3] = [3, 5, 1];

/// The integration weights (in units of the triangle area) of the three control values of a
/// vertex whose surrounding sectors are `sectors` (see [`UpsGrid::sectors`]). Sector k lies
/// between directions k and k + 1; a corner at direction d is on the bounding ray of sectors
/// d − 1 and d (weight 7/36 each), beyond sectors d − 2 and d + 1 (1/9) and opposite sectors
/// d + 2 and d + 3 (1/36) — summing to 2/3 for a full molecule (4.21).
pub fn integration_weights(sectors: &[bool; 6]) -> [f64; 3] {
    let mut w = [0.0; 3];
    for (k, &d) in CORNER_DIRECTIONS.iter().enumerate() {
        for (sec, &present) in sectors.iter().enumerate() {
            if !present {
                continue;
            }
            let rel = (sec + 6 - d) % 6;
            w[k] += match rel {
                0 | 5 => 7.0 / 36.0,
                1 | 4 => 1.0 / 9.0,
                _ => 1.0 / 36.0,
            };
        }
    }
    w
}

impl<V: Vector + Default> Ups<Weighted<V>> {
    /// A rational UPS-spline from points and positive weights, one triple each per vertex
    /// (slot order).
    pub fn rational(
        grid: UpsGrid,
        points: Vec<[V; 3]>,
        weights: Vec<[f64; 3]>,
    ) -> Result<Self, UpsError> {
        if points.len() != weights.len() {
            return Err(UpsError::WrongBlockCount {
                expected: points.len(),
                found: weights.len(),
            });
        }
        for (i, w) in weights.iter().enumerate() {
            if let Some(j) = w.iter().position(|&x| !crate::limits::weight_ok(x)) {
                return Err(UpsError::Ps(crate::ps::PsError::InvalidWeight {
                    vertex: i,
                    index: j,
                    weight: w[j],
                }));
            }
        }
        let values = points
            .iter()
            .zip(&weights)
            .map(|(p, w)| {
                std::array::from_fn(|k| Weighted {
                    point: p[k],
                    weight: w[k],
                })
            })
            .collect();
        Self::from_vertices(grid, values)
    }

    /// The same surface as a general NURPS.
    pub fn to_nurps(&self) -> Result<Nurps<V>, UpsError> {
        let basis = Arc::new(self.basis()?);
        let values = self.vertex_values();
        let points = values.iter().map(|t| t.map(|w| w.point)).collect();
        let weights = values.iter().map(|t| t.map(|w| w.weight)).collect();
        Nurps::new(basis, points, weights).map_err(UpsError::Ps)
    }
}

impl<V: Default> Default for Weighted<V> {
    fn default() -> Self {
        Weighted {
            point: V::default(),
            weight: 0.0,
        }
    }
}
