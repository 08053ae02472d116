//! `pssurf curve POLYGON.csv --subdivide chaikin|cubic|four-point --times N [--closed]
//! -o OUT.csv`: subdivision curves (issue 20, part 2; `pssurf::subdivision::curves`);
//! `pssurf curve CURVE.json --comb [--scale s] -o COMB.svg|csv`: the curvature comb of a
//! NURBS or Bézier curve file (part 1; `pssurf::interrogate::comb`).

use std::path::PathBuf;

use anyhow::{Result, bail};
use nalgebra::Vector3;
use pssurf::io::Durability;
use pssurf::subdivision::{CurveScheme, limit_points, subdivide_curve};

/// The scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SchemeArg {
    /// Chaikin's corner cutting (the quadratic B-spline).
    Chaikin,
    /// The cubic B-spline scheme.
    Cubic,
    /// The interpolatory four-point scheme (see --tension).
    FourPoint,
}

/// Arguments of `pssurf curve`.
#[derive(clap::Args, Debug)]
pub struct CurveArgs {
    /// The polygon (a CSV file with columns x, y and optionally z) for --subdivide, or a
    /// curve file (docs/format.md, "Curves") for --comb.
    #[arg(value_name = "POLYGON.csv|CURVE.json")]
    pub input: PathBuf,
    /// The subdivision scheme.
    #[arg(
        long,
        value_enum,
        required_unless_present = "comb",
        conflicts_with = "comb"
    )]
    pub subdivide: Option<SchemeArg>,
    /// Draw the curvature comb of a curve file: teeth of length scale × κ along the normal,
    /// outward, and their envelope. SVG (x, y) or CSV (t,x,y,z,kappa,tip_x,tip_y,tip_z).
    #[arg(long)]
    pub comb: bool,
    /// The comb's scale (default: the longest tooth is a quarter of the curve's extent).
    #[arg(long, allow_hyphen_values = true)]
    pub scale: Option<f64>,
    /// Teeth per knot span.
    #[arg(long, default_value_t = 24, value_parser = clap::value_parser!(u32).range(1..=10000))]
    pub samples: u32,
    /// How many steps (each doubles the points).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(0..=40))]
    pub times: u32,
    /// The polygon is closed (its last point joins its first).
    #[arg(long)]
    pub closed: bool,
    /// The four-point scheme's tension w (1/16 reproduces cubics).
    #[arg(long, default_value_t = 1.0 / 16.0, allow_hyphen_values = true)]
    pub tension: f64,
    /// Write the limit points in closed form (Chaikin: edge midpoints; cubic:
    /// (p₋ + 4p + p₊)/6; four-point: the points) of the subdivided polygon instead of it.
    #[arg(long)]
    pub limit: bool,
    /// The CSV file to write (x,y,z).
    #[arg(short, long, value_name = "OUT.csv")]
    pub output: PathBuf,
}

/// Runs `pssurf curve`.
pub fn run(args: &CurveArgs) -> Result<()> {
    let Some(subdivide) = args.subdivide else {
        return comb(args);
    };
    let table = crate::table::Table::read_columns(&args.input, Some(&["x", "y", "z"]))?;
    let (Some(x), Some(y)) = (table.column("x"), table.column("y")) else {
        bail!(
            "{}: needs columns x and y (and optionally z)",
            args.input.display()
        );
    };
    let z = table.column("z");
    let points: Vec<Vector3<f64>> = table
        .rows
        .iter()
        .map(|r| Vector3::new(r[x], r[y], z.map_or(0.0, |z| r[z])))
        .collect();
    let scheme = match subdivide {
        SchemeArg::Chaikin => CurveScheme::Chaikin,
        SchemeArg::Cubic => CurveScheme::CubicBSpline,
        SchemeArg::FourPoint => CurveScheme::FourPoint {
            tension: args.tension,
        },
    };
    let mut out = subdivide_curve(&points, args.closed, scheme, args.times as usize)?;
    if args.limit {
        out = limit_points(&out, args.closed, scheme)?;
    }
    crate::output::write_output(&args.output, Durability::Atomic, |w| {
        writeln!(w, "x,y,z")?;
        for p in &out {
            writeln!(w, "{},{},{}", p.x, p.y, p.z)?;
        }
        Ok(())
    })?;
    eprintln!(
        "{} points -> {} after {} steps{}; wrote {}",
        points.len(),
        out.len(),
        args.times,
        if args.limit { " (limit points)" } else { "" },
        args.output.display()
    );
    Ok(())
}

/// The curvature comb of a curve file.
fn comb(args: &CurveArgs) -> Result<()> {
    let curve = crate::budget::load_curve(&args.input)?;
    let probe = pssurf::interrogate::comb::curvature_comb(&curve, args.samples as usize, 0.0);
    let (lo, hi) = extent(probe.iter().map(|t| t.point));
    let size = (hi - lo).norm().max(f64::MIN_POSITIVE);
    let kmax = probe
        .iter()
        .map(|t| t.curvature)
        .filter(|k| k.is_finite())
        .fold(0.0, f64::max);
    let scale = match args.scale {
        Some(s) if s.is_finite() && s >= 0.0 => s,
        Some(s) => bail!("--scale {s}: give a finite number ≥ 0"),
        None if kmax > 0.0 => 0.25 * size / kmax,
        None => 0.0,
    };
    let teeth = pssurf::interrogate::comb::curvature_comb(&curve, args.samples as usize, scale);
    if teeth
        .iter()
        .any(|t| !t.tip.iter().all(|x| x.abs() <= pssurf::limits::MAX_VALUE))
    {
        bail!("--scale {scale}: the longest tooth would reach beyond ±1e60; give a smaller scale");
    }
    let svg = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    crate::output::write_output(&args.output, Durability::Atomic, |w| {
        if svg {
            write_svg(w, &teeth)
        } else {
            writeln!(w, "t,x,y,z,kappa,tip_x,tip_y,tip_z")?;
            for t in &teeth {
                let (p, q) = (t.point, t.tip);
                writeln!(
                    w,
                    "{},{},{},{},{},{},{},{}",
                    t.t, p.x, p.y, p.z, t.curvature, q.x, q.y, q.z
                )?;
            }
            Ok(())
        }
    })?;
    eprintln!(
        "{} teeth, curvature from {} to {}, scale {}; wrote {}",
        teeth.len(),
        pssurf::text::Significant(
            teeth
                .iter()
                .map(|t| t.curvature)
                .fold(f64::INFINITY, f64::min),
            4
        ),
        pssurf::text::Significant(kmax, 4),
        pssurf::text::Significant(scale, 4),
        args.output.display()
    );
    Ok(())
}

/// The bounding box of points.
fn extent(points: impl Iterator<Item = Vector3<f64>>) -> (Vector3<f64>, Vector3<f64>) {
    points.fold(
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.inf(&p), hi.sup(&p)),
    )
}

/// The comb in the (x, y) plane as SVG: the curve in black, the teeth in grey, the envelope
/// in orange.
fn write_svg(
    w: &mut dyn std::io::Write,
    teeth: &[pssurf::interrogate::comb::CombTooth],
) -> Result<()> {
    let (lo, hi) = extent(teeth.iter().flat_map(|t| [t.point, t.tip]));
    let size = (hi.x - lo.x).max(hi.y - lo.y).max(f64::MIN_POSITIVE);
    let (width, margin) = (800.0, 20.0);
    let k = (width - 2.0 * margin) / size;
    let height = (hi.y - lo.y) * k + 2.0 * margin;
    let at = |p: Vector3<f64>| {
        (
            (p.x - lo.x) * k + margin,
            height - ((p.y - lo.y) * k + margin),
        )
    };
    let line = |pts: &mut dyn Iterator<Item = Vector3<f64>>| -> String {
        pts.map(|p| {
            let (x, y) = at(p);
            format!("{x:.2},{y:.2}")
        })
        .collect::<Vec<_>>()
        .join(" ")
    };
    writeln!(
        w,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height:.0}\" viewBox=\"0 0 {width} {height:.2}\">"
    )?;
    writeln!(w, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>")?;
    for t in teeth {
        let ((x1, y1), (x2, y2)) = (at(t.point), at(t.tip));
        writeln!(
            w,
            "<line x1=\"{x1:.2}\" y1=\"{y1:.2}\" x2=\"{x2:.2}\" y2=\"{y2:.2}\" stroke=\"#999\" stroke-width=\"1\"/>"
        )?;
    }
    let envelope = line(&mut teeth.iter().map(|t| t.tip));
    writeln!(
        w,
        "<polyline points=\"{envelope}\" fill=\"none\" stroke=\"#e06e00\" stroke-width=\"1.5\"/>"
    )?;
    let curve = line(&mut teeth.iter().map(|t| t.point));
    writeln!(
        w,
        "<polyline points=\"{curve}\" fill=\"none\" stroke=\"black\" stroke-width=\"2\"/>"
    )?;
    writeln!(w, "</svg>")?;
    Ok(())
}
