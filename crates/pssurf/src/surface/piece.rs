//! Smooth pieces of a surface, whatever their shape: triangles (PS sub-triangles, Bézier
//! triangles) or rectangles (tensor-product pieces), with local coordinates and quadrature.

use nalgebra::{Point2, Vector3};

use super::ParametricSurface;
use crate::bezier::Jet;
use crate::geometry::{Bary, BaryMap, Triangle2};
use crate::quadrature::{TriangleRule, gauss_legendre};

/// An axis-parallel rectangle [min.x, max.x] × [min.y, max.y] of the parameter plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rectangle {
    /// The lower-left corner.
    pub min: Point2<f64>,
    /// The upper-right corner.
    pub max: Point2<f64>,
}

impl Rectangle {
    /// The rectangle with corners `min` and `max`.
    pub fn new(min: Point2<f64>, max: Point2<f64>) -> Self {
        Rectangle { min, max }
    }

    /// Width times height.
    pub fn area(&self) -> f64 {
        (self.max.x - self.min.x) * (self.max.y - self.min.y)
    }

    /// The corners counter-clockwise from `min`.
    pub fn corners(&self) -> [Point2<f64>; 4] {
        [
            self.min,
            Point2::new(self.max.x, self.min.y),
            self.max,
            Point2::new(self.min.x, self.max.y),
        ]
    }

    /// True when both sides are positive and finite.
    pub fn is_proper(&self) -> bool {
        let (w, h) = (self.max.x - self.min.x, self.max.y - self.min.y);
        w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()
    }
}

/// The two shapes a piece can have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PieceKind {
    /// Triangular pieces, addressed by barycentric coordinates.
    Triangle,
    /// Rectangular (tensor-product) pieces, addressed by (s, t) ∈ [0, 1]².
    Rectangle,
}

/// The parameter domain of one piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceShape {
    /// A triangle of the parameter plane.
    Triangle(Triangle2),
    /// An axis-parallel rectangle.
    Rectangle(Rectangle),
}

impl PieceShape {
    /// Triangle or rectangle.
    pub fn kind(&self) -> PieceKind {
        match self {
            PieceShape::Triangle(_) => PieceKind::Triangle,
            PieceShape::Rectangle(_) => PieceKind::Rectangle,
        }
    }

    /// The area in the parameter plane.
    pub fn area(&self) -> f64 {
        match self {
            PieceShape::Triangle(t) => t.area(),
            PieceShape::Rectangle(r) => r.area(),
        }
    }

    /// The corners, counter-clockwise for a positively oriented piece.
    pub fn corners(&self) -> Vec<Point2<f64>> {
        match self {
            PieceShape::Triangle(t) => t.v.to_vec(),
            PieceShape::Rectangle(r) => r.corners().to_vec(),
        }
    }

    /// The map to local coordinates, `None` for a degenerate piece.
    pub fn frame(&self) -> Option<PieceFrame> {
        match *self {
            PieceShape::Triangle(triangle) => Some(PieceFrame::Triangle {
                triangle,
                map: triangle.bary_map()?,
            }),
            PieceShape::Rectangle(rectangle) => rectangle.is_proper().then(|| {
                let (w, h) = (
                    rectangle.max.x - rectangle.min.x,
                    rectangle.max.y - rectangle.min.y,
                );
                PieceFrame::Rectangle {
                    rectangle,
                    scale: [1.0 / w, 1.0 / h],
                }
            }),
        }
    }
}

/// A piece's shape with its (affine) map between parameters and local coordinates, computed
/// once per piece and then used for every point of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceFrame {
    /// A triangle and its barycentric map (2.1).
    Triangle {
        /// The triangle.
        triangle: Triangle2,
        /// Its barycentric map.
        map: BaryMap,
    },
    /// A rectangle: s = (u − min.x)·scale\[0\], t = (v − min.y)·scale\[1\].
    Rectangle {
        /// The rectangle.
        rectangle: Rectangle,
        /// 1/width and 1/height: ∂s/∂u and ∂t/∂v.
        scale: [f64; 2],
    },
}

/// Local coordinates of a point in its piece, with their (constant) derivatives with respect
/// to the parameters, as the piece's polynomial needs them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LocalCoords {
    /// Barycentric coordinates τ in a triangle with ∂τ/∂u and ∂τ/∂v (the directions d_x, d_y of
    /// (2.18)–(2.19)).
    Bary {
        /// τ1, τ2, τ3.
        bary: Bary,
        /// ∂τ/∂u.
        du: Bary,
        /// ∂τ/∂v.
        dv: Bary,
    },
    /// (s, t) ∈ [0, 1]² in a rectangle with ∂s/∂u and ∂t/∂v.
    Rect {
        /// s, t.
        st: [f64; 2],
        /// ∂s/∂u, ∂t/∂v.
        scale: [f64; 2],
    },
}

/// A parameter point of a piece together with its local coordinates there: the one argument
/// of [`PiecewiseSurface::piece_jet`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PiecePoint {
    /// The parameters (u, v).
    pub uv: Point2<f64>,
    /// The same point in the piece's local coordinates.
    pub local: LocalCoords,
}

impl PieceFrame {
    /// The point with barycentric coordinates `bary` of a triangular piece.
    ///
    /// # Panics
    /// For a rectangular piece.
    #[inline]
    pub fn at_bary(&self, bary: Bary) -> PiecePoint {
        match self {
            PieceFrame::Triangle { triangle, map } => PiecePoint {
                uv: triangle.point(bary),
                local: LocalCoords::Bary {
                    bary,
                    du: map.dx(),
                    dv: map.dy(),
                },
            },
            PieceFrame::Rectangle { .. } => panic!("barycentric coordinates on a rectangle"),
        }
    }

    /// The point at (s, t) ∈ [0, 1]² of a rectangular piece.
    ///
    /// # Panics
    /// For a triangular piece.
    #[inline]
    pub fn at_st(&self, s: f64, t: f64) -> PiecePoint {
        match self {
            PieceFrame::Rectangle { rectangle, scale } => PiecePoint {
                uv: Point2::new(
                    rectangle.min.x + s / scale[0],
                    rectangle.min.y + t / scale[1],
                ),
                local: LocalCoords::Rect {
                    st: [s, t],
                    scale: *scale,
                },
            },
            PieceFrame::Triangle { .. } => panic!("rectangle coordinates on a triangle"),
        }
    }

    /// The point `uv` (inside the piece or not: pieces extend as polynomials).
    pub fn at_uv(&self, uv: Point2<f64>) -> PiecePoint {
        match self {
            PieceFrame::Triangle { triangle, .. } => PiecePoint {
                uv,
                ..self.at_bary(triangle.bary(uv))
            },
            PieceFrame::Rectangle { rectangle, scale } => PiecePoint {
                uv,
                ..self.at_st(
                    (uv.x - rectangle.min.x) * scale[0],
                    (uv.y - rectangle.min.y) * scale[1],
                )
            },
        }
    }

    /// The piece's area in the parameter plane.
    pub fn area(&self) -> f64 {
        match self {
            PieceFrame::Triangle { triangle, .. } => triangle.area(),
            PieceFrame::Rectangle { rectangle, .. } => rectangle.area(),
        }
    }
}

/// One node of a quadrature rule on a piece: ∫ f ≈ Σ weight · f(point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadratureNode {
    /// Where to evaluate.
    pub point: PiecePoint,
    /// The weight, including the piece's parameter area.
    pub weight: f64,
}

/// Quadrature rules for both piece shapes, exact for polynomials of a given degree: the
/// collapsed Gauss rule on triangles and the tensor Gauss–Legendre rule on rectangles.
#[derive(Clone, Debug)]
pub struct PieceRule {
    triangle: TriangleRule,
    square: Vec<([f64; 2], f64)>,
}

impl PieceRule {
    /// The rules exact for total degree ≤ `degree` on triangles and for degree ≤ `degree` in
    /// each variable on rectangles.
    pub fn exact_for(degree: usize) -> Self {
        let g = gauss_legendre(degree / 2 + 1);
        let square = g
            .iter()
            .flat_map(|&(s, ws)| g.iter().map(move |&(t, wt)| ([s, t], ws * wt)))
            .collect();
        PieceRule {
            triangle: TriangleRule::exact_for(degree),
            square,
        }
    }

    /// The nodes of the rule on one piece.
    pub fn nodes(&self, frame: &PieceFrame) -> Vec<QuadratureNode> {
        let area = frame.area();
        match frame {
            PieceFrame::Triangle { .. } => self
                .triangle
                .nodes
                .iter()
                .map(|&(bary, w)| QuadratureNode {
                    point: frame.at_bary(bary),
                    weight: w * area,
                })
                .collect(),
            PieceFrame::Rectangle { .. } => self
                .square
                .iter()
                .map(|&([s, t], w)| QuadratureNode {
                    point: frame.at_st(s, t),
                    weight: w * area,
                })
                .collect(),
        }
    }
}

/// A surface made of smooth (polynomial or rational) pieces, addressed by an index
/// `0..piece_count()`: the PS sub-triangles of Δ* (piece 6t + j is sub-triangle j of
/// triangle t) for PS, UPS and NURPS surfaces, the patch itself for a Bézier triangle, the
/// rectangles between knots for a tensor-product surface. Values and first derivatives are
/// continuous across the pieces; second derivatives, and so curvature, may jump. Sampling
/// piece by piece gives each piece its own values on shared edges, so plots show the jumps.
///
/// Every piece of one surface has the same [`PieceKind`].
pub trait PiecewiseSurface: ParametricSurface {
    /// The number of pieces.
    fn piece_count(&self) -> usize;

    /// The shape every piece has.
    fn piece_kind(&self) -> PieceKind;

    /// The parameter domain of piece `k`.
    fn piece_shape(&self, k: usize) -> PieceShape;

    /// The jet of piece `k` (extended as a polynomial or rational function beyond its domain)
    /// at `at`, whose local coordinates come from the frame of `piece_shape(k)`.
    fn piece_jet(&self, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>>;

    /// The nodes of `rule` on piece `k`, `None` for a degenerate piece.
    fn piece_quadrature(&self, k: usize, rule: &PieceRule) -> Option<Vec<QuadratureNode>> {
        Some(rule.nodes(&self.piece_shape(k).frame()?))
    }
}
