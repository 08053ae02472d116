//! The adaptive integrator behind lines of curvature, asymptotic lines and geodesics: the
//! Dormand–Prince 5(4) Runge–Kutta pair with its embedded error estimate and the usual step
//! control h ← h · 0.9 (tol/err)^(1/5), clamped to [0.2, 5].
//!
//! Two things are particular to curves on piecewise surfaces:
//! - the slope may be undefined (the point left the domain, or reached an umbilic, a
//!   parabolic line or a singular point): the step is shrunk, and when even the smallest
//!   step fails the curve ends there, with the reason;
//! - second derivatives jump across piece boundaries (the surfaces are C¹), so near a boundary
//!   the error estimate cannot be met by shrinking: a step of the smallest size is accepted
//!   whatever its estimate, which crosses the jump with an error of the order of that size.
//!
//! Line fields (principal and asymptotic directions) have no sign; the flow orients every
//! slope like a reference (the slope at the step's start), so a curve never reverses.

use nalgebra::SVector;

use crate::surface::Cursor;

/// A state of the integrated curve (parameters, and for geodesics their derivatives).
pub(crate) type State<const N: usize> = SVector<f64, N>;

/// Why a slope is undefined at a state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Halt {
    /// The parameters lie outside the domain.
    Outside,
    /// The point is an umbilic (principal directions undefined).
    Umbilic,
    /// The point is not hyperbolic (asymptotic directions undefined).
    NotHyperbolic,
    /// The surface is singular there.
    Singular,
}

/// The right-hand side y' = f(y) of a curve's differential equation.
pub(crate) trait Flow<const N: usize> {
    /// The slope at `y`, oriented like `reference` where the field has no sign.
    fn slope(
        &self,
        y: &State<N>,
        reference: &State<N>,
        cursor: &mut Cursor,
    ) -> Result<State<N>, Halt>;

    /// Projects an accepted state back onto an invariant of the flow (a geodesic's unit
    /// speed); the identity by default.
    fn project(&self, _y: &mut State<N>, _cursor: &mut Cursor) {}
}

/// The integrator's tolerances (in the units of the state).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Integrator {
    /// The largest error estimate (max norm) of an accepted step.
    pub tolerance: f64,
    /// The smallest step: a step this small is accepted whatever its error estimate.
    pub min_step: f64,
    /// The largest step.
    pub max_step: f64,
}

/// One accepted step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Advance<const N: usize> {
    /// The new state.
    pub y: State<N>,
    /// The slope there (oriented like the step).
    pub slope: State<N>,
    /// The step taken.
    pub taken: f64,
    /// The step proposed for next time.
    pub next: f64,
}

// The Dormand–Prince tableau.
const A: [[f64; 6]; 6] = [
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// The fifth-order weights minus the fourth-order ones (the error estimate).
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

impl Integrator {
    /// Takes one accepted step from `y` (slope `k1` there) starting with the trial size `h`;
    /// the reason why not if even the smallest step fails.
    pub fn advance<const N: usize, F: Flow<N>>(
        &self,
        flow: &F,
        y: &State<N>,
        k1: &State<N>,
        mut h: f64,
        cursor: &mut Cursor,
    ) -> Result<Advance<N>, Halt> {
        h = h.clamp(self.min_step, self.max_step);
        loop {
            match self.attempt(flow, y, k1, h, cursor) {
                Ok((mut y_new, slope, error)) => {
                    let smallest = h <= self.min_step;
                    if error <= self.tolerance || smallest {
                        flow.project(&mut y_new, cursor);
                        let grow = if error > 0.0 {
                            (0.9 * (self.tolerance / error).powf(0.2)).clamp(0.2, 5.0)
                        } else {
                            5.0
                        };
                        return Ok(Advance {
                            y: y_new,
                            slope,
                            taken: h,
                            next: (h * grow).clamp(self.min_step, self.max_step),
                        });
                    }
                    let shrink = (0.9 * (self.tolerance / error).powf(0.2)).clamp(0.1, 0.5);
                    h = (h * shrink).max(self.min_step);
                }
                Err(halt) if h <= self.min_step => return Err(halt),
                Err(_) => h = (h * 0.25).max(self.min_step),
            }
        }
    }

    /// One Dormand–Prince step of size `h`: the new state, its slope and the error estimate.
    fn attempt<const N: usize, F: Flow<N>>(
        &self,
        flow: &F,
        y: &State<N>,
        k1: &State<N>,
        h: f64,
        cursor: &mut Cursor,
    ) -> Result<(State<N>, State<N>, f64), Halt> {
        let mut k = [State::<N>::zeros(); 7];
        k[0] = *k1;
        let mut y_new = *y;
        for (stage, row) in A.iter().enumerate() {
            let mut ys = *y;
            for (j, a) in row.iter().enumerate().take(stage + 1) {
                ys += k[j] * (h * a);
            }
            k[stage + 1] = flow.slope(&ys, k1, cursor)?;
            if stage == 5 {
                y_new = ys;
            }
        }
        let mut err = State::<N>::zeros();
        for (kj, e) in k.iter().zip(E) {
            err += kj * (h * e);
        }
        Ok((y_new, k[6], err.amax()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = (−y₂, y₁): the unit circle, exactly cos and sin.
    struct Rotation;

    impl Flow<2> for Rotation {
        fn slope(&self, y: &State<2>, _: &State<2>, _: &mut Cursor) -> Result<State<2>, Halt> {
            Ok(State::<2>::new(-y[1], y[0]))
        }
    }

    /// y' = 1 on y < 1, undefined beyond.
    struct Wall;

    impl Flow<1> for Wall {
        fn slope(&self, y: &State<1>, _: &State<1>, _: &mut Cursor) -> Result<State<1>, Halt> {
            if y[0] < 1.0 {
                Ok(State::<1>::new(1.0))
            } else {
                Err(Halt::Outside)
            }
        }
    }

    #[test]
    fn integrates_a_rotation_to_its_tolerance_with_few_steps() {
        let ode = Integrator {
            tolerance: 1e-12,
            min_step: 1e-9,
            max_step: 1.0,
        };
        let mut y = State::<2>::new(1.0, 0.0);
        let mut k = Rotation.slope(&y, &y, &mut Cursor::default()).unwrap();
        let (mut t, mut h, mut steps) = (0.0_f64, 0.1_f64, 0);
        while t < std::f64::consts::TAU - 1e-15 {
            h = h.min(std::f64::consts::TAU - t);
            let a = ode
                .advance(&Rotation, &y, &k, h, &mut Cursor::default())
                .unwrap();
            (y, k, t, h) = (a.y, a.slope, t + a.taken, a.next);
            steps += 1;
        }
        assert!((y - State::<2>::new(1.0, 0.0)).norm() < 1e-10, "{y}");
        assert!(steps < 600, "{steps} steps");
    }

    #[test]
    fn stops_within_the_smallest_step_of_where_the_slope_ends() {
        let ode = Integrator {
            tolerance: 1e-10,
            min_step: 1e-7,
            max_step: 0.3,
        };
        let mut y = State::<1>::new(0.0);
        let k = State::<1>::new(1.0);
        let mut h = 0.3;
        let halt = loop {
            match ode.advance(&Wall, &y, &k, h, &mut Cursor::default()) {
                Ok(a) => (y, h) = (a.y, a.next),
                Err(halt) => break halt,
            }
        };
        assert_eq!(halt, Halt::Outside);
        assert!(y[0] < 1.0 && y[0] > 1.0 - 2e-7, "{}", y[0]);
    }
}
