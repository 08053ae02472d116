//! Conforming triangulations Δ of polygonal domains: validation, adjacency, molecules,
//! boundary and point location (thesis section 2.3.1).

mod delaunay;
mod error;
mod locate;
mod order;
mod validate;

pub use delaunay::{COORDINATE_RESOLUTION, PEEL_THICKNESS};
pub use error::TriangulationError;
pub use validate::check_coordinates;

/// The largest coordinate magnitude of a vertex: within the range of the Delaunay
/// triangulation (spade: 2^201 ≈ 3.2e60), and products of coordinate differences (areas,
/// squared lengths, orientation tests) stay far from overflow.
pub const MAX_COORDINATE: f64 = 1e60;

/// The smallest magnitude of a nonzero coordinate: spade's Delaunay triangulation refuses
/// nonzero coordinates below 2^-142 ≈ 1.8e-43.
pub const MIN_COORDINATE: f64 = 1e-42;
pub use locate::{Cursor, INSIDE_TOLERANCE, Location};
pub use order::morton_order;

use std::sync::OnceLock;

use nalgebra::Point2;
use rayon::prelude::*;

use crate::geometry::Triangle2;

/// Marks a missing neighbour (a boundary edge).
pub const NO_NEIGHBOR: u32 = u32::MAX;

/// A validated, conforming triangulation with counter-clockwise triangles.
///
/// Edge `i` of a triangle is the edge opposite its vertex `i`, from vertex `i + 1` to
/// vertex `i + 2` (indices mod 3); `neighbor(t, i)` is the triangle across it.
#[derive(Debug)]
pub struct Triangulation {
    vertices: Vec<Point2<f64>>,
    triangles: Vec<[u32; 3]>,
    neighbors: Vec<[u32; 3]>,
    molecule_offsets: Vec<u32>,
    molecule_list: Vec<u32>,
    on_boundary: Vec<bool>,
    locator: OnceLock<locate::Locator>,
    spatial: OnceLock<Vec<u32>>,
}

impl Clone for Triangulation {
    fn clone(&self) -> Self {
        Triangulation {
            vertices: self.vertices.clone(),
            triangles: self.triangles.clone(),
            neighbors: self.neighbors.clone(),
            molecule_offsets: self.molecule_offsets.clone(),
            molecule_list: self.molecule_list.clone(),
            on_boundary: self.on_boundary.clone(),
            locator: OnceLock::new(),
            spatial: OnceLock::new(),
        }
    }
}

impl PartialEq for Triangulation {
    fn eq(&self, other: &Self) -> bool {
        self.vertices == other.vertices && self.triangles == other.triangles
    }
}

impl Triangulation {
    /// A triangulation from vertices and triangles; panics on the errors of
    /// [`Triangulation::try_new`].
    pub fn new(vertices: Vec<Point2<f64>>, triangles: Vec<[usize; 3]>) -> Self {
        Self::try_new(vertices, triangles).unwrap_or_else(|e| panic!("{e}"))
    }

    /// A validated triangulation from vertices and triangles (zero-based vertex indices).
    ///
    /// Checks: finite coordinates, no coincident vertices, indices in range, no repeated or
    /// degenerate or duplicate triangles, one orientation for all triangles (clockwise input
    /// is reversed to counter-clockwise), every edge in at most two triangles lying on
    /// opposite sides, no overlaps or hanging nodes, no bow-tie vertices, no unused vertices.
    /// Each error names the offending triangle or vertex.
    pub fn try_new(
        vertices: Vec<Point2<f64>>,
        triangles: Vec<[usize; 3]>,
    ) -> Result<Self, TriangulationError> {
        validate::build(vertices, triangles)
    }

    /// The Delaunay triangulation of scattered points (by the `spade` crate). Vertex `i` of
    /// the result is `points[i]`; coincident points are an error naming both. Boundary
    /// slivers thinner than [`PEEL_THICKNESS`] are left out of the domain (their vertices
    /// stay in it).
    pub fn delaunay(points: Vec<Point2<f64>>) -> Result<Self, TriangulationError> {
        delaunay::delaunay(points).map(|(t, _)| t)
    }

    /// [`Triangulation::delaunay`], with the boundary slivers it left out (vertex indices of
    /// `points`), so that callers can name them.
    pub fn delaunay_with_peeled(
        points: Vec<Point2<f64>>,
    ) -> Result<(Self, Vec<[usize; 3]>), TriangulationError> {
        delaunay::delaunay(points)
    }

    /// The number of vertices n.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// The number of triangles t.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// All vertices V_i.
    pub fn vertices(&self) -> &[Point2<f64>] {
        &self.vertices
    }

    /// The vertex V_i.
    #[inline]
    pub fn vertex(&self, i: usize) -> Point2<f64> {
        self.vertices[i]
    }

    /// All triangles as counter-clockwise vertex-index triples.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The vertex indices of triangle `t` (counter-clockwise).
    #[inline]
    pub fn triangle(&self, t: usize) -> [usize; 3] {
        self.triangles[t].map(|v| v as usize)
    }

    /// The geometry of triangle `t`.
    #[inline]
    pub fn triangle_geometry(&self, t: usize) -> Triangle2 {
        let [a, b, c] = self.triangles[t];
        Triangle2::new(
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        )
    }

    /// The triangle across edge `i` of triangle `t` (the edge opposite vertex `i`), or `None`
    /// on the boundary.
    #[inline]
    pub fn neighbor(&self, t: usize, i: usize) -> Option<usize> {
        let n = self.neighbors[t][i];
        (n != NO_NEIGHBOR).then_some(n as usize)
    }

    /// The raw neighbour table ([`NO_NEIGHBOR`] on the boundary).
    pub fn neighbors(&self) -> &[[u32; 3]] {
        &self.neighbors
    }

    /// The molecule M_i of vertex i: the triangles having V_i as a vertex (Definition 2.14).
    pub fn molecule(&self, i: usize) -> &[u32] {
        let (a, b) = (
            self.molecule_offsets[i] as usize,
            self.molecule_offsets[i + 1] as usize,
        );
        &self.molecule_list[a..b]
    }

    /// The triangles of the molecules of `vertices` (the union of the M_i), each once, in
    /// increasing order: what a change of those vertices' control values touches.
    pub fn molecules_of(&self, vertices: impl IntoIterator<Item = usize>) -> Vec<usize> {
        let mut out: Vec<usize> = vertices
            .into_iter()
            .flat_map(|i| self.molecule(i).iter().map(|&t| t as usize))
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The molecule number m_i: the number of triangles in M_i (Definition 2.15).
    pub fn molecule_number(&self, i: usize) -> usize {
        self.molecule(i).len()
    }

    /// True when V_i lies on the boundary ∂Δ.
    pub fn is_boundary_vertex(&self, i: usize) -> bool {
        self.on_boundary[i]
    }

    /// True when edge `i` of triangle `t` lies on the boundary.
    pub fn is_boundary_edge(&self, t: usize, i: usize) -> bool {
        self.neighbors[t][i] == NO_NEIGHBOR
    }

    /// The boundary edges as (triangle, local edge) pairs.
    pub fn boundary_edges(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.triangles.len())
            .flat_map(|t| (0..3).map(move |i| (t, i)))
            .filter(|&(t, i)| self.is_boundary_edge(t, i))
    }

    /// The end points (as vertex indices, counter-clockwise within `t`) of edge `i` of `t`.
    #[inline]
    pub fn edge_vertices(&self, t: usize, i: usize) -> (usize, usize) {
        let tri = self.triangles[t];
        (tri[(i + 1) % 3] as usize, tri[(i + 2) % 3] as usize)
    }

    /// The number of distinct edges.
    pub fn edge_count(&self) -> usize {
        let boundary = self.boundary_edges().count();
        (3 * self.triangles.len() + boundary) / 2
    }

    /// The axis-aligned bounding box (min corner, max corner) of the vertices.
    pub fn bounds(&self) -> (Point2<f64>, Point2<f64>) {
        let mut lo = Point2::new(f64::INFINITY, f64::INFINITY);
        let mut hi = Point2::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        for v in &self.vertices {
            lo = Point2::new(lo.x.min(v.x), lo.y.min(v.y));
            hi = Point2::new(hi.x.max(v.x), hi.y.max(v.y));
        }
        (lo, hi)
    }

    /// The total area of the domain Ω.
    pub fn area(&self) -> f64 {
        (0..self.triangle_count())
            .map(|t| self.triangle_geometry(t).area())
            .sum()
    }

    /// The vertices in the order of a space-filling (Morton) curve: per-vertex work done in
    /// this order touches neighbouring triangles one after another, which keeps caches warm
    /// when the vertex numbering itself is random (as for scattered data).
    pub fn spatial_order(&self) -> &[u32] {
        self.spatial.get_or_init(|| morton_order(&self.vertices))
    }

    /// The local position (0, 1 or 2) of vertex `v` in triangle `t`, if it is a corner.
    #[inline]
    pub fn corner_of(&self, t: usize, v: usize) -> Option<usize> {
        self.triangles[t].iter().position(|&x| x as usize == v)
    }
}

/// The first pair (smaller index first) of points with identical coordinates, if any.
pub fn duplicate_points(points: &[Point2<f64>]) -> Option<(usize, usize)> {
    // Sorting the coordinates' order-preserving integer keys themselves (not indices into
    // the points) keeps the sort in cache; −0 and +0 get the same key.
    let key = |c: f64| {
        let b = (c + 0.0).to_bits() as i64;
        b ^ (((b >> 63) as u64) >> 1) as i64
    };
    let mut keys: Vec<(i64, i64, u32)> = points
        .iter()
        .enumerate()
        .map(|(k, p)| (key(p.x), key(p.y), k as u32))
        .collect();
    if keys.len() > PARALLEL_SORT {
        keys.par_sort_unstable();
    } else {
        keys.sort_unstable();
    }
    keys.windows(2)
        .map(|w| (w[0].2 as usize, w[1].2 as usize))
        .find(|&(a, b)| points[a] == points[b])
        .map(|(a, b)| (a.min(b), a.max(b)))
}

/// Above this many points [`duplicate_points`] sorts in parallel.
const PARALLEL_SORT: usize = 1 << 16;

#[cfg(test)]
mod tests;
