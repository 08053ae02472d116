//! Control points by stable ids: reading, validated editing, and the pieces each point
//! influences (its support), so that an edit re-samples only those pieces.

use std::ops::Range;

use nalgebra::{Point2, Vector3};
use thiserror::Error;

/// A control point's stable id: for PS, UPS and NURPS surfaces `3 i + j` is point j of the
/// control triangle of vertex i (Definition 2.24); for a Bézier triangle it is the ordinate's
/// storage index ([`crate::bezier::index`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ControlId(pub usize);

/// A control point in space and its weight (1 for polynomial surfaces).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlPoint {
    /// The point in R³ (for a functional surface (X, Y, c): only c is a degree of freedom).
    pub position: Vector3<f64>,
    /// The weight, positive; 1 for polynomial kinds.
    pub weight: f64,
}

impl ControlPoint {
    /// A polynomial control point (weight 1).
    pub fn new(position: Vector3<f64>) -> Self {
        ControlPoint {
            position,
            weight: 1.0,
        }
    }
}

/// Which coordinates of a control point can change.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ControlFreedom {
    /// All three coordinates (parametric and rational surfaces).
    Full,
    /// Only the height z: a functional surface z = s(x, y) has control points (X, Y, c) whose
    /// X and Y are fixed by the basis; edits use only the z coordinate.
    Height,
}

/// Why an edit was refused (the surface is then unchanged).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum EditError {
    /// The id names no control point.
    #[error("there is no control point {id} (the surface has {count})")]
    NoSuchPoint {
        /// The id given.
        id: usize,
        /// The number of control points.
        count: usize,
    },
    /// A coordinate is NaN, infinite or beyond ±[`MAX_VALUE`](crate::limits::MAX_VALUE).
    #[error("control point {0} must have finite coordinates within ±1e60")]
    NonFinite(usize),
    /// A weight is not finite and positive.
    #[error("the weight of control point {id} is {}; weights must lie between 1e-30 and 1e30", crate::text::Short(*weight))]
    InvalidWeight {
        /// The control point.
        id: usize,
        /// The value given.
        weight: f64,
    },
    /// A noise amplitude that is negative or not finite.
    #[error("the noise amplitude {} must be a finite non-negative number", crate::text::Short(*.0))]
    InvalidAmplitude(f64),
    /// A weight other than 1 was given to a polynomial surface.
    #[error(
        "control point {id} cannot take weight {weight}: the surface is not rational (weights are 1)"
    )]
    NotRational {
        /// The control point.
        id: usize,
        /// The value given.
        weight: f64,
    },
}

/// Checks one requested control point against the rules every kind shares.
pub(crate) fn check_point(
    id: ControlId,
    p: &ControlPoint,
    count: usize,
    rational: bool,
) -> Result<(), EditError> {
    if id.0 >= count {
        return Err(EditError::NoSuchPoint { id: id.0, count });
    }
    if !p.position.iter().all(|&x| crate::limits::value_ok(x)) {
        return Err(EditError::NonFinite(id.0));
    }
    if rational {
        if !crate::limits::weight_ok(p.weight) {
            return Err(EditError::InvalidWeight {
                id: id.0,
                weight: p.weight,
            });
        }
    } else if p.weight != 1.0 {
        return Err(EditError::NotRational {
            id: id.0,
            weight: p.weight,
        });
    }
    Ok(())
}

/// A surface defined by control points (and weights).
///
/// Ids are stable: they do not change when points are edited. An edit changes the surface
/// only on the support of the edited points: values on every other piece stay bitwise equal.
pub trait ControlNet {
    /// The number of control points; ids are `0..control_count()`.
    fn control_count(&self) -> usize;

    /// The control point `id`, `None` if there is none.
    fn control_point(&self, id: ControlId) -> Option<ControlPoint>;

    /// True for rational surfaces (weights are shape parameters).
    fn is_rational(&self) -> bool;

    /// Which coordinates can change.
    fn freedom(&self) -> ControlFreedom;

    /// The ids that belong together with `id` (a PS vertex's control triangle, a single
    /// Bézier ordinate): editors show and move them as one group.
    fn control_group(&self, id: ControlId) -> Range<usize>;

    /// The parameter point the control point belongs to: the vertex V_i of a PS control
    /// triangle, the domain point λ/m of a Bézier ordinate (Definition 2.8).
    fn control_anchor(&self, id: ControlId) -> Point2<f64>;

    /// The pieces (of [`super::PiecewiseSurface`]) on which the surface depends on
    /// control point `id`, in increasing order.
    fn support(&self, id: ControlId) -> Vec<usize>;

    /// Sets several control points at once. Everything is validated first (finite
    /// coordinates, finite positive weights for rational kinds, weight 1 otherwise); on an
    /// error nothing changes. Returns the union of the supports of the changed points (sorted,
    /// without repetitions): the pieces to re-sample.
    fn set_control_points(
        &mut self,
        changes: &[(ControlId, ControlPoint)],
    ) -> Result<Vec<usize>, EditError>;

    /// Sets one control point; see [`ControlNet::set_control_points`].
    fn set_control_point(
        &mut self,
        id: ControlId,
        point: ControlPoint,
    ) -> Result<Vec<usize>, EditError> {
        self.set_control_points(&[(id, point)])
    }

    /// The control structure as polylines of ids, for drawing the net: each group of two or
    /// more points as a closed polygon (a PS control triangle); a Bézier net by its lines of
    /// constant λ1, λ2 and λ3.
    fn control_polylines(&self) -> Vec<Vec<ControlId>> {
        let mut out = Vec::new();
        let mut id = 0;
        while id < self.control_count() {
            let group = self.control_group(ControlId(id));
            if group.len() >= 2 {
                let mut line: Vec<ControlId> = group.clone().map(ControlId).collect();
                line.push(ControlId(group.start));
                out.push(line);
            }
            id = group.end.max(id + 1);
        }
        out
    }

    /// All control points in id order.
    fn control_points(&self) -> Vec<ControlPoint> {
        (0..self.control_count())
            .map(|i| self.control_point(ControlId(i)).expect("id in range"))
            .collect()
    }
}
