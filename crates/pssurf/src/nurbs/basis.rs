//! Knot vectors and B-spline basis functions with their first and second derivatives,
//! without allocation (degrees up to [`MAX_DEGREE`]).
//!
//! The nonzero basis functions of degree p on the knot span [U_i, U_{i+1}) are
//! N_{i−p,p} … N_{i,p}, computed by the triangular scheme of Cox and de Boor (Piegl and
//! Tiller, *The NURBS Book*, A2.2). Derivatives come from the degree-(p−1) and (p−2) values of
//! the same scheme by N′_{k,p} = p (N_{k,p−1}/(U_{k+p} − U_k) − N_{k+1,p−1}/(U_{k+p+1} − U_{k+1}))
//! (eq. 2.7), applied twice for N″; a quotient with a zero-length denominator is zero.

use thiserror::Error;

/// The largest degree supported (IGES files from CAD systems use at most 9 or so).
pub const MAX_DEGREE: usize = 15;

/// Why a knot vector (with its degree and number of control points) is refused.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum KnotError {
    /// The degree is 0 or larger than [`MAX_DEGREE`].
    #[error("degree {0} is not supported (1 to {MAX_DEGREE})")]
    Degree(usize),
    /// Too few control points for the degree.
    #[error("{count} control points are too few for degree {degree} (at least {})", degree + 1)]
    TooFewPoints {
        /// The control points.
        count: usize,
        /// The degree.
        degree: usize,
    },
    /// The number of knots is not control points + degree + 1.
    #[error("{found} knots for {count} control points of degree {degree}: expected {}", count + degree + 1)]
    Length {
        /// The knots given.
        found: usize,
        /// The control points.
        count: usize,
        /// The degree.
        degree: usize,
    },
    /// A knot is not finite.
    #[error("knot {0} is not a finite number")]
    NotFinite(usize),
    /// A knot is smaller than the one before.
    #[error("knot {0} is smaller than the knot before it")]
    Decreasing(usize),
    /// An interior knot is repeated more than the degree (the curve would break there).
    #[error(
        "knot value {value} is repeated {times} times inside the domain (at most the degree, {degree})"
    )]
    Multiplicity {
        /// The knot value.
        value: f64,
        /// Its multiplicity.
        times: usize,
        /// The degree.
        degree: usize,
    },
    /// The domain [U_p, U_n] is empty.
    #[error("the parameter domain [U_p, U_n] = [{0}, {1}] is empty")]
    EmptyDomain(f64, f64),
}

/// A validated knot vector for `count` control points of degree `degree`.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    degree: usize,
    knots: Vec<f64>,
    /// The spans i (p ≤ i < n) with U_i < U_{i+1}: the pieces.
    spans: Vec<usize>,
    /// 1/(U_m − U_{m−j}) at `j · len + m` (0 where the difference is 0 or m < j): the
    /// evaluation then divides nowhere.
    inverse: Vec<f64>,
}

impl KnotVector {
    /// Checks and wraps `knots` for `count` control points of degree `degree`.
    pub fn try_new(degree: usize, knots: Vec<f64>, count: usize) -> Result<Self, KnotError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(KnotError::Degree(degree));
        }
        if count < degree + 1 {
            return Err(KnotError::TooFewPoints { count, degree });
        }
        if knots.len() != count + degree + 1 {
            return Err(KnotError::Length {
                found: knots.len(),
                count,
                degree,
            });
        }
        if let Some(i) = knots.iter().position(|k| !k.is_finite()) {
            return Err(KnotError::NotFinite(i));
        }
        if let Some(i) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
            return Err(KnotError::Decreasing(i));
        }
        let (lo, hi) = (knots[degree], knots[count]);
        if lo >= hi {
            return Err(KnotError::EmptyDomain(lo, hi));
        }
        // Multiplicity of knot values strictly inside the domain.
        let mut i = 0;
        while i < knots.len() {
            let j = (i..knots.len())
                .find(|&j| knots[j] != knots[i])
                .unwrap_or(knots.len());
            if knots[i] > lo && knots[i] < hi && j - i > degree {
                return Err(KnotError::Multiplicity {
                    value: knots[i],
                    times: j - i,
                    degree,
                });
            }
            i = j;
        }
        let spans = (degree..count)
            .filter(|&i| knots[i] < knots[i + 1])
            .collect();
        let len = knots.len();
        let inverse = (0..=degree)
            .flat_map(|j| (0..len).map(move |m| (j, m)))
            .map(|(j, m)| {
                let d = if m >= j { knots[m] - knots[m - j] } else { 0.0 };
                if d > 0.0 { 1.0 / d } else { 0.0 }
            })
            .collect();
        Ok(KnotVector {
            degree,
            knots,
            spans,
            inverse,
        })
    }

    /// The degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots U_0 … U_{n+p}.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The number of control points n.
    pub fn count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain [U_p, U_n].
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.count()])
    }

    /// The non-empty spans i (U_i < U_{i+1}), one per piece, increasing.
    pub fn spans(&self) -> &[usize] {
        &self.spans
    }

    /// The rank (piece index along this direction) of the span containing `t`, which must be
    /// in the domain; the last span contains the domain's end.
    pub fn span_rank(&self, t: f64) -> usize {
        // The first span whose end exceeds t, clamped to the last.
        let r = self.spans.partition_point(|&i| self.knots[i + 1] <= t);
        r.min(self.spans.len() - 1)
    }

    /// The basis functions at `t` on span `i` and their first and second derivatives.
    #[inline]
    pub fn basis(&self, i: usize, t: f64) -> BasisDerivs {
        BasisDerivs {
            d: self.basis_n::<{ MAX_DEGREE + 1 }>(i, t),
        }
    }

    /// N, N′ and N″ on span `i` at `t` in arrays of `N` ≥ p + 1 entries (small arrays for
    /// low degrees keep the hot loops in registers).
    #[inline]
    pub(crate) fn basis_n<const N: usize>(&self, i: usize, t: f64) -> [[f64; N]; 3] {
        self.basis_of_degree::<N>(self.degree, i, t)
    }

    /// [`KnotVector::basis_n`] with the degree `p` (= this vector's) given by the caller, so
    /// that a constant degree unrolls the loops.
    #[inline(always)]
    pub(crate) fn basis_of_degree<const N: usize>(
        &self,
        p: usize,
        i: usize,
        t: f64,
    ) -> [[f64; N]; 3] {
        debug_assert!(p == self.degree && p < N);
        let [n, lower, lower2] = self.levels::<N>(p, i, t);
        let d1 = self.derive::<N>(p, i, &lower);
        let d2 = if p >= 2 {
            // The derivatives of degree p − 1 on the same span, then once more.
            let d1_lower = self.derive::<N>(p - 1, i, &lower2);
            self.derive::<N>(p, i, &d1_lower)
        } else {
            [0.0; N]
        };
        [n, d1, d2]
    }

    /// The third derivatives N‴ of the p + 1 nonzero functions on span `i` at `t` (zero for
    /// p < 3): the triangular scheme down to degree p − 3, then eq. 2.7 three times. A cold
    /// path (torsion of curves); the hot loops use [`KnotVector::basis`].
    pub fn third_derivatives(&self, i: usize, t: f64) -> [f64; MAX_DEGREE + 1] {
        const N: usize = MAX_DEGREE + 1;
        let p = self.degree;
        if p < 3 {
            return [0.0; N];
        }
        let mut n = [0.0; N];
        let mut left = [0.0; N];
        let mut right = [0.0; N];
        n[0] = 1.0;
        // The values of degree p − 3.
        for j in 1..=p - 3 {
            self.raise(j, i, t, &mut n, &mut left, &mut right);
        }
        let d1 = self.derive::<N>(p - 2, i, &n);
        let d2 = self.derive::<N>(p - 1, i, &d1);
        self.derive::<N>(p, i, &d2)
    }

    /// 1/(U_m − U_{m−j}), or 0.
    #[inline]
    fn inv(&self, j: usize, m: usize) -> f64 {
        self.inverse[j * self.knots.len() + m]
    }

    /// Basis functions of degree 0 ..= p on span `i` by the triangular scheme; the values of
    /// degree p, p − 1 and p − 2 (zero where a degree does not exist).
    #[inline(always)]
    fn levels<const N: usize>(&self, p: usize, i: usize, t: f64) -> [[f64; N]; 3] {
        let mut n = [0.0; N];
        let mut left = [0.0; N];
        let mut right = [0.0; N];
        let mut out = [[0.0; N]; 3];
        n[0] = 1.0;
        let keep = |degree: usize, n: &[f64; N], out: &mut [[f64; N]; 3]| {
            if degree + 1 == p {
                out[1] = *n;
            } else if degree + 2 == p {
                out[2] = *n;
            }
        };
        keep(0, &n, &mut out);
        for j in 1..=p {
            self.raise(j, i, t, &mut n, &mut left, &mut right);
            keep(j, &n, &mut out);
        }
        out[0] = n;
        out
    }

    /// One step of the triangular scheme: the degree-(j − 1) functions on span `i` in `n`
    /// become the degree-j ones.
    #[inline(always)]
    fn raise<const N: usize>(
        &self,
        j: usize,
        i: usize,
        t: f64,
        n: &mut [f64; N],
        left: &mut [f64; N],
        right: &mut [f64; N],
    ) {
        let knots = &self.knots;
        left[j] = t - knots[i + 1 - j];
        right[j] = knots[i + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            // right[r + 1] + left[j − r] = U_{i+r+1} − U_{i+r+1−j}.
            let temp = n[r] * self.inv(j, i + r + 1);
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }

    /// The derivatives of the degree-`d` functions on span `i` from the degree-(d − 1) ones
    /// `lower` (N_{i−d+1,d−1} … N_{i,d−1}), by eq. 2.7.
    #[inline(always)]
    fn derive<const N: usize>(&self, d: usize, i: usize, lower: &[f64; N]) -> [f64; N] {
        let mut out = [0.0; N];
        let df = d as f64;
        for (r, o) in out.iter_mut().enumerate().take(d + 1) {
            // N_{k,d} with k = i − d + r.
            let k = i + r - d;
            let a = if r >= 1 {
                lower[r - 1] * self.inv(d, k + d)
            } else {
                0.0
            };
            let b = if r < d {
                lower[r] * self.inv(d, k + d + 1)
            } else {
                0.0
            };
            *o = df * (a - b);
        }
        out
    }
}

/// The p + 1 nonzero basis functions N_{i−p+r,p}(t), r = 0..=p, and their first and second
/// derivatives (entries beyond p are zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasisDerivs {
    /// N, N′ and N″.
    pub d: [[f64; MAX_DEGREE + 1]; 3],
}
