//! `pssurf edit`: prescribe a curvature at a point (issue 16). On a surface file the control
//! points near the point move (`pssurf::edit::local`); with `--graph-demo` the paper's method
//! runs on a built-in polynomial graph patch (`pssurf::edit::graph`) and writes the result as
//! a NURBS surface.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use nalgebra::Point2;
use pssurf::edit::graph::{Direction, GraphEditRequest, GraphPatch, GraphTarget, measure_on};
use pssurf::edit::{EditRequest, Measure, edit_locally};
use pssurf::surface::{ParametricSurface, Surface};
use pssurf::text::Significant;

/// What to keep while editing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Keep {
    /// The point s(u, v) stays where it is.
    Point,
    /// The tangent plane at the point stays.
    Tangent,
}

/// The coordinate curve of a graph edit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CurveDirection {
    /// The u curve (v fixed).
    U,
    /// The v curve (u fixed).
    V,
}

/// Arguments of `pssurf edit`.
#[derive(clap::Args, Debug)]
pub struct EditArgs {
    /// The surface file to edit (a PS, UPS or NURPS surface; Bézier and NURBS surfaces too).
    #[arg(value_name = "SURF.json", required_unless_present = "graph_demo")]
    pub input: Option<PathBuf>,
    /// Run the paper's method on the built-in graph patch X(u, v) = (u, h, v),
    /// h = 0.2 u² + 0.1 u v + 0.3 v² + 0.05 u³ on [−1, 1]², and write the result as NURBS.
    #[arg(long, conflicts_with = "input")]
    pub graph_demo: bool,
    /// The parameter point "u,v" (graph demo default: 0.1,-0.2).
    #[arg(long, value_name = "U,V", allow_hyphen_values = true)]
    pub at: Option<String>,
    /// What to prescribe: ku, kv (normal curvature in u, v), k1, k2, K or H, as NAME=VALUE;
    /// for the graph demo also cu, cv (the curvature (1) of the u or v coordinate curve).
    #[arg(long, value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub set: String,
    /// The region: a radius around the point (surface files: control points anchored within
    /// it may move; default 2.5 × the longest edge of the triangle at the point), or for the
    /// graph demo a half-width, or "u0,u2,v0,v2" (default -0.5,0.6,-0.7,0.4).
    #[arg(long, value_name = "R|U0,U2,V0,V2", allow_hyphen_values = true)]
    pub region: Option<String>,
    /// Keep the point, the tangent plane or both ("point,tangent").
    #[arg(long, value_enum, value_delimiter = ',')]
    pub keep: Vec<Keep>,
    /// Graph demo: C^k continuity at the region's border (0, 1 or 2).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub continuity: u8,
    /// Graph demo: twist the coordinate curve to this torsion (with --set cu=… or cv=… for its
    /// curvature).
    #[arg(long, value_name = "SIGMA", allow_hyphen_values = true)]
    pub torsion: Option<f64>,
    /// Graph demo: which coordinate curve carries the edit (default: from cu/cv, else u).
    #[arg(long, value_enum)]
    pub direction: Option<CurveDirection>,
    /// The surface file to write (binary when it ends in `.psb`, else JSON; docs/format.md).
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// Parses "NAME=VALUE".
fn parse_set(s: &str) -> Result<(String, f64)> {
    let (name, value) = s
        .split_once('=')
        .with_context(|| format!("--set {s}: write NAME=VALUE, e.g. --set K=0.25"))?;
    let v: f64 = value
        .trim()
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite())
        .with_context(|| format!("--set {s}: `{value}` is not a finite number"))?;
    Ok((name.trim().to_string(), v))
}

/// Parses comma-separated finite numbers.
fn numbers(s: &str, what: &str) -> Result<Vec<f64>> {
    s.split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .with_context(|| format!("{what} `{s}`: `{t}` is not a finite number"))
        })
        .collect()
}

/// Runs `pssurf edit`.
pub fn run(args: &EditArgs) -> Result<()> {
    let (name, value) = parse_set(&args.set)?;
    if args.graph_demo {
        return graph_demo(args, &name, value);
    }
    let input = args.input.as_ref().expect("clap requires it");
    let Some(measure) = Measure::parse(&name) else {
        bail!(
            "--set {name}=…: the measure is one of ku, kv, k1, k2, K, H (cu and cv are for --graph-demo)"
        );
    };
    if args.torsion.is_some() {
        bail!(
            "--torsion is for --graph-demo: the coordinate curves of PS surfaces are planar pieces, without torsion"
        );
    }
    let at = match &args.at {
        Some(a) => match numbers(a, "--at")?.as_slice() {
            [u, v] => Point2::new(*u, *v),
            _ => bail!("--at `{a}`: give u,v"),
        },
        None => bail!("give the point with --at u,v"),
    };
    let mut surface = crate::budget::load_surface(input)?;
    surface.jet(at).map_err(|_| {
        anyhow::anyhow!("--at {},{}: the point lies outside the domain", at.x, at.y)
    })?;
    let radius = match &args.region {
        Some(r) => match numbers(r, "--region")?.as_slice() {
            [r] if *r > 0.0 => *r,
            _ => bail!("--region `{r}`: give one positive radius"),
        },
        None => pssurf::edit::default_radius(&surface, at).unwrap_or(1.0),
    };
    let req = EditRequest {
        at,
        measure,
        target: value,
        radius,
        keep_point: args.keep.contains(&Keep::Point),
        keep_tangent: args.keep.contains(&Keep::Tangent),
    };
    let e = edit_locally(&mut surface, &req)?;
    crate::output::save_surface(&surface, &args.output)?;
    let groups: std::collections::BTreeSet<usize> = e.changes.iter().map(|c| c.id.0 / 3).collect();
    eprintln!(
        "{} at ({}, {}): {} -> {} (asked {}), {} iterations",
        measure.description(),
        at.x,
        at.y,
        Significant(e.before, 10),
        Significant(e.after, 12),
        value,
        e.iterations
    );
    eprintln!(
        "moved {} control points of {} control groups ({} free within radius {}); largest move {}; wrote {}",
        e.changes.len(),
        groups.len(),
        e.free_groups,
        Significant(radius, 4),
        Significant(e.largest_move, 4),
        args.output.display()
    );
    Ok(())
}

/// The paper's method on the built-in graph patch.
fn graph_demo(args: &EditArgs, name: &str, value: f64) -> Result<()> {
    let patch = GraphPatch::demo();
    let at = match &args.at {
        Some(a) => match numbers(a, "--at")?.as_slice() {
            [u, v] => [*u, *v],
            _ => bail!("--at `{a}`: give u,v"),
        },
        None => [0.1, -0.2],
    };
    let region = match &args.region {
        None => [[-0.5, 0.6], [-0.7, 0.4]],
        Some(r) => match numbers(r, "--region")?.as_slice() {
            [w] if *w > 0.0 => [[at[0] - w, at[0] + w], [at[1] - w, at[1] + w]],
            [u0, u2, v0, v2] => [[*u0, *u2], [*v0, *v2]],
            _ => bail!("--region `{r}`: give a half-width or u0,u2,v0,v2"),
        },
    };
    let direction = match (args.direction, name) {
        (Some(CurveDirection::V), _) | (None, "cv") => Direction::V,
        _ => Direction::U,
    };
    let target = match (name, args.torsion) {
        ("cu" | "cv", None) => GraphTarget::Curvature(value),
        ("cu" | "cv", Some(sigma)) => GraphTarget::Torsion {
            curvature: value,
            torsion: sigma,
        },
        (_, Some(_)) => {
            bail!("--torsion goes with --set cu=λ or cv=λ (the twisted curve's curvature)")
        }
        (m, None) => match Measure::parse(m) {
            Some(measure) => GraphTarget::Measure(measure, value),
            None => bail!("--set {m}=…: one of cu, cv, ku, kv, k1, k2, K, H"),
        },
    };
    let k = args.continuity as usize;
    let req = GraphEditRequest {
        at,
        region,
        direction,
        continuity: [k, k],
        target,
    };
    let edit = patch.edit(&req)?;
    let nurbs = edit.to_nurbs();
    crate::output::save_surface(&Surface::Nurbs(nurbs.clone()), &args.output)?;
    match target {
        GraphTarget::Measure(m, _) => eprintln!(
            "{} at ({}, {}): {} -> {} (asked {value})",
            m.description(),
            at[0],
            at[1],
            Significant(m.of(&patch.jet(at[0], at[1])).unwrap_or(f64::NAN), 10),
            Significant(measure_on(&nurbs, m, at).unwrap_or(f64::NAN), 12),
        ),
        GraphTarget::Torsion { .. } => {}
        GraphTarget::Curvature(_) => {
            let kappa = coordinate_curvature(&nurbs, at, direction);
            eprintln!(
                "curvature of the {} coordinate curve at ({}, {}): {} (asked {value})",
                if direction == Direction::U { "u" } else { "v" },
                at[0],
                at[1],
                Significant(kappa, 12)
            );
        }
    }
    if let (Some((f, g)), Some(sigma)) = (&edit.twisted, args.torsion) {
        let r1 = if direction == Direction::U {
            at[0]
        } else {
            at[1]
        };
        let d = |p: &pssurf::edit::graph::Poly1, m| p.derivative(m, r1);
        let a1 = nalgebra::Vector3::new(1.0, d(f, 1), d(g, 1));
        let a2 = nalgebra::Vector3::new(0.0, d(f, 2), d(g, 2));
        let a3 = nalgebra::Vector3::new(0.0, d(f, 3), d(g, 3));
        let cross = a1.cross(&a2);
        eprintln!(
            "twisted curve: curvature {}, torsion {} (asked {sigma}); the surface contains it at the {} nodes",
            Significant(cross.norm() / a1.norm().powi(3), 12),
            Significant(cross.dot(&a3) / cross.norm_squared(), 12),
            edit.nodes.len()
        );
    }
    eprintln!(
        "C{k} continuity at the border of [{}, {}] x [{}, {}]; wrote {} (a NURBS surface of degrees {} x {})",
        region[0][0],
        region[0][1],
        region[1][0],
        region[1][1],
        args.output.display(),
        nurbs.degree()[0],
        nurbs.degree()[1]
    );
    Ok(())
}

/// The curvature (1) of the coordinate curve through `at` of a graph X = (u, h, v), signed:
/// h''/(1 + h'²)^{3/2} along the curve.
fn coordinate_curvature(s: &pssurf::nurbs::NurbsSurface, at: [f64; 2], d: Direction) -> f64 {
    let j = s
        .jet(Point2::new(at[0], at[1]))
        .map_or_else(|_| None, |j| Some(j.jet));
    let Some(j) = j else { return f64::NAN };
    let (slope, second) = match d {
        Direction::U => (j.dx.y, j.dxx.y),
        Direction::V => (j.dy.y, j.dyy.y),
    };
    second / (1.0 + slope * slope).powf(1.5)
}
