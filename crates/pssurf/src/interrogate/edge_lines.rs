//! Level lines that run along piece edges: z = 0 of data gridded on the line x = 0, or any
//! level a surface takes on a whole edge of its refinement.
//!
//! There the pieces on both sides have the edge in their level set, each traces it with
//! rounding that puts its points now inside, now outside the piece, and the branches end at
//! random places along the edge, twice over; joined, they made dozens of short curves and
//! loops where there is one line. Instead, an edge along which the function takes the level
//! (at five points from the corners, within
//! [`CONTINUITY_TOLERANCES`](super::curve::CONTINUITY_TOLERANCES) corrector tolerances:
//! on a polynomial piece a quadratic or quartic restriction then vanishes identically up to
//! rounding) becomes one branch of the piece with the lowest index that owns it, from corner
//! to corner, and every branch that lies along such edges is dropped. The branches then join
//! at the corners like any others.

use std::collections::HashMap;

use nalgebra::Point2;

use super::continuation::{ConvexPolygon, distance_to_segment};
use super::joining::Edges;

/// Where an edge is tested: the corners first, then inside.
const TEST_POINTS: [f64; 5] = [0.0, 1.0, 0.5, 0.25, 0.75];

/// A branch along a whole edge of a piece.
pub(crate) struct EdgeLine {
    /// The piece (index in the [`Edges`]) it is a branch of.
    pub piece: usize,
    /// Its edge in that piece's polygon.
    pub edge: usize,
    /// Points from one corner to the other, at most `spacing` apart.
    pub uvs: Vec<Point2<f64>>,
}

/// The edges along which `on_level(piece, uv)` holds for an owner where `searched` is true,
/// as branches of the first such owner, points at most `spacing(piece)` apart, in a fixed
/// order (by corner ids).
pub(crate) fn level_edges(
    edges: &Edges,
    polygons: &[&ConvexPolygon],
    searched: &[bool],
    on_level: impl Fn(usize, Point2<f64>) -> bool,
    spacing: impl Fn(usize) -> f64,
) -> Vec<EdgeLine> {
    let mut found: Vec<((usize, usize), EdgeLine)> = Vec::new();
    for (key, owners) in edges.owned() {
        let mut sorted: Vec<usize> = owners.iter().copied().filter(|&o| searched[o]).collect();
        sorted.sort_unstable();
        for piece in sorted {
            let polygon = polygons[piece];
            let n = polygon.corners.len();
            let Some(e) = (0..n).find(|&e| edges.edge_of(piece, e) == key) else {
                continue;
            };
            let (a, b) = (polygon.corners[e], polygon.corners[(e + 1) % n]);
            if TEST_POINTS
                .iter()
                .all(|&t| on_level(piece, a + (b - a) * t))
            {
                // (At least one step: a NaN ratio from a zero spacing becomes 0 as usize.)
                let steps = ((b - a).norm() / spacing(piece)).ceil().min(1e4) as usize;
                let steps = steps.max(1);
                let uvs = (0..=steps)
                    .map(|k| a + (b - a) * (k as f64 / steps as f64))
                    .collect();
                found.push((
                    key,
                    EdgeLine {
                        piece,
                        edge: e,
                        uvs,
                    },
                ));
                break;
            }
        }
    }
    found.sort_unstable_by_key(|(key, _)| *key);
    found.into_iter().map(|(_, line)| line).collect()
}

/// The level edges by corner, to find those next to a piece.
pub(crate) struct EdgeLineIndex<'a> {
    lines: &'a [EdgeLine],
    edges: &'a Edges,
    by_corner: HashMap<usize, Vec<usize>>,
}

impl<'a> EdgeLineIndex<'a> {
    /// The index of `lines`, edges of `edges`.
    pub fn new(lines: &'a [EdgeLine], edges: &'a Edges) -> Self {
        let mut by_corner: HashMap<usize, Vec<usize>> = HashMap::new();
        for (k, line) in lines.iter().enumerate() {
            let (a, b) = edges.edge_of(line.piece, line.edge);
            by_corner.entry(a).or_default().push(k);
            by_corner.entry(b).or_default().push(k);
        }
        EdgeLineIndex {
            lines,
            edges,
            by_corner,
        }
    }

    /// Whether every point of a branch of `piece` lies within `reach` × (the edge's
    /// length) of the level edges that touch the piece: a copy of them (or of a corner of
    /// them) traced by the piece.
    pub fn covers(&self, piece: usize, uvs: &[Point2<f64>], reach: f64) -> bool {
        let mut near: Vec<usize> = self
            .edges
            .corners_of(piece)
            .iter()
            .filter_map(|c| self.by_corner.get(c))
            .flatten()
            .copied()
            .collect();
        near.sort_unstable();
        near.dedup();
        if near.is_empty() || uvs.is_empty() {
            return false;
        }
        let segments: Vec<(Point2<f64>, Point2<f64>)> = near
            .iter()
            .map(|&k| {
                let uvs = &self.lines[k].uvs;
                (uvs[0], uvs[uvs.len() - 1])
            })
            .collect();
        uvs.iter().all(|&p| {
            segments
                .iter()
                .any(|&(a, b)| distance_to_segment(p, a, b) <= reach * (b - a).norm())
        })
    }
}
