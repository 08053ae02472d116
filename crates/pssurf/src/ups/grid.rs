//! The uniform triangulation of a lattice polygon, stored as a block matrix (thesis 4.6.1,
//! 6.2.3): every lattice point of the polygon's bounding box has a slot, real vertices are
//! marked, and neighbours, molecules and boundary cases are index arithmetic.

use nalgebra::{Point2, Vector2};
use rayon::prelude::*;

use super::UpsError;
use super::lattice::{Lattice, LatticePoint, LatticePolygon};
use crate::triangulation::{Triangulation, TriangulationError};

/// The six neighbour directions of a lattice point, counter-clockwise from +x:
/// 0°, 60°, 120°, 180°, 240°, 300°.
pub const NEIGHBORS: [[i64; 2]; 6] = [[1, 0], [0, 1], [-1, 1], [-1, 0], [0, -1], [1, -1]];

/// A uniform triangulation Δ of a lattice polygon Ω. Slot (i, j) of the block matrix holds
/// lattice point (i0 + i, j0 + j). Its cells are the "up" triangles (i, j), (i+1, j), (i, j+1)
/// and the "down" triangles (i+1, j), (i+1, j+1), (i, j+1) (both counter-clockwise).
#[derive(Clone, Debug, PartialEq)]
pub struct UpsGrid {
    lattice: Lattice,
    polygon: LatticePolygon,
    lo: LatticePoint,
    n: [usize; 2],
    real: Vec<bool>,
    up: Vec<bool>,
    down: Vec<bool>,
}

/// Every lattice point of the polygon must have coordinates the triangulation accepts
/// (within ±[`MAX_COORDINATE`](crate::triangulation::MAX_COORDINATE)); the extremes of the
/// affine lattice map over the polygon are at its corners.
fn check_range(lattice: &Lattice, polygon: &LatticePolygon) -> Result<(), UpsError> {
    let extent = polygon
        .vertices()
        .iter()
        .map(|&c| lattice.point(c))
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let tiny = |c: f64| c != 0.0 && c.abs() < UpsGrid::MIN_SCALE;
    let (o, b) = (lattice.origin, lattice.base);
    if !(extent <= crate::triangulation::MAX_COORDINATE) {
        return Err(UpsError::OutOfRange { extent });
    }
    if b < UpsGrid::MIN_SCALE || tiny(o.x) || tiny(o.y) {
        return Err(UpsError::TooFine {
            base: b,
            origin: [o.x, o.y],
        });
    }
    Ok(())
}

impl UpsGrid {
    /// The triangulation of `polygon` on `lattice`: the cells whose centroid lies inside.
    pub fn new(lattice: Lattice, polygon: LatticePolygon) -> Result<Self, UpsError> {
        if !(lattice.base > 0.0
            && lattice.base.is_finite()
            && lattice.origin.x.is_finite()
            && lattice.origin.y.is_finite())
        {
            return Err(UpsError::InvalidBase(lattice.base));
        }
        let slots = polygon.block_slots();
        if slots > 1 << 31 {
            return Err(UpsError::TooLarge(slots));
        }
        check_range(&lattice, &polygon)?;
        let (lo, hi) = polygon.bounds();
        let n = [(hi[0] - lo[0] + 1) as usize, (hi[1] - lo[1] + 1) as usize];
        let cells = n[0] * n[1];
        let mut up = vec![false; cells];
        let mut down = vec![false; cells];
        up.par_iter_mut()
            .zip(down.par_iter_mut())
            .enumerate()
            .with_min_len(4096)
            .for_each(|(k, (u, d))| {
                let (i, j) = ((k % n[0]) as i64 + lo[0], (k / n[0]) as i64 + lo[1]);
                // Centroids: up (i + 1/3, j + 1/3), down (i + 2/3, j + 2/3).
                *u = polygon.contains_thirds(3 * i + 1, 3 * j + 1);
                *d = polygon.contains_thirds(3 * i + 2, 3 * j + 2);
            });
        Ok(Self::from_cells(lattice, polygon, lo, n, up, down))
    }

    /// The smallest base and nonzero origin coordinate accepted: with larger values no
    /// lattice point gets a nonzero coordinate below the triangulation's
    /// [`MIN_COORDINATE`](crate::triangulation::MIN_COORDINATE).
    pub const MIN_SCALE: f64 = 1e-20;

    fn from_cells(
        lattice: Lattice,
        polygon: LatticePolygon,
        lo: LatticePoint,
        n: [usize; 2],
        up: Vec<bool>,
        down: Vec<bool>,
    ) -> Self {
        let mut real = vec![false; n[0] * n[1]];
        for j in 0..n[1] {
            for i in 0..n[0] {
                let c = j * n[0] + i;
                let mut mark = |a: usize, b: usize| real[b * n[0] + a] = true;
                if up[c] {
                    mark(i, j);
                    mark(i + 1, j);
                    mark(i, j + 1);
                }
                if down[c] {
                    mark(i + 1, j);
                    mark(i + 1, j + 1);
                    mark(i, j + 1);
                }
            }
        }
        UpsGrid {
            lattice,
            polygon,
            lo,
            n,
            real,
            up,
            down,
        }
    }

    /// The lattice (base and origin).
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// The domain polygon.
    pub fn polygon(&self) -> &LatticePolygon {
        &self.polygon
    }

    /// The number of slots along i and j (the block matrix's columns and rows).
    pub fn dims(&self) -> [usize; 2] {
        self.n
    }

    /// The lattice coordinates of slot (0, 0).
    pub fn lower_corner(&self) -> LatticePoint {
        self.lo
    }

    /// The number of slots (real and pseudo vertices).
    pub fn slots(&self) -> usize {
        self.n[0] * self.n[1]
    }

    /// The slot index of slot (i, j).
    #[inline]
    pub fn slot(&self, i: usize, j: usize) -> usize {
        j * self.n[0] + i
    }

    /// The slot (i, j) of a slot index.
    #[inline]
    pub fn ij(&self, s: usize) -> (usize, usize) {
        (s % self.n[0], s / self.n[0])
    }

    /// The slot of lattice point p, if inside the block matrix.
    pub fn slot_of(&self, p: LatticePoint) -> Option<usize> {
        let (i, j) = (p[0] - self.lo[0], p[1] - self.lo[1]);
        (i >= 0 && j >= 0 && (i as usize) < self.n[0] && (j as usize) < self.n[1])
            .then(|| self.slot(i as usize, j as usize))
    }

    /// The lattice coordinates of a slot.
    #[inline]
    pub fn lattice_point(&self, s: usize) -> LatticePoint {
        let (i, j) = self.ij(s);
        [self.lo[0] + i as i64, self.lo[1] + j as i64]
    }

    /// True for a real vertex (a vertex of Δ), false for a pseudo-vertex.
    #[inline]
    pub fn is_real(&self, s: usize) -> bool {
        self.real[s]
    }

    /// The number of real vertices.
    pub fn vertex_count(&self) -> usize {
        self.real.iter().filter(|&&r| r).count()
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.up.iter().chain(&self.down).filter(|&&t| t).count()
    }

    /// Whether the up cell at slot (i, j) is a triangle of Δ.
    #[inline]
    pub fn has_up(&self, i: usize, j: usize) -> bool {
        i + 1 < self.n[0] && j + 1 < self.n[1] && self.up[self.slot(i, j)]
    }

    /// Whether the down cell at slot (i, j) is a triangle of Δ.
    #[inline]
    pub fn has_down(&self, i: usize, j: usize) -> bool {
        i + 1 < self.n[0] && j + 1 < self.n[1] && self.down[self.slot(i, j)]
    }

    /// The slot of the neighbour of slot s in direction `dir` (index into [`NEIGHBORS`]), if
    /// it is inside the block matrix.
    #[inline]
    pub fn neighbor(&self, s: usize, dir: usize) -> Option<usize> {
        let (i, j) = self.ij(s);
        let d = NEIGHBORS[dir];
        let (a, b) = (i as i64 + d[0], j as i64 + d[1]);
        (a >= 0 && b >= 0 && (a as usize) < self.n[0] && (b as usize) < self.n[1])
            .then(|| self.slot(a as usize, b as usize))
    }

    /// The six triangles around slot (i, j), in the order of the sectors between
    /// consecutive [`NEIGHBORS`] directions (sector k between directions k and k + 1):
    /// whether each is a triangle of Δ. Sector 0 is the up cell at (i, j), 1 the down cell at
    /// (i−1, j), 2 the up cell at (i−1, j), 3 the down cell at (i−1, j−1), 4 the up cell at
    /// (i, j−1), 5 the down cell at (i, j−1).
    pub fn sectors(&self, s: usize) -> [bool; 6] {
        let (i, j) = self.ij(s);
        let up = |a: Option<usize>, b: Option<usize>| matches!((a, b), (Some(a), Some(b)) if self.has_up(a, b));
        let down = |a: Option<usize>, b: Option<usize>| matches!((a, b), (Some(a), Some(b)) if self.has_down(a, b));
        let (im, jm) = (i.checked_sub(1), j.checked_sub(1));
        [
            up(Some(i), Some(j)),
            down(im, Some(j)),
            up(im, Some(j)),
            down(im, jm),
            up(Some(i), jm),
            down(Some(i), jm),
        ]
    }

    /// Whether the lattice edge from slot s in direction `dir` is an edge of Δ (one of the
    /// two triangles beside it is in Δ).
    pub fn has_edge(&self, s: usize, dir: usize) -> bool {
        let sec = self.sectors(s);
        sec[dir] || sec[(dir + 5) % 6]
    }

    /// The PS-points of the vertex in slot s (Lemma 2.1; as
    /// [`ps_points`](crate::ps::ps_triangles::ps_points) of the general form, without it):
    /// the vertex V, the points V + d/4 halfway to the midpoint of each edge V + d of Δ, and
    /// V + (d_k + d_{k+1})/6 halfway to the centroid (the incentre of an equilateral triangle)
    /// of each triangle of its molecule.
    pub fn ps_points(&self, s: usize) -> Vec<Point2<f64>> {
        let v = self.lattice.point(self.lattice_point(s));
        let d = |k: usize| {
            let e = self.lattice.point(NEIGHBORS[k]) - self.lattice.point([0, 0]);
            Vector2::new(e.x, e.y)
        };
        let sectors = self.sectors(s);
        let mut out = vec![v];
        for k in 0..6 {
            if self.has_edge(s, k) {
                out.push(v + d(k) / 4.0);
            }
            if sectors[k] {
                out.push(v + (d(k) + d((k + 1) % 6)) / 6.0);
            }
        }
        out
    }

    /// The molecule number m_i: the number of triangles around a real vertex.
    pub fn molecule_number(&self, s: usize) -> usize {
        self.sectors(s).iter().filter(|&&x| x).count()
    }

    /// True for a real vertex on the boundary ∂Δ.
    pub fn is_boundary(&self, s: usize) -> bool {
        self.is_real(s) && self.molecule_number(s) < 6
    }

    /// The triangulation one subdivision step finer, D⁻¹Δ: slot (i, j) becomes (2i, 2j), each
    /// triangle four (mid-edge subdivision).
    pub fn refined(&self) -> UpsGrid {
        let n = [2 * self.n[0] - 1, 2 * self.n[1] - 1];
        let mut up = vec![false; n[0] * n[1]];
        let mut down = vec![false; n[0] * n[1]];
        let at = |i: usize, j: usize| j * n[0] + i;
        for j in 0..self.n[1].saturating_sub(1) {
            for i in 0..self.n[0].saturating_sub(1) {
                let c = self.slot(i, j);
                let (a, b) = (2 * i, 2 * j);
                if self.up[c] {
                    up[at(a, b)] = true;
                    up[at(a + 1, b)] = true;
                    up[at(a, b + 1)] = true;
                    down[at(a, b)] = true;
                }
                if self.down[c] {
                    down[at(a + 1, b)] = true;
                    down[at(a + 1, b + 1)] = true;
                    down[at(a, b + 1)] = true;
                    up[at(a + 1, b + 1)] = true;
                }
            }
        }
        let lo = [2 * self.lo[0], 2 * self.lo[1]];
        Self::from_cells(
            self.lattice.refined(),
            self.polygon.refined(),
            lo,
            n,
            up,
            down,
        )
    }

    /// The triangulation one level coarser (base 2B), if this one is the refinement of one:
    /// every corner of the polygon must lie on the coarse lattice.
    pub fn coarsened(&self) -> Option<UpsGrid> {
        let polygon = self.polygon.coarsened()?;
        let lattice = Lattice {
            base: 2.0 * self.lattice.base,
            origin: self.lattice.origin,
        };
        UpsGrid::new(lattice, polygon).ok()
    }

    /// How many times the triangulation can be coarsened (each corner coordinate divisible
    /// by 2^levels).
    pub fn coarsening_levels(&self) -> u32 {
        self.polygon
            .vertices()
            .iter()
            .flat_map(|p| p.iter())
            .map(|&c| if c == 0 { 62 } else { c.trailing_zeros() })
            .min()
            .unwrap_or(0)
    }

    /// The real vertices' slots, in slot order (the vertex numbering of [`UpsGrid::triangulation`]).
    pub fn real_slots(&self) -> Vec<usize> {
        (0..self.slots()).filter(|&s| self.real[s]).collect()
    }

    /// The triangles as slot triples (counter-clockwise), up and down cells in slot order.
    pub fn triangle_slots(&self) -> Vec<[usize; 3]> {
        let mut out = Vec::with_capacity(self.triangle_count());
        for j in 0..self.n[1].saturating_sub(1) {
            for i in 0..self.n[0].saturating_sub(1) {
                if self.has_up(i, j) {
                    out.push([self.slot(i, j), self.slot(i + 1, j), self.slot(i, j + 1)]);
                }
                if self.has_down(i, j) {
                    out.push([
                        self.slot(i + 1, j),
                        self.slot(i + 1, j + 1),
                        self.slot(i, j + 1),
                    ]);
                }
            }
        }
        out
    }

    /// The general triangulation (vertices numbered as [`UpsGrid::real_slots`]).
    pub fn triangulation(&self) -> Result<Triangulation, TriangulationError> {
        let slots = self.real_slots();
        let mut index = vec![usize::MAX; self.slots()];
        for (k, &s) in slots.iter().enumerate() {
            index[s] = k;
        }
        let vertices = slots
            .iter()
            .map(|&s| self.lattice.point(self.lattice_point(s)))
            .collect();
        let tris = self
            .triangle_slots()
            .into_iter()
            .map(|t| t.map(|s| index[s]))
            .collect();
        Triangulation::try_new(vertices, tris)
    }
}
