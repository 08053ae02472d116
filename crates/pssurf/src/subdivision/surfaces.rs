//! Subdivision surfaces on triangle meshes (seed 004): Loop, √3 (Kobbelt) and the butterfly
//! scheme, with the seed's boundary rules, and Loop's limit positions and normals.

use std::f64::consts::PI;

use nalgebra::Vector3;
use rayon::prelude::*;

use super::mesh::{Mesh, MeshError, NONE, Topology};

/// A subdivision scheme for triangle meshes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceScheme {
    /// Loop: the 1-4 split, approximating; C² (quartic box spline) where regular.
    Loop,
    /// √3: a point per triangle and flipped old edges, 3 triangles for 1; approximating.
    Sqrt3,
    /// The butterfly scheme: the 1-4 split, interpolating (the modified rule of Zorin,
    /// Schröder and Sweldens at extraordinary vertices).
    Butterfly,
}

impl SurfaceScheme {
    /// Every scheme.
    pub const ALL: [SurfaceScheme; 3] = [
        SurfaceScheme::Loop,
        SurfaceScheme::Sqrt3,
        SurfaceScheme::Butterfly,
    ];

    /// The scheme with this [`SurfaceScheme::name`].
    pub fn parse(name: &str) -> Option<SurfaceScheme> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The name as the CLI spells it.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceScheme::Loop => "loop",
            SurfaceScheme::Sqrt3 => "sqrt3",
            SurfaceScheme::Butterfly => "butterfly",
        }
    }

    /// One step of the scheme.
    pub fn step(self, mesh: &Mesh) -> Result<Mesh, MeshError> {
        let topo = mesh.topology()?;
        Ok(match self {
            SurfaceScheme::Loop => loop_step(mesh, &topo),
            SurfaceScheme::Sqrt3 => sqrt3_step(mesh, &topo),
            SurfaceScheme::Butterfly => butterfly_step(mesh, &topo),
        })
    }

    /// The number of triangles after `times` steps from `triangles` (each step multiplies
    /// them by 4, or by 3 for √3), as a float so that absurd requests do not overflow.
    pub fn triangles_after(self, triangles: usize, times: u32) -> f64 {
        let factor: f64 = match self {
            SurfaceScheme::Sqrt3 => 3.0,
            SurfaceScheme::Loop | SurfaceScheme::Butterfly => 4.0,
        };
        triangles as f64 * factor.powi(times.min(64) as i32)
    }

    /// The vertex and triangle counts after one step of a mesh with `v` vertices, `e` edges
    /// (`eb` of them on the boundary) and `t` triangles.
    pub fn counts_after(self, v: usize, e: usize, eb: usize, t: usize) -> (usize, usize) {
        match self {
            SurfaceScheme::Loop | SurfaceScheme::Butterfly => (v + e, 4 * t),
            SurfaceScheme::Sqrt3 => (v + t + eb, 2 * e),
        }
    }
}

/// Loop's β for valence n: (1/n)(5/8 − (3 + 2 cos(2π/n))²/64) (seed 004).
pub fn loop_beta(n: usize) -> f64 {
    let c = 3.0 + 2.0 * (2.0 * PI / n as f64).cos();
    (0.625 - c * c / 64.0) / n as f64
}

/// Sums of neighbours and valences per vertex, and each boundary vertex's two boundary
/// neighbours (the end of its outgoing boundary half-edge, the start of its arriving one).
struct Neighbours {
    sum: Vec<Vector3<f64>>,
    valence: Vec<u32>,
    boundary: Vec<Option<(u32, u32)>>,
}

fn neighbours(mesh: &Mesh, topo: &Topology) -> Neighbours {
    let n = mesh.positions.len();
    let mut sum = vec![Vector3::zeros(); n];
    let mut valence = vec![0u32; n];
    let mut boundary: Vec<Option<(u32, u32)>> = vec![None; n];
    for &h in &topo.edges {
        let (a, b) = (mesh.from_vertex(h), mesh.to_vertex(h));
        sum[a as usize] += mesh.positions[b as usize];
        sum[b as usize] += mesh.positions[a as usize];
        valence[a as usize] += 1;
        valence[b as usize] += 1;
    }
    for h in 0..topo.opposite.len() as u32 {
        if topo.opposite[h as usize] == NONE {
            let (a, b) = (mesh.from_vertex(h), mesh.to_vertex(h));
            // b follows a along the boundary.
            let ea = boundary[a as usize].get_or_insert((NONE, NONE));
            ea.0 = b;
            let eb = boundary[b as usize].get_or_insert((NONE, NONE));
            eb.1 = a;
        }
    }
    Neighbours {
        sum,
        valence,
        boundary,
    }
}

/// The 1-4 split: old vertex i stays i, the point on edge e is V + e, and triangle (a, b, c)
/// with edge points ab, bc, ca becomes (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca).
fn split_four(mesh: &Mesh, topo: &Topology) -> Vec<[u32; 3]> {
    let v = mesh.positions.len() as u32;
    mesh.triangles
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, tri)| {
            let e = |k: usize| v + topo.edge_of[3 * t + k];
            let (ab, bc, ca) = (e(0), e(1), e(2));
            [
                [tri[0], ab, ca],
                [ab, tri[1], bc],
                [ca, bc, tri[2]],
                [ab, bc, ca],
            ]
        })
        .collect()
}

/// The seed's boundary vertex rule (the cubic B-spline's even stencil): ⅛ a + ¾ v + ⅛ b.
fn boundary_vertex(p: &[Vector3<f64>], v: usize, (a, b): (u32, u32)) -> Vector3<f64> {
    p[v] * 0.75 + (p[a as usize] + p[b as usize]) * 0.125
}

/// One Loop step: vertices (1 − nβ) v + β Σ neighbours, edge points ⅜ (a + b) + ⅛ (c + d);
/// on the boundary the cubic B-spline rules ⅛ ¾ ⅛ and ½ ½.
pub fn loop_step(mesh: &Mesh, topo: &Topology) -> Mesh {
    let p = &mesh.positions;
    let nb = neighbours(mesh, topo);
    let mut positions: Vec<Vector3<f64>> = (0..p.len())
        .into_par_iter()
        .map(|v| match nb.boundary[v] {
            Some(ends) => boundary_vertex(p, v, ends),
            None if nb.valence[v] == 0 => p[v],
            None => {
                let n = nb.valence[v] as usize;
                let beta = loop_beta(n);
                p[v] * (1.0 - n as f64 * beta) + nb.sum[v] * beta
            }
        })
        .collect();
    let edge_points: Vec<Vector3<f64>> = topo
        .edges
        .par_iter()
        .map(|&h| {
            let (a, b) = (mesh.from_vertex(h), mesh.to_vertex(h));
            let mid = p[a as usize] + p[b as usize];
            let g = topo.opposite[h as usize];
            if g == NONE {
                mid * 0.5
            } else {
                mid * 0.375 + (p[mesh.apex(h) as usize] + p[mesh.apex(g) as usize]) * 0.125
            }
        })
        .collect();
    positions.extend(edge_points);
    Mesh {
        positions,
        triangles: split_four(mesh, topo),
    }
}

/// √3's α for valence n: (4 − 2 cos(2π/n))/9 (Kobbelt).
pub fn sqrt3_alpha(n: usize) -> f64 {
    (4.0 - 2.0 * (2.0 * PI / n as f64).cos()) / 9.0
}

/// One √3 step: every triangle gets its barycentre; interior vertices move to
/// (1 − α) v + (α/n) Σ neighbours; every interior edge is flipped into the two triangles
/// (a, m_R, m_L), (b, m_L, m_R) of the barycentres beside it. As the seed says, boundaries
/// use Loop's rules: boundary vertices ⅛ ¾ ⅛, and only boundary edges get an edge point e,
/// their triangle's barycentre m giving the triangles (a, e, m) and (e, b, m). New vertices:
/// old ones, then one per triangle, then one per boundary edge.
pub fn sqrt3_step(mesh: &Mesh, topo: &Topology) -> Mesh {
    let p = &mesh.positions;
    let nb = neighbours(mesh, topo);
    let v = p.len() as u32;
    let t = mesh.triangles.len() as u32;
    let mut positions: Vec<Vector3<f64>> = (0..p.len())
        .into_par_iter()
        .map(|i| match nb.boundary[i] {
            Some(ends) => boundary_vertex(p, i, ends),
            None if nb.valence[i] == 0 => p[i],
            None => {
                let n = nb.valence[i] as usize;
                let alpha = sqrt3_alpha(n);
                p[i] * (1.0 - alpha) + nb.sum[i] * (alpha / n as f64)
            }
        })
        .collect();
    positions.par_extend(
        mesh.triangles
            .par_iter()
            .map(|tri| (p[tri[0] as usize] + p[tri[1] as usize] + p[tri[2] as usize]) / 3.0),
    );
    // Boundary edges, numbered in edge order.
    let mut boundary_index = vec![NONE; topo.edges.len()];
    let mut count = 0u32;
    for (e, &h) in topo.edges.iter().enumerate() {
        if topo.opposite[h as usize] == NONE {
            boundary_index[e] = count;
            count += 1;
            positions.push((p[mesh.from_vertex(h) as usize] + p[mesh.to_vertex(h) as usize]) * 0.5);
        }
    }
    let triangles = topo
        .edges
        .par_iter()
        .enumerate()
        .flat_map_iter(|(e, &h)| {
            let (a, b) = (mesh.from_vertex(h), mesh.to_vertex(h));
            let m = v + h / 3;
            let g = topo.opposite[h as usize];
            if g == NONE {
                let ep = v + t + boundary_index[e];
                [[a, ep, m], [ep, b, m]]
            } else {
                let r = v + g / 3;
                [[a, r, m], [b, m, r]]
            }
        })
        .collect();
    Mesh {
        positions,
        triangles,
    }
}

/// The modified butterfly's weights for an extraordinary vertex of valence k ≥ 3 (Zorin,
/// Schröder and Sweldens 1996): the vertex gets ¾ and its j-th neighbour (j = 0 at the
/// edge's other end, counter-clockwise) s_j.
pub fn butterfly_weights(k: usize) -> Vec<f64> {
    match k {
        3 => vec![5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0],
        4 => vec![3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0],
        _ => (0..k)
            .map(|j| {
                let a = 2.0 * PI * j as f64 / k as f64;
                (0.25 + a.cos() + 0.5 * (2.0 * a).cos()) / k as f64
            })
            .collect(),
    }
}

/// The edge point of an interior edge from the one-sided stencil of its interior end `a`
/// (whose ring starts at the edge's other end).
fn one_sided(p: &[Vector3<f64>], a: u32, ring: &[u32]) -> Vector3<f64> {
    let w = butterfly_weights(ring.len());
    ring.iter()
        .zip(&w)
        .fold(p[a as usize] * 0.75, |acc, (&r, &s)| {
            acc + p[r as usize] * s
        })
}

/// The ring of interior vertex `a` rotated to start at `b`.
fn ring_from(topo: &Topology, mesh: &Mesh, a: u32, b: u32) -> Option<Vec<u32>> {
    let (mut ring, boundary) = topo.ring(mesh, a);
    if boundary {
        return None;
    }
    let k = ring.iter().position(|&r| r == b)?;
    ring.rotate_left(k);
    Some(ring)
}

/// One butterfly step: old vertices stay; edge points by the butterfly scheme.
/// - Interior edges between two interior vertices of valence 6: the 8-point stencil
///   ½ (a + b) + ⅛ (c + d) − 1/16 (e₁ + e₂ + e₃ + e₄).
/// - Interior edges with one extraordinary interior end: that end's stencil
///   ¾ a + Σ s_j v_j; with two, the mean of both; with one end on the boundary, the other
///   end's stencil (also at valence 6); with both ends on the boundary, the midpoint.
/// - Boundary edges: the four-point scheme −1/16, 9/16, 9/16, −1/16 along the boundary.
pub fn butterfly_step(mesh: &Mesh, topo: &Topology) -> Mesh {
    let p = &mesh.positions;
    let nb = neighbours(mesh, topo);
    let interior = |v: u32| nb.boundary[v as usize].is_none();
    let regular = |v: u32| interior(v) && nb.valence[v as usize] == 6;
    let edge_points: Vec<Vector3<f64>> = topo
        .edges
        .par_iter()
        .map(|&h| {
            let (a, b) = (mesh.from_vertex(h), mesh.to_vertex(h));
            let g = topo.opposite[h as usize];
            if g == NONE {
                // a → b runs along the boundary: the vertex before a and after b.
                let before = nb.boundary[a as usize].map_or(a, |e| e.1);
                let after = nb.boundary[b as usize].map_or(b, |e| e.0);
                return (p[a as usize] + p[b as usize]) * (9.0 / 16.0)
                    - (p[before as usize] + p[after as usize]) * (1.0 / 16.0);
            }
            if regular(a) && regular(b) {
                let wing = |x: u32| {
                    let o = topo.opposite[x as usize];
                    (o != NONE).then(|| mesh.apex(o))
                };
                let next = |x: u32| x - x % 3 + (x % 3 + 1) % 3;
                let prev = |x: u32| x - x % 3 + (x % 3 + 2) % 3;
                let wings = [wing(next(h)), wing(prev(h)), wing(next(g)), wing(prev(g))];
                if wings.iter().all(Option::is_some) {
                    let (c, d) = (mesh.apex(h), mesh.apex(g));
                    let e: Vector3<f64> = wings.iter().map(|w| p[w.unwrap() as usize]).sum();
                    return (p[a as usize] + p[b as usize]) * 0.5
                        + (p[c as usize] + p[d as usize]) * 0.125
                        - e * (1.0 / 16.0);
                }
            }
            let from_a = ring_from(topo, mesh, a, b).map(|r| one_sided(p, a, &r));
            let from_b = ring_from(topo, mesh, b, a).map(|r| one_sided(p, b, &r));
            match (from_a, from_b) {
                (Some(x), Some(y)) => match (regular(a), regular(b)) {
                    (true, false) => y,
                    (false, true) => x,
                    _ => (x + y) * 0.5,
                },
                (Some(x), None) => x,
                (None, Some(y)) => y,
                (None, None) => (p[a as usize] + p[b as usize]) * 0.5,
            }
        })
        .collect();
    let mut positions = p.clone();
    positions.extend(edge_points);
    Mesh {
        positions,
        triangles: split_four(mesh, topo),
    }
}

/// Loop's limit positions: interior (ω v + Σ v_i)/(ω + n) with ω = 3/(8β); boundary
/// (a + 4 v + b)/6, the cubic B-spline's.
pub fn loop_limit_positions(mesh: &Mesh) -> Result<Vec<Vector3<f64>>, MeshError> {
    let topo = mesh.topology()?;
    let nb = neighbours(mesh, &topo);
    let p = &mesh.positions;
    Ok((0..p.len())
        .into_par_iter()
        .map(|v| match nb.boundary[v] {
            Some((a, b)) => (p[a as usize] + p[v] * 4.0 + p[b as usize]) / 6.0,
            None if nb.valence[v] == 0 => p[v],
            None => {
                let n = nb.valence[v] as f64;
                let omega = 3.0 / (8.0 * loop_beta(nb.valence[v] as usize));
                (p[v] * omega + nb.sum[v]) / (omega + n)
            }
        })
        .collect())
}

/// Loop's limit normals: at interior vertices the cross product of the tangent masks
/// Σ cos(2πj/n) v_j and Σ sin(2πj/n) v_j over the ring in counter-clockwise order; at
/// boundary vertices the tangent along the boundary, b − a, crossed with the tangent across
/// of Hoppe et al. (1994) for the cubic boundary rule. Unit vectors (zero where degenerate).
pub fn loop_limit_normals(mesh: &Mesh) -> Result<Vec<Vector3<f64>>, MeshError> {
    let topo = mesh.topology()?;
    let p = &mesh.positions;
    Ok((0..p.len() as u32)
        .into_par_iter()
        .map(|v| {
            let (ring, boundary) = topo.ring(mesh, v);
            let at = |i: usize| p[ring[i] as usize];
            let normal = if ring.is_empty() {
                Vector3::zeros()
            } else if !boundary {
                let n = ring.len();
                let (mut t1, mut t2) = (Vector3::zeros(), Vector3::zeros());
                for (j, _) in ring.iter().enumerate() {
                    let a = 2.0 * PI * j as f64 / n as f64;
                    t1 += at(j) * a.cos();
                    t2 += at(j) * a.sin();
                }
                t1.cross(&t2)
            } else {
                // ring[0] is the next boundary vertex, ring[k] the previous one.
                let k = ring.len() - 1;
                let pv = p[v as usize];
                let along = at(0) - at(k);
                let across = match k {
                    1 => at(0) + at(1) - pv * 2.0,
                    2 => at(1) - pv,
                    _ => {
                        let theta = PI / k as f64;
                        let inner: Vector3<f64> =
                            (1..k).map(|i| at(i) * (i as f64 * theta).sin()).sum();
                        // Hoppe's mask points out of the surface for k ≥ 3: negated.
                        -((at(0) + at(k)) * theta.sin() + inner * (2.0 * theta.cos() - 2.0))
                    }
                };
                // The fan runs counter-clockwise from ring[0], so `across` points into the
                // surface and along × across to its front side.
                along.cross(&across)
            };
            normal.try_normalize(0.0).unwrap_or_default()
        })
        .collect())
}
