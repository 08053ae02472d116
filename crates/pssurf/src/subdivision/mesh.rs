//! Triangle meshes for the subdivision surface schemes (seed 004): the mesh, its edges found
//! by sorting, and the manifold and orientation checks every scheme relies on.

use nalgebra::Vector3;
use rayon::prelude::*;
use thiserror::Error;

/// No half-edge across (a boundary edge).
pub const NONE: u32 = u32::MAX;

/// The most triangles a mesh may have (half-edge indices are 32-bit).
pub const MAX_TRIANGLES: usize = (u32::MAX / 4) as usize;

/// A triangle mesh: positions and counter-clockwise triangles of vertex indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The vertex positions.
    pub positions: Vec<Vector3<f64>>,
    /// The triangles.
    pub triangles: Vec<[u32; 3]>,
}

/// Why a mesh cannot be subdivided.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MeshError {
    /// No triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// Too many triangles.
    #[error("{0} triangles are too many (at most {MAX_TRIANGLES})")]
    TooLarge(usize),
    /// A triangle names a vertex that does not exist.
    #[error("triangle {triangle} uses vertex {vertex}, but there are only {count} vertices")]
    BadIndex {
        /// The triangle.
        triangle: usize,
        /// The vertex index.
        vertex: u32,
        /// The number of vertices.
        count: usize,
    },
    /// A triangle with a repeated vertex.
    #[error("triangle {0} uses the same vertex twice")]
    Degenerate(usize),
    /// A triangle whose corners are distinct but collinear.
    #[error("triangle {0} has no area: its corners are collinear")]
    Flat(usize),
    /// A position that is not finite.
    #[error("vertex {0} has a coordinate that is not a finite number (or beyond ±1e60)")]
    NotFinite(usize),
    /// Three or more triangles on one edge.
    #[error("the edge between vertices {} and {} belongs to {count} triangles (a manifold mesh has at most 2)", edge.0, edge.1)]
    NonManifoldEdge {
        /// The edge's vertices.
        edge: (u32, u32),
        /// How many triangles share it.
        count: usize,
    },
    /// Two triangles with the same three corners.
    #[error("triangles {first} and {second} have the same three corners (a repeated triangle)")]
    Repeated {
        /// The first of them.
        first: usize,
        /// The second.
        second: usize,
    },
    /// Two triangles on an edge run it the same way.
    #[error("the triangles beside the edge between vertices {} and {} are oriented inconsistently (one is flipped)", edge.0, edge.1)]
    Orientation {
        /// The edge's vertices.
        edge: (u32, u32),
    },
    /// A vertex where two fans of triangles meet (a bow tie).
    #[error("vertex {0} is not manifold: two separate fans of triangles meet there")]
    NonManifoldVertex(u32),
}

/// Whether three points lie on one line, decided exactly: their projections onto the three
/// coordinate planes are all collinear (by the exact orientation test).
fn collinear([a, b, c]: [Vector3<f64>; 3]) -> bool {
    use crate::geometry::orient_exact;
    use nalgebra::Point2;
    let on = |i: usize, j: usize| {
        let p = |v: Vector3<f64>| Point2::new(v[i], v[j]);
        orient_exact(p(a), p(b), p(c)) == 0.0
    };
    on(0, 1) && on(1, 2) && on(2, 0)
}

/// The edges of a mesh: each half-edge (corner k of triangle t, from its vertex k to k + 1,
/// numbered 3t + k) knows the half-edge across and its edge.
#[derive(Clone, Debug)]
pub struct Topology {
    /// The half-edge across each half-edge, or [`NONE`] on the boundary.
    pub opposite: Vec<u32>,
    /// The edge of each half-edge.
    pub edge_of: Vec<u32>,
    /// One half-edge of each edge (the one with an opposite, if any, is either).
    pub edges: Vec<u32>,
    /// For each vertex, an outgoing half-edge: the boundary one for boundary vertices (so
    /// that turning around the vertex visits the whole fan), [`NONE`] for unused vertices.
    pub outgoing: Vec<u32>,
}

impl Mesh {
    /// The regular octahedron with vertices ±e_x, ±e_y, ±e_z (closed, every vertex of
    /// valence 4): a small closed test mesh.
    pub fn octahedron() -> Mesh {
        let p = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        Mesh {
            positions: p.iter().map(|&c| Vector3::from(c)).collect(),
            triangles: vec![
                [0, 2, 4],
                [2, 1, 4],
                [1, 3, 4],
                [3, 0, 4],
                [2, 0, 5],
                [1, 2, 5],
                [3, 1, 5],
                [0, 3, 5],
            ],
        }
    }

    /// The regular lattice over the rhombus of n × n cells of unit edges, lifted by `f`:
    /// points (i + j/2, j √3/2, f(x, y)), 2n² triangles, interior valence 6.
    pub fn lattice(n: u32, f: impl Fn(f64, f64) -> f64) -> Mesh {
        let s = 0.75f64.sqrt();
        let mut positions = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f64 + 0.5 * j as f64, s * j as f64);
                positions.push(Vector3::new(x, y, f(x, y)));
            }
        }
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let mut triangles = Vec::with_capacity(2 * (n * n) as usize);
        for j in 0..n {
            for i in 0..n {
                triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        Mesh {
            positions,
            triangles,
        }
    }

    /// The start vertex of half-edge h.
    #[inline]
    pub fn from_vertex(&self, h: u32) -> u32 {
        self.triangles[(h / 3) as usize][(h % 3) as usize]
    }

    /// The end vertex of half-edge h.
    #[inline]
    pub fn to_vertex(&self, h: u32) -> u32 {
        self.triangles[(h / 3) as usize][((h % 3 + 1) % 3) as usize]
    }

    /// The vertex of h's triangle opposite h.
    #[inline]
    pub fn apex(&self, h: u32) -> u32 {
        self.triangles[(h / 3) as usize][((h % 3 + 2) % 3) as usize]
    }

    /// Checks indices, positions, triangles, and builds the edges: manifold edges (at most
    /// two triangles, oriented alike) and manifold vertices (one fan each).
    pub fn topology(&self) -> Result<Topology, MeshError> {
        self.check()?;
        let t = self.triangles.len();
        if let Some(k) = (self.triangles.iter())
            .position(|tri| tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
        {
            return Err(MeshError::Degenerate(k));
        }
        if let Some(k) = self
            .triangles
            .par_iter()
            .position_first(|t| collinear(t.map(|v| self.positions[v as usize])))
        {
            return Err(MeshError::Flat(k));
        }
        // Half-edges sorted by their undirected edge.
        let mut keys: Vec<(u64, u32)> = (0..3 * t as u32)
            .into_par_iter()
            .map(|h| {
                let (a, b) = (self.from_vertex(h), self.to_vertex(h));
                (((a.min(b) as u64) << 32) | a.max(b) as u64, h)
            })
            .collect();
        keys.par_sort_unstable();
        let mut opposite = vec![NONE; 3 * t];
        let mut edge_of = vec![0u32; 3 * t];
        let mut edges = Vec::with_capacity(3 * t / 2 + 1);
        let mut i = 0;
        while i < keys.len() {
            let mut j = i + 1;
            while j < keys.len() && keys[j].0 == keys[i].0 {
                j += 1;
            }
            let key = keys[i].0;
            let pair = ((key >> 32) as u32, key as u32);
            if j - i > 2 {
                return Err(MeshError::NonManifoldEdge {
                    edge: pair,
                    count: j - i,
                });
            }
            let e = edges.len() as u32;
            edges.push(keys[i].1);
            edge_of[keys[i].1 as usize] = e;
            if j - i == 2 {
                let (h, g) = (keys[i].1, keys[i + 1].1);
                let corners = |h: u32| {
                    let mut c = self.triangles[h as usize / 3];
                    c.sort_unstable();
                    c
                };
                // The same corners either way round: two triangles glued back to back (the
                // oppositely oriented pair passed, and one subdivision step then failed on
                // an edge of four triangles between vertices the input does not have).
                if corners(h) == corners(g) {
                    let (a, b) = (h as usize / 3, g as usize / 3);
                    return Err(MeshError::Repeated {
                        first: a.min(b),
                        second: a.max(b),
                    });
                }
                if self.from_vertex(h) == self.from_vertex(g) {
                    return Err(MeshError::Orientation { edge: pair });
                }
                opposite[h as usize] = g;
                opposite[g as usize] = h;
                edge_of[g as usize] = e;
            }
            i = j;
        }
        let outgoing = self.outgoing(&opposite)?;
        Ok(Topology {
            opposite,
            edge_of,
            edges,
            outgoing,
        })
    }

    /// One outgoing half-edge per vertex (the boundary one where there is one), checking that
    /// every vertex has a single fan.
    fn outgoing(&self, opposite: &[u32]) -> Result<Vec<u32>, MeshError> {
        let n = self.positions.len();
        let mut out = vec![NONE; n];
        let mut boundary_out = vec![0u8; n];
        let mut corners = vec![0u32; n];
        for h in 0..opposite.len() as u32 {
            let v = self.from_vertex(h) as usize;
            corners[v] += 1;
            if opposite[h as usize] == NONE {
                boundary_out[v] += 1;
                out[v] = h;
            } else if out[v] == NONE {
                out[v] = h;
            }
        }
        // A single fan: turning from the start half-edge visits every corner of the vertex.
        for v in 0..n {
            if out[v] == NONE {
                continue;
            }
            if boundary_out[v] > 1 {
                return Err(MeshError::NonManifoldVertex(v as u32));
            }
            let mut count = 0;
            let mut h = out[v];
            loop {
                count += 1;
                // The half-edge arriving at v in h's triangle, then across it.
                let back = h - h % 3 + (h % 3 + 2) % 3;
                let next = opposite[back as usize];
                if next == NONE || next == out[v] || count > corners[v] {
                    break;
                }
                h = next;
            }
            if count != corners[v] {
                return Err(MeshError::NonManifoldVertex(v as u32));
            }
        }
        Ok(out)
    }
}

impl Topology {
    /// The neighbours of vertex v in counter-clockwise order, starting at the end of its
    /// outgoing half-edge (for a boundary vertex: from one boundary neighbour round to the
    /// other), and whether v is on the boundary.
    pub fn ring(&self, mesh: &Mesh, v: u32) -> (Vec<u32>, bool) {
        let start = self.outgoing[v as usize];
        let mut ring = Vec::with_capacity(8);
        if start == NONE {
            return (ring, false);
        }
        let mut h = start;
        loop {
            ring.push(mesh.to_vertex(h));
            let back = h - h % 3 + (h % 3 + 2) % 3;
            let next = self.opposite[back as usize];
            if next == NONE {
                // The boundary: the last neighbour is the start of the arriving half-edge.
                ring.push(mesh.from_vertex(back));
                return (ring, true);
            }
            if next == start {
                return (ring, false);
            }
            h = next;
        }
    }

    /// Whether edge e is on the boundary.
    pub fn is_boundary_edge(&self, e: u32) -> bool {
        self.opposite[self.edges[e as usize] as usize] == NONE
    }
}

/// Discrete curvatures per vertex, for comparing schemes: the Gaussian curvature by the
/// angle deficit (2π − Σ θ) / (A/3), and the mean curvature |Σ (cot α + cot β)(v − v_j)| /
/// (4 A/3) with the sign of the normal (Meyer et al. 2003, with a third of the area of the
/// triangles around v). NaN at boundary vertices and unused ones.
pub fn discrete_curvature(mesh: &Mesh) -> Result<(Vec<f64>, Vec<f64>), MeshError> {
    let topo = mesh.topology()?;
    let n = mesh.positions.len();
    let p = &mesh.positions;
    let mut angle = vec![0.0; n];
    let mut area = vec![0.0; n];
    let mut laplace = vec![Vector3::zeros(); n];
    let mut normal = vec![Vector3::zeros(); n];
    for tri in &mesh.triangles {
        let [a, b, c] = tri.map(|v| p[v as usize]);
        let face = (b - a).cross(&(c - a));
        let third = face.norm() / 6.0;
        for k in 0..3 {
            let (v, w, x) = (
                tri[k] as usize,
                tri[(k + 1) % 3] as usize,
                tri[(k + 2) % 3] as usize,
            );
            let (e1, e2) = (p[w] - p[v], p[x] - p[v]);
            angle[v] += e1.angle(&e2);
            area[v] += third;
            normal[v] += face;
            // The angle at v weighs the opposite edge w–x: cot θ_v (w − x) terms.
            let cot = e1.dot(&e2) / e1.cross(&e2).norm();
            laplace[w] += (p[w] - p[x]) * cot;
            laplace[x] += (p[x] - p[w]) * cot;
        }
    }
    let ring_is_boundary = |v: usize| {
        let h = topo.outgoing[v];
        h == NONE || topo.opposite[h as usize] == NONE
    };
    let k = (0..n)
        .map(|v| {
            if ring_is_boundary(v) {
                f64::NAN
            } else {
                (2.0 * std::f64::consts::PI - angle[v]) / area[v]
            }
        })
        .collect();
    let h = (0..n)
        .map(|v| {
            if ring_is_boundary(v) {
                f64::NAN
            } else {
                let l = laplace[v];
                let sign = if l.dot(&normal[v]) < 0.0 { -1.0 } else { 1.0 };
                sign * l.norm() / (4.0 * area[v])
            }
        })
        .collect();
    Ok((k, h))
}
