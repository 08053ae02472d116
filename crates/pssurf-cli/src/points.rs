//! The parameter points at which commands evaluate: a CSV file or a regular grid.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use anyhow::{Result, bail};
use nalgebra::Point2;
use pssurf::surface::{ParametricSurface, SurfaceJet, fill_rows};

use crate::budget::{Estimate, base_memory, count, mul};
use crate::output::{write_raster, write_streamed};
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

/// The evaluation points of a command: a list read from a file, or a grid generated on the fly.
pub enum Points {
    /// Points read from a CSV file (reported by row number).
    List(Vec<Point2<f64>>),
    /// A grid over a box (reported by grid position).
    Grid {
        /// The grid's size.
        size: GridSize,
        /// The box.
        bounds: (Point2<f64>, Point2<f64>),
    },
}

impl Points {
    /// How many points.
    pub fn len(&self) -> usize {
        match self {
            Points::List(v) => v.len(),
            Points::Grid { size, .. } => size.nx.saturating_mul(size.ny),
        }
    }

    /// The k-th point (grids row by row: v outer, u inner, endpoints included).
    pub fn get(&self, k: usize) -> Point2<f64> {
        match self {
            Points::List(v) => v[k],
            Points::Grid {
                size,
                bounds: (lo, hi),
            } => {
                let (i, j) = (k % size.nx, k / size.nx);
                Point2::new(
                    lo.x + (hi.x - lo.x) * i as f64 / (size.nx - 1) as f64,
                    lo.y + (hi.y - lo.y) * j as f64 / (size.ny - 1) as f64,
                )
            }
        }
    }

    /// A human description of the k-th point: its CSV row, or its grid position.
    pub fn describe(&self, k: usize) -> String {
        let p = self.get(k);
        match self {
            Points::List(_) => format!("row {} ({}, {})", k + 1, p.x, p.y),
            Points::Grid { size, .. } => format!(
                "grid point ({}, {}) = ({}, {})",
                k % size.nx,
                k / size.nx,
                p.x,
                p.y
            ),
        }
    }
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

/// The output options shared by commands that write one row per point.
#[derive(clap::Args, Clone, Debug)]
pub struct TableOutputArgs {
    /// Output file: `.npy` (float64 array) or anything else for CSV; standard output (CSV)
    /// when absent.
    #[arg(short, long, value_name = "OUT.csv|OUT.npy")]
    pub output: Option<PathBuf>,
    /// Points outside the domain: an error naming the point (default), NaN values, or skipped.
    #[arg(long, value_enum, default_value_t = Outside::Error)]
    pub outside: Outside,
}

impl PointArgs {
    /// The points; `functional` allows `x,y` as column names.
    pub fn resolve(&self, bounds: (Point2<f64>, Point2<f64>), functional: bool) -> Result<Points> {
        match (&self.at, self.grid) {
            (Some(p), _) => read_points(p, functional).map(Points::List),
            (None, Some(size)) => Ok(Points::Grid { size, bounds }),
            (None, None) => bail!("give --at PTS.csv or --grid NXxNY"),
        }
    }
}

/// Reads points from a CSV file with columns `u,v` (or `x,y` when `functional`).
pub fn read_points(path: &Path, functional: bool) -> Result<Vec<Point2<f64>>> {
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

/// What writing a table of one row per point costs: the bytes written (CSV numbers take at
/// most 25 characters with their separator, `.npy` 8 bytes) and, when skipping points outside
/// the domain, the rows kept in memory until their number is known.
fn table_estimate(
    points: &Points,
    width: usize,
    outside: Outside,
    output: Option<&Path>,
) -> Estimate {
    let rows = points.len() as u64;
    let per_row = match crate::output::Format::of(output) {
        crate::output::Format::Csv => 25 * width as u64,
        crate::output::Format::Npy => 8 * width as u64,
    };
    // Kept rows (skipping into .npy) grow a vector by doubling: up to twice their size.
    let npy = crate::output::Format::of(output) == crate::output::Format::Npy;
    let kept = if outside == Outside::Skip && npy {
        mul(rows, 16 * width as u64)
    } else {
        0
    };
    Estimate {
        what: match points {
            Points::Grid { size, .. } => format!("a {} × {} grid", size.nx, size.ny),
            Points::List(_) => "evaluating the points".to_string(),
        },
        makes: format!("{} rows", count(rows)),
        // Chunks of 65,536 rows evaluated in parallel and their text: 64 MB (measured 35–90
        // MB in all for a streamed curvature grid).
        memory: base_memory().saturating_add(64 << 20).saturating_add(kept),
        output: mul(rows, per_row).saturating_add(1024),
    }
}

/// Which of a table's columns are written, and how.
pub struct TableLayout {
    /// The columns written, by index into the full table's columns, in this order.
    pub select: Vec<usize>,
    /// Write the single selected column of a grid as an NY × NX raster.
    pub raster: bool,
}

impl TableLayout {
    /// Every column, as a table.
    pub fn all(width: usize) -> Self {
        TableLayout {
            select: (0..width).collect(),
            raster: false,
        }
    }

    /// The columns named in `names` (case-insensitive, in that order) out of `columns`, as a
    /// table or (with `raster`) as the raster of one column over a grid.
    pub fn choose(
        columns: &[String],
        names: Option<&[String]>,
        raster: bool,
        points: &Points,
        outside: Outside,
    ) -> Result<Self> {
        let select = match names {
            None => (0..columns.len()).collect(),
            Some(names) => names
                .iter()
                .map(|name| {
                    columns
                        .iter()
                        .position(|c| c.eq_ignore_ascii_case(name.trim()))
                        .ok_or_else(|| {
                            anyhow::anyhow!(
                                "--columns: there is no column `{}` (choose from {})",
                                crate::table::short(name),
                                columns.join(",")
                            )
                        })
                })
                .collect::<Result<Vec<usize>>>()?,
        };
        if select.is_empty() {
            bail!("--columns: name at least one column");
        }
        if let Some((k, _)) = select
            .iter()
            .enumerate()
            .find(|&(k, c)| select[..k].contains(c))
        {
            // (A table with a repeated column name is one that `Table::read` refuses.)
            let name = names.map_or("", |n| n[k].trim());
            bail!("--columns: `{}` is named twice", crate::table::short(name));
        }
        if raster {
            if !matches!(points, Points::Grid { .. }) {
                bail!("--raster needs --grid");
            }
            if select.len() != 1 {
                bail!("--raster writes one column: choose it with --columns (e.g. --columns z)");
            }
            if outside == Outside::Skip {
                bail!("--raster keeps every grid point: use --outside nan or error");
            }
        }
        Ok(TableLayout { select, raster })
    }
}

/// Evaluates a surface at the points and writes a table whose columns are `u, v` followed by
/// what `fill` writes from each point's jet (`columns.len() − 2` numbers). Points outside the
/// domain are handled by `outside`. The table is produced in chunks (evaluated in parallel)
/// and streamed to the output, so memory stays small for any number of points; on error no
/// output file is left.
pub fn evaluate_table<S: ParametricSurface>(
    surface: &S,
    points: &Points,
    columns: &[String],
    outside: Outside,
    output: Option<&Path>,
    fill: impl Fn(&SurfaceJet, &mut [f64]) + Sync,
) -> Result<()> {
    let layout = TableLayout::all(columns.len());
    evaluate_table_as(surface, points, columns, &layout, outside, output, fill)
}

/// [`evaluate_table`] writing only the columns `layout` selects, as a table or a raster.
pub fn evaluate_table_as<S: ParametricSurface>(
    surface: &S,
    points: &Points,
    columns: &[String],
    layout: &TableLayout,
    outside: Outside,
    output: Option<&Path>,
    fill: impl Fn(&SurfaceJet, &mut [f64]) + Sync,
) -> Result<()> {
    const CHUNK: usize = 1 << 16;
    let width = columns.len();
    let select = &layout.select;
    table_estimate(points, select.len(), outside, output).check()?;
    // One extra column per row flags points outside the domain.
    let wide = width + 1;
    let n = points.len();
    let mut pts = Vec::with_capacity(CHUNK.min(n));
    let mut buf = vec![0.0; CHUNK.min(n) * wide];
    let mut rows = Vec::with_capacity(CHUNK.min(n) * width);
    let chunk = |start: usize, pts: &mut Vec<Point2<f64>>, buf: &mut Vec<f64>| {
        let len = CHUNK.min(n - start);
        pts.clear();
        pts.extend((start..start + len).map(|k| points.get(k)));
        buf.resize(len * wide, 0.0);
        fill_rows(surface, pts, wide, buf, |p, r, row| {
            row[0] = p.x;
            row[1] = p.y;
            match r {
                Ok(j) => {
                    fill(j, &mut row[2..width]);
                    row[width] = 0.0;
                }
                Err(_) => {
                    row[2..width].fill(f64::NAN);
                    row[width] = 1.0;
                }
            }
        });
    };
    // A .npy header states the number of rows: when skipping points, evaluate everything
    // first (kept in memory). A CSV file is streamed, skipped rows left out on the way.
    let npy = crate::output::Format::of(output) == crate::output::Format::Npy;
    let skipping = outside == Outside::Skip && npy;
    let mut kept: Vec<f64> = Vec::new();
    if skipping {
        for start in (0..n).step_by(CHUNK) {
            chunk(start, &mut pts, &mut buf);
            for row in buf.chunks(wide).filter(|r| r[width] == 0.0) {
                kept.extend(select.iter().map(|&c| row[c]));
            }
        }
    }
    let total = if skipping {
        kept.len() / select.len()
    } else {
        n
    };
    let names: Vec<String> = select.iter().map(|&c| columns[c].clone()).collect();
    let write =
        |produce: &mut dyn FnMut(&mut crate::output::TableSink<'_>) -> Result<()>| match points {
            Points::Grid { size, .. } if layout.raster => {
                write_raster(output, size.ny, size.nx, produce)
            }
            _ => write_streamed(output, &names, total, produce),
        };
    write(&mut |sink| {
        if skipping {
            return sink.rows(&kept);
        }
        for start in (0..n).step_by(CHUNK) {
            chunk(start, &mut pts, &mut buf);
            if outside == Outside::Error
                && let Some(k) = buf.chunks(wide).position(|r| r[width] != 0.0)
            {
                bail!(
                    "{} lies outside the domain (use --outside nan|skip to continue)",
                    points.describe(start + k)
                );
            }
            rows.clear();
            for row in buf.chunks(wide) {
                if outside == Outside::Skip && row[width] != 0.0 {
                    continue;
                }
                rows.extend(select.iter().map(|&c| row[c]));
            }
            sink.rows(&rows)?;
        }
        Ok(())
    })
}
