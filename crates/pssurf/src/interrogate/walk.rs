//! The derivative-free 4- and 8-point walks of seed 001 (section 3 a): from each point, step
//! to the neighbour at distance h (along the axes, or also the diagonals) where |f| is
//! smallest, never turning back; halve h until that |f| is within the tolerance.

use nalgebra::{Point2, Vector2};

use super::continuation::{Branch, End, Region, Sample};

/// How a walk proceeds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walk {
    /// The first step h in the parameter plane.
    pub step: f64,
    /// The accepted |f| (the seed's ε).
    pub tolerance: f64,
    /// The tolerance of the end solved on the region's edge (tight, so that ends of
    /// neighbouring pieces meet).
    pub edge_tolerance: f64,
    /// Eight neighbours (axes and diagonals) rather than four.
    pub eight: bool,
    /// The most points.
    pub max_points: usize,
}

/// Walks the zero set of `f` from `start` in the direction of `dir` inside `region`; the end
/// on the region's edge is solved as in the predictor–corrector.
pub(crate) fn walk(
    f: &mut dyn FnMut(Point2<f64>) -> Option<Sample>,
    region: &dyn Region,
    start: (Point2<f64>, Sample),
    dir: Vector2<f64>,
    w: Walk,
    seen: &mut dyn FnMut(Point2<f64>, Point2<f64>) -> bool,
) -> Branch {
    let mut out = Branch::empty();
    let directions = neighbours(w.eight);
    let (origin, mut uv) = (start.0, start.0);
    let mut heading = dir;
    let mut travelled = 0.0;
    while out.uvs.len() < w.max_points {
        let mut h = w.step;
        let best = loop {
            let best = directions
                .iter()
                .filter(|d| d.dot(&heading) > -1e-9)
                .filter_map(|d| {
                    let p = uv + d * h;
                    f(p).map(|s| (s.f.abs(), p, s))
                })
                .min_by(|a, b| a.0.total_cmp(&b.0));
            match best {
                Some(b) if b.0 <= w.tolerance => break Some(b),
                _ if h > w.step * 1e-6 => h *= 0.5,
                _ => break None,
            }
        };
        let Some((_, next, sample)) = best else {
            out.end = End::Stuck;
            return out;
        };
        if !region.contains(next) {
            let mut value = |p: Point2<f64>| f(p);
            for exit in region.exits(uv, next) {
                // The walk's points are only within w.tolerance of the curve, so where the
                // curve meets the edge at a shallow angle it crosses it well beyond a chord
                // of where the step does: as far along the edge as f takes to change by
                // the tolerance (twice, for the crossing's own |f| ≤ tolerance).
                let edge = exit.to - exit.from;
                let rate = sample.grad.dot(&edge).abs() / edge.norm();
                let slack = (2.0 * w.tolerance / rate).min(edge.norm());
                let root = super::continuation::edge_root(
                    &mut value,
                    exit,
                    uv,
                    next,
                    w.edge_tolerance,
                    slack,
                );
                if let Some((e_uv, e_s)) = root {
                    out.uvs.push(e_uv);
                    out.points.push(e_s.point);
                    seen(uv, e_uv);
                    out.end = End::Edge(exit.edge);
                    return out;
                }
            }
            out.end = End::Stuck;
            return out;
        }
        travelled += (next - uv).norm();
        if out.uvs.len() >= 3 && (next - origin).norm() <= h && travelled > 3.0 * h {
            out.uvs.push(origin);
            out.points.push(start.1.point);
            out.end = End::Closed;
            return out;
        }
        out.uvs.push(next);
        out.points.push(sample.point);
        seen(uv, next);
        // The heading is the chord over the last four steps: a step must go forward along
        // it, so the walk cannot dither back and forth.
        let back = out.uvs.len().saturating_sub(5);
        let from = if out.uvs.len() >= 5 {
            out.uvs[back]
        } else {
            origin
        };
        heading = (next - from).try_normalize(0.0).unwrap_or(heading);
        uv = next;
    }
    out
}

/// The unit steps to the neighbours.
fn neighbours(eight: bool) -> Vec<Vector2<f64>> {
    let mut d = vec![
        Vector2::new(1.0, 0.0),
        Vector2::new(-1.0, 0.0),
        Vector2::new(0.0, 1.0),
        Vector2::new(0.0, -1.0),
    ];
    if eight {
        let r = std::f64::consts::FRAC_1_SQRT_2;
        d.extend([
            Vector2::new(r, r),
            Vector2::new(-r, r),
            Vector2::new(r, -r),
            Vector2::new(-r, -r),
        ]);
    }
    d
}
