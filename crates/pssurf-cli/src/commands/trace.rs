//! `pssurf trace`: curves on a surface. Level lines of a field (K, H, κ1, κ2, |κ1| + |κ2|,
//! the height or a formula), traced by the predictor–corrector of seed 001 and joined across
//! pieces; lines of curvature, asymptotic lines and geodesics (in `trace_lines`). To CSV
//! (`curve,u,v,x,y,z`), OBJ line elements, or an SVG of the domain with the lines.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use pssurf::interrogate::{
    SurfaceCurve, SurfaceField, TraceMethod, ZeroSet, ZeroSetOptions, auto_levels, level_lines,
};
use pssurf::io::Durability;
use pssurf::surface::PiecewiseSurface;
use pssurf_viz::{DomainCurve, DomainOptions};

/// How branches are followed (`--method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// Euler predictor and Newton corrector (seed 001, 3 b).
    PredictorCorrector,
    /// The seed's four-point walk (3 a).
    FourPoint,
    /// The seed's eight-point walk.
    EightPoint,
}

/// Arguments of `pssurf trace`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).multiple(false)
    .args(["level", "curvature_lines", "asymptotic", "geodesic"])))]
pub struct TraceArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// A field and its levels: `K=0,0.5`, `H=auto:10` (ten levels over the bulk of the
    /// values), `z=0.1,0.2`, or a formula of u, v, x, y, z, K, H, k1, k2, kabs
    /// (`x^2+y^2=0.25`). Repeat for several fields. `K=0` gives the parabolic lines.
    #[arg(long, value_name = "FIELD=LEVELS")]
    pub level: Vec<String>,
    /// Lines of curvature (both families unless --family), evenly spaced (--seeds) or from
    /// given points (--from PTS.csv); umbilics are reported.
    #[arg(long)]
    pub curvature_lines: bool,
    /// Asymptotic lines (where K < 0), seeded like --curvature-lines.
    #[arg(long)]
    pub asymptotic: bool,
    /// A geodesic: from --from u,v along --dir du,dv for --length L, or the shortest one
    /// from --from u,v to --to u,v.
    #[arg(long)]
    pub geodesic: bool,
    /// Which family of lines: 1 (κ1, or +θ for asymptotic lines), 2 (κ2, or −θ) or both.
    #[arg(long, value_enum, default_value_t = Family::Both)]
    pub family: Family,
    /// Evenly spaced lines about 1/N of the domain's diagonal apart (Jobard–Lefer seeding).
    #[arg(long, value_name = "N", default_value_t = 20,
        value_parser = clap::value_parser!(u32).range(1..=2000))]
    pub seeds: u32,
    /// Seeds: a CSV file with columns u,v (lines through each point), or for --geodesic the
    /// start point `u,v`.
    #[arg(long, value_name = "PTS.csv|u,v", allow_hyphen_values = true)]
    pub from: Option<String>,
    /// The end point `u,v` of a shortest geodesic.
    #[arg(long, value_name = "u,v", allow_hyphen_values = true)]
    pub to: Option<String>,
    /// The start direction `du,dv` (in parameters) of a geodesic.
    #[arg(long, value_name = "du,dv", allow_hyphen_values = true)]
    pub dir: Option<String>,
    /// The length of a geodesic, or the longest line of curvature each way from its seed
    /// (in space).
    #[arg(long, value_name = "L")]
    pub length: Option<f64>,
    /// Hunting lines per direction on every piece (seed points; more finds smaller loops).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub hunting: u32,
    /// The largest step as a fraction of a piece's size (level lines) or of the domain's
    /// diagonal (lines of curvature, asymptotic lines).
    #[arg(long)]
    pub step: Option<f64>,
    /// How branches are followed.
    #[arg(long, value_enum, default_value_t = Method::PredictorCorrector)]
    pub method: Method,
    /// The most points in all lines together (bounded work on wild surfaces).
    #[arg(long, default_value_t = 1_000_000)]
    pub max_points: usize,
    /// Where to write: `.csv` (curve,u,v,x,y,z), `.obj` (line elements) or `.svg` (the
    /// domain with the lines); `-` or nothing for CSV on standard output.
    #[arg(short, long, value_name = "LINES.csv|.obj|.svg")]
    pub output: Option<PathBuf>,
}

/// Which family of field lines (`--family`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Family {
    /// κ1 lines (or asymptotic lines at +θ).
    #[value(name = "1")]
    First,
    /// κ2 lines (or asymptotic lines at −θ).
    #[value(name = "2")]
    Second,
    /// Both.
    Both,
}

/// One field with its levels.
struct LevelRequest {
    field: SurfaceField,
    levels: Levels,
}

enum Levels {
    Values(Vec<f64>),
    Auto(usize),
}

/// Parses `FIELD=LEVELS` (split at the last `=`).
fn parse_level(text: &str) -> Result<LevelRequest> {
    let Some((field, levels)) = text.rsplit_once('=') else {
        bail!("--level {text}: expected FIELD=LEVELS, e.g. K=0,0.5 or H=auto:10");
    };
    let field = SurfaceField::parse(field).with_context(|| format!("--level {text}"))?;
    let levels = match levels.trim().strip_prefix("auto:") {
        Some(n) => {
            let n: usize = n
                .trim()
                .parse()
                .ok()
                .filter(|n| (1..=1000).contains(n))
                .with_context(|| format!("--level {text}: auto:N needs N from 1 to 1000"))?;
            Levels::Auto(n)
        }
        None => {
            let values: Vec<f64> = levels
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .ok()
                .filter(|v: &Vec<f64>| !v.is_empty() && v.len() <= 1000 && v.iter().all(|x| x.is_finite()))
                .with_context(|| {
                    format!("--level {text}: levels must be 1 to 1000 finite numbers separated by commas, or auto:N")
                })?;
            Levels::Values(values)
        }
    };
    Ok(LevelRequest { field, levels })
}

/// Runs `pssurf trace --level` (the field-line and geodesic modes are
/// `trace_lines::run`).
pub fn run(args: &TraceArgs) -> Result<()> {
    check_output(args)?;
    let step = args.step.unwrap_or(0.125);
    if !(step > 0.0 && step <= 1.0) {
        bail!("--step must be in (0, 1]");
    }
    if args.max_points == 0 || args.max_points > 100_000_000 {
        bail!("--max-points must be from 1 to 100000000");
    }
    let requests: Vec<LevelRequest> = args
        .level
        .iter()
        .map(|t| parse_level(t))
        .collect::<Result<_>>()?;
    let surface = crate::budget::load_surface(&args.surface)?;
    let levels: usize = requests
        .iter()
        .map(|r| match &r.levels {
            Levels::Values(v) => v.len(),
            Levels::Auto(n) => *n,
        })
        .sum();
    estimate(
        surface.piece_count(),
        args.hunting as u64,
        levels,
        args.max_points,
    )
    .check()?;
    let opts = ZeroSetOptions {
        hunting: args.hunting as usize,
        step,
        max_points: args.max_points,
        method: match args.method {
            Method::PredictorCorrector => TraceMethod::PredictorCorrector,
            Method::FourPoint => TraceMethod::FourPoint,
            Method::EightPoint => TraceMethod::EightPoint,
        },
        ..ZeroSetOptions::default()
    };
    let mut traced: Vec<(String, ZeroSet)> = Vec::new();
    for r in &requests {
        let levels = match &r.levels {
            Levels::Values(v) => v.clone(),
            Levels::Auto(n) => auto_levels(&surface, &r.field, *n),
        };
        for set in level_lines(&surface, &r.field, &levels, &opts)? {
            traced.push((r.field.name(), set));
        }
    }
    report(&traced);
    let curves: Vec<SurfaceCurve> = traced
        .iter()
        .flat_map(|(_, s)| s.curves.iter().cloned())
        .collect();
    write(args, &surface, &traced, &curves)
}

/// What a trace needs before it starts: the hunting meshes (points, values and lines of every
/// piece), a slot per piece and level, and the points themselves (in memory and as CSV).
fn estimate(
    pieces: usize,
    hunting: u64,
    levels: usize,
    max_points: usize,
) -> crate::budget::Estimate {
    use crate::budget::mul;
    let per_piece = mul((hunting + 1) * (hunting + 1), 64).saturating_add(256);
    let memory = crate::budget::base_memory()
        .saturating_add(mul(pieces as u64, per_piece))
        .saturating_add(mul(mul(pieces as u64, levels as u64), 64))
        .saturating_add(mul(max_points as u64, 160));
    crate::budget::Estimate {
        what: format!("tracing {levels} levels on {pieces} pieces"),
        makes: format!("up to {max_points} points"),
        memory,
        output: mul(max_points as u64, 110),
    }
}

/// The most levels reported one line each; beyond, one line of totals.
const REPORTED_LEVELS: usize = 20;

/// ", N line ends left unjoined (the field is continuous there)" when N > 0.
fn unjoined_ends(n: usize) -> String {
    if n == 0 {
        return String::new();
    }
    format!(", {n} line ends left unjoined where the field is continuous")
}

/// One line per level on standard error (curves, loops, points, gaps), or totals when there
/// are many levels.
fn report(traced: &[(String, ZeroSet)]) {
    let points = |s: &ZeroSet| s.curves.iter().map(|c| c.uvs.len()).sum::<usize>();
    if traced.len() > REPORTED_LEVELS {
        let curves: usize = traced.iter().map(|(_, s)| s.curves.len()).sum();
        let all: usize = traced.iter().map(|(_, s)| points(s)).sum();
        let gaps: usize = traced.iter().map(|(_, s)| s.gaps.len()).sum();
        let unjoined: usize = traced.iter().map(|(_, s)| s.unjoined).sum();
        let cut = traced.iter().any(|(_, s)| s.truncated);
        eprintln!(
            "{} levels: {curves} curves, {all} points, {gaps} gaps where the field jumps across pieces{}{}",
            traced.len(),
            unjoined_ends(unjoined),
            if cut {
                ", cut short by --max-points"
            } else {
                ""
            }
        );
        return;
    }
    let mut first = 0;
    for (name, s) in traced {
        let closed = s.curves.iter().filter(|c| c.closed).count();
        let ids = if s.curves.is_empty() {
            String::new()
        } else {
            format!(" (curves {}–{})", first, first + s.curves.len() - 1)
        };
        eprintln!(
            "{name} = {}: {} curves{ids}, {closed} closed, {} points, {} gaps where the field jumps across pieces{}{}{}",
            pssurf::text::Significant(s.level, 6),
            s.curves.len(),
            points(s),
            s.gaps.len(),
            unjoined_ends(s.unjoined),
            if s.stuck > 0 {
                format!(", {} branches stopped", s.stuck)
            } else {
                String::new()
            },
            if s.truncated {
                ", cut short by --max-points"
            } else {
                ""
            },
        );
        first += s.curves.len();
    }
}

/// A colour per level (a qualitative palette).
pub(crate) const PALETTE: [[u8; 3]; 8] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [255, 127, 14],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
];

fn write(
    args: &TraceArgs,
    surface: &pssurf::surface::Surface,
    traced: &[(String, ZeroSet)],
    curves: &[SurfaceCurve],
) -> Result<()> {
    let colors: Vec<[u8; 3]> = traced
        .iter()
        .enumerate()
        .flat_map(|(k, (_, s))| std::iter::repeat_n(PALETTE[k % PALETTE.len()], s.curves.len()))
        .collect();
    write_curves(args, surface, curves, &colors)
}

/// Writes curves to `--output` as CSV, OBJ or a domain SVG (each curve in its colour).
/// Refuses an `--output` whose extension `pssurf trace` cannot write, before any work.
pub(crate) fn check_output(args: &TraceArgs) -> Result<()> {
    let ext = args
        .output
        .as_ref()
        .and_then(|p| p.extension())
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        None | Some("csv" | "obj" | "svg") => Ok(()),
        Some(other) => bail!("cannot write .{other}: use .csv, .obj or .svg"),
    }
}

pub(crate) fn write_curves(
    args: &TraceArgs,
    surface: &pssurf::surface::Surface,
    curves: &[SurfaceCurve],
    colors: &[[u8; 3]],
) -> Result<()> {
    let path = args.output.clone().unwrap_or_else(|| PathBuf::from("-"));
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => crate::output::write_output(&path, Durability::Atomic, |w| {
            Ok(pssurf::io::write_curves_obj(w, curves)?)
        })?,
        Some("svg") => {
            let lines = curves
                .iter()
                .zip(colors)
                .map(|(c, color)| DomainCurve {
                    uvs: c.uvs.clone(),
                    closed: c.closed,
                    color: *color,
                })
                .collect();
            let opts = DomainOptions {
                refinement: false,
                ps_triangles: false,
                curves: lines,
                ..DomainOptions::default()
            };
            let svg = pssurf_viz::domain_svg(surface, &opts);
            crate::output::write_output(&path, Durability::Atomic, |w| {
                Ok(w.write_all(svg.as_bytes())?)
            })?
        }
        Some("csv") | None => crate::output::write_output(&path, Durability::Atomic, |w| {
            Ok(pssurf::io::write_curves_csv(w, curves)?)
        })?,
        Some(other) => bail!("cannot write .{other}: use .csv, .obj or .svg"),
    }
    if !crate::output::is_stdout(&path) {
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
