//! A validated hole boundary: 3 to 6 curves joined end to end into a loop, run so that the
//! filling patch's normal agrees with the given normals (counter-clockwise seen from them).

use nalgebra::Vector3;

use super::HoleError;
use super::curves::{BoundaryCurve, Reversed};

/// A boundary curve as the hole filler holds it.
pub type DynCurve = Box<dyn BoundaryCurve + Send + Sync>;

/// Samples per curve for the checks (and for the model size).
const CHECK_SAMPLES: usize = 32;
/// Ends closer than this fraction of the model size join.
pub const JOIN_TOLERANCE: f64 = 1e-6;
/// |γ̂ × n̂| below this: the normal lies along the tangent (sin of 0.06°).
const PARALLEL: f64 = 1e-3;
/// |γ̂_in × γ̂_out| below this at a joint: no corner (sin of 0.06°).
const NO_CORNER: f64 = 1e-3;

/// A corner whose surrounding normals disagree with its tangent plane by more than this
/// (degrees) is singular: G1 is not asked for on the boundary edges touching it.
pub const SINGULAR_CORNER_DEGREES: f64 = 1.0;

/// The loop of boundary curves of a hole, in order, each oriented to run into the next.
pub struct HoleBoundary {
    curves: Vec<DynCurve>,
    /// The number (1-based, as given) of each curve, for messages and reports.
    numbers: Vec<usize>,
    size: f64,
    /// Per corner k (where curve k starts): the angle between the surrounding normals next
    /// to it and the normal of the plane of the two tangents there.
    corner_mismatch: Vec<f64>,
}

/// The unit vector of v, or `None` when v is zero or not finite.
pub(crate) fn unit(v: Vector3<f64>) -> Option<Vector3<f64>> {
    let n = v.norm();
    (n.is_finite() && n > 0.0).then(|| v / n)
}

/// The angle between two vectors in degrees, accurate also near 0 and 180°
/// (atan2(|a × b|, a · b)).
pub fn angle_degrees(a: Vector3<f64>, b: Vector3<f64>) -> f64 {
    a.cross(&b).norm().atan2(a.dot(&b)).to_degrees()
}

impl HoleBoundary {
    /// Checks and orders `curves` (numbered 1, 2, … in messages, in the order given): every
    /// value finite, tangents non-zero, normals not along the tangents away from the ends,
    /// the curves joined end to end into one loop (each may be reversed), a real corner at
    /// every joint, and normals that agree in orientation. The loop is run counter-clockwise
    /// as seen from the normals (reversed if needed).
    pub fn new(curves: Vec<DynCurve>) -> Result<Self, HoleError> {
        let count = curves.len();
        if !(3..=6).contains(&count) {
            return Err(HoleError::Sides(count));
        }
        let size = model_size(&curves)?;
        for (k, c) in curves.iter().enumerate() {
            check_curve(c.as_ref(), k + 1, size)?;
        }
        let (mut curves, mut numbers) = chain(curves, size)?;
        let orientation = corner_orientation(&curves, &numbers)?;
        if orientation < 0.0 {
            curves.reverse();
            numbers.reverse();
            curves = curves
                .into_iter()
                .map(|c| Box::new(Reversed(c)) as DynCurve)
                .collect();
        }
        let corner_mismatch = (0..curves.len())
            .map(|k| corner_mismatch(&curves, k))
            .collect();
        Ok(HoleBoundary {
            curves,
            numbers,
            size,
            corner_mismatch,
        })
    }

    /// The curves in loop order.
    pub fn curves(&self) -> &[DynCurve] {
        &self.curves
    }

    /// The number of curves.
    pub fn len(&self) -> usize {
        self.curves.len()
    }

    /// Never true (a boundary has 3 to 6 curves); for the `len` convention.
    pub fn is_empty(&self) -> bool {
        self.curves.is_empty()
    }

    /// The number (1-based, as given by the caller) of the curve at loop position `k`.
    pub fn number(&self, k: usize) -> usize {
        self.numbers[k]
    }

    /// At corner k (where curve k starts): the largest angle, in degrees, between the given
    /// normals next to it and the normal of the plane of the two curves' tangents, which is
    /// the patch's tangent plane there. Near 0 when the data are consistent; large at a
    /// singular point of the surrounding surface (the apex of a cone), where no patch can
    /// meet the normals of both sides.
    pub fn corner_mismatch(&self, k: usize) -> f64 {
        self.corner_mismatch[k]
    }

    /// Whether corner k is singular: its [`Self::corner_mismatch`] exceeds
    /// [`SINGULAR_CORNER_DEGREES`].
    pub fn is_singular_corner(&self, k: usize) -> bool {
        self.corner_mismatch[k] > SINGULAR_CORNER_DEGREES
    }

    /// The model size: the diagonal of the bounding box of the curves.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The unit tangent of curve `k` at t.
    pub fn unit_tangent(&self, k: usize, t: f64) -> Vector3<f64> {
        unit(self.curves[k].tangent(t)).unwrap_or(Vector3::repeat(f64::NAN))
    }

    /// The unit normal of curve `k` at t.
    pub fn unit_normal(&self, k: usize, t: f64) -> Vector3<f64> {
        unit(self.curves[k].normal(t)).unwrap_or(Vector3::repeat(f64::NAN))
    }

    /// The point of curve `k` closest to `x`, searched from parameter `t0` (the parameter
    /// where x is expected): Gauss–Newton steps τ ← τ − (c(τ) − x)·c′(τ)/|c′(τ)|², clamped to
    /// [0, 1]. Returns τ and the distance. Deviations are measured this way, geometrically:
    /// the patch's edge curve is a different parametrisation of nearly the same curve.
    pub fn closest(&self, k: usize, x: Vector3<f64>, t0: f64) -> (f64, f64) {
        let c = &self.curves[k];
        let mut t = t0.clamp(0.0, 1.0);
        for _ in 0..12 {
            let d = c.tangent(t);
            let step = (c.point(t) - x).dot(&d) / d.norm_squared();
            if !step.is_finite() {
                break;
            }
            let next = (t - step).clamp(0.0, 1.0);
            let done = (next - t).abs() < 1e-15;
            t = next;
            if done {
                break;
            }
        }
        let d = (c.point(t) - x).norm();
        // Never report more than the distance at the expected parameter.
        let d0 = (c.point(t0) - x).norm();
        if d <= d0 { (t, d) } else { (t0, d0) }
    }

    /// The unit cross-boundary tangent δ = γ × n of curve `k` at t (thesis 5.1), pointing
    /// out of the hole.
    pub fn cross_tangent(&self, k: usize, t: f64) -> Vector3<f64> {
        let g = self.unit_tangent(k, t);
        unit(g.cross(&self.unit_normal(k, t))).unwrap_or(Vector3::repeat(f64::NAN))
    }
}

/// See [`HoleBoundary::corner_mismatch`]; the normals are taken just inside the curves, where
/// they exist also when the corner itself is singular.
fn corner_mismatch(curves: &[DynCurve], k: usize) -> f64 {
    let n = curves.len();
    let (cin, cout) = (&curves[(k + n - 1) % n], &curves[k]);
    let plane = cin.tangent(1.0).cross(&cout.tangent(0.0));
    [cin.normal(1.0 - 1e-6), cout.normal(1e-6)]
        .into_iter()
        .map(|m| {
            let a = angle_degrees(m, plane);
            // Normals are lines here: the orientation was checked already.
            if a.is_finite() { a.min(180.0 - a) } else { 0.0 }
        })
        .fold(0.0, f64::max)
}

/// The diagonal of the bounding box of sample points of all curves.
fn model_size(curves: &[DynCurve]) -> Result<f64, HoleError> {
    let mut lo = Vector3::repeat(f64::INFINITY);
    let mut hi = Vector3::repeat(f64::NEG_INFINITY);
    for (k, c) in curves.iter().enumerate() {
        for i in 0..=CHECK_SAMPLES {
            let t = i as f64 / CHECK_SAMPLES as f64;
            let p = c.point(t);
            if !p
                .iter()
                .all(|x| x.is_finite() && x.abs() <= crate::limits::MAX_COORDINATE)
            {
                return Err(HoleError::NotFinite {
                    curve: k + 1,
                    t,
                    what: "point",
                });
            }
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        }
    }
    let size = (hi - lo).norm();
    if size > 0.0 {
        Ok(size)
    } else {
        Err(HoleError::ZeroSize)
    }
}

/// Tangents finite and non-zero everywhere; normals finite, non-zero and off the tangent
/// away from the ends.
fn check_curve(c: &dyn BoundaryCurve, number: usize, size: f64) -> Result<(), HoleError> {
    for i in 0..=CHECK_SAMPLES {
        let t = i as f64 / CHECK_SAMPLES as f64;
        let d = c.tangent(t);
        if !d.iter().all(|x| x.is_finite()) {
            return Err(HoleError::NotFinite {
                curve: number,
                t,
                what: "tangent",
            });
        }
        // A tangent this short against the model size is a stationary point.
        if d.norm() <= 1e-12 * size {
            return Err(HoleError::ZeroTangent { curve: number, t });
        }
        if i == 0 || i == CHECK_SAMPLES {
            continue;
        }
        let n = c.normal(t);
        if !n.iter().all(|x| x.is_finite()) || n.norm() == 0.0 {
            return Err(HoleError::NotFinite {
                curve: number,
                t,
                what: "normal",
            });
        }
        if (d / d.norm()).cross(&(n / n.norm())).norm() < PARALLEL {
            return Err(HoleError::NormalAlongTangent { curve: number, t });
        }
    }
    Ok(())
}

/// Orders and orients the curves so that each ends where the next starts; returns them with
/// their 1-based numbers.
fn chain(curves: Vec<DynCurve>, size: f64) -> Result<(Vec<DynCurve>, Vec<usize>), HoleError> {
    let tolerance = JOIN_TOLERANCE * size;
    let mut left: Vec<Option<DynCurve>> = curves.into_iter().map(Some).collect();
    let first = left[0].take().expect("at least three curves");
    let start = first.point(0.0);
    let mut end = first.point(1.0);
    let mut out = vec![first];
    let mut numbers = vec![1];
    while out.len() < left.len() {
        let mut best: Option<(usize, bool, f64)> = None;
        for (k, c) in left.iter().enumerate() {
            let Some(c) = c else { continue };
            for (reversed, p) in [(false, c.point(0.0)), (true, c.point(1.0))] {
                let gap = (p - end).norm();
                if best.is_none_or(|b| gap < b.2) {
                    best = Some((k, reversed, gap));
                }
            }
        }
        let (k, reversed, gap) = best.expect("a curve is left");
        if gap > tolerance {
            return Err(HoleError::DoNotJoin {
                curve: *numbers.last().expect("one curve"),
                gap,
                tolerance,
            });
        }
        let c = left[k].take().expect("unused");
        let c: DynCurve = if reversed { Box::new(Reversed(c)) } else { c };
        end = c.point(1.0);
        out.push(c);
        numbers.push(k + 1);
    }
    let gap = (end - start).norm();
    if gap > tolerance {
        return Err(HoleError::DoNotJoin {
            curve: *numbers.last().expect("curves"),
            gap,
            tolerance,
        });
    }
    Ok((out, numbers))
}

/// Σ over the joints of sign((γ_in × γ_out) · (n_in + n_out)): +n when the loop runs
/// counter-clockwise seen from the normals. Errors when a joint has no corner or the joints
/// disagree.
fn corner_orientation(curves: &[DynCurve], numbers: &[usize]) -> Result<f64, HoleError> {
    let n = curves.len();
    let mut signs = Vec::with_capacity(n);
    for k in 0..n {
        let (cin, cout) = (&curves[(k + n - 1) % n], &curves[k]);
        let g_in = unit(cin.tangent(1.0)).expect("checked tangents");
        let g_out = unit(cout.tangent(0.0)).expect("checked tangents");
        let c = g_in.cross(&g_out);
        let pair = (numbers[(k + n - 1) % n], numbers[k]);
        if c.norm() < NO_CORNER {
            return Err(HoleError::NoCorner { curves: pair });
        }
        // The normals at the very ends may be undefined; just inside them they are not.
        let normal = unit(cin.normal(1.0 - 1e-6)).unwrap_or_default()
            + unit(cout.normal(1e-6)).unwrap_or_default();
        let s = c.dot(&normal);
        if s == 0.0 || !s.is_finite() {
            return Err(HoleError::Orientation { curves: pair });
        }
        signs.push(s.signum());
    }
    if signs.iter().all(|&s| s == signs[0]) {
        Ok(signs[0])
    } else {
        let k = signs
            .iter()
            .position(|&s| s != signs[0])
            .expect("a different sign");
        Err(HoleError::Orientation {
            curves: (numbers[(k + n - 1) % n], numbers[k]),
        })
    }
}
