//! `pssurf fit`: the Hermite PS-spline through scattered data.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use nalgebra::Point2;
use pssurf::prelude::*;
use pssurf::scattered::{GradientFit, estimate_gradients};

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

/// Arguments of `pssurf fit`.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// Scattered data: CSV with a header naming the columns `x,y,z`, and optionally `zx,zy`
    /// (the partial derivatives of z; estimated when absent).
    #[arg(value_name = "DATA.csv")]
    pub data: PathBuf,
    /// The surface file to write (pssurf JSON, see docs/format.md).
    #[arg(short, long, value_name = "SURF.json")]
    pub output: PathBuf,
    /// Use these triangles instead of the Delaunay triangulation: CSV rows `i,j,k` of
    /// zero-based data row indices.
    #[arg(long, value_name = "TRI.csv")]
    pub triangles: Option<PathBuf>,
    /// The interior split point of each triangle of the Powell–Sabin refinement.
    #[arg(long, value_enum, default_value_t = Split::Incenter)]
    pub split: Split,
}

/// Runs `pssurf fit`.
pub fn run(args: &FitArgs) -> Result<()> {
    let table = Table::read(&args.data)?;
    let col = |name: &str| table.column(name);
    let (Some(x), Some(y), Some(z)) = (col("x"), col("y"), col("z")) else {
        bail!(
            "{}: needs columns x,y,z (found: {})",
            args.data.display(),
            table.headers.join(",")
        );
    };
    let grads = match (col("zx"), col("zy")) {
        (Some(a), Some(b)) => Some((a, b)),
        (None, None) => None,
        _ => bail!("{}: give both zx and zy, or neither", args.data.display()),
    };
    let mut points: Vec<Point2<f64>> = table.rows.iter().map(|r| Point2::new(r[x], r[y])).collect();
    let mut rows: Vec<&Vec<f64>> = table.rows.iter().collect();
    let mut row_of: Vec<usize> = (0..points.len()).collect();
    if args.triangles.is_none() {
        // Without given triangles the vertex order is ours to choose: a space-filling curve
        // keeps neighbouring vertices close in memory, which makes every later step faster.
        // (Duplicates are still reported by their data rows, below.)
        if let Some((first, second)) = pssurf::triangulation::duplicate_points(&points) {
            bail!(
                "{}: rows {} and {} have the same (x, y); remove one",
                args.data.display(),
                first + 1,
                second + 1
            );
        }
        let order = pssurf::triangulation::morton_order(&points);
        points = order.iter().map(|&i| points[i as usize]).collect();
        rows = order.iter().map(|&i| &table.rows[i as usize]).collect();
        row_of = order.iter().map(|&i| i as usize).collect();
    }
    let values: Vec<f64> = rows.iter().map(|r| r[z]).collect();
    warn_near_duplicates(&points, &row_of);
    let tri = match &args.triangles {
        Some(path) => {
            let t = read_triangles(path, points.len())?;
            Triangulation::try_new(points, t)
                .with_context(|| format!("{}: invalid triangulation", path.display()))?
        }
        None => Triangulation::delaunay(points).map_err(|e| match e {
            TriangulationError::DuplicateVertex { first, second } => anyhow::anyhow!(
                "{}: rows {} and {} have the same (x, y); remove one",
                args.data.display(),
                first + 1,
                second + 1
            ),
            e => anyhow::anyhow!("{}: cannot triangulate: {e}", args.data.display()),
        })?,
    };
    warn_slivers(&tri, &row_of);
    let (gradients, method) = match grads {
        Some((a, b)) => {
            let g: Vec<(f64, f64)> = rows.iter().map(|r| (r[a], r[b])).collect();
            (g, "given in the data (zx, zy)".to_string())
        }
        None => {
            let est = estimate_gradients(&tri, &values)?;
            let linear = est
                .iter()
                .filter(|(_, k)| *k == GradientFit::Linear)
                .count();
            let wide = est
                .iter()
                .filter(|(_, k)| matches!(k, GradientFit::Quadratic { rings } if *rings > 1))
                .count();
            let g = est.iter().map(|(g, _)| (g.x, g.y)).collect();
            let mut m = "estimated by local weighted quadratic least squares".to_string();
            if wide > 0 || linear > 0 {
                m += &format!(
                    " ({wide} vertices needed a wider neighbourhood, {linear} a plane fit)"
                );
            }
            (g, m)
        }
    };
    let basis = Arc::new(PsBasis::new(
        tri,
        args.split.into(),
        &PsTriangleChoice::Optimal,
    )?);
    let data: Vec<Hermite<f64>> = values
        .iter()
        .zip(&gradients)
        .map(|(&value, &(dx, dy))| Hermite { value, dx, dy })
        .collect();
    let spline = PsSpline::hermite(basis.clone(), &data)?;
    let t = basis.triangulation();
    pssurf::io::save(&Surface::from(spline), &args.output)?;
    eprintln!(
        "fitted {} points ({} triangles{}); gradients {method}; wrote {}",
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

/// Relative distance below which two data points count as nearly duplicate.
const NEAR_DUPLICATE: f64 = 1e-9;
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
            "warning: rows {} and {} are only {:.2e} apart (under {NEAR_DUPLICATE:e} of the data's extent): the surface will be steep between them; merge or remove one",
            row(d.first).min(row(d.second)),
            row(d.first).max(row(d.second)),
            d.distance
        );
    }
    if pairs.len() > NAMED {
        eprintln!("warning: more nearly duplicate rows than these {NAMED}");
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
