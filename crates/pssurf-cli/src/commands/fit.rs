//! `pssurf fit`: the Hermite PS-spline through scattered data.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use nalgebra::{Point2, Vector2};
use pssurf::prelude::*;
use pssurf::ps::Energy;
use pssurf::scattered::{
    FitError, GradientMethod, NEAR_DUPLICATE, Smoothing, data_basis, estimate_gradients_by,
    group_mean, hermite_spline, near_duplicate_distance, near_duplicate_groups, smooth_scattered,
    smoothing_fit,
};

use crate::budget::{Estimate, base_memory, count, mul};
use crate::table::{Table, read_triangles};

/// How to choose the split point of each triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Split {
    /// The incentre (always valid).
    Incenter,
    /// The centroid (may be rejected on some triangulations).
    Centroid,
}

impl From<Split> for SplitRule {
    fn from(s: Split) -> Self {
        match s {
            Split::Incenter => SplitRule::Incenter,
            Split::Centroid => SplitRule::Centroid,
        }
    }
}

/// How to estimate the gradients when the data has none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Gradients {
    /// Local weighted quadratic least squares at each vertex (fastest).
    Local,
    /// Least curvature of the edge network beyond the locally fitted one, over the whole
    /// triangulation (one well-conditioned sparse solve): more accurate on smooth data.
    Global,
    /// Least Hessian-jump energy over the whole triangulation (the least-energy interpolant;
    /// one sparse factorisation): the most accurate on smooth gridded data, the least on
    /// rough real data, and the slowest.
    Jumps,
}

impl From<Gradients> for GradientMethod {
    fn from(g: Gradients) -> Self {
        match g {
            Gradients::Local => GradientMethod::Local,
            Gradients::Global => GradientMethod::Global,
            Gradients::Jumps => GradientMethod::Jumps,
        }
    }
}

/// Arguments of `pssurf fit`.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// Scattered data: CSV with a header naming the columns `x,y,z`, and optionally `zx,zy`
    /// (the partial derivatives of z; estimated when absent).
    #[arg(value_name = "DATA.csv")]
    pub data: PathBuf,
    /// The surface file to write: pssurf JSON, or the binary encoding when it ends in `.psb`
    /// (docs/format.md).
    #[arg(short, long, value_name = "SURF.json")]
    pub output: PathBuf,
    /// Use these triangles instead of the Delaunay triangulation: CSV rows `i,j,k` of
    /// zero-based data row indices (with --approximate-on: of the rows of VERTICES.csv).
    #[arg(long, value_name = "TRI.csv")]
    pub triangles: Option<PathBuf>,
    /// The interior split point of each triangle of the Powell–Sabin refinement.
    #[arg(long, value_enum, default_value_t = Split::Incenter)]
    pub split: Split,
    /// How to estimate the gradients when the data has no zx, zy. `local` is the default
    /// and the fastest; `global` is 2–3× more accurate on smooth scattered data
    /// (docs/performance.md, "The global gradient estimator").
    #[arg(long, value_enum, default_value_t = Gradients::Local)]
    pub gradients: Gradients,
    /// Approximate instead of interpolating: a least-squares PS-spline on a grid of about M
    /// vertices over the data's bounding box (on the Delaunay triangulation of the points
    /// themselves when M ≥ their number).
    #[arg(long, value_name = "M", group = "approximation")]
    pub approximate: Option<usize>,
    /// Approximate on your own coarse triangulation: its vertices as CSV columns `x,y`, its
    /// triangles from --triangles (rows of VERTICES.csv), else their Delaunay triangulation.
    /// Every data point must lie in it.
    #[arg(long, value_name = "VERTICES.csv", group = "approximation")]
    pub approximate_on: Option<PathBuf>,
    /// With --approximate(-on): the smoothing weight λ of Σ residual² + λ·energy, or `gcv`
    /// to choose it by generalised cross-validation.
    #[arg(
        long,
        value_name = "λ|gcv",
        default_value = "gcv",
        requires = "approximation"
    )]
    pub smooth: SmoothArg,
    /// With --approximate(-on): the energy that λ weighs.
    #[arg(long, value_enum, default_value_t = EnergyArg::HessianJumps, requires = "approximation")]
    pub energy: EnergyArg,
}

/// The value of `--smooth`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothArg(Smoothing);

impl std::str::FromStr for SmoothArg {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s.eq_ignore_ascii_case("gcv") {
            return Ok(SmoothArg(Smoothing::Gcv));
        }
        match s.parse::<f64>() {
            // (+ 0.0 turns −0 into 0.)
            Ok(l) if l >= 0.0 && l.is_finite() => Ok(SmoothArg(Smoothing::Fixed(l + 0.0))),
            _ => Err(format!("expected a finite λ ≥ 0 or `gcv`, not `{s}`")),
        }
    }
}

/// The energy of a smoothing fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EnergyArg {
    /// Jumps of the Hessian across the PS refinement's edges (~∫‖∇³s‖²; smooths towards a
    /// quadratic).
    HessianJumps,
    /// ∫ s_xx² + 2 s_xy² + s_yy² (smooths towards a plane).
    ThinPlate,
}

impl From<EnergyArg> for Energy {
    fn from(e: EnergyArg) -> Self {
        match e {
            EnergyArg::HessianJumps => Energy::HessianJumps,
            EnergyArg::ThinPlate => Energy::ThinPlate,
        }
    }
}

/// Runs `pssurf fit`.
pub fn run(args: &FitArgs) -> Result<()> {
    if let Some(m) = args.approximate {
        return approximate(args, Coarse::Grid(m));
    }
    if let Some(vertices) = &args.approximate_on {
        return approximate(args, Coarse::Given(vertices));
    }
    let table = Table::read_columns(&args.data, Some(&DATA_COLUMNS))?;
    fit_estimate(table.rows.len(), args.gradients, None).check()?;
    let Columns { x, y, z, gradient } = Columns::find(&table, &args.data)?;
    let mut points: Vec<Point2<f64>> = table.rows.iter().map(|r| Point2::new(r[x], r[y])).collect();
    check_range(&points, &args.data)?;
    check_values(table.rows.iter().map(|r| r[z]), &args.data)?;
    let mut rows: Vec<Vec<f64>> = table.rows.clone();
    let mut row_of: Vec<usize> = (0..points.len()).collect();
    if args.triangles.is_none() {
        if let Some((first, second)) = pssurf::triangulation::duplicate_points(&points) {
            bail!(
                "{}: rows {} and {} have the same (x, y); remove one",
                args.data.display(),
                first + 1,
                second + 1
            );
        }
        // Without given triangles the vertices are ours to choose: nearly coincident points
        // become one at their mean (their slopes would be meaningless), ...
        let groups = near_duplicate_groups(&points, NEAR_DUPLICATE);
        warn_merged(
            &points,
            &groups,
            near_duplicate_distance(&points, NEAR_DUPLICATE),
        );
        (rows, row_of) = merge_rows(rows, &groups);
        points = rows.iter().map(|r| Point2::new(r[x], r[y])).collect();
        // ... and a space-filling curve keeps neighbouring vertices close in memory, which
        // makes every later step faster.
        let order = pssurf::triangulation::morton_order(&points);
        points = order.iter().map(|&i| points[i as usize]).collect();
        rows = order.iter().map(|&i| rows[i as usize].clone()).collect();
        row_of = order.iter().map(|&i| row_of[i as usize]).collect();
    } else {
        warn_near_duplicates(&points, &row_of);
    }
    let values: Vec<f64> = rows.iter().map(|r| r[z]).collect();
    let tri = match &args.triangles {
        Some(path) => {
            let t = read_triangles(path, points.len())?;
            Triangulation::try_new(points, t)
                .with_context(|| format!("{}: invalid triangulation", path.display()))?
        }
        None => Triangulation::delaunay_with_peeled(points)
            .map(|(t, peeled)| {
                warn_peeled(&peeled, &row_of);
                t
            })
            .map_err(|e| match e {
                TriangulationError::DuplicateVertex { first, second } => anyhow::anyhow!(
                    "{}: rows {} and {} have the same (x, y); remove one",
                    args.data.display(),
                    first + 1,
                    second + 1
                ),
                TriangulationError::NearlyCollinearPoints { points } => {
                    let [a, b, c] = points.map(|v| row_of[v] + 1);
                    anyhow::anyhow!(
                        "{}: rows {a}, {b} and {c} are nearly collinear (their Delaunay triangle has numerically zero area): remove or move one of them",
                        args.data.display()
                    )
                }
                e => anyhow::anyhow!("{}: cannot triangulate: {e}", args.data.display()),
            })?,
    };
    warn_slivers(&tri, &row_of);
    let basis = Arc::new(
        data_basis(tri, args.split.into())
            .map_err(|e| fit_error(&args.data, e.map_points(|v| row_of[v])))?,
    );
    let (gradients, method) = match gradient {
        Some((a, b)) => {
            let g: Vec<Vector2<f64>> = rows.iter().map(|r| Vector2::new(r[a], r[b])).collect();
            (g, "given in the data (zx, zy)".to_string())
        }
        None => {
            let (g, report) = estimate_gradients_by(&basis, &values, args.gradients.into())
                .map_err(|e| fit_error(&args.data, e.map_points(|v| row_of[v])))?;
            let mut m = match args.gradients {
                Gradients::Local => "estimated by local weighted quadratic least squares",
                Gradients::Global => "estimated by least network curvature (global)",
                Gradients::Jumps => "estimated by least Hessian-jump energy (jumps)",
            }
            .to_string();
            match report.stronger_anchor {
                Some(eta) if eta.is_finite() => {
                    m += &format!(
                        " (the global system is ill-conditioned on this triangulation: anchored to the local estimate with weight {eta:e})"
                    )
                }
                Some(_) => {
                    m += " (the global system is too ill-conditioned on this triangulation to be solved: the local estimate is used)"
                }
                None => {}
            }
            if report.kept_local > 0 {
                m += &format!(
                    " ({} vertices closer than {:e} of the data's extent to a neighbour keep their local estimate: there the values cannot fix slopes to 1e-10)",
                    report.kept_local,
                    pssurf::scattered::CLOSE
                );
            }
            if report.widened > 0 || report.planar > 0 {
                m += &format!(
                    " (local fits: {} vertices needed a wider neighbourhood, {} a plane)",
                    report.widened, report.planar
                );
            }
            (g, m)
        }
    };
    let spline = hermite_spline(basis.clone(), &values, &gradients)
        .map_err(|e| fit_error(&args.data, e.map_points(|v| row_of[v])))?;
    let t = basis.triangulation();
    crate::output::save_surface(&Surface::from(spline), &args.output)?;
    eprintln!(
        "fitted {} rows on {} vertices ({} triangles{}); gradients {method}; wrote {}",
        table.rows.len(),
        t.vertex_count(),
        t.triangle_count(),
        if args.triangles.is_some() {
            ", given"
        } else {
            ", Delaunay"
        },
        args.output.display()
    );
    Ok(())
}

/// The columns of the data that `fit` reads (others may hold anything).
const DATA_COLUMNS: [&str; 5] = ["x", "y", "z", "zx", "zy"];

/// The data columns `fit` uses: x, y, z and optionally the gradient (zx, zy).
struct Columns {
    x: usize,
    y: usize,
    z: usize,
    gradient: Option<(usize, usize)>,
}

impl Columns {
    /// Finds the columns by name, or says which are missing.
    fn find(table: &Table, path: &Path) -> Result<Self> {
        let col = |name: &str| table.column(name);
        let (Some(x), Some(y), Some(z)) = (col("x"), col("y"), col("z")) else {
            bail!(
                "{}: needs columns x,y,z (found: {})",
                path.display(),
                table.headers.join(",")
            );
        };
        let gradient = match (col("zx"), col("zy")) {
            (Some(a), Some(b)) => Some((a, b)),
            (None, None) => None,
            _ => bail!("{}: give both zx and zy, or neither", path.display()),
        };
        Ok(Columns { x, y, z, gradient })
    }
}

/// The coarse triangulation of a smoothing fit.
enum Coarse<'a> {
    /// About this many vertices, chosen by the library.
    Grid(usize),
    /// The user's vertices (and --triangles, if given).
    Given(&'a Path),
}

/// What a fit of `rows` data rows costs (measured at 200,000 random rows: local gradients 2.2
/// kB per row, global 2.1 kB, least-jump 7.2 kB; a smoothing fit 1 kB per row and 15 kB per
/// coarse vertex): 3 kB per row for local gradients, 4 kB for global ones, 9 kB for
/// least-jump ones; for a smoothing fit on `vertices`
/// coarse vertices 2 kB per row and 20 kB per vertex.
fn fit_estimate(rows: usize, gradients: Gradients, smoothing: Option<usize>) -> Estimate {
    let rows = rows as u64;
    let (memory, what) = match smoothing {
        Some(v) => (
            mul(rows, 2048).saturating_add(mul(v as u64, 20 * 1024)),
            format!("a smoothing fit on {} vertices", count(v as u64)),
        ),
        None => (
            mul(
                rows,
                match gradients {
                    Gradients::Local => 3 * 1024,
                    Gradients::Global => 4 * 1024,
                    Gradients::Jumps => 9 * 1024,
                },
            ),
            "an interpolating fit".to_string(),
        ),
    };
    Estimate {
        what,
        makes: format!("{} rows", count(rows)),
        memory: base_memory().saturating_add(memory),
        output: mul(rows.max(smoothing.unwrap_or(0) as u64), 300),
    }
}

/// `pssurf fit --approximate M` or `--approximate-on VERTICES.csv`: the smoothing fit.
fn approximate(args: &FitArgs, coarse: Coarse) -> Result<()> {
    if let Coarse::Grid(m) = coarse {
        if args.triangles.is_some() {
            bail!(
                "--approximate makes its own coarse triangulation; give yours with --approximate-on VERTICES.csv --triangles TRI.csv"
            );
        }
        if m < 3 {
            bail!("--approximate {m}: needs at least 3 vertices");
        }
    }
    let table = Table::read_columns(&args.data, Some(&DATA_COLUMNS))?;
    let vertices = match coarse {
        // The grid has about M vertices; on the data themselves (M ≥ rows), one per row.
        Coarse::Grid(m) => m.min(table.rows.len()),
        // The user's triangulation: bounded by the size of its file.
        Coarse::Given(path) => std::fs::metadata(path).map_or(0, |m| m.len() as usize / 4),
    };
    fit_estimate(table.rows.len(), args.gradients, Some(vertices)).check()?;
    let Columns { x, y, z, gradient } = Columns::find(&table, &args.data)?;
    if gradient.is_some() {
        eprintln!(
            "warning: {}: the columns zx, zy are not used by --approximate (it fits values only)",
            args.data.display()
        );
    }
    let points: Vec<Point2<f64>> = table.rows.iter().map(|r| Point2::new(r[x], r[y])).collect();
    let values: Vec<f64> = table.rows.iter().map(|r| r[z]).collect();
    // (Nearly coincident rows do no harm to a least-squares fit: no warning.)
    check_range(&points, &args.data)?;
    check_values(values.iter().copied(), &args.data)?;
    let given = match coarse {
        Coarse::Given(path) => Some(Arc::new(user_coarse_basis(
            path,
            args.triangles.as_deref(),
        )?)),
        Coarse::Grid(_) => None,
    };
    // GCV factorises the system for each λ it tries: show them as they come (indicatif
    // draws only on a terminal).
    let spinner = indicatif::ProgressBar::new_spinner().with_style(
        indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
            .expect("a valid template"),
    );
    let mut tried = 0;
    let mut on_trial = |t: &pssurf::scattered::Trial| {
        tried += 1;
        spinner.set_message(format!(
            "λ #{tried}: {:.2e} (GCV score {:.4e}, {:.1} degrees of freedom)",
            t.lambda, t.gcv, t.dof
        ));
        spinner.tick();
    };
    let (energy, smoothing) = (args.energy.into(), args.smooth.0);
    let fit = match (coarse, given) {
        (_, Some(basis)) => {
            smoothing_fit(basis, &points, &values, energy, smoothing, &mut on_trial)
        }
        (Coarse::Grid(m), None) => {
            smooth_scattered(&points, &values, m, energy, smoothing, &mut on_trial)
        }
        (Coarse::Given(_), None) => unreachable!("a given triangulation was read above"),
    };
    spinner.finish_and_clear();
    let fit = fit.map_err(|e| match e {
        pssurf::scattered::SmoothingError::Triangulation(TriangulationError::DuplicateVertex {
            first,
            second,
        }) => anyhow::anyhow!(
            "{}: rows {} and {} have the same (x, y); remove one",
            args.data.display(),
            first + 1,
            second + 1
        ),
        pssurf::scattered::SmoothingError::BeyondPrecision(FitError::BeyondPrecision {
            vertices,
            height,
            magnitude,
        }) => beyond_precision(&args.data, vertices, height, magnitude),
        pssurf::scattered::SmoothingError::Outside(k) => anyhow::anyhow!(
            "{}: row {} ({}, {}) lies outside the coarse triangulation",
            args.data.display(),
            k + 1,
            points[k].x,
            points[k].y
        ),
        pssurf::scattered::SmoothingError::Ps(PsError::NonFiniteCoefficient { .. }) => {
            anyhow::anyhow!(
                "{}: the fitted surface does not fit in floating point (values too large?)",
                args.data.display()
            )
        }
        e => anyhow::anyhow!("{}: {e}", args.data.display()),
    })?;
    let t = fit.spline.basis().triangulation();
    let (vertices, triangles) = (t.vertex_count(), t.triangle_count());
    crate::output::save_surface(&Surface::from(fit.spline), &args.output)?;
    eprintln!(
        "smoothing fit of {} points on {vertices} vertices ({triangles} triangles): λ = {:.3e}{}, RMS residual {:.4e}, effective degrees of freedom {:.1}{}; wrote {}",
        points.len(),
        fit.lambda,
        if args.smooth.0 == Smoothing::Gcv {
            " (by GCV)"
        } else {
            ""
        },
        fit.rms_residual,
        fit.effective_dof,
        if fit.dof_estimated {
            " (estimated)"
        } else {
            ""
        },
        args.output.display()
    );
    Ok(())
}

/// Relative area below which a triangle counts as a sliver (nearly collinear vertices).
const SLIVER: f64 = 1e-9;
/// How many cases of each kind are named.
const NAMED: usize = 5;

/// Warns (without failing) about nearly duplicate points, naming their data rows (1-based,
/// as in the CSV without its header); `row_of[k]` is point k's data row.
fn warn_near_duplicates(points: &[Point2<f64>], row_of: &[usize]) {
    let row = |v: usize| row_of[v] + 1;
    let pairs = pssurf::scattered::near_duplicates(points, NEAR_DUPLICATE, NAMED + 1);
    for d in pairs.iter().take(NAMED) {
        eprintln!(
            "warning: rows {} and {} are only {:.2e} apart (nearly coincident for this data's extent and coordinates): the surface will be steep between them; merge or remove one",
            row(d.first).min(row(d.second)),
            row(d.first).max(row(d.second)),
            d.distance
        );
    }
    if pairs.len() > NAMED {
        eprintln!("warning: more nearly duplicate rows than these {NAMED}");
    }
}

/// The PS basis on the user's coarse triangulation: vertices `x,y` from `path`, triangles
/// from `triangles` or else Delaunay.
fn user_coarse_basis(path: &Path, triangles: Option<&Path>) -> Result<PsBasis> {
    let table = Table::read_columns(path, Some(&["x", "y"]))?;
    let (Some(x), Some(y)) = (table.column("x"), table.column("y")) else {
        bail!(
            "{}: needs columns x,y (found: {})",
            path.display(),
            table.headers.join(",")
        );
    };
    let vertices: Vec<Point2<f64>> = table.rows.iter().map(|r| Point2::new(r[x], r[y])).collect();
    let tri = match triangles {
        Some(t) => {
            let list = read_triangles(t, vertices.len())?;
            Triangulation::try_new(vertices, list)
                .with_context(|| format!("{}: invalid triangulation", t.display()))?
        }
        None => Triangulation::delaunay(vertices)
            .with_context(|| format!("{}: cannot triangulate", path.display()))?,
    };
    data_basis(tri, SplitRule::Incenter).map_err(|e| fit_error(path, e))
}

/// A failure of the fit on the data of `path`, its point indices being 0-based rows.
fn fit_error(path: &Path, e: FitError) -> anyhow::Error {
    match e {
        FitError::BeyondPrecision {
            vertices,
            height,
            magnitude,
        } => beyond_precision(path, vertices, height, magnitude),
        FitError::NearlyCollinear {
            vertices,
            height,
            length,
        } => {
            let [a, b, c] = vertices.map(|r| r + 1);
            anyhow::anyhow!(
                "{}: rows {a}, {b} and {c} are nearly collinear (their triangle is {height:.1e} high and {length:.1e} long): the split points of so thin a triangle cannot be placed reliably; remove or move one of them",
                path.display()
            )
        }
        FitError::ControlValueOutOfRange { point } => anyhow::anyhow!(
            "{}: row {}: its value and gradient give control values that are not finite numbers within ±1e60 (the gradient times the distance to its neighbours is too large): scale z or the gradients down",
            path.display(),
            point + 1
        ),
        FitError::SplitMissesEdge { triangles } => {
            let [[a, b, c], [d, e, f]] = triangles.map(|t| t.map(|r| r + 1));
            anyhow::anyhow!(
                "{}: the split points of the triangles at rows {a}, {b}, {c} and {d}, {e}, {f} are joined by a segment that misses their common edge: this split rule does not fit the triangulation here; use --split incenter, which always does",
                path.display()
            )
        }
        FitError::RefinementFails { corners, reason } => {
            let [a, b, c] = corners.map(|r| r + 1);
            anyhow::anyhow!(
                "{}: the PS refinement of the triangle at rows {a}, {b} and {c} fails: {reason}",
                path.display()
            )
        }
        FitError::GradientAtPoint { point } => anyhow::anyhow!(
            "{}: cannot estimate the gradient at row {}: its neighbours do not span the plane",
            path.display(),
            point + 1
        ),
        e => anyhow::anyhow!("{}: {e}", path.display()),
    }
}

/// Refuses coordinates outside the range pssurf supports, naming the row (the table reader already refuses
/// non-finite numbers).
fn check_range(points: &[Point2<f64>], path: &Path) -> Result<()> {
    match pssurf::triangulation::check_coordinates(points) {
        Ok(()) => Ok(()),
        Err(TriangulationError::CoordinateOutOfRange(k)) => bail!(
            "{}: row {}: a coordinate outside the range pssurf supports (0, or 1e-42 to 1e60 in magnitude)",
            path.display(),
            k + 1
        ),
        Err(e) => bail!("{}: {e}", path.display()),
    }
}

/// Every value within ±1e60, the control values' range ([`pssurf::limits::MAX_VALUE`]), or
/// an error naming the first row beyond it. (A value of 1e308 was only found by the control
/// values of the neighbour whose gradient it spoiled, and that row was named.)
fn check_values(values: impl Iterator<Item = f64>, path: &Path) -> Result<()> {
    for (k, v) in values.enumerate() {
        if !pssurf::limits::value_ok(v) {
            bail!(
                "{}: row {}: z = {v:e} is beyond ±1e60, the range of values pssurf supports: scale z down",
                path.display(),
                k + 1
            );
        }
    }
    Ok(())
}

/// The error for a triangle of data rows (0-based) finer than the coordinates resolve.
fn beyond_precision(path: &Path, rows: [usize; 3], height: f64, magnitude: f64) -> anyhow::Error {
    let [a, b, c] = rows.map(|r| r + 1);
    anyhow::anyhow!(
        "{}: rows {a}, {b} and {c} make a triangle only {height:.1e} high, too fine for coordinates of magnitude {magnitude:.1e} (spaced {:.1e} apart in floating point): subtract an origin from x and y, e.g. their minimum, and fit again",
        path.display(),
        magnitude * f64::EPSILON
    )
}

/// Warns (without failing) that groups of nearly coincident rows were merged, naming them.
fn warn_merged(points: &[Point2<f64>], groups: &[Vec<usize>], distance: f64) {
    for g in groups.iter().take(NAMED) {
        let spread = g
            .iter()
            .map(|&k| (points[k] - points[g[0]]).norm())
            .fold(0.0, f64::max);
        let named: Vec<String> = g.iter().take(NAMED).map(|&k| (k + 1).to_string()).collect();
        let rows = match (named.as_slice(), g.len() - named.len()) {
            ([a, b], 0) => format!("{a} and {b}"),
            (_, 0) => {
                let (last, rest) = named.split_last().expect("a group has two rows or more");
                format!("{} and {last}", rest.join(", "))
            }
            (_, more) => format!("{} and {more} more", named.join(", ")),
        };
        eprintln!(
            "warning: rows {rows} are only {spread:.2e} apart (under {distance:.2e}, nearly coincident for this data's extent and coordinates): merged into one point with their mean"
        );
    }
    if groups.len() > NAMED {
        eprintln!(
            "warning: {} more groups of nearly coincident rows merged",
            groups.len() - NAMED
        );
    }
}

/// The data rows and their first row numbers after replacing each group of rows by their
/// mean (every column; offsets from the group's first row keep it exact to rounding far from
/// the origin), in the order of the groups' first rows.
fn merge_rows(rows: Vec<Vec<f64>>, groups: &[Vec<usize>]) -> (Vec<Vec<f64>>, Vec<usize>) {
    if groups.is_empty() {
        let n = rows.len();
        return (rows, (0..n).collect());
    }
    let mut group_of = vec![None; rows.len()];
    for g in groups {
        g.iter().for_each(|&k| group_of[k] = Some(g));
    }
    let mut merged = (Vec::new(), Vec::new());
    for (k, row) in rows.iter().enumerate() {
        let row = match group_of[k] {
            None => row.clone(),
            Some(g) if g[0] == k => (0..row.len())
                .map(|c| group_mean(g, |i| rows[i][c]))
                .collect(),
            Some(_) => continue,
        };
        merged.0.push(row);
        merged.1.push(k);
    }
    merged
}

/// Warns that boundary slivers were left out of the Delaunay domain, naming their rows.
fn warn_peeled(peeled: &[[usize; 3]], row_of: &[usize]) {
    for t in peeled.iter().take(NAMED) {
        let [a, b, c] = t.map(|v| row_of[v] + 1);
        eprintln!(
            "warning: rows {a}, {b} and {c} are nearly collinear on the boundary: the sliver between them (thinner than {:e} of its length) is left out of the domain",
            pssurf::triangulation::PEEL_THICKNESS
        );
    }
    if peeled.len() > NAMED {
        eprintln!(
            "warning: {} more boundary slivers left out",
            peeled.len() - NAMED
        );
    }
}

/// Warns (without failing) about sliver triangles, naming their vertices' data rows.
fn warn_slivers(tri: &Triangulation, row_of: &[usize]) {
    let row = |v: usize| row_of[v] + 1;
    let thin = pssurf::scattered::slivers(tri, SLIVER, NAMED + 1);
    for &t in thin.iter().take(NAMED) {
        let [a, b, c] = tri.triangle(t).map(row);
        eprintln!(
            "warning: rows {a}, {b} and {c} are nearly collinear (a sliver triangle): the fit may be poor or fail there"
        );
    }
    if thin.len() > NAMED {
        eprintln!("warning: more sliver triangles than these {NAMED}");
    }
}
