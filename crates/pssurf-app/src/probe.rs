//! The probe (seed 003): a point on a surface with its exact curvature, two cross-planes
//! through the normal in parametric or principal alignment, the curves in which they cut the
//! surface (normal sections, traced exactly), their osculating circles, the normal and the
//! principal directions.

use nalgebra::{Point2, Point3, Vector3};
use pssurf::interrogate::{
    CoordinateCurve, Curvature, SectionOptions, coordinate_curves, plane_section,
};
use pssurf::surface::{Cursor, ParametricSurface};
use pssurf::text::Significant;

use crate::display::LineVertex;
use crate::scene::Scene;

/// How the two cross-planes are turned about the normal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Alignment {
    /// Along the principal directions (the sections have curvatures κ1 and κ2).
    #[default]
    Principal,
    /// Along the parameter directions s_u and s_v.
    Parametric,
}

/// What the probe shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ProbeSettings {
    /// Alignment of the cross-planes.
    pub alignment: Alignment,
    /// Draw the two cross-planes.
    pub planes: bool,
    /// Draw the curves in which they cut the surface.
    pub sections: bool,
    /// Draw the osculating circles of those curves.
    pub circles: bool,
    /// Draw the normal and the principal directions.
    pub glyphs: bool,
    /// Draw the torsion coils of the coordinate curves (seed 003).
    pub coil: bool,
    /// The size of the planes, sections, circles and glyphs, in percent of their default
    /// (which follows the scene's diameter): 5 … 400.
    pub size_percent: u32,
}

impl ProbeSettings {
    /// The length that sets the probe's drawing sizes in a scene of diameter `diameter`.
    pub fn reach(&self, diameter: f64) -> f64 {
        diameter * f64::from(self.size_percent.clamp(5, 400)) / 100.0
    }
}

impl Default for ProbeSettings {
    fn default() -> Self {
        ProbeSettings {
            alignment: Alignment::Principal,
            planes: true,
            sections: true,
            circles: true,
            glyphs: true,
            coil: false,
            size_percent: 100,
        }
    }
}

/// A probed surface point, everything in scene coordinates.
#[derive(Clone, Debug)]
pub struct Probe {
    /// The object's index when probed.
    pub object: usize,
    /// The object's identity (see `SceneObject::id`).
    pub id: u64,
    /// The object's revision when probed (the probe is recomputed when it changes).
    pub revision: u64,
    /// The parameters.
    pub uv: Point2<f64>,
    /// The point.
    pub point: Vector3<f64>,
    /// The curvature there (in scene units), or None at a singular point.
    pub curvature: Option<Curvature>,
    /// The cross-planes and what lies in them (None at a singular point).
    pub cross: Option<CrossPlanes>,
    /// The u- and v-coordinate curves' Frenet frames and torsion (scene units), if defined.
    pub coordinate: Option<[CoordinateCurve; 2]>,
}

/// The two cross-planes of a probe.
#[derive(Clone, Debug)]
pub struct CrossPlanes {
    /// Unit tangent directions of the two planes (each plane holds it and the normal).
    pub directions: [Vector3<f64>; 2],
    /// The normal curvature in each direction (scene units).
    pub curvatures: [f64; 2],
    /// The curves in which the planes cut the surface.
    pub sections: [Vec<Vector3<f64>>; 2],
}

impl Probe {
    /// One line for the status bar.
    pub fn summary(&self) -> String {
        let f = |x: f64| format!("{:<9}", Significant(x, 5));
        let head = format!(
            "u,v = ({}, {})",
            Significant(self.uv.x, 5),
            Significant(self.uv.y, 5)
        );
        match &self.curvature {
            Some(c) => format!(
                "{head}  K = {}  H = {}  κ1 = {}  κ2 = {}",
                f(c.gaussian),
                f(c.mean),
                f(c.k1),
                f(c.k2)
            ),
            None => format!("{head}  curvature undefined (singular point)"),
        }
    }

    /// The unit normal (scene coordinates), when defined.
    pub fn normal(&self) -> Option<Vector3<f64>> {
        self.curvature.as_ref().map(|c| c.normal)
    }
}

/// Probes object `object` of `scene` at `uv`; `size` is the scene's diameter, which sets how
/// far the sections are traced. None outside the domain.
pub fn probe_at(
    scene: &Scene,
    object: usize,
    uv: Point2<f64>,
    alignment: Alignment,
    size: f64,
) -> Option<Probe> {
    let o = scene.objects.get(object)?;
    let surface = o.surface()?;
    let mut cursor: Cursor = surface.cursor_near(uv);
    let jet = surface.jet_with(uv, &mut cursor).ok()?.jet;
    let m = o.transform.matrix();
    let rotation = m.fixed_view::<3, 3>(0, 0).into_owned() / o.transform.scale;
    let s = o.transform.scale;
    let to_scene = |p: &Vector3<f64>| m.transform_point(&Point3::from(*p)).coords;
    let local = Curvature::from_jet(&jet).ok();
    let cross = local.as_ref().map(|c| {
        let directions = match alignment {
            Alignment::Principal => [c.dir1, c.dir2],
            Alignment::Parametric => [jet.dx.normalize(), jet.dy.normalize()],
        };
        let opts = SectionOptions {
            step: size / (300.0 * s),
            length: 0.25 * size / s,
        };
        let sections = directions.map(|d| {
            plane_section(surface, uv, c.normal.cross(&d), opts)
                .map(|curve| curve.points.iter().map(to_scene).collect())
                .unwrap_or_default()
        });
        CrossPlanes {
            directions: directions.map(|d| rotation * d),
            curvatures: directions.map(|d| c.normal_curvature(d) / s),
            sections,
        }
    });
    let coordinate = coordinate_curves(surface, uv).ok().map(|(cc, _)| {
        cc.map(|mut c| {
            // Curvature and torsion scale as 1/length; the frame rotates.
            c.curvature /= s;
            c.torsion = c.torsion.map(|t| t / s);
            c.tangent = rotation * c.tangent;
            c.normal = c.normal.map(|v| rotation * v);
            c.binormal = c.binormal.map(|v| rotation * v);
            c
        })
    });
    let curvature = local.map(|mut c| {
        // Curvatures scale as 1/length (K as 1/length²); directions rotate.
        c.gaussian /= s * s;
        c.mean /= s;
        c.k1 /= s;
        c.k2 /= s;
        c.normal = rotation * c.normal;
        c.dir1 = rotation * c.dir1;
        c.dir2 = rotation * c.dir2;
        c
    });
    Some(Probe {
        object,
        id: o.id,
        revision: o.revision,
        uv,
        point: to_scene(&jet.value),
        curvature,
        cross,
        coordinate,
    })
}

/// The colours of the first and second cross-plane, and of the normal.
pub const COLORS: [[u8; 3]; 3] = [[220, 60, 30], [30, 90, 220], [20, 150, 60]];

/// The probe's lines for the 3D view (sections, osculating circles, glyphs); `size` is the
/// scene's diameter.
pub fn probe_lines(p: &Probe, settings: &ProbeSettings, size: f64) -> Vec<LineVertex> {
    let mut out = Vec::new();
    let (Some(c), Some(cross)) = (&p.curvature, &p.cross) else {
        return out;
    };
    let n = c.normal;
    let glyph = 0.12 * size;
    for k in 0..2 {
        let color = COLORS[k];
        if settings.sections {
            polyline(&cross.sections[k], color, &mut out);
        }
        if settings.circles {
            let circle = osculating_circle(
                p.point,
                n,
                cross.directions[k],
                cross.curvatures[k],
                0.6 * size,
            );
            polyline(&circle, color, &mut out);
        }
        if settings.glyphs {
            let d = [c.dir1, c.dir2][k];
            let dark = color.map(|x| x / 2);
            polyline(&[p.point - glyph * d, p.point + glyph * d], dark, &mut out);
        }
    }
    if settings.glyphs {
        polyline(&[p.point, p.point + 1.5 * glyph * n], COLORS[2], &mut out);
    }
    if settings.coil
        && let Some(cc) = &p.coordinate
    {
        for (k, c) in cc.iter().enumerate() {
            torsion_coil(p.point, n, c, 0.125 * size, COLORS[k], &mut out);
        }
    }
    out
}

/// The seed's torsion coil of a coordinate curve: a sheet rolled from the normal line at the
/// point, tangent to the curve, curling to the side of the plane (tangent, normal) where the
/// curve's binormal lies. Its first radius is 1/|τ| and shrinks by 20 % every half turn; it
/// is `reach` long and 2·`reach` high. Zero torsion leaves it flat, on the plane.
pub fn torsion_coil(
    point: Vector3<f64>,
    n: Vector3<f64>,
    c: &CoordinateCurve,
    reach: f64,
    color: [u8; 3],
    out: &mut Vec<LineVertex>,
) {
    let t = (c.tangent - n * c.tangent.dot(&n)).normalize();
    let side = n.cross(&t);
    let (tau, b) = (c.torsion.unwrap_or(0.0), c.binormal.unwrap_or(side));
    let m = if b.dot(&side) >= 0.0 { side } else { -side };
    let r0 = if tau == 0.0 {
        f64::INFINITY
    } else {
        1.0 / tau.abs()
    };
    let mut spiral = vec![point];
    let (mut phi, mut travelled, mut q) = (0.0f64, 0.0, point);
    let steps = 200;
    let ds = reach / steps as f64;
    for _ in 0..steps {
        let r = r0 * 0.8f64.powf(phi / std::f64::consts::PI);
        q += (t * phi.cos() + m * phi.sin()) * ds;
        phi += if r.is_finite() { ds / r } else { 0.0 };
        travelled += ds;
        spiral.push(q);
    }
    debug_assert!((travelled - reach).abs() < 1e-9 * reach.max(1.0));
    let dark = color.map(|x| x / 2);
    for h in [-reach, reach] {
        let edge: Vec<Vector3<f64>> = spiral.iter().map(|p| p + n * h).collect();
        polyline(&edge, dark, out);
    }
    for p in spiral.iter().step_by(steps / 8) {
        polyline(&[p - n * reach, p + n * reach], dark, out);
    }
}

/// The corners of the two cross-planes (squares of side 0.25·`size` centred at the point), for
/// drawing them translucent.
pub fn plane_corners(p: &Probe, size: f64) -> Vec<[Vector3<f64>; 4]> {
    let (Some(c), Some(cross)) = (&p.curvature, &p.cross) else {
        return Vec::new();
    };
    let h = 0.125 * size;
    cross
        .directions
        .iter()
        .map(|d| {
            let (a, b) = (d * h, c.normal * h);
            [
                p.point - a - b,
                p.point + a - b,
                p.point + a + b,
                p.point - a + b,
            ]
        })
        .collect()
}

/// The osculating circle of the normal section in direction `d` (normal curvature `kappa`)
/// at `point`: centre point + n/κ, radius 1/|κ|, in the plane of d and n. A large circle is
/// cut to an arc of length about `size` around the point; a flat section is a line.
pub fn osculating_circle(
    point: Vector3<f64>,
    n: Vector3<f64>,
    d: Vector3<f64>,
    kappa: f64,
    size: f64,
) -> Vec<Vector3<f64>> {
    let half = 0.5 * size;
    if kappa.abs() * half < 1e-9 {
        return vec![point - half * d, point + half * d];
    }
    let r = 1.0 / kappa;
    let centre = point + n * r;
    let reach = (half * kappa.abs()).min(std::f64::consts::PI);
    let steps = 128;
    (0..=steps)
        .map(|i| {
            let t = -reach + 2.0 * reach * i as f64 / steps as f64;
            // t = 0 is the point; the circle turns towards the centre.
            centre - n * (r * t.cos()) + d * (r.abs() * t.sin())
        })
        .collect()
}

fn polyline(points: &[Vector3<f64>], color: [u8; 3], out: &mut Vec<LineVertex>) {
    let color = [color[0], color[1], color[2], 255];
    for w in points.windows(2) {
        for p in w {
            out.push(LineVertex {
                position: p.map(|x| x as f32).into(),
                color,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_torsion_coil_is_flat_without_torsion_and_curls_to_the_binormal_with_radius_one_over_tau()
    {
        let (p, n, t) = (Vector3::new(1.0, 2.0, 3.0), Vector3::z(), Vector3::x());
        let curve = |tau: f64, binormal: Vector3<f64>| CoordinateCurve {
            curvature: 1.0,
            torsion: Some(tau),
            tangent: t,
            normal: Some(n),
            binormal: Some(binormal),
        };
        let points = |c: &CoordinateCurve| {
            let mut out = Vec::new();
            torsion_coil(p, n, c, 0.5, [0, 0, 0], &mut out);
            out.iter()
                .map(|v| v.position.map(f64::from).into())
                .collect::<Vec<Vector3<f64>>>()
        };
        // τ = 0: every point lies in the plane of t and n through p.
        for q in points(&curve(0.0, -Vector3::y())) {
            assert!((q.y - p.y).abs() < 1e-6, "{q}");
        }
        // τ = 2: radius 1/2 at first, towards the binormal's side (−y here).
        let q = points(&curve(2.0, -Vector3::y()));
        let bottom: Vec<Vector3<f64>> = q
            .iter()
            .filter(|v| (v.z - (p.z - 0.5)).abs() < 1e-6)
            .copied()
            .collect();
        assert!(bottom.iter().all(|v| v.y <= p.y + 1e-6));
        let near = bottom
            .iter()
            .find(|v| ((*v - p).xy().norm() - 0.05).abs() < 3e-3)
            .unwrap();
        // Its radius there, from the chord c and the deviation d from the tangent: c²/(2d),
        // 1/τ = 0.5 to within the glyph's drawing error (steps of 1/400 of its length).
        let (c, d) = ((near - p).xy().norm(), p.y - near.y);
        assert!(
            (c * c / (2.0 * d) - 0.5).abs() < 0.05,
            "radius {}",
            c * c / (2.0 * d)
        );
    }

    #[test]
    fn an_osculating_circle_passes_through_the_point_with_radius_one_over_kappa() {
        let (p, n, d) = (Vector3::new(1.0, 2.0, 3.0), Vector3::z(), Vector3::x());
        for kappa in [2.0, -0.5, 5.0] {
            let c = osculating_circle(p, n, d, kappa, 10.0);
            let centre = p + n / kappa;
            for q in &c {
                assert!(((q - centre).norm() - 1.0 / kappa.abs()).abs() < 1e-12);
                assert!((q - p).y.abs() < 1e-15, "in the plane of d and n");
            }
            assert!((c[c.len() / 2] - p).norm() < 1e-12, "through the point");
        }
        assert_eq!(osculating_circle(p, n, d, 0.0, 2.0).len(), 2);
    }
}

/// The probe of the running application: where it is, what it found, and its lines for the
/// GPU, recomputed only when its object, its place or its settings change.
#[derive(Debug, Default)]
pub struct ProbeState {
    /// The probed point, if any.
    pub probe: Option<Probe>,
    /// Its lines for the 3D view.
    pub lines: std::sync::Arc<crate::gpu::LineSet>,
    key: Option<(u64, ProbeSettings)>,
}

impl ProbeState {
    /// Puts the probe on object `object` at `uv` (removes it outside the domain); `size` is
    /// the scene's diameter. Returns whether the point lies on the object.
    pub fn set(
        &mut self,
        scene: &Scene,
        object: usize,
        uv: Point2<f64>,
        settings: &ProbeSettings,
        size: f64,
    ) -> bool {
        self.probe = probe_at(scene, object, uv, settings.alignment, settings.reach(size));
        self.key = None;
        self.refresh(scene, settings, size);
        self.probe.is_some()
    }

    /// Removes the probe.
    pub fn clear(&mut self) {
        self.probe = None;
        self.key = None;
        self.lines = Default::default();
    }

    /// Recomputes the probe after its object changed (following it by identity when another
    /// object's removal moved it in the list), and its lines after it or `settings` changed.
    pub fn refresh(&mut self, scene: &Scene, settings: &ProbeSettings, size: f64) {
        if let Some(p) = &self.probe {
            let found = scene.index_of(p.id);
            let stale =
                found.is_none_or(|i| i != p.object || scene.objects[i].revision != p.revision);
            let realigned = self.key.is_some_and(|(_, s)| {
                s.alignment != settings.alignment || s.size_percent != settings.size_percent
            });
            if stale || realigned {
                let (uv, reach) = (p.uv, settings.reach(size));
                self.probe = found.and_then(|i| probe_at(scene, i, uv, settings.alignment, reach));
            }
        }
        let key = self.probe.as_ref().map(|p| (p.revision, *settings));
        if key == self.key && self.key.is_some() {
            return;
        }
        let lines = self
            .probe
            .as_ref()
            .map(|p| probe_lines(p, settings, settings.reach(size)))
            .unwrap_or_default();
        self.lines = std::sync::Arc::new(crate::gpu::LineSet {
            generation: crate::scene::fresh_revision(),
            lines,
        });
        self.key = key;
    }
}
