//! UPS surfaces in the surface model: the uniform form of each kind ([`UpsSurface`]), the
//! pairing with its general form built on first use ([`UniformSurface`]), which keeps both in
//! step under edits, and the wavelet operations that dispatch on the kind here, once.

use std::ops::Range;
use std::sync::OnceLock;

use nalgebra::{Point2, Vector3};

use super::control::check_point;
use super::piece::{PieceKind, PiecePoint, PieceShape};
use super::{
    ControlFreedom, ControlId, ControlNet, ControlPoint, Cursor, EditError, OutsideDomain,
    ParametricSurface, PiecewiseSurface, Surface, SurfaceJet,
};
use crate::bezier::Jet;
use crate::noise::{NoiseKind, perturb};
use crate::ps::net::Weighted;
use crate::ups::threshold::{LevelStats, Shrink, ThresholdRule};
use crate::ups::wavelet::{Decomposition, Update};
use crate::ups::{LatticePoint, Ups, UpsError, UpsGrid, fixed_ps_triangle};
use crate::vector::Vector;

/// A uniform PS-spline of any kind, in its block-matrix form.
#[derive(Clone, Debug, PartialEq)]
pub enum UpsSurface {
    /// A functional UPS-spline z = s(x, y).
    Functional(Ups<f64>),
    /// A parametric UPS-spline surface.
    Parametric(Ups<Vector3<f64>>),
    /// A rational UPS-spline surface (NURPS on a uniform triangulation).
    Rational(Ups<Weighted<Vector3<f64>>>),
}

/// Runs `$body` with `$s` bound to the `Ups<_>` of any kind.
macro_rules! each_ups {
    ($value:expr, $s:ident => $body:expr) => {
        match $value {
            UpsSurface::Functional($s) => $body,
            UpsSurface::Parametric($s) => $body,
            UpsSurface::Rational($s) => $body,
        }
    };
}

impl UpsSurface {
    /// The triangulation.
    pub fn grid(&self) -> &UpsGrid {
        each_ups!(self, s => s.grid())
    }

    /// The names of the coordinates of a control value: `z` for functional surfaces, `x, y, z`
    /// otherwise.
    pub fn coordinate_names(&self) -> &'static [&'static str] {
        match self {
            UpsSurface::Functional(_) => &["z"],
            _ => &["x", "y", "z"],
        }
    }

    /// True for rational UPS surfaces.
    pub fn is_rational(&self) -> bool {
        matches!(self, UpsSurface::Rational(_))
    }

    /// The position of the first vertex (in slot order) with a control value that is not a
    /// finite number within ±[`crate::limits::MAX_VALUE`] or a weight out of range, which
    /// the general form and the file loader would refuse; `None` when every one is usable.
    /// Constructors from functions ([`crate::ups::graph_surface_from_formula`], the NURBS
    /// approximation) check their result with it.
    pub fn first_unusable_vertex(&self) -> Option<Point2<f64>> {
        use crate::limits::{value_ok, weight_ok};
        let point_ok = |p: &Vector3<f64>| p.iter().all(|&x| value_ok(x));
        let grid = self.grid();
        let bad = grid.real_slots().into_iter().find(|&s| match self {
            UpsSurface::Functional(u) => !u.blocks()[s].iter().all(|&z| value_ok(z)),
            UpsSurface::Parametric(u) => !u.blocks()[s].iter().all(point_ok),
            UpsSurface::Rational(u) => !u.blocks()[s]
                .iter()
                .all(|w| point_ok(&w.point) && weight_ok(w.weight)),
        })?;
        Some(grid.lattice().point(grid.lattice_point(bad)))
    }

    /// The same surface as a general PS surface (functional, parametric or NURPS).
    pub fn to_general(&self) -> Result<Surface, UpsError> {
        Ok(match self {
            UpsSurface::Functional(s) => Surface::Functional(s.to_ps()?),
            UpsSurface::Parametric(s) => Surface::Parametric(s.to_ps()?),
            UpsSurface::Rational(s) => Surface::Nurps(s.to_nurps()?),
        })
    }

    /// `times` subdivision steps (exact refinement, section 4.4).
    pub fn subdivide_times(&self, times: usize) -> UpsSurface {
        match self {
            UpsSurface::Functional(s) => UpsSurface::Functional(s.subdivide_times(times)),
            UpsSurface::Parametric(s) => UpsSurface::Parametric(s.subdivide_times(times)),
            UpsSurface::Rational(s) => UpsSurface::Rational(s.subdivide_times(times)),
        }
    }

    /// The surface with every free coordinate of every control point perturbed
    /// reproducibly (see [`perturb`]); rational surfaces keep their weights.
    pub fn with_noise(&self, amplitude: f64, kind: NoiseKind, seed: u64) -> UpsSurface {
        match self {
            UpsSurface::Functional(s) => {
                UpsSurface::Functional(s.with_noise(amplitude, kind, seed))
            }
            UpsSurface::Parametric(s) => {
                UpsSurface::Parametric(s.with_noise(amplitude, kind, seed))
            }
            UpsSurface::Rational(s) => {
                let mut out = s.clone();
                let slots = out.grid().real_slots();
                let blocks = out.blocks_mut();
                let mut points: Vec<Vector3<f64>> = slots
                    .iter()
                    .flat_map(|&k| blocks[k].map(|w| w.point))
                    .collect();
                perturb(points.iter_mut(), amplitude, kind, seed);
                for (n, &k) in slots.iter().enumerate() {
                    for j in 0..3 {
                        blocks[k][j].point = points[3 * n + j];
                    }
                }
                UpsSurface::Rational(out)
            }
        }
    }

    /// The lifting wavelet transform of the thesis over `levels` levels (section 4.5).
    pub fn wavelet_transform(&self, levels: u32) -> Result<UpsDecomposition, UpsError> {
        self.wavelet_transform_with(levels, Update::Thesis)
    }

    /// The lifting wavelet transform over `levels` levels with the given update step.
    pub fn wavelet_transform_with(
        &self,
        levels: u32,
        update: Update,
    ) -> Result<UpsDecomposition, UpsError> {
        match self {
            UpsSurface::Functional(s) => Ok(UpsDecomposition::Functional(
                s.wavelet_transform_with(levels, update)?,
            )),
            UpsSurface::Parametric(s) => Ok(UpsDecomposition::Parametric(
                s.wavelet_transform_with(levels, update)?,
            )),
            UpsSurface::Rational(_) => Err(UpsError::RationalWavelet),
        }
    }

    /// Denoising by wavelet thresholding: transform over `levels` levels with the stable
    /// update ([`Update::Stable`]; with the thesis' update the coarse part of a noisy surface
    /// is noisier than the surface, see docs/ups.md), shrink every detail coefficient with the
    /// threshold `rule(level, component)` (level 0 is the coarsest), and reconstruct. Returns
    /// the result and the per-level statistics.
    pub fn denoise(
        &self,
        levels: u32,
        rule: impl Fn(usize, usize) -> ThresholdRule,
        mode: Shrink,
    ) -> Result<(UpsSurface, Vec<LevelStats>), UpsError> {
        self.denoise_with(levels, rule, mode, Update::Stable)
    }

    /// [`UpsSurface::denoise`] with the given update step.
    pub fn denoise_with(
        &self,
        levels: u32,
        rule: impl Fn(usize, usize) -> ThresholdRule,
        mode: Shrink,
        update: Update,
    ) -> Result<(UpsSurface, Vec<LevelStats>), UpsError> {
        let mut dec = self.wavelet_transform_with(levels, update)?;
        let stats = dec.threshold(rule, mode);
        Ok((dec.reconstruct(), stats))
    }

    /// The control triangle of the vertex in `slot`, as control points.
    pub(crate) fn vertex_points(&self, slot: usize) -> [ControlPoint; 3] {
        match self {
            UpsSurface::Functional(s) => {
                let lattice = s.grid().lattice();
                let v = lattice.point(s.grid().lattice_point(slot));
                let q = fixed_ps_triangle(lattice, v);
                std::array::from_fn(|j| {
                    ControlPoint::new(Vector3::new(q.v[j].x, q.v[j].y, s.blocks()[slot][j]))
                })
            }
            UpsSurface::Parametric(s) => s.blocks()[slot].map(ControlPoint::new),
            UpsSurface::Rational(s) => s.blocks()[slot].map(|w| ControlPoint {
                position: w.point,
                weight: w.weight,
            }),
        }
    }

    /// Writes control point `j` of the vertex in `slot` (validated by the caller).
    fn write_point(&mut self, slot: usize, j: usize, p: ControlPoint) {
        match self {
            UpsSurface::Functional(s) => s.blocks_mut()[slot][j] = p.position.z,
            UpsSurface::Parametric(s) => s.blocks_mut()[slot][j] = p.position,
            UpsSurface::Rational(s) => {
                s.blocks_mut()[slot][j] = Weighted {
                    point: p.position,
                    weight: p.weight,
                }
            }
        }
    }
}

/// The wavelet decomposition of a polynomial UPS surface of either kind.
#[derive(Clone, Debug, PartialEq)]
pub enum UpsDecomposition {
    /// Of a functional surface.
    Functional(Decomposition<f64>),
    /// Of a parametric surface.
    Parametric(Decomposition<Vector3<f64>>),
}

/// The details of one vertex at one level: its lattice point and one row of coordinates per
/// control value.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailRow {
    /// The vertex on the finer lattice of its level.
    pub ij: LatticePoint,
    /// The three detail values, each with one number per coordinate.
    pub d: [Vec<f64>; 3],
}

/// Runs `$body` with `$d` bound to the decomposition of either kind.
macro_rules! each_decomposition {
    ($value:expr, $d:ident => $body:expr) => {
        match $value {
            UpsDecomposition::Functional($d) => $body,
            UpsDecomposition::Parametric($d) => $body,
        }
    };
}

impl UpsDecomposition {
    /// The number of detail levels.
    pub fn levels(&self) -> usize {
        each_decomposition!(self, d => d.levels.len())
    }

    /// Per level and coordinate: count, max |d|, norm (level 1 is the coarsest).
    pub fn spectrum(&self) -> Vec<LevelStats> {
        each_decomposition!(self, d => d.spectrum())
    }

    /// The detail coefficients of one level (0 = coarsest) and coordinate.
    pub fn coefficients(&self, level: usize, component: usize) -> Vec<f64> {
        each_decomposition!(self, d => d.coefficients(level, component))
    }

    /// The lattice base of the finer triangulation of `level` (0 = coarsest).
    pub fn level_base(&self, level: usize) -> f64 {
        each_decomposition!(self, d => d.levels[level].grid.lattice().base)
    }

    /// The details of `level` (0 = coarsest), vertex by vertex.
    pub fn detail_rows(&self, level: usize) -> Vec<DetailRow> {
        fn rows<V: Vector>(d: &Decomposition<V>, level: usize) -> Vec<DetailRow> {
            let l = &d.levels[level];
            l.detail_slots()
                .map(|s| DetailRow {
                    ij: l.grid.lattice_point(s),
                    d: l.details[s].map(|v| (0..V::DIM).map(|i| v.coord(i)).collect()),
                })
                .collect()
        }
        each_decomposition!(self, d => rows(d, level))
    }

    /// Shrinks every detail coefficient (see [`Decomposition::threshold`]).
    pub fn threshold(
        &mut self,
        rule: impl Fn(usize, usize) -> ThresholdRule,
        mode: Shrink,
    ) -> Vec<LevelStats> {
        each_decomposition!(self, d => d.threshold(rule, mode))
    }

    /// The spline at the coarsest level.
    pub fn coarse(&self) -> UpsSurface {
        match self {
            UpsDecomposition::Functional(d) => UpsSurface::Functional(d.coarse.clone()),
            UpsDecomposition::Parametric(d) => UpsSurface::Parametric(d.coarse.clone()),
        }
    }

    /// The inverse transform.
    pub fn reconstruct(&self) -> UpsSurface {
        match self {
            UpsDecomposition::Functional(d) => UpsSurface::Functional(d.reconstruct()),
            UpsDecomposition::Parametric(d) => UpsSurface::Parametric(d.reconstruct()),
        }
    }
}

/// A UPS surface with its general PS form, built on first use (for evaluation, pieces and
/// supports). Edits through [`ControlNet`] change both forms alike.
///
/// Control point `3 k + j` is point j of the k-th real vertex in slot order — the same id as
/// in the general form, whose vertex k is that vertex.
#[derive(Debug)]
pub struct UniformSurface {
    ups: UpsSurface,
    slots: Vec<usize>,
    general: OnceLock<Box<Surface>>,
}

impl Clone for UniformSurface {
    fn clone(&self) -> Self {
        let general = OnceLock::new();
        if let Some(g) = self.general.get() {
            let _ = general.set(g.clone());
        }
        UniformSurface {
            ups: self.ups.clone(),
            slots: self.slots.clone(),
            general,
        }
    }
}

impl UniformSurface {
    /// The surface of a uniform form (its general form is built when first needed); fails
    /// when a control value is not usable
    /// ([`UpsSurface::first_unusable_vertex`]), since the general form could not hold it.
    pub fn new(ups: UpsSurface) -> Result<Self, UpsError> {
        if let Some(p) = ups.first_unusable_vertex() {
            return Err(UpsError::UnusableValues { at: [p.x, p.y] });
        }
        Ok(UniformSurface {
            slots: ups.grid().real_slots(),
            ups,
            general: OnceLock::new(),
        })
    }

    /// The uniform form.
    pub fn ups(&self) -> &UpsSurface {
        &self.ups
    }

    /// The general form (functional, parametric or NURPS), built on first use.
    pub fn general(&self) -> &Surface {
        self.general.get_or_init(|| {
            Box::new(
                self.ups
                    .to_general()
                    .expect("a validated uniform triangulation always has a PS basis with t(6), and `new` checked the values"),
            )
        })
    }

    /// True when the general form has been built.
    pub fn has_general(&self) -> bool {
        self.general.get().is_some()
    }

    /// The slot of control point `id`'s vertex.
    fn slot(&self, id: ControlId) -> usize {
        self.slots[id.0 / 3]
    }
}

impl ParametricSurface for UniformSurface {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        // The polygon's corners are its extreme lattice points (no general form needed).
        let grid = self.ups.grid();
        let lattice = grid.lattice();
        grid.polygon().vertices().iter().fold(
            (
                Point2::new(f64::INFINITY, f64::INFINITY),
                Point2::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
            ),
            |(lo, hi), &c| {
                let p = lattice.point(c);
                (
                    Point2::new(lo.x.min(p.x), lo.y.min(p.y)),
                    Point2::new(hi.x.max(p.x), hi.y.max(p.y)),
                )
            },
        )
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        self.general().cursor_near(uv)
    }
    #[inline]
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        self.general().jet_with(uv, cursor)
    }
}

impl PiecewiseSurface for UniformSurface {
    fn piece_count(&self) -> usize {
        // Six sub-triangles per triangle of the uniform triangulation.
        6 * self.ups.grid().triangle_count()
    }
    fn piece_kind(&self) -> PieceKind {
        PieceKind::Triangle
    }
    fn piece_shape(&self, k: usize) -> PieceShape {
        self.general().piece_shape(k)
    }
    #[inline]
    fn piece_jet(&self, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
        self.general().piece_jet(k, at)
    }
}

impl ControlNet for UniformSurface {
    fn control_count(&self) -> usize {
        3 * self.slots.len()
    }
    fn control_point(&self, id: ControlId) -> Option<ControlPoint> {
        (id.0 < self.control_count()).then(|| self.ups.vertex_points(self.slot(id))[id.0 % 3])
    }
    fn is_rational(&self) -> bool {
        self.ups.is_rational()
    }
    fn freedom(&self) -> ControlFreedom {
        match self.ups {
            UpsSurface::Functional(_) => ControlFreedom::Height,
            _ => ControlFreedom::Full,
        }
    }
    fn control_group(&self, id: ControlId) -> Range<usize> {
        3 * (id.0 / 3)..3 * (id.0 / 3) + 3
    }
    fn control_anchor(&self, id: ControlId) -> Point2<f64> {
        let grid = self.ups.grid();
        grid.lattice().point(grid.lattice_point(self.slot(id)))
    }
    fn support(&self, id: ControlId) -> Vec<usize> {
        self.general().support(id)
    }
    fn set_control_points(
        &mut self,
        changes: &[(ControlId, ControlPoint)],
    ) -> Result<Vec<usize>, EditError> {
        let (count, rational) = (self.control_count(), self.is_rational());
        for (id, p) in changes {
            check_point(*id, p, count, rational)?;
        }
        for &(id, p) in changes {
            let slot = self.slot(id);
            self.ups.write_point(slot, id.0 % 3, p);
        }
        match self.general.get_mut() {
            // Same ids, already validated: the general form follows.
            Some(g) => g.set_control_points(changes),
            None => {
                let general = self.general();
                let mut pieces: Vec<usize> = changes
                    .iter()
                    .flat_map(|(id, _)| general.support(*id))
                    .collect();
                pieces.sort_unstable();
                pieces.dedup();
                Ok(pieces)
            }
        }
    }
}
