//! Joining the branches traced piece by piece into curves over the whole surface: ends on a
//! shared edge or corner of two pieces that lie within the join tolerance are joined, chains
//! that come back to themselves are closed, and ends inside the domain that find no partner
//! are reported as gaps.
//!
//! Piece corners are welded (corners within 1e-9 of the pieces' extent are one point), so
//! neighbouring pieces that computed a shared split point with different rounding still
//! share their edge.

use std::collections::HashMap;

use nalgebra::{Point2, Vector3};

use super::continuation::ConvexPolygon;
use super::curve::{CONTINUITY_TOLERANCES, LevelGap, SurfaceCurve, ZeroSet};

/// The pieces' edges with welded corners: which pieces own each edge.
pub(crate) struct Edges {
    /// Per piece (in the order given), the welded id of each corner.
    corner_ids: Vec<Vec<usize>>,
    /// Per edge (pair of welded ids, smaller first), its owners.
    owners: HashMap<(usize, usize), Vec<usize>>,
    /// Welded ids of corners on the domain's boundary (on an edge with one owner).
    boundary: std::collections::HashSet<usize>,
    /// The position of each welded corner.
    positions: Vec<Point2<f64>>,
}

impl Edges {
    /// The edges of `pieces` (indices in iteration order).
    pub fn new<'a>(pieces: impl Iterator<Item = &'a ConvexPolygon>) -> Self {
        let polygons: Vec<&ConvexPolygon> = pieces.collect();
        let all: Vec<Point2<f64>> = polygons
            .iter()
            .flat_map(|p| p.corners.iter().copied())
            .collect();
        let (ids, positions) = weld(&all);
        let mut corner_ids = Vec::with_capacity(polygons.len());
        let mut k = 0;
        for p in &polygons {
            corner_ids.push(ids[k..k + p.corners.len()].to_vec());
            k += p.corners.len();
        }
        let mut owners: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        for (i, c) in corner_ids.iter().enumerate() {
            for e in 0..c.len() {
                owners
                    .entry(edge(c[e], c[(e + 1) % c.len()]))
                    .or_default()
                    .push(i);
            }
        }
        let mut boundary = std::collections::HashSet::new();
        for (&(a, b), o) in &owners {
            if o.len() == 1 {
                boundary.insert(a);
                boundary.insert(b);
            }
        }
        Edges {
            corner_ids,
            owners,
            boundary,
            positions,
        }
    }

    /// The welded corner ids of edge `e` of piece `piece`.
    pub fn edge_of(&self, piece: usize, e: usize) -> (usize, usize) {
        let c = &self.corner_ids[piece];
        edge(c[e], c[(e + 1) % c.len()])
    }

    /// Every edge (its welded corner ids, smaller first) with the pieces that own it.
    pub fn owned(&self) -> impl Iterator<Item = ((usize, usize), &[usize])> + '_ {
        self.owners.iter().map(|(&e, o)| (e, o.as_slice()))
    }

    /// The welded ids of piece `piece`'s corners.
    pub fn corners_of(&self, piece: usize) -> &[usize] {
        &self.corner_ids[piece]
    }
}

fn edge(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Welded ids: points within 1e-9 of the extent of all points get one id.
fn weld(points: &[Point2<f64>]) -> (Vec<usize>, Vec<Point2<f64>>) {
    let (mut lo, mut hi) = (
        Point2::new(f64::MAX, f64::MAX),
        Point2::new(f64::MIN, f64::MIN),
    );
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let eps = 1e-9 * (hi - lo).norm().max(f64::MIN_POSITIVE);
    let cell = |p: &Point2<f64>| {
        (
            ((p.x - lo.x) / (4.0 * eps)) as i64,
            ((p.y - lo.y) / (4.0 * eps)) as i64,
        )
    };
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut ids = vec![0; points.len()];
    let mut reps: Vec<Point2<f64>> = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let (cx, cy) = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for &r in grid
                    .get(&(cx + dx, cy + dy))
                    .map_or(&[][..], |v| v.as_slice())
                {
                    if (reps[r] - p).norm() <= eps {
                        found = Some(r);
                        break 'search;
                    }
                }
            }
        }
        ids[i] = found.unwrap_or_else(|| {
            reps.push(*p);
            grid.entry((cx, cy)).or_default().push(reps.len() - 1);
            reps.len() - 1
        });
    }
    (ids, reps)
}

/// A branch of one piece as the joiner sees it.
pub(crate) struct BranchEnds<'a> {
    /// The piece's index in the [`Edges`].
    pub piece: usize,
    pub uvs: &'a [Point2<f64>],
    pub points: &'a [Vector3<f64>],
    pub closed: bool,
    /// The piece edge the first point lies on.
    pub start_edge: Option<usize>,
    /// The piece edge the last point lies on.
    pub end_edge: Option<usize>,
}

/// Where an end lies: on an edge, or at a corner (welded ids).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Place {
    Edge(usize, usize),
    Corner(usize),
}

struct End {
    branch: usize,
    at_start: bool,
    uv: Point2<f64>,
    point: Vector3<f64>,
    place: Place,
    piece: usize,
    reach: f64,
}

/// The ends of a level's branches and which are joined.
pub(crate) struct Pairing {
    ends: Vec<End>,
    partner: Vec<Option<usize>>,
}

impl Pairing {
    /// Pairs the ends of `branches` on shared edges and corners.
    pub fn new(branches: &[BranchEnds], edges: &Edges, join_tolerance: f64) -> Self {
        let ends = collect_ends(branches, edges, join_tolerance);
        let partner = pair(&ends);
        Pairing { ends, partner }
    }

    /// Unpaired ends on edges inside the domain: (the neighbouring piece, the end's point).
    pub fn unfinished(&self, edges: &Edges) -> Vec<(usize, Point2<f64>)> {
        self.ends
            .iter()
            .zip(&self.partner)
            .filter(|(_, p)| p.is_none())
            .filter_map(|(e, _)| Some((inside_neighbour(e, edges)?, e.uv)))
            .collect()
    }

    /// Chains the branches into `set.curves` and reports the unpaired inner ends as gaps;
    /// `across(piece, uv)` is the function's value on the neighbouring piece.
    pub fn finish(
        &self,
        set: &mut ZeroSet,
        branches: &[BranchEnds],
        edges: &Edges,
        across: &dyn Fn(usize, Point2<f64>) -> f64,
    ) {
        for (e, p) in self.ends.iter().zip(&self.partner) {
            if p.is_some() {
                continue;
            }
            if let Some(other) = inside_neighbour(e, edges) {
                let there = across(other, e.uv);
                // The field's values on the two sides at the end's point: equal (a
                // continuous field) means the line was left unjoined, not cut by a jump.
                if (there - across(e.piece, e.uv)).abs() <= CONTINUITY_TOLERANCES * set.tolerance {
                    set.unjoined += 1;
                    continue;
                }
                set.gaps.push(LevelGap {
                    uv: e.uv,
                    point: e.point,
                    across: there,
                });
            }
        }
        chain(set, branches, &self.ends, &self.partner);
    }
}

/// The piece across the edge of an end, unless the end lies on the domain's boundary.
fn inside_neighbour(e: &End, edges: &Edges) -> Option<usize> {
    let Place::Edge(a, b) = e.place else {
        return None;
    };
    let owners = edges.owners.get(&(a, b))?;
    let at_boundary_corner = [a, b]
        .iter()
        .any(|&c| edges.boundary.contains(&c) && (edges.positions[c] - e.uv).norm() <= e.reach);
    if owners.len() < 2 || at_boundary_corner {
        return None;
    }
    owners.iter().copied().find(|&o| o != e.piece)
}

fn collect_ends(branches: &[BranchEnds], edges: &Edges, join_tolerance: f64) -> Vec<End> {
    let mut ends = Vec::new();
    for (bi, b) in branches.iter().enumerate() {
        if b.closed || b.uvs.is_empty() {
            continue;
        }
        for (at_start, e) in [(true, b.start_edge), (false, b.end_edge)] {
            let Some(e) = e else { continue };
            let k = if at_start { 0 } else { b.uvs.len() - 1 };
            let (a, c) = edges.edge_of(b.piece, e);
            let uv = b.uvs[k];
            ends.push(End {
                branch: bi,
                at_start,
                uv,
                point: b.points[k],
                place: Place::Edge(a, c),
                piece: b.piece,
                reach: join_tolerance * (edges.positions[a] - edges.positions[c]).norm(),
            });
        }
    }
    ends
}

/// Pairs ends of different pieces on the same edge or at a shared corner that lie within
/// reach of each other, nearest first.
fn pair(ends: &[End]) -> Vec<Option<usize>> {
    let mut by_place: HashMap<Place, Vec<usize>> = HashMap::new();
    for (i, e) in ends.iter().enumerate() {
        by_place.entry(e.place).or_default().push(i);
        if let Place::Edge(a, b) = e.place {
            by_place.entry(Place::Corner(a)).or_default().push(i);
            by_place.entry(Place::Corner(b)).or_default().push(i);
        }
    }
    let mut candidates = Vec::new();
    for group in by_place.values() {
        for (x, &i) in group.iter().enumerate() {
            for &j in &group[x + 1..] {
                let d = (ends[i].uv - ends[j].uv).norm();
                if ends[i].piece != ends[j].piece && d <= ends[i].reach.max(ends[j].reach) {
                    candidates.push((d, i.min(j), i.max(j)));
                }
            }
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut partner = vec![None; ends.len()];
    for (_, i, j) in candidates {
        if partner[i].is_none() && partner[j].is_none() {
            partner[i] = Some(j);
            partner[j] = Some(i);
        }
    }
    partner
}

/// Chains the branches through the paired ends into curves.
fn chain(set: &mut ZeroSet, branches: &[BranchEnds], ends: &[End], partner: &[Option<usize>]) {
    let mut end_of: HashMap<(usize, bool), usize> = HashMap::new();
    for (i, e) in ends.iter().enumerate() {
        end_of.insert((e.branch, e.at_start), i);
    }
    // The branch end joined to end (b, at_start), if any.
    let next = |b: usize, at_start: bool| -> Option<(usize, bool)> {
        let p = partner[*end_of.get(&(b, at_start))?]?;
        Some((ends[p].branch, ends[p].at_start))
    };
    let mut visited = vec![false; branches.len()];
    for b in 0..branches.len() {
        if visited[b] || branches[b].uvs.is_empty() {
            continue;
        }
        if branches[b].closed {
            visited[b] = true;
            set.curves.push(SurfaceCurve {
                uvs: branches[b].uvs.to_vec(),
                points: branches[b].points.to_vec(),
                closed: true,
            });
            continue;
        }
        // Walk back through start ends to the chain's head, or round a loop.
        let (mut head, mut enter_at_start) = (b, true);
        let mut closed = false;
        for _ in 0..branches.len() {
            let Some((b2, s2)) = next(head, enter_at_start) else {
                break;
            };
            if b2 == b {
                closed = true;
                break;
            }
            head = b2;
            enter_at_start = !s2;
        }
        if closed {
            (head, enter_at_start) = (b, true);
        }
        let mut curve = SurfaceCurve {
            closed,
            ..Default::default()
        };
        let (mut cur, mut from_start) = (head, enter_at_start);
        loop {
            visited[cur] = true;
            let pb = &branches[cur];
            // The joined end repeats the previous branch's last point (within the tolerance).
            let skip = usize::from(!curve.uvs.is_empty());
            if from_start {
                curve.uvs.extend(pb.uvs.iter().skip(skip));
                curve.points.extend(pb.points.iter().skip(skip));
            } else {
                curve.uvs.extend(pb.uvs.iter().rev().skip(skip));
                curve.points.extend(pb.points.iter().rev().skip(skip));
            }
            match next(cur, !from_start) {
                Some((b2, s2)) if !visited[b2] => {
                    cur = b2;
                    from_start = s2;
                }
                _ => break,
            }
        }
        if closed && curve.uvs.len() > 1 {
            curve.uvs.pop();
            curve.points.pop();
        }
        drop_repeats(&mut curve);
        set.curves.push(curve);
    }
}

/// Drops points within 1e-12 of the curve's extent of their predecessor (a join repeats the
/// crossing point, computed once on each side of the edge).
fn drop_repeats(curve: &mut SurfaceCurve) {
    let Some(&first) = curve.uvs.first() else {
        return;
    };
    let (lo, hi) = curve
        .uvs
        .iter()
        .fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let eps = 1e-12 * (hi - lo).norm();
    let mut k = 0;
    for i in 0..curve.uvs.len() {
        if k == 0 || (curve.uvs[i] - curve.uvs[k - 1]).norm() > eps {
            k += 1;
        } else if i + 1 < curve.uvs.len() {
            continue; // keep the earlier point, except at the curve's end
        }
        curve.uvs[k - 1] = curve.uvs[i];
        curve.points[k - 1] = curve.points[i];
    }
    curve.uvs.truncate(k);
    curve.points.truncate(k);
    if curve.closed && k > 1 && (curve.uvs[k - 1] - curve.uvs[0]).norm() <= eps {
        curve.uvs.pop();
        curve.points.pop();
    }
}
