//! Validation and construction of the adjacency structure.

use std::f64::consts::TAU;
use std::sync::OnceLock;

use nalgebra::Point2;
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

use super::{NO_NEIGHBOR, Triangulation, TriangulationError};
use crate::geometry::{Triangle2, orient_exact};

type E = TriangulationError;

/// Validates the input and builds the triangulation (see [`Triangulation::try_new`]).
pub(super) fn build(
    vertices: Vec<Point2<f64>>,
    triangles: Vec<[usize; 3]>,
) -> Result<Triangulation, TriangulationError> {
    if triangles.is_empty() {
        return Err(E::NoTriangles);
    }
    let n = vertices.len();
    if n >= NO_NEIGHBOR as usize || triangles.len() >= NO_NEIGHBOR as usize {
        return Err(E::TooLarge(n.max(triangles.len())));
    }
    check_coordinates(&vertices)?;
    check_duplicates(&vertices)?;
    let mut tris = check_triangles(&vertices, &triangles)?;
    check_duplicate_triangles(&tris)?;
    orient_counter_clockwise(&vertices, &mut tris)?;
    let (offsets, list) = molecules(n, &tris)?;
    let neighbors = adjacency(&tris, &offsets, &list)?;
    let t = assemble(vertices, tris, neighbors, (offsets, list));
    let bow_tie = check_vertex_fans(&t)?;
    check_boundary_crossings(&t)?;
    // A bow-tie is reported after the boundary contacts, which name the cause more exactly
    // when both are found (a vertex on another triangle's edge also makes a bow-tie there).
    if let Some(vertex) = bow_tie {
        return Err(E::NonManifoldVertex { vertex });
    }
    check_boundary_loops(&t)?;
    Ok(t)
}

/// Builds the triangulation of a Delaunay triangulation (see [`super::delaunay`]), whose
/// coordinates and distinct points were checked before it was made, from its triangles and
/// the neighbours read from its half-edge structure.
///
/// A Delaunay triangulation made with exact predicates is a conforming triangulation of the
/// convex hull of its points: every edge lies in one triangle or two on opposite sides, no
/// triangles overlap, each vertex's fan is a disc or a half-disc, and the boundary is one
/// convex loop. So [`build`]'s checks of the adjacency, the fans and the boundary are left
/// out (they cost as much as the triangulation itself). The triangles' shapes are still
/// checked: [`Triangle2::is_degenerate`] ones are reported as in [`build`], and if one of
/// them is not counter-clockwise by the exact orientation test, the whole input goes
/// through [`build`], which names what is wrong.
pub(super) fn build_delaunay(
    vertices: Vec<Point2<f64>>,
    triangles: Vec<[usize; 3]>,
    neighbors: Vec<[u32; 3]>,
) -> Result<Triangulation, TriangulationError> {
    let n = vertices.len();
    if triangles.is_empty() {
        return Err(E::NoTriangles);
    }
    if n >= NO_NEIGHBOR as usize || triangles.len() >= NO_NEIGHBOR as usize {
        return Err(E::TooLarge(n.max(triangles.len())));
    }
    let shape = |tri: &[usize; 3]| {
        let [a, b, c] = tri.map(|i| vertices[i]);
        if Triangle2::new(a, b, c).is_degenerate() {
            Shape::Degenerate
        } else if orient_exact(a, b, c) > 0.0 {
            Shape::CounterClockwise
        } else {
            Shape::Other
        }
    };
    let first_bad = triangles
        .par_iter()
        .with_min_len(4096)
        .position_first(|tri| tri.iter().any(|&i| i >= n) || shape(tri) != Shape::CounterClockwise);
    if let Some(t) = first_bad {
        if triangles[t].iter().all(|&i| i < n) && shape(&triangles[t]) == Shape::Degenerate {
            return Err(E::DegenerateTriangle { triangle: t });
        }
        return build(vertices, triangles);
    }
    let tris: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|i| i as u32)).collect();
    let molecules = molecules(n, &tris)?;
    Ok(assemble(vertices, tris, neighbors, molecules))
}

/// The triangulation of checked parts, its boundary vertices marked from the neighbours.
fn assemble(
    vertices: Vec<Point2<f64>>,
    triangles: Vec<[u32; 3]>,
    neighbors: Vec<[u32; 3]>,
    (molecule_offsets, molecule_list): (Vec<u32>, Vec<u32>),
) -> Triangulation {
    let n = vertices.len();
    let mut t = Triangulation {
        vertices,
        triangles,
        neighbors,
        molecule_offsets,
        molecule_list,
        on_boundary: vec![false; n],
        locator: OnceLock::new(),
        spatial: OnceLock::new(),
    };
    mark_boundary(&mut t);
    t
}

/// How a triangle of a Delaunay triangulation is shaped, for [`build_delaunay`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum Shape {
    /// Thinner than [`Triangle2::is_degenerate`] allows.
    Degenerate,
    /// Counter-clockwise by the exact orientation test.
    CounterClockwise,
    /// Neither: not what a Delaunay triangulation gives.
    Other,
}

pub(super) fn check_duplicates(vertices: &[Point2<f64>]) -> Result<(), E> {
    match super::duplicate_points(vertices) {
        Some((first, second)) => Err(E::DuplicateVertex { first, second }),
        None => Ok(()),
    }
}

fn check_triangles(vertices: &[Point2<f64>], triangles: &[[usize; 3]]) -> Result<Vec<[u32; 3]>, E> {
    let n = vertices.len();
    let mut out = Vec::with_capacity(triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&i| i >= n) {
            return Err(E::IndexOutOfRange {
                triangle: t,
                index,
                vertex_count: n,
            });
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            return Err(E::RepeatedVertex { triangle: t });
        }
        let g = Triangle2::new(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]);
        if g.is_degenerate() {
            return Err(E::DegenerateTriangle { triangle: t });
        }
        out.push(tri.map(|i| i as u32));
    }
    Ok(out)
}

fn check_duplicate_triangles(tris: &[[u32; 3]]) -> Result<(), E> {
    let mut keyed: Vec<([u32; 3], usize)> = tris
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let mut k = *tri;
            k.sort_unstable();
            (k, t)
        })
        .collect();
    keyed.sort_unstable();
    for w in keyed.windows(2) {
        if w[0].0 == w[1].0 {
            return Err(E::DuplicateTriangle {
                triangle: w[1].1,
                first: w[0].1,
            });
        }
    }
    Ok(())
}

fn orient_counter_clockwise(vertices: &[Point2<f64>], tris: &mut [[u32; 3]]) -> Result<(), E> {
    let sign = |t: &[u32; 3]| {
        orient_exact(
            vertices[t[0] as usize],
            vertices[t[1] as usize],
            vertices[t[2] as usize],
        ) > 0.0
    };
    let first = sign(&tris[0]);
    if let Some(t) = tris.iter().position(|t| sign(t) != first) {
        return Err(E::InconsistentOrientation {
            triangle: t,
            first: 0,
        });
    }
    if !first {
        for t in tris.iter_mut() {
            t.swap(1, 2);
        }
    }
    Ok(())
}

/// Checks that every coordinate is finite and 0 or between
/// [`MIN_COORDINATE`](super::MIN_COORDINATE) and [`MAX_COORDINATE`](super::MAX_COORDINATE) in
/// magnitude, naming the first vertex that is not.
pub fn check_coordinates(vertices: &[Point2<f64>]) -> Result<(), E> {
    for (i, v) in vertices.iter().enumerate() {
        if !(v.x.is_finite() && v.y.is_finite()) {
            return Err(E::NonFiniteVertex(i));
        }
        let usable =
            |c: f64| c == 0.0 || (super::MIN_COORDINATE..=super::MAX_COORDINATE).contains(&c.abs());
        if !(usable(v.x) && usable(v.y)) {
            return Err(E::CoordinateOutOfRange(i));
        }
    }
    Ok(())
}

/// The vertex → triangles incidence in compressed form; fails on unused vertices.
fn molecules(n: usize, tris: &[[u32; 3]]) -> Result<(Vec<u32>, Vec<u32>), E> {
    let mut offsets = vec![0u32; n + 1];
    for t in tris {
        for &v in t {
            offsets[v as usize + 1] += 1;
        }
    }
    if let Some(i) = (0..n).find(|&i| offsets[i + 1] == 0) {
        return Err(E::UnusedVertex(i));
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut list = vec![0u32; 3 * tris.len()];
    for (t, tri) in tris.iter().enumerate() {
        for &v in tri {
            list[fill[v as usize] as usize] = t as u32;
            fill[v as usize] += 1;
        }
    }
    Ok((offsets, list))
}

/// Neighbours across each edge; detects duplicate triangles, edges in more than two
/// triangles and triangles on the same side of an edge. In parallel over the triangles; the
/// error reported is that of the first offending triangle.
fn adjacency(tris: &[[u32; 3]], offsets: &[u32], list: &[u32]) -> Result<Vec<[u32; 3]>, E> {
    let mut neighbors = vec![[NO_NEIGHBOR; 3]; tris.len()];
    let first_error = neighbors
        .par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .filter_map(|(t, out)| {
            triangle_neighbors(tris, offsets, list, t, out)
                .err()
                .map(|e| (t, e))
        })
        .min_by_key(|(t, _)| *t);
    match first_error {
        Some((_, e)) => Err(e),
        None => Ok(neighbors),
    }
}

/// The neighbours of triangle `t` across its three edges, into `out`.
fn triangle_neighbors(
    tris: &[[u32; 3]],
    offsets: &[u32],
    list: &[u32],
    t: usize,
    out: &mut [u32; 3],
) -> Result<(), E> {
    let tri = tris[t];
    for i in 0..3 {
        let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
        // Scan the smaller of the two molecules: a vertex of degree d otherwise costs d² (a
        // fan of 100,000 triangles took 6 s).
        let molecule =
            |v: u32| &list[offsets[v as usize] as usize..offsets[v as usize + 1] as usize];
        let (mol_a, mol_b) = (molecule(a), molecule(b));
        // The molecule scanned is that of `v`; `w` is the edge's other end.
        let from_a = mol_a.len() <= mol_b.len();
        let (mol, v, w) = if from_a { (mol_a, a, b) } else { (mol_b, b, a) };
        for &s in mol {
            let s = s as usize;
            if s == t {
                continue;
            }
            let other = tris[s];
            // v is in s (s is in its molecule); its successor and predecessor in s.
            let p = if other[0] == v {
                0
            } else if other[1] == v {
                1
            } else {
                2
            };
            let (next, prev) = (other[(p + 1) % 3], other[(p + 2) % 3]);
            if next != w && prev != w {
                continue;
            }
            // Both contain a and b: the same triangle when their third vertices agree.
            let third = if next == w { prev } else { next };
            if third == tri[i] {
                return Err(E::DuplicateTriangle {
                    triangle: t.max(s),
                    first: t.min(s),
                });
            }
            // In s the edge must run b → a (opposite direction), not a → b.
            let same_direction = if from_a { next == b } else { prev == a };
            if same_direction {
                return Err(E::NonConforming {
                    triangle: t.max(s),
                    detail: format!(
                        "triangles {} and {} lie on the same side of their common edge ({a}, {b}), so they overlap",
                        t.min(s),
                        t.max(s)
                    ),
                });
            }
            if out[i] != NO_NEIGHBOR && out[i] as usize != s {
                return Err(E::NonManifoldEdge {
                    triangle: t,
                    a: a as usize,
                    b: b as usize,
                });
            }
            out[i] = s as u32;
        }
    }
    Ok(())
}

fn mark_boundary(t: &mut Triangulation) {
    for tri in 0..t.triangles.len() {
        for i in 0..3 {
            if t.neighbors[tri][i] == NO_NEIGHBOR {
                let (a, b) = t.edge_vertices(tri, i);
                t.on_boundary[a] = true;
                t.on_boundary[b] = true;
            }
        }
    }
}

/// The number of boundary edges at vertex `v` and how often its triangles wind around it:
/// for a closed fan of counter-clockwise triangles the angles add up to 2π times the number
/// of triangles covering the ray from V in the +x direction (counted with a half-open rule,
/// no trigonometry); for an open fan the angle sum itself (by atan2).
fn fan(t: &Triangulation, v: usize) -> (usize, f64) {
    let mut boundary_edges = 0;
    let mut crossings = 0;
    let mut angle = 0.0;
    let pv = t.vertex(v);
    for &s in t.molecule(v) {
        let s = s as usize;
        let c = t.corner_of(s, v).expect("molecule triangle has the vertex");
        // The two edges of s at v are opposite corners c+1 and c+2.
        for e in [(c + 1) % 3, (c + 2) % 3] {
            if t.is_boundary_edge(s, e) {
                boundary_edges += 1;
            }
        }
        let tri = t.triangle(s);
        let (u, w) = (
            t.vertex(tri[(c + 1) % 3]) - pv,
            t.vertex(tri[(c + 2) % 3]) - pv,
        );
        if u.y < 0.0 && w.y >= 0.0 {
            crossings += 1;
        }
    }
    if boundary_edges == 0 {
        return (0, TAU * crossings as f64);
    }
    for &s in t.molecule(v) {
        let s = s as usize;
        let c = t.corner_of(s, v).expect("molecule triangle has the vertex");
        let tri = t.triangle(s);
        let (u, w) = (
            t.vertex(tri[(c + 1) % 3]) - pv,
            t.vertex(tri[(c + 2) % 3]) - pv,
        );
        angle += crate::geometry::cross(u, w).atan2(u.dot(&w));
    }
    (boundary_edges, angle)
}

/// The angles of a vertex's triangles must add up to 2π around an interior vertex and to
/// less than 2π at a boundary vertex; otherwise the triangles wind around it more than once.
/// A vertex whose fan has more than one gap joins parts that touch at a point (a bow-tie).
/// In parallel over the vertices; the first offending vertex is reported, a winding as an
/// error, a bow-tie as the returned vertex.
fn check_vertex_fans(t: &Triangulation) -> Result<Option<usize>, E> {
    let bad = (0..t.vertex_count())
        .into_par_iter()
        .with_min_len(4096)
        .filter_map(|v| {
            let (boundary_edges, angle) = fan(t, v);
            let tol = 1e-9 * TAU;
            let wound = if boundary_edges == 0 {
                (angle - TAU).abs() > tol
            } else {
                angle > TAU + tol
            };
            if wound {
                return Some((v, Err(angle)));
            }
            (boundary_edges > 2).then_some((v, Ok(())))
        })
        .min_by_key(|(v, _)| *v);
    match bad {
        None => Ok(None),
        Some((vertex, Ok(()))) => Ok(Some(vertex)),
        Some((v, Err(angle))) => Err(E::NonConforming {
            triangle: t.molecule(v)[0] as usize,
            detail: format!(
                "the triangles around vertex {v} cover an angle of {}π instead of {}, so they overlap",
                crate::text::Short(angle / std::f64::consts::PI),
                if fan(t, v).0 == 0 {
                    "2π"
                } else {
                    "less than 2π"
                }
            ),
        }),
    }
}

/// Boundary edges may meet only at shared end points: a crossing, a touching, or a vertex in
/// the middle of another boundary edge (a hanging node) makes the triangulation non-conforming.
fn check_boundary_crossings(t: &Triangulation) -> Result<(), E> {
    let edges: Vec<(usize, usize, usize)> = t
        .boundary_edges()
        .map(|(tri, i)| {
            let (a, b) = t.edge_vertices(tri, i);
            (tri, a, b)
        })
        .collect();
    let (lo, hi) = t.bounds();
    let pad = 1e-12 * (hi - lo).norm();
    let tree = RTree::bulk_load(
        edges
            .iter()
            .enumerate()
            .map(|(k, &(_, a, b))| {
                let (pa, pb) = (t.vertex(a), t.vertex(b));
                let rect = Rectangle::from_corners(
                    [pa.x.min(pb.x) - pad, pa.y.min(pb.y) - pad],
                    [pa.x.max(pb.x) + pad, pa.y.max(pb.y) + pad],
                );
                GeomWithData::new(rect, k)
            })
            .collect(),
    );
    for (k, &(tri, a, b)) in edges.iter().enumerate() {
        let (pa, pb) = (t.vertex(a), t.vertex(b));
        let env = AABB::from_corners(
            [pa.x.min(pb.x) - pad, pa.y.min(pb.y) - pad],
            [pa.x.max(pb.x) + pad, pa.y.max(pb.y) + pad],
        );
        for other in tree.locate_in_envelope_intersecting(env) {
            let l = other.data;
            if l <= k {
                continue;
            }
            let (tri2, c, d) = edges[l];
            if let Some(detail) = segments_conflict(t, (a, b), (c, d)) {
                return Err(E::NonConforming {
                    triangle: tri.min(tri2),
                    detail: format!(
                        "boundary edges ({a}, {b}) of triangle {tri} and ({c}, {d}) of triangle {tri2}: {detail}"
                    ),
                });
            }
        }
    }
    Ok(())
}

/// Why two boundary segments conflict, if they do.
fn segments_conflict(
    t: &Triangulation,
    (a, b): (usize, usize),
    (c, d): (usize, usize),
) -> Option<String> {
    let p = |i| t.vertex(i);
    // Exactly on the closed segment (s, e), other than at its end points.
    let on_segment = |q: usize, s: usize, e: usize| {
        let (ps, pe, pq) = (p(s), p(e), p(q));
        let between = |a: f64, b: f64, x: f64| a.min(b) <= x && x <= a.max(b);
        orient_exact(ps, pe, pq) == 0.0
            && between(ps.x, pe.x, pq.x)
            && between(ps.y, pe.y, pq.y)
            && pq != ps
            && pq != pe
    };
    for (q, s, e) in [(a, c, d), (b, c, d), (c, a, b), (d, a, b)] {
        if q != s && q != e && on_segment(q, s, e) {
            return Some(format!(
                "vertex {q} lies on the edge ({s}, {e}) (a hanging node)"
            ));
        }
    }
    let shared = a == c || a == d || b == c || b == d;
    if shared {
        return None;
    }
    let (pa, pb, pc, pd) = (p(a), p(b), p(c), p(d));
    let side = |a, b, c| orient_exact(a, b, c).signum();
    let (o1, o2) = (side(pa, pb, pc), side(pa, pb, pd));
    let (o3, o4) = (side(pc, pd, pa), side(pc, pd, pb));
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return Some("they cross".to_string());
    }
    None
}

/// The boundary loops: closed chains of boundary edges, each edge directed as in its
/// (counter-clockwise) triangle, so that the domain lies on the left. Needs each boundary
/// vertex to start exactly one boundary edge (no bow-ties, checked before).
fn boundary_loops(t: &Triangulation) -> Vec<Vec<usize>> {
    let mut next = vec![usize::MAX; t.vertex_count()];
    for (tri, i) in t.boundary_edges() {
        let (a, b) = t.edge_vertices(tri, i);
        next[a] = b;
    }
    let mut seen = vec![false; t.vertex_count()];
    let mut loops = Vec::new();
    for start in 0..t.vertex_count() {
        if next[start] == usize::MAX || seen[start] {
            continue;
        }
        let mut cycle = Vec::new();
        let mut v = start;
        while !seen[v] && next[v] != usize::MAX {
            seen[v] = true;
            cycle.push(v);
            v = next[v];
        }
        loops.push(cycle);
    }
    loops
}

/// How often the closed polygon `cycle` winds around `p` (not on it), counter-clockwise
/// positive, with exact orientation tests (the crossing rule of Sunday's winding number).
fn winding(t: &Triangulation, cycle: &[usize], p: Point2<f64>) -> i64 {
    let mut w = 0;
    for k in 0..cycle.len() {
        let (a, b) = (t.vertex(cycle[k]), t.vertex(cycle[(k + 1) % cycle.len()]));
        if a.y <= p.y {
            if b.y > p.y && orient_exact(a, b, p) > 0.0 {
                w += 1;
            }
        } else if b.y <= p.y && orient_exact(a, b, p) < 0.0 {
            w -= 1;
        }
    }
    w
}

/// Whether the simple polygon `cycle` runs clockwise: the turn at its lowest (then leftmost)
/// vertex, a convex corner, decided exactly.
fn clockwise(t: &Triangulation, cycle: &[usize]) -> bool {
    let n = cycle.len();
    let k = (0..n)
        .min_by(|&i, &j| {
            let (a, b) = (t.vertex(cycle[i]), t.vertex(cycle[j]));
            a.y.total_cmp(&b.y).then(a.x.total_cmp(&b.x))
        })
        .expect("a loop has vertices");
    let (prev, here, next) = (
        t.vertex(cycle[(k + n - 1) % n]),
        t.vertex(cycle[k]),
        t.vertex(cycle[(k + 1) % n]),
    );
    orient_exact(prev, here, next) < 0.0
}

/// No part of the plane may be covered twice. With every triangle counter-clockwise and
/// every interior edge shared by two triangles in opposite directions, the number of
/// triangles covering a point p equals the winding number of the boundary chain around p
/// (the interior edges cancel). The loops being simple and disjoint (checked before), that
/// number is 0 or 1 everywhere exactly when it is 0 just to the right of every loop: for a
/// point beside a vertex v of loop L, the sum of the other loops' windings around v, plus −1
/// if L runs clockwise (the right side of a clockwise loop is inside it). This catches a
/// part of the domain lying inside another (folded or stacked parts), which no local test
/// sees. Exact; O(loops × boundary edges) with bounding-box filtering.
fn check_boundary_loops(t: &Triangulation) -> Result<(), E> {
    let loops = boundary_loops(t);
    if loops.len() < 2 {
        // One simple loop: its right side is outside it (clockwise loops were refused by
        // the orientation check of the triangles around it).
        return match loops.first() {
            Some(l) if clockwise(t, l) => Err(overlap(t, l[0], "winds clockwise")),
            _ => Ok(()),
        };
    }
    let boxes: Vec<(Point2<f64>, Point2<f64>)> = loops
        .iter()
        .map(|l| {
            l.iter()
                .fold((t.vertex(l[0]), t.vertex(l[0])), |(lo, hi), &v| {
                    let p = t.vertex(v);
                    (
                        Point2::new(lo.x.min(p.x), lo.y.min(p.y)),
                        Point2::new(hi.x.max(p.x), hi.y.max(p.y)),
                    )
                })
        })
        .collect();
    for (k, l) in loops.iter().enumerate() {
        let p = t.vertex(l[0]);
        let mut cover = if clockwise(t, l) { -1 } else { 0 };
        for (m, other) in loops.iter().enumerate() {
            let (lo, hi) = boxes[m];
            if m != k && lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y {
                cover += winding(t, other, p);
            }
        }
        if cover != 0 {
            return Err(overlap(
                t,
                l[0],
                "lies inside another part of the domain, which it overlaps",
            ));
        }
    }
    Ok(())
}

/// The error for a boundary loop through `vertex` that makes parts of the domain overlap.
fn overlap(t: &Triangulation, vertex: usize, what: &str) -> E {
    E::NonConforming {
        triangle: t.molecule(vertex)[0] as usize,
        detail: format!("the boundary through vertex {vertex} {what}"),
    }
}
