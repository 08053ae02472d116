//! Curves traced on the scene's surfaces (issue 15): level lines of a field, lines of
//! curvature, asymptotic lines and geodesics, kept per object and drawn in the 3D view (scene
//! coordinates) and the domain view (parameters). They follow their object: after a drag of
//! a control point only the seeded curves that pass through the moved vertex's support are
//! traced again; level lines (whose connectivity can change anywhere) and any other change of
//! the surface trace the whole set again.

use std::sync::Arc;

use nalgebra::{Point2, Point3, Vector3};
use pssurf::interrogate::{
    FieldLineOptions, GeodesicOptions, LineFamily, SurfaceCurve, SurfaceField, ZeroSetOptions,
    auto_levels, even_field_lines, level_lines, shortest_geodesic, trace_field_line,
};
use pssurf::surface::{ParametricSurface, Surface};

use crate::display::LineVertex;
use crate::gpu::LineSet;
use crate::scene::{Scene, SceneObject};

/// The most points of one traced set (bounded work while dragging).
pub const MAX_POINTS: usize = 200_000;

/// What to trace.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum CurveRequest {
    /// Level lines of a field (`K`, `H`, `z`, a formula …) at levels given as `0,0.5` or
    /// `auto:N`.
    Levels {
        /// The field.
        field: String,
        /// The levels.
        levels: String,
    },
    /// Evenly spaced lines of curvature (both families), about 1/`seeds` of the domain's
    /// diagonal apart.
    CurvatureLines {
        /// Lines across the domain.
        seeds: u32,
    },
    /// Evenly spaced asymptotic lines (both families) where K < 0.
    AsymptoticLines {
        /// Lines across the domain.
        seeds: u32,
    },
    /// The shortest geodesic between two parameter points.
    Geodesic {
        /// The start (u, v).
        from: [f64; 2],
        /// The end (u, v).
        to: [f64; 2],
    },
}

impl CurveRequest {
    /// A short description for lists and messages.
    pub fn describe(&self) -> String {
        match self {
            CurveRequest::Levels { field, levels } => format!("{field} = {levels}"),
            CurveRequest::CurvatureLines { seeds } => format!("lines of curvature ({seeds})"),
            CurveRequest::AsymptoticLines { seeds } => format!("asymptotic lines ({seeds})"),
            CurveRequest::Geodesic { from, to } => format!(
                "geodesic ({:.3}, {:.3}) to ({:.3}, {:.3})",
                from[0], from[1], to[0], to[1]
            ),
        }
    }
}

/// One traced curve with what is needed to trace it again.
#[derive(Clone, Debug)]
pub struct TracedCurve {
    /// The polyline (object coordinates).
    pub curve: SurfaceCurve,
    /// Its colour.
    pub color: [u8; 3],
    /// How to trace it again alone (a seeded line), or None (part of a level set).
    pub seed: Option<(LineFamily, Point2<f64>)>,
    /// The pieces it passes through, sorted.
    pub pieces: Vec<usize>,
}

/// A traced set of curves on one object.
#[derive(Clone, Debug)]
pub struct CurveSet {
    /// The object's identity.
    pub object: u64,
    /// The object's revision the curves belong to.
    pub revision: u64,
    /// What was asked.
    pub request: CurveRequest,
    /// The curves.
    pub curves: Vec<TracedCurve>,
    /// One line about the result (counts, or why nothing was traced).
    pub summary: String,
}

/// Colours of the families and of level lines.
const COLORS: [[u8; 3]; 4] = [[200, 40, 40], [30, 80, 200], [20, 140, 60], [150, 60, 170]];

/// Traces `request` on `surface`; an error says why nothing could be traced.
pub fn trace(
    surface: &Surface,
    request: &CurveRequest,
) -> Result<(Vec<TracedCurve>, String), String> {
    match request {
        CurveRequest::Levels { field, levels } => {
            let f = SurfaceField::parse(field).map_err(|e| e.to_string())?;
            let values = parse_levels(surface, &f, levels)?;
            let opts = ZeroSetOptions {
                max_points: MAX_POINTS,
                ..ZeroSetOptions::default()
            };
            let sets = level_lines(surface, &f, &values, &opts).map_err(|e| e.to_string())?;
            let mut out = Vec::new();
            let mut gaps = 0;
            for (k, s) in sets.into_iter().enumerate() {
                gaps += s.gaps.len();
                out.extend(
                    s.curves
                        .into_iter()
                        .map(|c| traced(surface, c, COLORS[k % 4], None)),
                );
            }
            let summary = format!(
                "{} curves on {} levels, {gaps} gaps",
                out.len(),
                values.len()
            );
            Ok((out, summary))
        }
        CurveRequest::CurvatureLines { seeds } | CurveRequest::AsymptoticLines { seeds } => {
            let families = if matches!(request, CurveRequest::CurvatureLines { .. }) {
                LineFamily::CURVATURE
            } else {
                LineFamily::ASYMPTOTIC
            };
            let (lo, hi) = surface.domain_bounds();
            let spacing = (hi - lo).norm() / f64::from((*seeds).clamp(1, 200));
            let mut out = Vec::new();
            for (k, family) in families.into_iter().enumerate() {
                let even =
                    even_field_lines(surface, family, spacing, &line_options(), MAX_POINTS / 2);
                out.extend(even.lines.into_iter().map(|l| {
                    let seed = l.curve.uvs[l.seed];
                    traced(surface, l.curve, COLORS[k], Some((family, seed)))
                }));
            }
            let summary = format!("{} lines", out.len());
            Ok((out, summary))
        }
        CurveRequest::Geodesic { from, to } => {
            let (a, b) = (Point2::new(from[0], from[1]), Point2::new(to[0], to[1]));
            let g = shortest_geodesic(surface, a, b, &GeodesicOptions::default())
                .map_err(|e| e.to_string())?;
            let summary = format!(
                "length {:.6}{}",
                g.length,
                if g.exact { "" } else { " (relaxed polyline)" }
            );
            Ok((vec![traced(surface, g.curve, COLORS[2], None)], summary))
        }
    }
}

fn line_options() -> FieldLineOptions {
    FieldLineOptions {
        max_points: 5_000,
        ..FieldLineOptions::default()
    }
}

/// `0,0.5` or `auto:N` (N from 1 to 100).
fn parse_levels(surface: &Surface, field: &SurfaceField, text: &str) -> Result<Vec<f64>, String> {
    if let Some(n) = text.trim().strip_prefix("auto:") {
        let n: usize = n
            .trim()
            .parse()
            .ok()
            .filter(|n| (1..=100).contains(n))
            .ok_or("auto:N needs N from 1 to 100")?;
        return Ok(auto_levels(surface, field, n));
    }
    let values: Vec<f64> = text
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| "levels are numbers separated by commas, or auto:N")?;
    if values.is_empty() || values.len() > 100 || !values.iter().all(|x| x.is_finite()) {
        return Err("give 1 to 100 finite levels".into());
    }
    Ok(values)
}

/// A traced curve with the pieces it passes through.
fn traced(
    surface: &Surface,
    curve: SurfaceCurve,
    color: [u8; 3],
    seed: Option<(LineFamily, Point2<f64>)>,
) -> TracedCurve {
    let mut cursor = surface.cursor_near(curve.uvs.first().copied().unwrap_or_default());
    let mut pieces: Vec<usize> = curve
        .uvs
        .iter()
        .filter_map(|uv| surface.jet_with(*uv, &mut cursor).ok().map(|j| j.piece))
        .collect();
    pieces.sort_unstable();
    pieces.dedup();
    TracedCurve {
        curve,
        color,
        seed,
        pieces,
    }
}

/// The curves of the running application and their lines for the 3D view.
#[derive(Debug, Default)]
pub struct CurvesState {
    /// The traced sets, oldest first.
    pub sets: Vec<CurveSet>,
    /// Their lines in scene coordinates.
    pub lines: Arc<LineSet>,
    /// Whether `lines` must be rebuilt.
    dirty: bool,
}

/// Why curves are not traced on an object.
const CURVES_NEED_A_SURFACE: &str = "curves are traced on surfaces, and this object is a mesh";

impl CurvesState {
    /// Traces `request` on object `object` and keeps the result; the summary or the error.
    pub fn add(
        &mut self,
        scene: &Scene,
        object: usize,
        request: CurveRequest,
    ) -> Result<String, String> {
        let o = scene.objects.get(object).ok_or("no such object")?;
        let surface = o.surface().ok_or(CURVES_NEED_A_SURFACE)?;
        let (curves, summary) = trace(surface, &request)?;
        self.sets.push(CurveSet {
            object: o.id,
            revision: o.revision,
            request,
            curves,
            summary: summary.clone(),
        });
        self.dirty = true;
        Ok(summary)
    }

    /// Removes every set on object `id` (all sets for None).
    pub fn clear(&mut self, id: Option<u64>) {
        self.sets.retain(|s| id.is_some_and(|id| s.object != id));
        self.dirty = true;
    }

    /// After a drag moved control group of object `object` from revision `old`, changing
    /// `pieces`: traces again only the seeded curves that pass through those pieces.
    pub fn edited(&mut self, o: &SceneObject, old: u64, pieces: &[usize]) {
        let Some(surface) = o.surface() else {
            return;
        };
        for set in self
            .sets
            .iter_mut()
            .filter(|s| s.object == o.id && s.revision == old)
        {
            if !matches!(
                set.request,
                CurveRequest::CurvatureLines { .. } | CurveRequest::AsymptoticLines { .. }
            ) {
                continue; // traced again as a whole by `refresh`
            }
            for c in &mut set.curves {
                let touched = c.pieces.iter().any(|p| pieces.binary_search(p).is_ok());
                if let (true, Some((family, seed))) = (touched, c.seed) {
                    match trace_field_line(surface.as_ref(), family, seed, &line_options()) {
                        Ok(line) => *c = traced(surface, line.curve, c.color, Some((family, seed))),
                        Err(_) => c.curve = SurfaceCurve::default(),
                    }
                }
            }
            set.revision = o.revision;
            self.dirty = true;
        }
    }

    /// Traces again the sets whose object changed otherwise, drops the sets of deleted
    /// objects, and rebuilds the lines when anything changed.
    pub fn refresh(&mut self, scene: &Scene) {
        let before = self.sets.len();
        self.sets.retain(|s| scene.index_of(s.object).is_some());
        self.dirty |= self.sets.len() != before;
        for set in &mut self.sets {
            let Some(o) = scene.index_of(set.object).map(|i| &scene.objects[i]) else {
                continue;
            };
            if o.revision == set.revision {
                continue;
            }
            let traced = (o.surface().ok_or_else(|| CURVES_NEED_A_SURFACE.to_string()))
                .and_then(|s| trace(s, &set.request));
            match traced {
                Ok((curves, summary)) => (set.curves, set.summary) = (curves, summary),
                Err(e) => (set.curves, set.summary) = (Vec::new(), e),
            }
            set.revision = o.revision;
            self.dirty = true;
        }
        if self.dirty {
            self.lines = Arc::new(LineSet {
                generation: crate::scene::fresh_revision(),
                lines: self.scene_lines(scene),
            });
            self.dirty = false;
        }
    }

    /// Line-list vertices of every curve, in scene coordinates.
    fn scene_lines(&self, scene: &Scene) -> Vec<LineVertex> {
        let mut out = Vec::new();
        for set in &self.sets {
            let Some(o) = scene.index_of(set.object).map(|i| &scene.objects[i]) else {
                continue;
            };
            if !o.visible {
                continue;
            }
            let m = o.transform.matrix();
            let to_scene = |p: &Vector3<f64>| m.transform_point(&Point3::from(*p)).coords;
            for c in &set.curves {
                let color = [c.color[0], c.color[1], c.color[2], 255];
                let pts: Vec<Vector3<f64>> = c.curve.points.iter().map(to_scene).collect();
                let closing = c.curve.closed.then(|| [pts.last(), pts.first()]);
                for w in pts
                    .windows(2)
                    .map(|w| [Some(&w[0]), Some(&w[1])])
                    .chain(closing)
                {
                    if let [Some(a), Some(b)] = w {
                        for p in [a, b] {
                            out.push(LineVertex {
                                position: p.map(|x| x as f32).into(),
                                color,
                            });
                        }
                    }
                }
            }
        }
        out
    }

    /// The parameter polylines of object `id` with their colours (for the domain view).
    pub fn domain_polylines(&self, id: u64) -> Vec<(Vec<Point2<f64>>, [u8; 3])> {
        self.sets
            .iter()
            .filter(|s| s.object == id)
            .flat_map(|s| s.curves.iter())
            .map(|c| {
                let mut uvs = c.curve.uvs.clone();
                if c.curve.closed
                    && let Some(first) = uvs.first()
                {
                    uvs.push(*first);
                }
                (uvs, c.color)
            })
            .collect()
    }
}
