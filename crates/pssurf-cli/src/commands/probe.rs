//! `pssurf probe`: the probe of seed 003 from the command line (see
//! [`pssurf::interrogate::probe`]), as text or JSON.

use std::path::PathBuf;

use anyhow::{Context, Result};
use nalgebra::{Point2, Vector3};
use pssurf::interrogate::{
    Alignment, CoordinateCurve, CrossPlane, ProbeOptions, SurfaceCurve, probe,
};
use pssurf::surface::ParametricSurface;
use pssurf::text::{Short, Significant};
use serde_json::{Value, json};

/// Cross-plane alignment (`--align`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum AlignArg {
    /// Along the principal directions.
    Principal,
    /// Along the parameter directions s_u, s_v.
    Parametric,
}

/// Arguments of `pssurf probe`.
#[derive(clap::Args, Debug)]
pub struct ProbeArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// The parameters of the point.
    #[arg(long, value_name = "u,v", allow_hyphen_values = true)]
    pub at: String,
    /// How the two cross-planes are turned about the normal.
    #[arg(long, value_enum, default_value_t = AlignArg::Principal)]
    pub align: AlignArg,
    /// How far the normal sections are traced each way (in space; 1e-6 … 10 times the
    /// surface's size, default a tenth of it).
    #[arg(long, value_name = "R")]
    pub extent: Option<f64>,
    /// Write JSON (with the section polylines) instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also write the two normal sections as a curves CSV (curve,u,v,x,y,z), for
    /// `pssurf plot --lines`.
    #[arg(short, long, value_name = "SECTIONS.csv")]
    pub output: Option<PathBuf>,
}

/// The shortest `--extent`, relative to the surface's size.
const MIN_EXTENT: f64 = 1e-6;

/// The longest `--extent`, relative to the surface's size (a section cannot usefully be
/// longer than a few times the surface).
const MAX_EXTENT: f64 = 10.0;

/// Runs `pssurf probe`.
pub fn run(args: &ProbeArgs) -> Result<()> {
    let at = parse_uv(&args.at).with_context(|| format!("--at {}", args.at))?;
    let surface = crate::budget::load_surface(&args.surface)?;
    let size = size(&surface);
    let extent = match args.extent {
        Some(r) if r > 0.0 && r.is_finite() => {
            // A section 1e-9 of the size made 200,000 points (44 MB of JSON) of rounding; one
            // of 1e12 left the domain in its first step (one point).
            let (lo, hi) = (MIN_EXTENT * size, MAX_EXTENT * size);
            if size > 0.0 && size.is_finite() && !(r >= lo && r <= hi) {
                anyhow::bail!(
                    "--extent {} is outside {} … {} ({MIN_EXTENT:e} to {MAX_EXTENT} times the surface's size {})",
                    Short(r),
                    Short(lo),
                    Short(hi),
                    Short(size)
                );
            }
            r
        }
        Some(_) => anyhow::bail!("--extent must be a positive finite number"),
        None => 0.1 * size,
    };
    let opts = ProbeOptions {
        alignment: match args.align {
            AlignArg::Principal => Alignment::Principal,
            AlignArg::Parametric => Alignment::Parametric,
        },
        extent,
        step: extent / 200.0,
    };
    let p = probe(&surface, at, &opts)?;
    if let Some(path) = &args.output {
        let sections: Vec<SurfaceCurve> = p
            .planes
            .iter()
            .map(|c| SurfaceCurve {
                uvs: c.section.uvs.clone(),
                points: c.section.points.clone(),
                closed: c.section.closed,
            })
            .collect();
        crate::output::write_output(path, pssurf::io::Durability::Atomic, |w| {
            Ok(pssurf::io::write_curves_csv(w, &sections)?)
        })?;
    }
    if args.json {
        let v = |x: &Vector3<f64>| json!([x.x, x.y, x.z]);
        let plane = |c: &CrossPlane| {
            json!({
                "direction": v(&c.direction),
                "angle_from_k1_deg": c.angle.to_degrees(),
                "normal_curvature": c.normal_curvature,
                "normal_curvature_from_forms": c.normal_curvature_forms,
                "osculating_circle": c.osculating.map(|o| json!({
                    "centre": v(&o.centre), "radius": o.radius, "axis": v(&o.axis)})),
                "section": c.section.points.iter().map(v).collect::<Vec<Value>>(),
            })
        };
        let curve = |c: &CoordinateCurve| {
            json!({
                "curvature": c.curvature,
                "torsion": c.torsion,
                "tangent": v(&c.tangent),
                "normal": c.normal.as_ref().map(v),
                "binormal": c.binormal.as_ref().map(v),
            })
        };
        let c = &p.curvature;
        let out = json!({
            "uv": [p.uv.x, p.uv.y],
            "point": v(&p.point),
            "normal": v(&c.normal),
            "s_u": v(&p.tangents[0]),
            "s_v": v(&p.tangents[1]),
            "first_form": {"E": p.forms.e, "F": p.forms.f, "G": p.forms.g},
            "second_form": {"L": p.forms.l, "M": p.forms.m, "N": p.forms.n},
            "K": c.gaussian, "H": c.mean, "k1": c.k1, "k2": c.k2,
            "dir1": v(&c.dir1), "dir2": v(&c.dir2),
            "dir1_uv": [c.dir1_uv.x, c.dir1_uv.y], "dir2_uv": [c.dir2_uv.x, c.dir2_uv.y],
            "umbilic": p.umbilic,
            "cross_planes": p.planes.iter().map(plane).collect::<Vec<Value>>(),
            "coordinate_curves": {"u": curve(&p.coordinate_curves[0]), "v": curve(&p.coordinate_curves[1])},
            "torsion_source": p.torsion_source,
        });
        return emit(serde_json::to_string_pretty(&out)? + "\n");
    }
    emit(text(&p))
}

/// Writes the report to standard output.
fn emit(text: String) -> Result<()> {
    crate::output::write_output(
        std::path::Path::new("-"),
        pssurf::io::Durability::Atomic,
        |w| Ok(w.write_all(text.as_bytes())?),
    )
}

/// `u,v` as a point.
fn parse_uv(text: &str) -> Result<Point2<f64>> {
    let (a, b) = text.split_once(',').context("expected u,v")?;
    let (u, v): (f64, f64) = (a.trim().parse()?, b.trim().parse()?);
    anyhow::ensure!(u.is_finite() && v.is_finite(), "u and v must be finite");
    Ok(Point2::new(u, v))
}

/// The diagonal of the surface's bounding box, from a few points of the domain.
fn size(surface: &pssurf::surface::Surface) -> f64 {
    let (lo, hi) = surface.domain_bounds();
    let mut pts = Vec::new();
    for i in 0..=8 {
        for j in 0..=8 {
            let uv =
                lo + (hi - lo).component_mul(&nalgebra::Vector2::new(i as f64, j as f64)) / 8.0;
            if let Ok(p) = surface.point(uv) {
                pts.push(p);
            }
        }
    }
    let (mut a, mut b) = (
        Vector3::repeat(f64::INFINITY),
        Vector3::repeat(f64::NEG_INFINITY),
    );
    for p in &pts {
        a = a.inf(p);
        b = b.sup(p);
    }
    let d = (b - a).norm();
    if d.is_finite() && d > 0.0 {
        d
    } else {
        (hi - lo).norm()
    }
}

fn text(p: &pssurf::interrogate::ProbeReport) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let s = |x: f64| Significant(x, 8).to_string();
    let v = |x: &Vector3<f64>| format!("({}, {}, {})", s(x.x), s(x.y), s(x.z));
    let c = &p.curvature;
    let _ = writeln!(
        out,
        "point        s({}, {}) = {}",
        s(p.uv.x),
        s(p.uv.y),
        v(&p.point)
    );
    let _ = writeln!(out, "normal       {}", v(&c.normal));
    let _ = writeln!(
        out,
        "first form   E = {}  F = {}  G = {}",
        s(p.forms.e),
        s(p.forms.f),
        s(p.forms.g)
    );
    let _ = writeln!(
        out,
        "second form  L = {}  M = {}  N = {}",
        s(p.forms.l),
        s(p.forms.m),
        s(p.forms.n)
    );
    let _ = writeln!(
        out,
        "curvature    K = {}  H = {}  κ1 = {}  κ2 = {}{}",
        s(c.gaussian),
        s(c.mean),
        s(c.k1),
        s(c.k2),
        if p.umbilic { "  (umbilic)" } else { "" }
    );
    let _ = writeln!(out, "directions   d1 = {}  d2 = {}", v(&c.dir1), v(&c.dir2));
    for (k, plane) in p.planes.iter().enumerate() {
        let _ = writeln!(
            out,
            "plane {}      direction {} at {}° from d1: κn = {} (Euler), {} (II/I); section of {} points; osculating radius {}",
            k + 1,
            v(&plane.direction),
            s(plane.angle.to_degrees()),
            s(plane.normal_curvature),
            s(plane.normal_curvature_forms),
            plane.section.points.len(),
            plane
                .osculating
                .map_or("∞ (no curvature)".to_string(), |o| s(o.radius)),
        );
    }
    for (name, cc) in ["u", "v"].iter().zip(&p.coordinate_curves) {
        let _ = writeln!(
            out,
            "{name}-curve      curvature {}  torsion {}",
            s(cc.curvature),
            cc.torsion
                .map_or("undefined (a straight line here)".to_string(), s)
        );
    }
    let _ = writeln!(out, "torsion      {}", p.torsion_source);
    out
}
