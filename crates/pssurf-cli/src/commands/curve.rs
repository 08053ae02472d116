//! `pssurf curve POLYGON.csv --subdivide chaikin|cubic|four-point --times N [--closed]
//! -o OUT.csv`: subdivision curves (issue 20, part 2; `pssurf::subdivision::curves`);
//! `pssurf curve CURVE.json|POLYLINE.csv --comb [--scale s] -o COMB.svg|png|csv`: the
//! curvature comb of a NURBS or Bézier curve file, or of polylines (a polygon x,y[,z], or the
//! traced curves `pssurf trace` writes, curve,u,v,x,y,z) by the circle through each point and
//! its neighbours (part 1; `pssurf::interrogate::comb`).

use std::path::PathBuf;

use anyhow::{Result, bail};
use nalgebra::Vector3;
use pssurf::interrogate::comb::{CombTooth, curvature_comb, polyline_comb};
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
    /// The polygon (a CSV file with columns x, y and optionally z) for --subdivide; for
    /// --comb a curve file (docs/format.md, "Curves"), a polygon, or the curves `pssurf
    /// trace` writes (curve,u,v,x,y,z).
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
    /// Draw the curvature comb of a curve file, or of the polylines of a CSV file (a polygon
    /// x,y[,z], or traced curves curve,u,v,x,y,z; κ of the circle through each point and its
    /// neighbours): teeth of length scale × κ along the normal, outward, and their envelope.
    /// SVG or PNG (x, y), or CSV ([curve,]t,x,y,z,kappa,tip_x,tip_y,tip_z).
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
    /// The file to write: CSV (x,y,z) for --subdivide; SVG, PNG or CSV for --comb.
    #[arg(short, long, value_name = "OUT")]
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

/// The combs to draw: one for a curve file, one per polyline of a CSV file, computed at
/// `scale` (0 for teeth of no length).
/// Teeth where the curvature is undefined (the curve stops: zero speed, e.g. coinciding
/// control points) are left out.
fn combs_at(args: &CurveArgs, scale: f64) -> Result<Vec<Vec<CombTooth>>> {
    let mut combs = if is_csv(&args.input) {
        let polylines = read_polylines(&args.input)?;
        (polylines.iter())
            .map(|p| polyline_comb(p, args.closed, scale))
            .collect()
    } else {
        let curve = crate::budget::load_curve(&args.input)?;
        vec![curvature_comb(&curve, args.samples as usize, scale)]
    };
    for comb in &mut combs {
        comb.retain(|t| t.curvature.is_finite());
    }
    Ok(combs)
}

/// The number of teeth [`combs_at`] leaves out (curvature undefined).
fn undefined_teeth(args: &CurveArgs) -> Result<usize> {
    if is_csv(&args.input) {
        return Ok(0); // polyline_comb skips repeated points itself
    }
    let curve = crate::budget::load_curve(&args.input)?;
    let all = curvature_comb(&curve, args.samples as usize, 0.0);
    Ok(all.iter().filter(|t| !t.curvature.is_finite()).count())
}

/// Whether a path names a CSV file.
fn is_csv(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
}

/// The polylines of a CSV file: one polygon (columns x, y and optionally z), or one per value
/// of a `curve` column (the traced curves of `pssurf trace`), in file order.
fn read_polylines(path: &std::path::Path) -> Result<Vec<Vec<Vector3<f64>>>> {
    let table = crate::table::Table::read_columns(path, Some(&["curve", "x", "y", "z"]))?;
    let (Some(x), Some(y)) = (table.column("x"), table.column("y")) else {
        bail!(
            "{}: needs columns x and y (and optionally z, curve)",
            path.display()
        );
    };
    let (z, curve) = (table.column("z"), table.column("curve"));
    let mut lines: Vec<Vec<Vector3<f64>>> = Vec::new();
    let mut current = None;
    for (k, r) in table.rows.iter().enumerate() {
        let p = Vector3::new(r[x], r[y], z.map_or(0.0, |z| r[z]));
        if !p.iter().all(|c| c.abs() <= pssurf::limits::MAX_VALUE) {
            bail!(
                "{}: row {}: a coordinate beyond ±1e60 (the library's limit)",
                path.display(),
                k + 1
            );
        }
        let id = curve.map(|c| r[c]);
        if lines.is_empty() || id != current {
            lines.push(Vec::new());
            current = id;
        }
        lines.last_mut().expect("pushed above").push(p);
    }
    Ok(lines)
}

/// The comb of a curve file or of the polylines of a CSV file.
fn comb(args: &CurveArgs) -> Result<()> {
    let probe = combs_at(args, 0.0)?;
    if probe.iter().all(|c| c.is_empty()) {
        bail!(
            "{}: no curve with three distinct points (or a defined curvature) to draw a comb of",
            args.input.display()
        );
    }
    let undefined = undefined_teeth(args)?;
    if undefined > 0 {
        eprintln!(
            "warning: the curve stops (zero speed) at {undefined} sample points: curvature is undefined there, and those teeth are left out"
        );
    }
    let (lo, hi) = extent(probe.iter().flatten().map(|t| t.point));
    let size = (hi - lo).norm().max(f64::MIN_POSITIVE);
    let kmax = (probe.iter().flatten())
        .map(|t| t.curvature)
        .filter(|k| k.is_finite())
        .fold(0.0, f64::max);
    let scale = match args.scale {
        Some(s) if s.is_finite() && s >= 0.0 => s,
        Some(s) => bail!("--scale {s}: give a finite number ≥ 0"),
        None if kmax > 0.0 => 0.25 * size / kmax,
        None => 0.0,
    };
    let combs = combs_at(args, scale)?;
    if (combs.iter().flatten()).any(|t| !t.tip.iter().all(|x| x.abs() <= pssurf::limits::MAX_VALUE))
    {
        bail!("--scale {scale}: the longest tooth would reach beyond ±1e60; give a smaller scale");
    }
    let ext = (args.output.extension())
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    let several = combs.len() > 1;
    if matches!(ext.as_str(), "png" | "svg") && !CombFrame::of(&combs).k.is_finite() {
        bail!(
            "{}: the comb has no extent in the (x, y) plane that a picture shows (the curve runs along z); write a .csv instead",
            args.output.display()
        );
    }
    match ext.as_str() {
        "png" => {
            let mut png = Vec::new();
            comb_picture(&combs)
                .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)?;
            crate::output::write_output(&args.output, Durability::Atomic, |w| {
                Ok(w.write_all(&png)?)
            })?;
        }
        "svg" => {
            crate::output::write_output(&args.output, Durability::Atomic, |w| write_svg(w, &combs))?
        }
        _ => crate::output::write_output(&args.output, Durability::Atomic, |w| {
            let column = if several { "curve," } else { "" };
            writeln!(w, "{column}t,x,y,z,kappa,tip_x,tip_y,tip_z")?;
            for (k, comb) in combs.iter().enumerate() {
                let id = if several {
                    format!("{k},")
                } else {
                    String::new()
                };
                for t in comb {
                    let (p, q) = (t.point, t.tip);
                    writeln!(
                        w,
                        "{id}{},{},{},{},{},{},{},{}",
                        t.t, p.x, p.y, p.z, t.curvature, q.x, q.y, q.z
                    )?;
                }
            }
            Ok(())
        })?,
    }
    let teeth = combs.iter().map(Vec::len).sum::<usize>();
    let kmin = (combs.iter().flatten())
        .map(|t| t.curvature)
        .fold(f64::INFINITY, f64::min);
    eprintln!(
        "{teeth} teeth{}, curvature from {} to {}, scale {}; wrote {}",
        if several {
            format!(" on {} curves", combs.len())
        } else {
            String::new()
        },
        pssurf::text::Significant(kmin, 4),
        pssurf::text::Significant(kmax, 4),
        pssurf::text::Significant(scale, 4),
        args.output.display()
    );
    Ok(())
}

/// Where the (x, y) plane of the combs lands in a picture 800 units wide with a margin of 20:
/// the scale, the lower corner and the height.
struct CombFrame {
    k: f64,
    lo: Vector3<f64>,
    height: f64,
}

impl CombFrame {
    const WIDTH: f64 = 800.0;
    const MARGIN: f64 = 20.0;

    fn of(combs: &[Vec<CombTooth>]) -> CombFrame {
        let (lo, hi) = extent(combs.iter().flatten().flat_map(|t| [t.point, t.tip]));
        let size = (hi.x - lo.x).max(hi.y - lo.y).max(f64::MIN_POSITIVE);
        let k = (Self::WIDTH - 2.0 * Self::MARGIN) / size;
        let height = ((hi.y - lo.y) * k + 2.0 * Self::MARGIN).clamp(2.0 * Self::MARGIN, 4000.0);
        CombFrame { k, lo, height }
    }

    fn at(&self, p: Vector3<f64>) -> (f64, f64) {
        (
            (p.x - self.lo.x) * self.k + Self::MARGIN,
            self.height - ((p.y - self.lo.y) * self.k + Self::MARGIN),
        )
    }
}

/// The combs as a PNG picture: the curves in black, the teeth in grey, the envelopes in
/// orange, as the SVG draws them.
fn comb_picture(combs: &[Vec<CombTooth>]) -> image::RgbImage {
    let frame = CombFrame::of(combs);
    let mut img = image::RgbImage::from_pixel(
        CombFrame::WIDTH as u32,
        frame.height.ceil() as u32,
        image::Rgb([255, 255, 255]),
    );
    let mut segment = |a: Vector3<f64>, b: Vector3<f64>, color: [u8; 3], width: i64| {
        let ((x0, y0), (x1, y1)) = (frame.at(a), frame.at(b));
        let steps = (x1 - x0).abs().max((y1 - y0).abs()).ceil().clamp(1.0, 1e5) as usize;
        for s in 0..=steps {
            let t = s as f64 / steps as f64;
            let (x, y) = (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
            for (dx, dy) in (0..width).flat_map(|i| (0..width).map(move |j| (i, j))) {
                let (px, py) = (x.floor() as i64 + dx, y.floor() as i64 + dy);
                if px >= 0 && py >= 0 && (px as u32) < img.width() && (py as u32) < img.height() {
                    img.put_pixel(px as u32, py as u32, image::Rgb(color));
                }
            }
        }
    };
    for comb in combs {
        for t in comb {
            segment(t.point, t.tip, [153, 153, 153], 1);
        }
    }
    for comb in combs {
        for w in comb.windows(2) {
            segment(w[0].tip, w[1].tip, [224, 110, 0], 2);
        }
        for w in comb.windows(2) {
            segment(w[0].point, w[1].point, [0, 0, 0], 2);
        }
    }
    img
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

/// The combs in the (x, y) plane as SVG: the curves in black, the teeth in grey, the
/// envelopes in orange.
fn write_svg(w: &mut dyn std::io::Write, combs: &[Vec<CombTooth>]) -> Result<()> {
    let frame = CombFrame::of(combs);
    let (width, height) = (CombFrame::WIDTH, frame.height);
    let line = |pts: &mut dyn Iterator<Item = Vector3<f64>>| -> String {
        pts.map(|p| {
            let (x, y) = frame.at(p);
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
    for teeth in combs {
        for t in teeth {
            let ((x1, y1), (x2, y2)) = (frame.at(t.point), frame.at(t.tip));
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
    }
    writeln!(w, "</svg>")?;
    Ok(())
}
