//! Why a triangulation was rejected.

use thiserror::Error;

/// A problem found while validating a triangulation. Each variant names the offending
/// vertex or triangle (zero-based indices, as in the input).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TriangulationError {
    /// No triangles were given.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.)];
    /// assert_eq!(Triangulation::try_new(v, vec![]).unwrap_err(), TriangulationError::NoTriangles);
    /// ```
    #[error("the triangulation has no triangles")]
    NoTriangles,
    /// More vertices or triangles than 32-bit indices can address.
    #[error("too many vertices or triangles ({0}); at most 2^32 − 2 are supported")]
    TooLarge(usize),
    /// A vertex has a NaN or infinite coordinate.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(f64::NAN, 0.), Point2::new(0., 1.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 2]]).unwrap_err(),
    ///     TriangulationError::NonFiniteVertex(1));
    /// ```
    #[error("vertex {0} has a coordinate that is not a finite number")]
    NonFiniteVertex(usize),
    /// A coordinate lies beyond ±[`MAX_COORDINATE`](super::MAX_COORDINATE), or is nonzero and
    /// smaller than [`MIN_COORDINATE`](super::MIN_COORDINATE) in magnitude.
    #[error(
        "vertex {0} has a coordinate outside the range pssurf supports (0, or 1e-42 to 1e60 in magnitude)"
    )]
    CoordinateOutOfRange(usize),
    /// Two vertices have the same coordinates.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.), Point2::new(1., 0.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 2]]).unwrap_err(),
    ///     TriangulationError::DuplicateVertex { first: 1, second: 3 });
    /// ```
    #[error("vertices {first} and {second} have the same coordinates")]
    DuplicateVertex {
        /// The smaller index.
        first: usize,
        /// The larger index.
        second: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 7]]).unwrap_err(),
    ///     TriangulationError::IndexOutOfRange { triangle: 0, index: 7, vertex_count: 3 });
    /// ```
    #[error(
        "triangle {triangle} refers to vertex {index}, but there are only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The bad index.
        index: usize,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// A triangle uses the same vertex twice.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 1]]).unwrap_err(),
    ///     TriangulationError::RepeatedVertex { triangle: 0 });
    /// ```
    #[error("triangle {triangle} uses the same vertex twice")]
    RepeatedVertex {
        /// The triangle.
        triangle: usize,
    },
    /// A triangle has (numerically) zero area.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(2., 0.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 2]]).unwrap_err(),
    ///     TriangulationError::DegenerateTriangle { triangle: 0 });
    /// ```
    #[error("triangle {triangle} is degenerate (its vertices are collinear)")]
    DegenerateTriangle {
        /// The triangle.
        triangle: usize,
    },
    /// Triangles are listed with different orientations (some clockwise, some counter-clockwise).
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.), Point2::new(1., 1.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 2], [1, 2, 3]]).unwrap_err(),
    ///     TriangulationError::InconsistentOrientation { triangle: 1, first: 0 });
    /// ```
    #[error(
        "triangle {triangle} is oriented differently from triangle {first}: list all triangles clockwise or all counter-clockwise"
    )]
    InconsistentOrientation {
        /// The offending triangle.
        triangle: usize,
        /// The triangle whose orientation sets the convention.
        first: usize,
    },
    /// The same triangle is listed twice.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 2], [1, 2, 0]]).unwrap_err(),
    ///     TriangulationError::DuplicateTriangle { triangle: 1, first: 0 });
    /// ```
    #[error("triangle {triangle} repeats triangle {first}")]
    DuplicateTriangle {
        /// The repeated triangle.
        triangle: usize,
        /// Its first occurrence.
        first: usize,
    },
    /// An edge belongs to more than two triangles.
    #[error("edge ({a}, {b}) of triangle {triangle} belongs to more than two triangles")]
    NonManifoldEdge {
        /// The triangle.
        triangle: usize,
        /// One end of the edge.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// Two triangles overlap: they lie on the same side of a shared edge, wind around a vertex
    /// more than once, or a vertex of one lies on an edge of another (a hanging node).
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// // Vertex 3 lies in the middle of the edge (0, 1) of triangle 0.
    /// let v = vec![Point2::new(0., 0.), Point2::new(2., 0.), Point2::new(1., 1.),
    ///              Point2::new(1., 0.), Point2::new(1., -1.)];
    /// let e = Triangulation::try_new(v, vec![[0, 1, 2], [0, 4, 3], [3, 4, 1]]).unwrap_err();
    /// assert!(matches!(e, TriangulationError::NonConforming { .. }), "{e}");
    /// ```
    #[error("the triangulation is not conforming near triangle {triangle}: {detail}")]
    NonConforming {
        /// A triangle involved.
        triangle: usize,
        /// What was found.
        detail: String,
    },
    /// Two parts of the domain touch at a single vertex (a "bow-tie"), so its molecule is
    /// not a disk.
    #[error(
        "vertex {vertex} joins parts of the domain that touch only at that point (a bow-tie vertex)"
    )]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
    },
    /// A vertex is used by no triangle.
    ///
    /// ```
    /// use pssurf::triangulation::{Triangulation, TriangulationError};
    /// use nalgebra::Point2;
    /// let v = vec![Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.), Point2::new(5., 5.)];
    /// assert_eq!(Triangulation::try_new(v, vec![[0, 1, 2]]).unwrap_err(),
    ///     TriangulationError::UnusedVertex(3));
    /// ```
    #[error("vertex {0} is not used by any triangle")]
    UnusedVertex(usize),
    /// Too few distinct, non-collinear points to triangulate.
    #[error("the points are collinear or too few: no triangle can be formed")]
    CollinearPoints,
    /// The Delaunay triangulation of the points has a triangle of (numerically) zero area
    /// inside the domain (only boundary slivers are peeled off): three points nearly on one
    /// line, with others on both sides.
    #[error(
        "points {}, {} and {} are nearly collinear (their Delaunay triangle has numerically zero area): remove or move one of them",
        points[0], points[1], points[2]
    )]
    NearlyCollinearPoints {
        /// The three points (indices of the points given).
        points: [usize; 3],
    },
}
