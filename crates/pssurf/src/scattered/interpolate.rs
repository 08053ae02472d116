//! The Hermite PS-spline through scattered values: triangulate, estimate gradients, build
//! the basis and interpolate — the job of `pssurf fit`, as one library call.

use std::sync::Arc;

use nalgebra::{Point2, Vector2};

use super::anchor::{GlobalGradientError, close_vertices};
use super::jumps::anchored_jump_gradients;
use super::local::{GradientError, GradientFit, estimate_jets};
use super::merge::{NEAR_DUPLICATE, merge_near_duplicates};
use super::network::network_gradients;
use crate::ps::{Hermite, PsBasis, PsError, PsSpline, PsTriangleChoice, SplitRule};
use crate::triangulation::{
    MAX_COORDINATE, Triangulation, TriangulationError, duplicate_points, morton_order,
};

/// How the gradients at the vertices are estimated from the values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GradientMethod {
    /// Local weighted quadratic least squares at each vertex
    /// ([`estimate_gradients`](super::estimate_gradients)): O(n), embarrassingly parallel.
    /// The default: the fastest, and on one of the two real elevation data sets of
    /// docs/performance.md the more accurate.
    #[default]
    Local,
    /// The least curvature of the edge network beyond the locally fitted one, over the
    /// whole triangulation ([`estimate_gradients_global`](super::estimate_gradients_global),
    /// Clough–Tocher's choice made exact on quadratics): one well-conditioned sparse solve
    /// by conjugate gradients; 2–3× lower RMS error than `Local` on Franke's function.
    Global,
    /// The least Hessian-jump energy over the whole triangulation
    /// ([`estimate_gradients_jumps`](super::estimate_gradients_jumps)): the least-energy
    /// interpolant, the limit λ → 0 of the smoothing fit; one sparse Cholesky solve, the
    /// most accurate on smooth gridded data, the least on rough real data.
    Jumps,
}

/// Why an interpolant could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// Values and points differ in number.
    #[error("{points} points but {values} values")]
    Mismatch {
        /// The number of points.
        points: usize,
        /// The number of values.
        values: usize,
    },
    /// A value is NaN or infinite.
    #[error("the value of point {0} is not a finite number within ±1e60")]
    NonFiniteValue(usize),
    /// A data point's coordinate is NaN or infinite ([`check_points`]).
    #[error("point {0} has a coordinate that is not a finite number")]
    NonFiniteCoordinate(usize),
    /// A data point's coordinate is outside the range pssurf supports ([`check_points`]).
    #[error(
        "point {0} has a coordinate outside the range pssurf supports (0, or 1e-42 to 1e60 in magnitude)"
    )]
    CoordinateOutOfRange(usize),
    /// Two data points are equal ([`check_points`]).
    #[error("points {first} and {second} have the same (x, y); remove one")]
    DuplicatePoints {
        /// The first of them.
        first: usize,
        /// The second.
        second: usize,
    },
    /// The points cannot be triangulated (duplicates, collinear, non-finite…).
    #[error(transparent)]
    Triangulation(#[from] TriangulationError),
    /// The local gradient estimate failed.
    #[error(transparent)]
    Gradient(#[from] GradientError),
    /// The global gradient estimate failed.
    #[error(transparent)]
    GlobalGradient(#[from] GlobalGradientError),
    /// The PS basis or the spline could not be built.
    #[error(transparent)]
    Ps(#[from] PsError),
    /// The PS refinement failed at a triangle whose detail is near the precision of the
    /// coordinates: far from the origin, f64 cannot place its split points.
    #[error(
        "points {}, {} and {} make a triangle only {height:.1e} high, too fine for coordinates of magnitude {magnitude:.1e} (spaced {:.1e} apart in floating point): subtract an origin from x and y, e.g. their minimum, and fit again",
        vertices[0], vertices[1], vertices[2], magnitude * f64::EPSILON
    )]
    BeyondPrecision {
        /// The triangle's vertices (indices of the points given).
        vertices: [usize; 3],
        /// Its smallest height.
        height: f64,
        /// The largest coordinate magnitude of the points.
        magnitude: f64,
    },
    /// The PS refinement failed at a triangle thinner than [`COLLINEAR_HINT`] × its longest
    /// side: its corners are nearly collinear, and its split points cannot be placed
    /// reliably with any split rule.
    #[error(
        "points {}, {} and {} are nearly collinear (their triangle is {height:.1e} high and {length:.1e} long): the split points of so thin a triangle cannot be placed reliably; remove or move one of them",
        vertices[0], vertices[1], vertices[2]
    )]
    NearlyCollinear {
        /// The triangle's vertices (indices of the points given).
        vertices: [usize; 3],
        /// Its smallest height.
        height: f64,
        /// Its longest side.
        length: f64,
    },
    /// The value and gradient at a point give control values (2.45) that are not finite
    /// within ±1e60: the gradient is not finite, or too large for the distance to the
    /// corners of the point's PS-triangle.
    #[error(
        "the value and gradient of point {point} give control values that are not finite numbers within ±1e60 (a gradient that is not finite, or too large for the distance to its neighbours): scale the values or gradients down"
    )]
    ControlValueOutOfRange {
        /// The vertex, until [`FitError::map_points`] maps it to the caller's point.
        point: usize,
    },
    /// The split rule's points do not make a PS refinement (Definition 2.16): the segment
    /// joining the split points of two neighbouring triangles misses their common edge (the
    /// centroid split on obtuse neighbours; the incentre split never fails so).
    #[error(
        "the split points of the triangles at points {}, {}, {} and at points {}, {}, {} are joined by a segment that misses their common edge: this split rule does not fit the triangulation here; use the incentre split, which always does",
        triangles[0][0], triangles[0][1], triangles[0][2], triangles[1][0], triangles[1][1], triangles[1][2]
    )]
    SplitMissesEdge {
        /// The corners of the two triangles (indices of the points given, after
        /// [`FitError::map_points`]).
        triangles: [[usize; 3]; 2],
    },
    /// The PS refinement of a triangle that is not thin fails: its split point is outside
    /// it, or one of its six pieces has (nearly) zero area.
    #[error(
        "the PS refinement of the triangle at points {}, {} and {} fails: {reason}",
        corners[0], corners[1], corners[2]
    )]
    RefinementFails {
        /// The triangle's corners (indices of the points given, after
        /// [`FitError::map_points`]).
        corners: [usize; 3],
        /// What fails.
        reason: &'static str,
    },
    /// The gradient at a point could not be estimated: its neighbours do not span the plane
    /// (a [`GradientError`] mapped to the caller's point by [`FitError::map_points`]).
    #[error("cannot estimate the gradient at point {point}: its neighbours do not span the plane")]
    GradientAtPoint {
        /// The point (its index among the points given).
        point: usize,
    },
}

impl FitError {
    /// The same error with the point indices it names mapped by `index` (vertex numbers of
    /// a reordered triangulation back to the caller's points); a gradient that could not be
    /// estimated, locally or as the global estimate's anchor, becomes
    /// [`FitError::GradientAtPoint`].
    pub fn map_points(self, index: impl Fn(usize) -> usize) -> Self {
        match self {
            FitError::BeyondPrecision {
                vertices,
                height,
                magnitude,
            } => FitError::BeyondPrecision {
                vertices: vertices.map(&index),
                height,
                magnitude,
            },
            FitError::NearlyCollinear {
                vertices,
                height,
                length,
            } => FitError::NearlyCollinear {
                vertices: vertices.map(&index),
                height,
                length,
            },
            FitError::NonFiniteValue(k) => FitError::NonFiniteValue(index(k)),
            FitError::NonFiniteCoordinate(k) => FitError::NonFiniteCoordinate(index(k)),
            FitError::CoordinateOutOfRange(k) => FitError::CoordinateOutOfRange(index(k)),
            FitError::DuplicatePoints { first, second } => {
                let (a, b) = (index(first), index(second));
                FitError::DuplicatePoints {
                    first: a.min(b),
                    second: a.max(b),
                }
            }
            FitError::ControlValueOutOfRange { point } => FitError::ControlValueOutOfRange {
                point: index(point),
            },
            FitError::Gradient(GradientError { vertex })
            | FitError::GlobalGradient(GlobalGradientError::Local(GradientError { vertex })) => {
                FitError::GradientAtPoint {
                    point: index(vertex),
                }
            }
            FitError::GradientAtPoint { point } => FitError::GradientAtPoint {
                point: index(point),
            },
            FitError::SplitMissesEdge { triangles } => FitError::SplitMissesEdge {
                triangles: triangles.map(|t| t.map(&index)),
            },
            FitError::RefinementFails { corners, reason } => FitError::RefinementFails {
                corners: corners.map(&index),
                reason,
            },
            FitError::Triangulation(TriangulationError::NearlyCollinearPoints { points }) => {
                FitError::Triangulation(TriangulationError::NearlyCollinearPoints {
                    points: points.map(&index),
                })
            }
            e => e,
        }
    }
}

/// Checks data points as every fit needs them, in the order given so that errors name the
/// caller's points: finite coordinates within the range pssurf supports (see
/// [`check_coordinates`](crate::triangulation::check_coordinates)) and no two equal.
pub fn check_points(points: &[Point2<f64>]) -> Result<(), FitError> {
    check_point_coordinates(points)?;
    match duplicate_points(points) {
        Some((first, second)) => Err(FitError::DuplicatePoints { first, second }),
        None => Ok(()),
    }
}

/// The coordinate half of [`check_points`].
pub(super) fn check_point_coordinates(points: &[Point2<f64>]) -> Result<(), FitError> {
    crate::triangulation::check_coordinates(points).map_err(|e| match e {
        TriangulationError::NonFiniteVertex(k) => FitError::NonFiniteCoordinate(k),
        TriangulationError::CoordinateOutOfRange(k) => FitError::CoordinateOutOfRange(k),
        e => e.into(),
    })
}

/// Relative thinness (smallest height over longest side) below which a failure of the PS
/// refinement is blamed on nearly collinear points ([`FitError::NearlyCollinear`]).
pub const COLLINEAR_HINT: f64 = 1e-6;

/// Relative detail (a triangle's smallest height over the largest coordinate magnitude,
/// about 4.5e5 units in the last place) below which a failure of the PS refinement is
/// blamed on the coordinates' precision ([`FitError::BeyondPrecision`]).
pub const PRECISION_HINT: f64 = 1e-10;

/// The PS basis on `tri` with the split by `split` and optimal PS-triangles; a failure at a
/// triangle finer than [`PRECISION_HINT`] × the coordinates' magnitude is reported as
/// [`FitError::BeyondPrecision`] (vertex indices of `tri`), with what to do.
pub fn data_basis(tri: Triangulation, split: SplitRule) -> Result<PsBasis, FitError> {
    data_basis_with(tri, split, &PsTriangleChoice::Optimal)
}

/// [`data_basis`] with the PS-triangles chosen by `choice`.
pub fn data_basis_with(
    tri: Triangulation,
    split: SplitRule,
    choice: &PsTriangleChoice,
) -> Result<PsBasis, FitError> {
    let magnitude = tri
        .vertices()
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let suspects = |e: &PsError, tri: &Triangulation| -> Vec<usize> {
        match *e {
            PsError::SplitPointOutside { triangle } | PsError::DegeneratePiece { triangle } => {
                vec![triangle]
            }
            PsError::EdgePointOutside {
                triangle, neighbor, ..
            } => vec![triangle, neighbor],
            PsError::DegeneratePsTriangle { vertex } | PsError::PsPointOutside { vertex, .. } => {
                tri.molecule(vertex).iter().map(|&t| t as usize).collect()
            }
            _ => Vec::new(),
        }
    };
    match PsBasis::new(tri.clone(), split, choice) {
        Ok(b) => Ok(b),
        Err(e) => {
            // The thinnest suspect relative to its size.
            let thinnest = suspects(&e, &tri)
                .into_iter()
                .map(|t| {
                    let g = tri.triangle_geometry(t);
                    (g.min_height(), g.diameter(), t)
                })
                .min_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)));
            match thinnest {
                // Far from the origin relative to its size: the coordinates' precision.
                Some((height, length, t))
                    if height < PRECISION_HINT * magnitude && length < 1e-3 * magnitude =>
                {
                    Err(FitError::BeyondPrecision {
                        vertices: tri.triangle(t),
                        height,
                        magnitude,
                    })
                }
                Some((height, length, t)) if height < COLLINEAR_HINT * length => {
                    Err(FitError::NearlyCollinear {
                        vertices: tri.triangle(t),
                        height,
                        length,
                    })
                }
                _ => match e {
                    PsError::EdgePointOutside {
                        triangle, neighbor, ..
                    } => Err(FitError::SplitMissesEdge {
                        triangles: [tri.triangle(triangle), tri.triangle(neighbor)],
                    }),
                    PsError::SplitPointOutside { triangle } => Err(FitError::RefinementFails {
                        corners: tri.triangle(triangle),
                        reason: "its split point is not strictly inside it",
                    }),
                    PsError::DegeneratePiece { triangle } => Err(FitError::RefinementFails {
                        corners: tri.triangle(triangle),
                        reason: "one of its six pieces has (nearly) zero area: its split points lie too close to its edges or vertices",
                    }),
                    e => Err(e.into()),
                },
            }
        }
    }
}

/// How the gradients of an interpolant were obtained.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GradientReport {
    /// The method used.
    pub method: GradientMethod,
    /// Vertices whose local fit needed more than the first ring of neighbours.
    pub widened: usize,
    /// Vertices whose local fit fell back to a plane.
    pub planar: usize,
    /// The global method's anchor to the local estimate when the system needed one
    /// stronger than [`ANCHOR`](super::ANCHOR) to be factorised (ill-conditioned
    /// triangulations; see [`STRONGER_ANCHORS`](super::STRONGER_ANCHORS)); infinity when
    /// no anchor made it factorisable and the local estimate was used.
    pub stronger_anchor: Option<f64>,
    /// With the global method: vertices that kept their local estimate because a neighbour
    /// lies closer than [`CLOSE`](super::CLOSE) × the data's extent.
    pub kept_local: usize,
}

/// The gradients at the vertices of `basis`'s triangulation from the values there, by
/// `method`, with what the local fits needed.
pub fn estimate_gradients_by(
    basis: &PsBasis,
    values: &[f64],
    method: GradientMethod,
) -> Result<(Vec<Vector2<f64>>, GradientReport), FitError> {
    let jets = estimate_jets(basis.triangulation(), values)?;
    let mut report = GradientReport {
        method,
        widened: jets
            .iter()
            .filter(|jet| matches!(jet.fit, GradientFit::Quadratic { rings } if rings > 1))
            .count(),
        planar: jets
            .iter()
            .filter(|jet| jet.fit == GradientFit::Linear)
            .count(),
        stronger_anchor: None,
        kept_local: 0,
    };
    let local: Vec<Vector2<f64>> = jets.iter().map(|jet| jet.gradient).collect();
    let gradients = match method {
        GradientMethod::Local => local,
        GradientMethod::Global | GradientMethod::Jumps => {
            let (g, eta) = if method == GradientMethod::Jumps {
                anchored_jump_gradients(basis, values, &local)?
            } else {
                network_gradients(basis, values, &jets)
            };
            if eta > super::ANCHOR {
                report.stronger_anchor = Some(eta);
            }
            report.kept_local = close_vertices(basis).iter().filter(|&&c| c).count();
            g
        }
    };
    Ok((gradients, report))
}

/// The Hermite PS-spline on `basis` with these vertex values and gradients; control values
/// beyond ±1e60 are [`FitError::ControlValueOutOfRange`], naming the vertex (map it to the
/// caller's point with [`FitError::map_points`]).
pub fn hermite_spline(
    basis: Arc<PsBasis>,
    values: &[f64],
    gradients: &[Vector2<f64>],
) -> Result<PsSpline<f64>, FitError> {
    hermite_spline_with(
        basis,
        &hermite_data(values, gradients),
        &PsTriangleChoice::Optimal,
    )
}

/// The Hermite data (2.30) of these values and gradients, one per vertex.
pub fn hermite_data(values: &[f64], gradients: &[Vector2<f64>]) -> Vec<Hermite<f64>> {
    values
        .iter()
        .zip(gradients)
        .map(|(&value, g)| Hermite {
            value,
            dx: g.x,
            dy: g.y,
        })
        .collect()
}

/// The Hermite spline of `data` on `basis`, whose PS-triangles were chosen by `choice`:
/// [`PsSpline::hermite`] on optimal or given ones (nets as a saved file has them),
/// [`PsSpline::hermite_direct`] on [`Circumscribed`](PsTriangleChoice::Circumscribed)
/// ones (nets independent of them). Control values beyond ±1e60 on the larger
/// circumscribed triangles are decided again on the optimal ones, so that data is
/// accepted or refused exactly as [`hermite_spline`] decides.
pub fn hermite_spline_with(
    basis: Arc<PsBasis>,
    data: &[Hermite<f64>],
    choice: &PsTriangleChoice,
) -> Result<PsSpline<f64>, FitError> {
    let spline = match choice {
        PsTriangleChoice::Circumscribed => match PsSpline::hermite_direct(basis.clone(), data) {
            Err(PsError::NonFiniteCoefficient { .. }) => basis
                .with_ps_triangles(&PsTriangleChoice::Optimal)
                .and_then(|optimal| PsSpline::hermite(Arc::new(optimal), data)),
            built => built,
        },
        _ => PsSpline::hermite(basis, data),
    };
    spline.map_err(|e| match e {
        PsError::NonFiniteCoefficient { vertex, .. } => {
            FitError::ControlValueOutOfRange { point: vertex }
        }
        e => e.into(),
    })
}

/// An interpolant of scattered data and how it was made.
#[derive(Clone, Debug)]
pub struct Interpolant {
    /// The PS-spline; its vertex k is data point `data_index[k]`.
    pub spline: PsSpline<f64>,
    /// The data point of each vertex (vertices are ordered along a space-filling curve); for
    /// a vertex made by merging nearly coincident points, the first of them.
    pub data_index: Vec<usize>,
    /// The groups of data points (indices, sorted) that were nearly coincident and were
    /// merged into one vertex at their mean with their mean value ([`NEAR_DUPLICATE`]).
    pub merged: Vec<Vec<usize>>,
    /// The value and gradient at each vertex, which the spline interpolates (the same
    /// spline on other PS-triangles is [`hermite_spline_with`] this data).
    pub hermite: Vec<Hermite<f64>>,
    /// The boundary slivers thinner than [`PEEL_THICKNESS`](crate::triangulation::PEEL_THICKNESS)
    /// that were left out of the domain (indices of the data points at their corners).
    pub peeled: Vec<[usize; 3]>,
    /// How the gradients were estimated.
    pub gradients: GradientReport,
}

/// The Hermite PS-spline through (points\[k\], values\[k\]) on their Delaunay triangulation,
/// with the incentre split and optimal PS-triangles, and gradients estimated by `method`.
///
/// Points closer than [`NEAR_DUPLICATE`] × the data's extent are merged first (see
/// [`merge_near_duplicates`]); exactly repeated points are an error.
pub fn interpolate(
    points: &[Point2<f64>],
    values: &[f64],
    method: GradientMethod,
) -> Result<Interpolant, FitError> {
    interpolate_with(points, values, method, &PsTriangleChoice::Optimal)
}

/// [`interpolate`] with the PS-triangles chosen by `choice`: the same function, other
/// B-spline coefficients ([`PsTriangleChoice::Circumscribed`] for an interpolant made to be
/// evaluated, about a third faster to build).
pub fn interpolate_with(
    points: &[Point2<f64>],
    values: &[f64],
    method: GradientMethod,
    choice: &PsTriangleChoice,
) -> Result<Interpolant, FitError> {
    if points.len() != values.len() {
        return Err(FitError::Mismatch {
            points: points.len(),
            values: values.len(),
        });
    }
    // Checked in the input order, so that errors name the data points.
    if let Some(k) = values.iter().position(|v| !(v.abs() <= MAX_COORDINATE)) {
        return Err(FitError::NonFiniteValue(k));
    }
    check_points(points)?;
    let data = merge_near_duplicates(points, values, NEAR_DUPLICATE);
    // A space-filling-curve order keeps neighbouring vertices close in memory.
    let order: Vec<usize> = morton_order(&data.points)
        .iter()
        .map(|&i| i as usize)
        .collect();
    let ordered: Vec<Point2<f64>> = order.iter().map(|&k| data.points[k]).collect();
    let z: Vec<f64> = order.iter().map(|&k| data.values[k]).collect();
    let data_index: Vec<usize> = order.iter().map(|&k| data.first_index[k]).collect();
    let (tri, peeled) = Triangulation::delaunay_with_peeled(ordered)
        .map_err(|e| FitError::from(e).map_points(|v| data_index[v]))?;
    let basis = Arc::new(
        data_basis_with(tri, SplitRule::Incenter, choice)
            .map_err(|e| e.map_points(|v| data_index[v]))?,
    );
    let named = |e: FitError| e.map_points(|v| data_index[v]);
    let (g, gradients) = estimate_gradients_by(&basis, &z, method).map_err(named)?;
    let hermite = hermite_data(&z, &g);
    let spline = hermite_spline_with(basis, &hermite, choice).map_err(named)?;
    let peeled = peeled.iter().map(|t| t.map(|v| data_index[v])).collect();
    Ok(Interpolant {
        spline,
        data_index,
        merged: data.merged,
        hermite,
        peeled,
        gradients,
    })
}
