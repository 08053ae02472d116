//! The parameter points at which commands evaluate: a CSV file or a regular grid.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use anyhow::{Result, bail};
use nalgebra::Point2;

use crate::table::Table;

/// A regular grid of NX × NY points over the domain's bounding box, written `NXxNY`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GridSize {
    /// Points along x (u).
    pub nx: usize,
    /// Points along y (v).
    pub ny: usize,
}

impl FromStr for GridSize {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (a, b) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("`{s}` is not of the form NXxNY, e.g. 200x100"))?;
        let parse = |t: &str| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("`{t}` is not a whole number"))
        };
        let (nx, ny) = (parse(a)?, parse(b)?);
        if nx < 2 || ny < 2 {
            return Err("a grid needs at least 2 points in each direction".into());
        }
        Ok(GridSize { nx, ny })
    }
}

/// What to do with points outside the domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Outside {
    /// Stop with an error naming the first such point (the default).
    Error,
    /// Write NaN in the computed columns.
    Nan,
    /// Leave the point out of the output.
    Skip,
}

/// Where the points come from.
pub enum PointSource<'a> {
    /// A CSV file with columns `u,v` (or `x,y`).
    File(&'a Path, bool),
    /// A grid over the bounding box.
    Grid(GridSize),
}

/// Reads or generates the points; `functional` allows `x,y` as column names.
pub fn points(
    source: PointSource<'_>,
    bounds: (Point2<f64>, Point2<f64>),
) -> Result<Vec<Point2<f64>>> {
    match source {
        PointSource::File(path, functional) => {
            let t = Table::read(path)?;
            let cols = match (t.column("u"), t.column("v"), t.column("x"), t.column("y")) {
                (Some(u), Some(v), _, _) => (u, v),
                (_, _, Some(x), Some(y)) if functional => (x, y),
                _ => bail!(
                    "{}: needs columns `u,v`{} (found: {})",
                    path.display(),
                    if functional { " or `x,y`" } else { "" },
                    t.headers.join(",")
                ),
            };
            Ok(t.rows
                .iter()
                .map(|r| Point2::new(r[cols.0], r[cols.1]))
                .collect())
        }
        PointSource::Grid(g) => Ok(grid(g, bounds)),
    }
}

/// The grid points, row by row (v outer, u inner), endpoints included.
pub fn grid(g: GridSize, (lo, hi): (Point2<f64>, Point2<f64>)) -> Vec<Point2<f64>> {
    let mut out = Vec::with_capacity(g.nx * g.ny);
    for j in 0..g.ny {
        let v = lo.y + (hi.y - lo.y) * j as f64 / (g.ny - 1) as f64;
        for i in 0..g.nx {
            let u = lo.x + (hi.x - lo.x) * i as f64 / (g.nx - 1) as f64;
            out.push(Point2::new(u, v));
        }
    }
    out
}

/// The `--at` / `--grid` pair shared by commands that evaluate at points.
#[derive(clap::Args, Clone, Debug)]
#[group(required = true, multiple = false)]
pub struct PointArgs {
    /// Evaluate at the points of a CSV file with columns `u,v` (for functional surfaces `x,y`
    /// is accepted too).
    #[arg(long, value_name = "PTS.csv")]
    pub at: Option<PathBuf>,
    /// Evaluate on a regular grid of NX × NY points spanning the domain's bounding box,
    /// endpoints included (e.g. `--grid 1000x1000`).
    #[arg(long, value_name = "NXxNY")]
    pub grid: Option<GridSize>,
}

impl PointArgs {
    /// The points.
    pub fn resolve(
        &self,
        bounds: (Point2<f64>, Point2<f64>),
        functional: bool,
    ) -> Result<Vec<Point2<f64>>> {
        match (&self.at, self.grid) {
            (Some(p), _) => points(PointSource::File(p, functional), bounds),
            (None, Some(g)) => points(PointSource::Grid(g), bounds),
            (None, None) => bail!("give --at PTS.csv or --grid NXxNY"),
        }
    }
}
