//! Delaunay triangulations of scattered points (by the `spade` crate).

use std::collections::HashMap;

use nalgebra::Point2;
use spade::{DelaunayTriangulation, Triangulation as _};

use super::{NO_NEIGHBOR, Triangulation, TriangulationError};
use crate::geometry::Triangle2;

/// Whether all points lie on one line (or there are fewer than three), decided with exact
/// orientation tests in one pass.
pub(super) fn all_collinear(points: &[Point2<f64>]) -> bool {
    let Some(&a) = points.first() else {
        return true;
    };
    let Some(&b) = points.iter().find(|&&p| p != a) else {
        return true;
    };
    points
        .iter()
        .all(|&p| crate::geometry::orient_exact(a, b, p) == 0.0)
}

/// The Delaunay triangulation and the boundary slivers peeled from it.
pub(super) fn delaunay(
    points: Vec<Point2<f64>>,
) -> Result<(Triangulation, Vec<[usize; 3]>), TriangulationError> {
    super::validate::check_coordinates(&points)?;
    // Coincident points would be merged silently by spade; report them instead.
    super::validate::check_duplicates(&points)?;
    // spade inserts collinear points one by one in quadratic time (100,000 took 27 s): decide
    // exactly, in linear time, before.
    if all_collinear(&points) {
        return Err(TriangulationError::CollinearPoints);
    }
    let sp: Vec<spade::Point2<f64>> = points
        .iter()
        .map(|p| spade::Point2::new(p.x, p.y))
        .collect();
    let dt = DelaunayTriangulation::<spade::Point2<f64>>::bulk_load_stable(sp)
        .map_err(|_| TriangulationError::CollinearPoints)?;
    let (triangles, neighbors) = triangles_and_neighbors(&dt);
    let (kept, peeled) = peel_hull_slivers(&points, triangles);
    if kept.is_empty() {
        return Err(TriangulationError::CollinearPoints);
    }
    // Triangles in the order of a space-filling curve through their centroids: neighbouring
    // triangles get nearby indices, so per-triangle arrays are traversed cache-friendly.
    let centroids: Vec<Point2<f64>> = kept
        .iter()
        .map(|t| {
            Point2::from((points[t[0]].coords + points[t[1]].coords + points[t[2]].coords) / 3.0)
        })
        .collect();
    let order = super::morton_order(&centroids);
    let built = if peeled.is_empty() {
        // Spade's triangles as they are: their neighbours come from its half-edges.
        let (triangles, neighbors) = reordered(&order, &kept, &neighbors);
        super::validate::build_delaunay(points, triangles, neighbors)
    } else {
        // Peeling changed the domain: validate it in full.
        let triangles: Vec<[usize; 3]> = order.iter().map(|&k| kept[k as usize]).collect();
        Triangulation::try_new(points, triangles)
    };
    match built {
        Ok(t) => Ok((t, peeled)),
        Err(TriangulationError::DegenerateTriangle { triangle }) => {
            Err(TriangulationError::NearlyCollinearPoints {
                points: kept[order[triangle] as usize],
            })
        }
        Err(e) => Err(e),
    }
}

/// The triangles in the order `order` (new index k: old index `order[k]`), with their
/// neighbour indices renumbered to match.
fn reordered(
    order: &[u32],
    triangles: &[[usize; 3]],
    neighbors: &[[u32; 3]],
) -> (Vec<[usize; 3]>, Vec<[u32; 3]>) {
    let mut new_index = vec![0u32; order.len()];
    for (k, &old) in order.iter().enumerate() {
        new_index[old as usize] = k as u32;
    }
    let renumber = |n: u32| {
        if n == NO_NEIGHBOR {
            n
        } else {
            new_index[n as usize]
        }
    };
    order
        .iter()
        .map(|&k| (triangles[k as usize], neighbors[k as usize].map(renumber)))
        .unzip()
}

/// The inner faces of `dt` as counter-clockwise vertex triples, and the face across each
/// edge (edge `i` opposite vertex `i`, as in [`Triangulation`]; [`NO_NEIGHBOR`] on the hull),
/// read from spade's half-edge structure.
fn triangles_and_neighbors(
    dt: &DelaunayTriangulation<spade::Point2<f64>>,
) -> (Vec<[usize; 3]>, Vec<[u32; 3]>) {
    let mut position = vec![NO_NEIGHBOR; dt.num_all_faces()];
    for (k, f) in dt.inner_faces().enumerate() {
        position[f.fix().index()] = k as u32;
    }
    dt.inner_faces()
        .map(|f| {
            // Edge k of a spade face runs from its vertex k to vertex k + 1.
            let edges = f.adjacent_edges();
            let across = |k: usize| {
                edges[k]
                    .rev()
                    .face()
                    .fix()
                    .as_inner()
                    .map_or(NO_NEIGHBOR, |g| position[g.index()])
            };
            let vertices = edges.map(|e| e.from().fix().index());
            (vertices, [across(1), across(2), across(0)])
        })
        .unzip()
}

/// Relative thickness (twice the area over the longest edge squared, about height / length)
/// below which a boundary triangle of a Delaunay triangulation is peeled off.
///
/// Nearly collinear points on the convex hull make boundary slivers. No choice of PS split
/// points suits them: the segments joining a sliver's split point to its neighbours' cross the
/// sliver's short edges within about its thickness of a vertex (measured: 1e-13 for points
/// 1e-12 off a line), far below the refinement's margin (1e-10). A sliver this thin covers
/// at most 1e-8 × its edge² / 2 of area.
pub const PEEL_THICKNESS: f64 = 1e-8;

/// The finest detail, relative to the largest coordinate magnitude, that the split points of
/// the PS refinement (rounded to the coordinates' precision) can resolve with a margin:
/// 2^-44 ≈ 5.7e-14, 256 units in the last place. (At UTM-sized coordinates of 1e7 this is
/// 0.57 µm.) Boundary slivers lower than this are peeled whatever their length, and
/// [`crate::scattered`] merges data points closer than this.
pub const COORDINATE_RESOLUTION: f64 = 1.0 / (1u64 << 44) as f64;

/// Removes thin triangles from the boundary, repeatedly: a triangle thinner than
/// [`PEEL_THICKNESS`] (or lower than [`COORDINATE_RESOLUTION`] × the largest coordinate
/// magnitude) with exactly one boundary edge whose opposite vertex is interior. Its
/// vertices stay in the neighbouring triangles and the domain stays a proper one (no vertex
/// is lost, no bow-tie is made); thin triangles that cannot be peeled so are left for the
/// caller to report.
/// Returns the triangles kept and those peeled.
fn peel_hull_slivers(
    points: &[Point2<f64>],
    mut tris: Vec<[usize; 3]>,
) -> (Vec<[usize; 3]>, Vec<[usize; 3]>) {
    let mut peeled = Vec::new();
    let magnitude = points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let resolution = COORDINATE_RESOLUTION * magnitude;
    let thin = |t: &[usize; 3]| {
        let g = Triangle2::new(points[t[0]], points[t[1]], points[t[2]]);
        let (h, det) = (g.diameter(), g.det().abs());
        !(det > PEEL_THICKNESS * h * h && det > resolution * h)
    };
    loop {
        if !tris.iter().any(thin) {
            return (tris, peeled);
        }
        let key = |a: usize, b: usize| (a.min(b), a.max(b));
        let mut edge_count: HashMap<(usize, usize), u32> = HashMap::new();
        for t in &tris {
            for i in 0..3 {
                *edge_count.entry(key(t[i], t[(i + 1) % 3])).or_default() += 1;
            }
        }
        let mut on_boundary = vec![false; points.len()];
        for (&(a, b), &n) in &edge_count {
            if n == 1 {
                on_boundary[a] = true;
                on_boundary[b] = true;
            }
        }
        // A triangle is peeled when exactly one edge is on the boundary and the vertex
        // opposite it is not; at most one triangle per boundary vertex per round, so that two
        // peels never meet at a vertex within one round.
        let mut touched = vec![false; points.len()];
        let before = tris.len();
        tris.retain(|t| {
            if !thin(t) {
                return true;
            }
            let boundary: Vec<usize> = (0..3)
                .filter(|&i| edge_count[&key(t[i], t[(i + 1) % 3])] == 1)
                .collect();
            let [i] = boundary[..] else {
                return true;
            };
            let opposite = t[(i + 2) % 3];
            if on_boundary[opposite] || t.iter().any(|&v| touched[v]) {
                return true;
            }
            t.iter().for_each(|&v| touched[v] = true);
            peeled.push(*t);
            false
        });
        if tris.len() == before {
            return (tris, peeled); // what is left is for validation to report
        }
    }
}
