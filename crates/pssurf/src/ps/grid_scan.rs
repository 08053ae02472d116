//! Values of a PS-spline on a sorted rectilinear grid by scan conversion of the refinement
//! Δ*: each triangle of Δ is visited once, and on each grid line x = xs[i] that crosses it,
//! the grid points between the line's entry and exit are handed to the pieces of Δ* in the
//! order the line meets them, each filled from one univariate quadratic. No point is
//! located.
//!
//! **Which pieces a line meets.** The six pieces (P_k, P_{k+1}, Z) of a triangle fan around
//! its split point Z, with P = (V0, R0, V1, R1, V2, R2) counter-clockwise. A line x = c right
//! of Z (c ≥ Z.x) meets the rays Z P_k with P_k.x ≥ c — a contiguous arc k1 … k2 of them,
//! as the P_k lie on a convex polygon — and upwards it passes through the pieces k1 − 1,
//! k1, …, k2 counter-clockwise; left of Z the same clockwise with P_k.x ≤ c.
//!
//! **Coverage** is decided in floating point, consistently: a segment shared by two pieces or
//! triangles is evaluated by the same expression from both sides (its end points in a fixed
//! order; the edge points R of Δ's edges computed once per edge), and exactly at its end
//! points, so the spans along a line leave no gap. A span ending on the domain's boundary is
//! extended to the points that [`PsSpline::eval`] also accepts there (barycentric
//! coordinates ≥ −[`INSIDE_TOLERANCE`] in the boundary triangle).
//!
//! **Values.** Along a line a piece's barycentric coordinates are affine,
//! λ(y) = λ₀ + (y − y₀) w, so with the quadratic form Q of its Bézier ordinates (s = λᵀQλ,
//! the quadratic patch of thesis (2.18)) s = λ₀ᵀQλ₀ + 2 (y − y₀) λ₀ᵀQw + (y − y₀)² wᵀQw. As
//! (y − y₀) w is the change of λ inside the piece (each component at most 1 in size), this is
//! as stable as de Casteljau's algorithm. Usually only the first piece along a line needs
//! λ₀: the spline is C¹ across the rays Z P_k, so a further piece can start with the value
//! and slope of the one below at their ray, and only its wᵀQw differs. A slope carried out
//! of a thin piece (large w) would bring that piece's rounding, scaled by the ratio of
//! their thicknesses, into a wide one: a piece is set up afresh when the pieces carried
//! through are more than [`CARRY_RATIO`] times steeper than it.

use std::ops::Range;

use nalgebra::Point2;
use rayon::prelude::*;

use super::basis::PsBasis;
use super::net::{NET_LEN, SUB_ORDINATES};
use super::spline::PsSpline;
use crate::geometry::{BaryMap, Triangle2};
use crate::triangulation::{INSIDE_TOLERANCE, Triangulation};
use crate::vector::Vector;

/// The fewest grid points per triangle for which the scan is used. Its set-up is per
/// triangle and per line, the run evaluation's per point; they cost the same at about 5 points
/// per triangle (1000 × 1000 grids on splines of 1k, 10k, 100k vertices: the scan takes
/// 0.6, 0.75 and 1.05 × the time of the runs).
pub(super) const SCAN_POINTS_PER_TRIANGLE: f64 = 8.0;

/// How much steeper (thinner along a vertical line) the pieces a value and slope were
/// carried through may be than the piece they are carried into: beyond this its quadratic is
/// set up afresh, so that carrying never loses more than a few units in the last place.
const CARRY_RATIO: f64 = 4.0;

/// Grid lines per parallel band, at least (a band owns its rows of the output).
const MIN_LINES_PER_BAND: usize = 4;

/// Bands per thread (more bands balance better; fewer repeat less set-up of the triangles
/// that straddle two bands).
const BANDS_PER_THREAD: usize = 8;

/// A finite, non-decreasing coordinate axis with a bucket table that finds where a value
/// falls in about constant time on evenly spaced axes (a binary search in one bucket at worst).
pub(super) struct Axis<'a> {
    values: &'a [f64],
    origin: f64,
    scale: f64,
    /// The number of buckets less one.
    last_bucket: usize,
    /// `starts[b]`: the first index whose value falls in bucket ≥ b (one past the end last).
    starts: Vec<u32>,
}

impl<'a> Axis<'a> {
    /// The axis, or `None` unless the values are finite and non-decreasing (and fewer than
    /// 2³² of them).
    pub(super) fn new(values: &'a [f64]) -> Option<Self> {
        let (&first, &last) = (values.first()?, values.last()?);
        let sorted = values.iter().all(|v| v.is_finite()) && values.is_sorted();
        if !sorted || values.len() >= u32::MAX as usize {
            return None;
        }
        let buckets = values.len();
        let scale = buckets as f64 / (last - first);
        let mut axis = Axis {
            values,
            origin: first,
            scale: if scale.is_finite() { scale } else { 0.0 },
            last_bucket: buckets - 1,
            starts: Vec::with_capacity(buckets + 1),
        };
        // The bucket of each value is non-decreasing along the axis.
        let mut k = 0;
        for b in 0..buckets {
            while k < values.len() && axis.bucket(values[k]) < b {
                k += 1;
            }
            axis.starts.push(k as u32);
        }
        axis.starts.push(values.len() as u32);
        Some(axis)
    }

    /// The bucket of `v`: a non-decreasing function of v, so that every value below `v`'s
    /// bucket start is smaller than v and every value past its end is larger.
    #[inline]
    fn bucket(&self, v: f64) -> usize {
        let f = (v - self.origin) * self.scale;
        if f > 0.0 {
            (f as usize).min(self.last_bucket)
        } else {
            0
        }
    }

    /// The first index whose value is ≥ v (the length if none).
    #[inline]
    pub(super) fn first_at_least(&self, v: f64) -> usize {
        let b = self.bucket(v);
        let (lo, hi) = (self.starts[b] as usize, self.starts[b + 1] as usize);
        lo + self.values[lo..hi].partition_point(|&x| x < v)
    }

    /// The first index whose value is > v (the length if none).
    #[inline]
    pub(super) fn first_above(&self, v: f64) -> usize {
        let b = self.bucket(v);
        let (lo, hi) = (self.starts[b] as usize, self.starts[b + 1] as usize);
        lo + self.values[lo..hi].partition_point(|&x| x <= v)
    }

    /// The indices whose values lie in [lo, hi].
    #[inline]
    fn within(&self, lo: f64, hi: f64) -> Range<usize> {
        self.first_at_least(lo)..self.first_above(hi)
    }
}

/// A segment of Δ* with its end points in (x, y) order, so that every piece sharing it
/// computes the same y at the same x.
#[derive(Clone, Copy)]
struct Segment {
    p: Point2<f64>,
    q: Point2<f64>,
    slope: f64,
}

impl Segment {
    fn new(a: Point2<f64>, b: Point2<f64>) -> Self {
        let (p, q) = if (a.x, a.y) <= (b.x, b.y) {
            (a, b)
        } else {
            (b, a)
        };
        Segment {
            p,
            q,
            slope: (q.y - p.y) / (q.x - p.x),
        }
    }

    /// y on the segment at abscissa x: exactly p.y and q.y at its ends (and on a vertical
    /// segment, p.y).
    #[inline(always)]
    fn y_at(&self, x: f64) -> f64 {
        // Selects rather than branches: the line's position along a segment is unpredictable.
        let inner = self.p.y + self.slope * (x - self.p.x);
        let y = if x >= self.q.x { self.q.y } else { inner };
        if x <= self.p.x { self.p.y } else { y }
    }
}

/// One piece (P_k, P_{k+1}, Z) of Δ* ready for evaluation along vertical lines.
///
/// Along a line its barycentric coordinates are affine, λ(y) = λ₀ + (y − y₀) w with
/// w = ∂λ/∂y, so with the quadratic form Q of its ordinates (s = λᵀQλ, the quadratic patch
/// of thesis (2.18)) s = λ₀ᵀQλ₀ + 2 (y − y₀) λ₀ᵀQw + (y − y₀)² wᵀQw. Taking y₀ on the
/// piece, (y − y₀) w is a change of λ inside it (each component at most 1 in size), which
/// keeps this as stable as de Casteljau's algorithm even on thin pieces, where a power
/// form about a fixed point is not.
struct Piece<V> {
    /// Its barycentric coordinates λ, about its corner Z (where λ = (0, 0, 1)).
    map: BaryMap,
    /// The quadratic form of its ordinates: s = λᵀQλ, stored [q00, q01, q02, q11, q12, q22].
    q: [V; 6],
    /// Qw and wᵀQw for w = ∂λ/∂y.
    qw: [V; 3],
    wqw: V,
    /// max |w_i|: about the inverse of the piece's height along a vertical line.
    steepness: f64,
}

/// A piece's values along one line x = const about a height y₀ on it:
/// s = a0 + d (a1 + a2 d) for d = y − y₀.
#[derive(Clone, Copy)]
struct LineQuadratic<V> {
    y0: f64,
    a0: V,
    a1: V,
    a2: V,
}

impl<V: Vector> LineQuadratic<V> {
    /// Zero everywhere (a placeholder for degenerate pieces).
    fn zero() -> Self {
        LineQuadratic {
            y0: 0.0,
            a0: V::zero(),
            a1: V::zero(),
            a2: V::zero(),
        }
    }

    /// The value at height y.
    #[inline(always)]
    fn at(&self, y: f64) -> V {
        let d = y - self.y0;
        self.a0 + (self.a1 + self.a2 * d) * d
    }

    /// The next piece up the line, entered at height y1 on the ray it shares with this one:
    /// the same value and slope there (the spline is C¹ across the ray), its own curvature
    /// `a2` (wᵀQw of that piece).
    #[inline(always)]
    fn continued(&self, y1: f64, a2: V) -> Self {
        let d = y1 - self.y0;
        LineQuadratic {
            y0: y1,
            a0: self.at(y1),
            a1: self.a1 + self.a2 * (2.0 * d),
            a2,
        }
    }
}

impl<V: Vector> Piece<V> {
    /// Piece `sub` of a triangle with net `net`, its corners `p` (the third Z); `None` if
    /// they are numerically collinear.
    fn new(p: [Point2<f64>; 3], net: &[V; NET_LEN], sub: usize) -> Option<Self> {
        let map = Triangle2::new(p[0], p[1], p[2])
            .bary_map()?
            .with_origin(p[2], [0.0, 0.0, 1.0]);
        let q = SUB_ORDINATES[sub].map(|k| net[k]);
        let w = map.dy();
        let qw = mul_q(&q, &w);
        let wqw = dot(&qw, &w);
        let steepness = w.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        Some(Piece {
            map,
            q,
            qw,
            wqw,
            steepness,
        })
    }

    /// λ at (x, y).
    #[inline(always)]
    fn bary(&self, x: f64, y: f64) -> [f64; 3] {
        self.map.apply(Point2::new(x, y))
    }

    /// The piece's values along the line at abscissa x, about the height y0 (on the piece).
    #[inline(always)]
    fn along(&self, x: f64, y0: f64) -> LineQuadratic<V> {
        let l = self.bary(x, y0);
        LineQuadratic {
            y0,
            a0: dot(&mul_q(&self.q, &l), &l),
            a1: dot(&self.qw, &l) * 2.0,
            a2: self.wqw,
        }
    }

    /// The value at (x, y).
    #[inline(always)]
    fn value(&self, x: f64, y: f64) -> V {
        self.along(x, y).a0
    }
}

/// Qλ for the symmetric Q stored as [q00, q01, q02, q11, q12, q22].
#[inline(always)]
fn mul_q<V: Vector>(q: &[V; 6], l: &[f64; 3]) -> [V; 3] {
    [
        q[0] * l[0] + q[1] * l[1] + q[2] * l[2],
        q[1] * l[0] + q[3] * l[1] + q[4] * l[2],
        q[2] * l[0] + q[4] * l[1] + q[5] * l[2],
    ]
}

/// Σ v_i l_i.
#[inline(always)]
fn dot<V: Vector>(v: &[V; 3], l: &[f64; 3]) -> V {
    v[0] * l[0] + v[1] * l[1] + v[2] * l[2]
}

/// The grid as the scan sees it: its two sorted axes.
struct Grid<'a> {
    xs: Axis<'a>,
    ys: Axis<'a>,
}

impl Grid<'_> {
    /// The grid points per triangle of `tri` within the domain's bounding box (triangles
    /// counted in proportion to the part of the box the grid spans).
    fn density_over(&self, tri: &Triangulation) -> f64 {
        let (lo, hi) = tri.bounds();
        let (xs, ys) = (self.xs.within(lo.x, hi.x), self.ys.within(lo.y, hi.y));
        if xs.is_empty() || ys.is_empty() {
            return 0.0;
        }
        let fraction = |axis: &Axis<'_>, r: Range<usize>, lo: f64, hi: f64| {
            let span = axis.values[r.end - 1] - axis.values[r.start];
            if hi > lo {
                (span / (hi - lo)).min(1.0)
            } else {
                1.0
            }
        };
        let (fx, fy) = (
            fraction(&self.xs, xs.clone(), lo.x, hi.x),
            fraction(&self.ys, ys.clone(), lo.y, hi.y),
        );
        let triangles = (tri.triangle_count() as f64 * fx * fy).max(1.0);
        (xs.len() * ys.len()) as f64 / triangles
    }
}

/// One triangle of Δ ready for scanning (reused from triangle to triangle).
struct Cell<'a, V> {
    spline: &'a PsSpline<V>,
    /// The triangle's index in Δ.
    t: usize,
    /// P = (V0, R0, V1, R1, V2, R2).
    p: [Point2<f64>; 6],
    z: Point2<f64>,
    /// The segments Z P_k.
    rays: [Segment; 6],
    /// The segments P_k P_{k+1} (on the edges of Δ).
    outer: [Segment; 6],
    /// Whether P_k P_{k+1} lies on the domain's boundary.
    boundary: [bool; 6],
    /// Whether any does.
    on_boundary: bool,
    /// The pieces (P_k, P_{k+1}, Z) (`None` for a piece that is numerically degenerate).
    pieces: [Option<Piece<V>>; 6],
}

impl<'a, V: Vector> Cell<'a, V> {
    fn new(spline: &'a PsSpline<V>) -> Self {
        let o = Point2::origin();
        Cell {
            spline,
            t: 0,
            p: [o; 6],
            z: o,
            rays: [Segment::new(o, o); 6],
            outer: [Segment::new(o, o); 6],
            boundary: [false; 6],
            on_boundary: false,
            pieces: [None, None, None, None, None, None],
        }
    }

    /// Makes this triangle `t`. Each edge point R is computed from the lower-numbered of the
    /// two triangles sharing its edge, so both get the same bits.
    fn load(&mut self, t: usize) {
        let basis = self.spline.basis();
        let (tri, refinement) = (basis.triangulation(), basis.refinement());
        let ids = tri.triangle(t);
        for c in 0..3 {
            // Edge c = (V_c, V_{c+1}) is opposite vertex c + 2.
            let neighbor = tri.neighbor(t, (c + 2) % 3);
            let r = match neighbor {
                Some(n) if n < t => {
                    let m = tri.triangle(n);
                    let k = (0..3)
                        .find(|&k| m[k] == ids[(c + 1) % 3] && m[(k + 1) % 3] == ids[c])
                        .unwrap_or(c);
                    refinement.edge_point(tri, n, k)
                }
                _ => refinement.edge_point(tri, t, c),
            };
            self.p[2 * c] = tri.vertex(ids[c]);
            self.p[2 * c + 1] = r;
            self.boundary[2 * c] = neighbor.is_none();
            self.boundary[2 * c + 1] = neighbor.is_none();
        }
        self.t = t;
        self.z = refinement.z(t);
        self.on_boundary = self.boundary.contains(&true);
        let net = self.spline.net(t);
        for k in 0..6 {
            self.rays[k] = Segment::new(self.z, self.p[k]);
            self.outer[k] = Segment::new(self.p[k], self.p[NEXT[k]]);
            self.pieces[k] = Piece::new([self.p[k], self.p[NEXT[k]], self.z], net, k);
        }
    }

    /// Piece k. `None` only when its corners are numerically collinear: the refinement
    /// rejects such pieces, but the edge point shared with the neighbour may differ from this
    /// triangle's own by rounding; its points are then left to the neighbouring pieces,
    /// which reach to within rounding of them.
    #[inline(always)]
    fn piece(&self, k: usize) -> Option<&Piece<V>> {
        self.pieces[k].as_ref()
    }
}

/// k + 1 mod 6.
const NEXT: [usize; 6] = [1, 2, 3, 4, 5, 0];

/// k mod 6 for k < 18.
const MOD6: [usize; 18] = [0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5];

impl<V: Vector> PsSpline<V> {
    /// [`PsSpline::values_on_grid`] for sorted finite axes by scan conversion; `None` when
    /// an axis is not sorted or not finite, or when the grid has fewer than `min_density`
    /// points per triangle in view (see [`SCAN_POINTS_PER_TRIANGLE`]).
    pub(super) fn scan_grid(
        &self,
        xs: &[f64],
        ys: &[f64],
        outside: V,
        min_density: f64,
    ) -> Option<Vec<V>> {
        let grid = Grid {
            xs: Axis::new(xs)?,
            ys: Axis::new(ys)?,
        };
        let (nx, ny) = (xs.len(), ys.len());
        let tri = self.basis().triangulation();
        if grid.density_over(tri) < min_density {
            return None;
        }
        // The lines each triangle's closure crosses; for a triangle on the domain's boundary
        // also those that pass within point location's tolerance outside it.
        let lines: Vec<Range<u32>> = (0..tri.triangle_count())
            .into_par_iter()
            .map(|t| {
                let v = tri.triangle(t).map(|i| tri.vertex(i));
                let (lo, hi) = (v[0].inf(&v[1]).inf(&v[2]), v[0].sup(&v[1]).sup(&v[2]));
                let reach = if (0..3).any(|k| tri.neighbor(t, k).is_none()) {
                    fringe_reach(lo, hi)
                } else {
                    0.0
                };
                let r = grid.xs.within(lo.x - reach, hi.x + reach);
                r.start as u32..r.end as u32
            })
            .collect();
        let per_band = nx
            .div_ceil(BANDS_PER_THREAD * rayon::current_num_threads())
            .max(MIN_LINES_PER_BAND);
        let bands = triangles_by_band(&lines, nx.div_ceil(per_band), per_band);
        let mut out = vec![outside; nx * ny];
        out.par_chunks_mut(per_band * ny)
            .zip(bands.par_iter())
            .enumerate()
            .for_each(|(b, (rows, triangles))| {
                let band = b * per_band..(b * per_band + per_band).min(nx);
                let mut cell = Cell::new(self);
                for &t in triangles {
                    let t = t as usize;
                    let span = lines[t].start as usize..lines[t].end as usize;
                    let own = span.start.max(band.start)..span.end.min(band.end);
                    cell.load(t);
                    for i in own {
                        let row = &mut rows[(i - band.start) * ny..(i - band.start + 1) * ny];
                        scan_line(&cell, &grid, i, row);
                    }
                }
            });
        Some(out)
    }
}

/// Groups the triangles by the bands of `per_band` lines their line ranges meet.
fn triangles_by_band(lines: &[Range<u32>], bands: usize, per_band: usize) -> Vec<Vec<u32>> {
    let mut out = vec![Vec::new(); bands];
    for (t, r) in lines.iter().enumerate() {
        if r.start < r.end {
            let (first, last) = (r.start as usize / per_band, (r.end as usize - 1) / per_band);
            for band in &mut out[first..=last] {
                band.push(t as u32);
            }
        }
    }
    out
}

/// The first element of the cyclic run of set bits in a 6-bit mask (neither empty nor
/// full): the set bit whose predecessor is clear.
#[inline(always)]
fn arc_start(mask: u32) -> usize {
    let rotated = ((mask << 1) | (mask >> 5)) & 0b11_1111; // bit k: bit k − 1 of mask
    (mask & !rotated).trailing_zeros() as usize
}

/// Fills the grid points of line `i` inside `cell`'s triangle.
///
/// The line passes upwards through pieces m = 0 … len, piece m up to the height top_m at
/// which it crosses the next ray (the exit from the triangle for the last). A grid point at
/// height y belongs to the first piece m with y ≤ top_m; with the running maxima T_m of the
/// tops (equal to them but for rounding) that m is the number of T_m below y, counted
/// without branches.
fn scan_line<V: Vector>(cell: &Cell<'_, V>, grid: &Grid<'_>, i: usize, row: &mut [V]) {
    let x = grid.xs.values[i];
    let right = x >= cell.z.x;
    let mut mask = 0u32;
    for (k, p) in cell.p.iter().enumerate() {
        let beyond = if right { p.x >= x } else { p.x <= x };
        mask |= (beyond as u32) << k;
    }
    if mask == 0 || mask == 0b11_1111 {
        // The line misses the triangle; on the boundary it may pass within the tolerance.
        if cell.on_boundary {
            fringe(cell, x, grid, row);
        }
        return;
    }
    let (k1, len) = (arc_start(mask), mask.count_ones() as usize);
    // The pieces in upward order, and the rays between them.
    // Right of Z upwards: pieces k1 − 1, k1, …, k1 + len − 1 and rays k1, …; left of Z:
    // pieces k1 + len − 1, …, k1 − 1 and rays k1 + len − 1, … (all mod 6).
    let piece = |m: usize| MOD6[if right { k1 + 5 + m } else { k1 + len + 5 - m }];
    let ray = |m: usize| MOD6[if right { k1 + m } else { k1 + len + 5 - m }];
    let (first, last) = (piece(0), piece(len));
    let entry = cell.outer[first].y_at(x);
    let exit = cell.outer[last].y_at(x);
    let ys = grid.ys.values;
    let hi = entry.max(exit);
    let (start, end) = (
        grid.ys.first_at_least(entry.min(exit)),
        grid.ys.first_above(hi),
    );
    if cell.on_boundary {
        extend(cell, x, ys, start, row, -1);
    }
    // T_m for m < len; the rest never lie below a point of the span.
    let mut tops = [f64::INFINITY; 5];
    let mut below = f64::NEG_INFINITY;
    for (m, top) in tops.iter_mut().enumerate().take(len) {
        below = below.max(cell.rays[ray(m)].y_at(x).min(hi));
        *top = below;
    }
    // Each piece about the height where the line enters it: its value and slope carried
    // from the piece below (C¹ across their ray) or, for the first piece, after a
    // degenerate one and beyond CARRY_RATIO, from its barycentric coordinates there.
    // Bit m of `present`: piece m has its quadratic in lines[m] (not degenerate).
    let mut lines = [LineQuadratic::zero(); 6];
    let mut present = 0u32;
    let mut bottom = entry.min(exit);
    let mut below: Option<LineQuadratic<V>> = None;
    // The steepest piece the carried value and slope passed through since the last fresh
    // set-up: a slope rounded in a piece of steepness S is off by about ε |Q| S, which a
    // piece of steepness s multiplies by S / s.
    let mut carried = 0.0f64;
    for (m, line) in lines.iter_mut().enumerate().take(len + 1) {
        below = cell.piece(piece(m)).map(|p| match below {
            Some(q) if carried <= CARRY_RATIO * p.steepness => {
                carried = carried.max(p.steepness);
                q.continued(bottom, p.wqw)
            }
            _ => {
                carried = p.steepness;
                p.along(x, bottom)
            }
        });
        if let Some(q) = below {
            *line = q;
            present |= 1 << m;
        }
        bottom = tops[m.min(4)];
    }
    for (o, &y) in row[start..end.max(start)].iter_mut().zip(&ys[start..]) {
        let m = tops.iter().map(|&t| (t < y) as usize).sum::<usize>();
        if present & (1 << m) != 0 {
            *o = lines[m].at(y);
        }
    }
    if cell.on_boundary {
        extend(cell, x, ys, end.max(start), row, 1);
    }
}

/// How far outside a boundary triangle with bounding box [lo, hi] point location may still
/// take a point: barycentric coordinates ≥ −[`INSIDE_TOLERANCE`] reach that times a height
/// outside an edge (at most the box's width plus height), with room for rounding.
fn fringe_reach(lo: Point2<f64>, hi: Point2<f64>) -> f64 {
    2.0 * INSIDE_TOLERANCE * ((hi.x - lo.x) + (hi.y - lo.y))
}

/// The points of a line that passes just outside a boundary triangle (x beyond its corners
/// by less than [`fringe_reach`]) and that point location takes as inside it: filled from the
/// boundary piece they are near, as [`extend`] does beyond a span.
fn fringe<V: Vector>(cell: &Cell<'_, V>, x: f64, grid: &Grid<'_>, row: &mut [V]) {
    let (lo, hi) = cell
        .p
        .iter()
        .fold((cell.p[0], cell.p[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let reach = fringe_reach(lo, hi);
    let ys = grid.ys.values;
    for j in grid.ys.within(lo.y - reach, hi.y + reach) {
        if let Some(piece) = near_boundary_piece(cell, x, ys[j]) {
            row[j] = piece.value(x, ys[j]);
        }
    }
}

/// The boundary piece of `cell` whose polynomial point location would use at (x, y) just
/// outside the triangle (see [`accepts_near_edge`]), if any.
fn near_boundary_piece<'c, V: Vector>(
    cell: &'c Cell<'_, V>,
    x: f64,
    y: f64,
) -> Option<&'c Piece<V>> {
    let p = Point2::new(x, y);
    let basis = cell.spline.basis();
    (0..6)
        .filter(|&k| cell.boundary[k])
        .find(|&k| {
            cell.piece(k).is_some_and(|piece| {
                let l = piece.bary(x, y);
                l[0] >= -INSIDE_TOLERANCE && l[1] >= -INSIDE_TOLERANCE
            }) && accepts_near_edge(basis, cell.t, k / 2, p)
        })
        .and_then(|k| cell.piece(k))
}

/// Points beyond the span of a triangle on the domain's boundary that point location would
/// still take (within its tolerance of a boundary edge), each filled from a boundary piece
/// it is near (so that the piece's polynomial is the one to extend there): from index `from`
/// downwards (`step` = −1, `from` excluded) or upwards (`step` = 1, `from` included). Along
/// a line that runs on a boundary edge, the piece the line enters by need not be that edge's.
fn extend<V: Vector>(
    cell: &Cell<'_, V>,
    x: f64,
    ys: &[f64],
    from: usize,
    row: &mut [V],
    step: isize,
) {
    let mut j = if step < 0 { from.wrapping_sub(1) } else { from };
    while j < ys.len() {
        let Some(piece) = near_boundary_piece(cell, x, ys[j]) else {
            return;
        };
        row[j] = piece.value(x, ys[j]);
        j = j.wrapping_add_signed(step);
    }
}

/// Whether point location takes `p` as inside triangle `t` (all its barycentric coordinates
/// ≥ −[`INSIDE_TOLERANCE`], as the evaluation walk computes them or as the triangulation's
/// exhaustive search, which decides near the boundary, does) while `p` lies within that
/// tolerance of the line of the triangle's edge `e` = (V_e, V_{e+1}).
fn accepts_near_edge(basis: &PsBasis, t: usize, e: usize, p: Point2<f64>) -> bool {
    let near = |b: [f64; 3]| {
        b.iter().all(|&b| b >= -INSIDE_TOLERANCE) && b[(e + 2) % 3] <= INSIDE_TOLERANCE
    };
    near(basis.triangle_bary(t, p)) || near(basis.triangulation().bary(t, p))
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use nalgebra::Point2;

    use super::Axis;
    use crate::ps::tests::{assert_grid_agrees, random_hermite, random_hermite_spline};
    use crate::ps::{PsBasis, PsRefinement, PsSpline, PsTriangleChoice};
    use crate::test_util::{rng, uniform};
    use crate::triangulation::Triangulation;

    /// The scan and point-by-point evaluation agree on every grid point: the same points
    /// outside, values to 1e-13. Returns how many points were inside and outside.
    fn assert_agrees(s: &PsSpline<f64>, xs: &[f64], ys: &[f64]) -> (usize, usize) {
        let grid = s.scan_grid(xs, ys, f64::NAN, 0.0).expect("sorted axes");
        assert_grid_agrees(s, xs, ys, &grid, f64::NAN)
    }

    /// Split points within `thin` (relative) of the bottom side make needle pieces along it
    /// with wide pieces above them. Carrying a needle's slope into the wide
    /// piece would multiply its rounding by their aspect ratio (1e-5 … 1e-9 here); the scan
    /// still agrees with `eval` to 1e-13.
    #[test]
    fn needle_pieces_under_wide_ones_agree_with_pointwise_evaluation() {
        for (seed, thin) in [(0u64, 1e-5), (1, 1e-7), (2, 1e-9)] {
            let mut r = rng(70 + seed);
            let mut pts = vec![
                Point2::new(0.0, 0.0),
                Point2::new(1.0, 0.0),
                Point2::new(0.0, 1.0),
                Point2::new(1.0, 1.0),
            ];
            pts.extend((1..8).map(|k| Point2::new(k as f64 / 8.0, 0.0)));
            pts.extend(
                (0..60)
                    .map(|_| Point2::new(uniform(&mut r, 0.01, 0.99), uniform(&mut r, 0.01, 0.99))),
            );
            let tri = Triangulation::delaunay(pts).unwrap();
            // The split point of each triangle on the bottom side (away from the corners,
            // where two such split points would pinch an edge point into a vertex) close to
            // that side, the others at the incentre.
            let on_bottom = |t: usize, i: usize| {
                let (a, b) = tri.edge_vertices(t, i);
                let inner = |v: usize| {
                    let p = tri.vertex(v);
                    p.y == 0.0 && p.x > 0.0 && p.x < 1.0
                };
                tri.neighbor(t, i).is_none() && inner(a) && inner(b)
            };
            let z: Vec<Point2<f64>> = (0..tri.triangle_count())
                .map(|t| {
                    let g = tri.triangle_geometry(t);
                    match (0..3).find(|&i| on_bottom(t, i)) {
                        Some(i) => {
                            let mut b = [(1.0 - thin) / 2.0; 3];
                            b[i] = thin;
                            g.point(b)
                        }
                        None => g.incenter(),
                    }
                })
                .collect();
            let refinement = PsRefinement::with_points(&tri, z).unwrap();
            let basis =
                PsBasis::with_refinement(tri, refinement, &PsTriangleChoice::Optimal).unwrap();
            let data = random_hermite(&mut r, basis.triangulation().vertex_count());
            let s = PsSpline::hermite(Arc::new(basis), &data).unwrap();
            let xs: Vec<f64> = (0..157).map(|k| k as f64 / 156.0).collect();
            let ys: Vec<f64> = (0..143).map(|k| (k as f64 / 142.0).powi(3)).collect();
            let (inside, _) = assert_agrees(&s, &xs, &ys);
            assert!(inside > 20_000, "{inside} points inside");
        }
    }

    /// Random Delaunay data, random sorted axes (repeated values included) reaching beyond
    /// the domain.
    #[test]
    fn scanned_values_agree_with_pointwise_evaluation() {
        for seed in 0..4 {
            let mut r = rng(40 + seed);
            let pts: Vec<Point2<f64>> = (0..300)
                .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
                .collect();
            let s = random_hermite_spline(Triangulation::delaunay(pts).unwrap(), seed);
            let mut xs: Vec<f64> = (0..70).map(|_| uniform(&mut r, -0.1, 1.1)).collect();
            let mut ys: Vec<f64> = (0..60).map(|_| uniform(&mut r, -0.1, 1.1)).collect();
            xs.sort_by(f64::total_cmp);
            ys.sort_by(f64::total_cmp);
            xs[10] = xs[11];
            ys[20] = ys[21];
            let (inside, outside) = assert_agrees(&s, &xs, &ys);
            assert!(
                inside > 2000 && outside > 1000,
                "{inside} in, {outside} out"
            );
        }
    }

    /// Grid lines a few units in the last place (or 1e-17) beyond the domain's leftmost and
    /// rightmost vertices: point location takes their points near the boundary as inside, and
    /// the scan, which visited only the lines within a triangle's corners, left them NaN (the
    /// Python package's `f(x, y, grid=True)` gave NaN where `f(X, Y)` gave values).
    #[test]
    fn lines_just_outside_the_domain_agree_with_pointwise_evaluation() {
        for seed in 0..4 {
            let mut r = rng(90 + seed);
            // An 11 × 11 grid of data (vertical boundary edges) or random points (a hull with
            // a leftmost and a rightmost vertex).
            let pts: Vec<Point2<f64>> = if seed % 2 == 0 {
                (0..121)
                    .map(|k| Point2::new((k % 11) as f64 / 10.0, (k / 11) as f64 / 10.0))
                    .collect()
            } else {
                (0..200)
                    .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
                    .collect()
            };
            let tri = Triangulation::delaunay(pts).unwrap();
            let (lo, hi) = tri.bounds();
            let s = random_hermite_spline(tri, seed);
            let mut xs = vec![lo.x - 1e-17, lo.x - 4e-16, lo.x, 0.5, hi.x, hi.x + 2e-16];
            xs.extend([lo.x.next_down(), hi.x.next_up(), lo.x - 1e-9, hi.x + 1e-9]);
            xs.sort_by(f64::total_cmp);
            let ys: Vec<f64> = (0..400).map(|k| -0.01 + k as f64 / 390.0).collect();
            let grid = s.scan_grid(&xs, &ys, f64::NAN, 0.0).expect("sorted axes");
            let (inside, _) = assert_grid_agrees(&s, &xs, &ys, &grid, f64::NAN);
            // The lines within rounding of the boundary have points inside.
            let within = |i: usize| (xs[i] - lo.x).abs() < 1e-15 || (xs[i] - hi.x).abs() < 1e-15;
            let near: usize = (0..xs.len())
                .filter(|&i| within(i))
                .map(|i| {
                    grid[i * ys.len()..(i + 1) * ys.len()]
                        .iter()
                        .filter(|v| !v.is_nan())
                        .count()
                })
                .sum();
            assert!(
                inside > 300 && (seed % 2 == 1 || near > 100),
                "{inside} inside, {near} near"
            );
        }
    }

    /// Vertices on a lattice and grid lines through them: points exactly at vertices, on
    /// vertical, horizontal and slanted edges of the domain's boundary and inside, are found
    /// as `eval` finds them.
    #[test]
    fn grid_points_on_vertices_and_edges() {
        for seed in 0..4 {
            let mut r = rng(60 + seed);
            // A trapezoid's corners (slanted sides) and lattice points inside.
            let mut pts = vec![
                Point2::new(0.0, 0.0),
                Point2::new(1.0, 0.0),
                Point2::new(0.75, 1.0),
                Point2::new(0.125, 1.0),
            ];
            while pts.len() < 120 {
                let p = Point2::new(
                    (uniform(&mut r, 0.0, 1.0) * 32.0).round() / 32.0,
                    (uniform(&mut r, 0.0, 1.0) * 32.0).round() / 32.0,
                );
                let inside = p.y > 0.0
                    && p.y < 1.0
                    && p.x > p.y / 8.0
                    && p.x < 1.0 - p.y / 4.0
                    && !pts.contains(&p);
                if inside {
                    pts.push(p);
                }
            }
            let s = random_hermite_spline(Triangulation::delaunay(pts).unwrap(), seed);
            let axis: Vec<f64> = (-4..=68).map(|k| k as f64 / 64.0).collect();
            let (inside, outside) = assert_agrees(&s, &axis, &axis);
            assert!(
                inside > 2500 && outside > 1000,
                "{inside} in, {outside} out"
            );
            // Also on a grid not aligned with anything.
            let fine: Vec<f64> = (0..200).map(|k| -0.01 + k as f64 / 197.0).collect();
            assert_agrees(&s, &fine, &fine[..150]);
        }
    }

    /// Grid points just outside a slanted boundary edge, within the tolerance of point
    /// location (1e-14, 3e-13 below it) and beyond it (1e-10): the scan takes the same ones
    /// as `eval`.
    #[test]
    fn points_within_the_tolerance_of_the_boundary() {
        let mut r = rng(70);
        let mut pts = vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.3),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ];
        pts.extend(
            (0..60).map(|_| Point2::new(uniform(&mut r, 0.1, 0.9), uniform(&mut r, 0.4, 0.9))),
        );
        let s = random_hermite_spline(Triangulation::delaunay(pts).unwrap(), 3);
        let xs: Vec<f64> = (0..=20).map(|k| k as f64 / 20.0).collect();
        let mut ys: Vec<f64> = (0..=40).map(|k| k as f64 / 40.0).collect();
        for &x in &xs {
            let edge = 0.3 * x;
            ys.extend([edge, edge - 1e-14, edge - 3e-13, edge - 1e-10, edge + 1e-14]);
        }
        ys.sort_by(f64::total_cmp);
        assert_agrees(&s, &xs, &ys);
        // The test means something: eval takes points below the edge line.
        let below = xs
            .iter()
            .flat_map(|&x| ys.iter().map(move |&y| Point2::new(x, y)))
            .filter(|p| p.y < 0.3 * p.x && s.eval(*p).is_ok())
            .count();
        assert!(below >= 20, "{below}");
    }

    /// A non-convex domain (an L of lattice triangles): nothing is filled in its notch.
    #[test]
    fn non_convex_domains() {
        let n = 8;
        let id = |i: usize, j: usize| j * (n + 1) + i;
        let vertices: Vec<Point2<f64>> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| Point2::new(i as f64 / 8.0, j as f64 / 8.0)))
            .collect();
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                if i >= n / 2 && j >= n / 2 {
                    continue; // the notch
                }
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let used: std::collections::BTreeSet<usize> = triangles.iter().flatten().copied().collect();
        // Drop the vertices of the notch, renumbering.
        let keep: Vec<usize> = (0..vertices.len()).filter(|v| used.contains(v)).collect();
        let mut new_id = vec![usize::MAX; vertices.len()];
        for (k, &v) in keep.iter().enumerate() {
            new_id[v] = k;
        }
        let tri = Triangulation::try_new(
            keep.iter().map(|&v| vertices[v]).collect(),
            triangles.iter().map(|t| t.map(|v| new_id[v])).collect(),
        )
        .unwrap();
        let s = random_hermite_spline(tri, 7);
        let axis: Vec<f64> = (-2..=42).map(|k| k as f64 / 40.0).collect();
        let (inside, outside) = assert_agrees(&s, &axis, &axis);
        assert!(inside > 1200 && outside > 500, "{inside} in, {outside} out");
    }

    /// Careless axes: ±1e308 (their extent overflows), grids far from the domain, all
    /// points equal, a subnormal spacing — the scan agrees with `eval` on each.
    #[test]
    fn extreme_axes() {
        let mut r = rng(95);
        let pts: Vec<Point2<f64>> = (0..50)
            .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
            .collect();
        let s = random_hermite_spline(Triangulation::delaunay(pts).unwrap(), 5);
        let axes: [Vec<f64>; 5] = [
            vec![-1e308, -1.0, 0.25, 0.5, 0.75, 1e308],
            vec![1e300, 2e300],
            vec![0.5; 7],
            vec![0.5, 0.5 + 5e-324, 0.5 + 1e-323],
            (0..40).map(|k| k as f64 / 39.0).collect(),
        ];
        for xs in &axes {
            for ys in &axes {
                assert_agrees(&s, xs, ys);
            }
        }
    }

    /// The bucket search equals a binary search on even, uneven and repeated axes.
    #[test]
    fn axis_search_matches_binary_search() {
        let mut r = rng(80);
        let axes: Vec<Vec<f64>> = vec![
            (0..100).map(|k| k as f64 * 0.01).collect(),
            (0..100).map(|k| 1.1f64.powi(k) - 50.0).collect(),
            vec![3.0; 10],
            vec![-1.0, -1.0, 0.0, 0.0, 0.0, 1e-300, 2.0, 2.0],
            vec![5.0],
        ];
        for values in &axes {
            let axis = Axis::new(values).unwrap();
            let lo = values[0] - 1.0;
            let hi = values[values.len() - 1] + 1.0;
            let probes = values
                .iter()
                .copied()
                .chain((0..500).map(|_| uniform(&mut r, lo, hi)));
            for v in probes {
                assert_eq!(axis.first_at_least(v), values.partition_point(|&x| x < v));
                assert_eq!(axis.first_above(v), values.partition_point(|&x| x <= v));
            }
        }
        assert!(Axis::new(&[1.0, 0.0]).is_none());
        assert!(Axis::new(&[0.0, f64::NAN]).is_none());
        assert!(Axis::new(&[0.0, f64::INFINITY]).is_none());
        assert!(Axis::new(&[]).is_none());
    }
}
