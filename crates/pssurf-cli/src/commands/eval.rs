//! `pssurf eval`: points (and derivatives) of a surface at given parameters.

use std::path::PathBuf;

use anyhow::Result;
use pssurf::surface::ParametricSurface;

use crate::points::{PointArgs, TableLayout, TableOutputArgs, evaluate_table_as};

/// Arguments of `pssurf eval`.
#[derive(clap::Args, Debug)]
pub struct EvalArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// Where to evaluate.
    #[command(flatten)]
    pub points: PointArgs,
    /// Also write the partial derivatives xu,yu,zu,xv,yv,zv.
    #[arg(long)]
    pub derivatives: bool,
    /// Write only these columns, in this order, out of u,v,x,y,z (and xu,yu,zu,xv,yv,zv
    /// with --derivatives), e.g. `--columns z` or `--columns x,y,z`.
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    pub columns: Option<Vec<String>>,
    /// With --grid and one column (--columns z): write it as a raster of NY rows of NX
    /// numbers, v outer and u inner (a 2-D `.npy` array of shape (NY, NX), as SciPy returns
    /// f(X, Y) on a meshgrid; CSV: one line per grid row, no header).
    #[arg(long)]
    pub raster: bool,
    /// Where the table goes and what happens to points outside the domain.
    #[command(flatten)]
    pub table: TableOutputArgs,
}

/// Runs `pssurf eval`.
pub fn run(args: &EvalArgs) -> Result<()> {
    let surface = crate::budget::load_surface(&args.surface)?;
    let functional = surface.kind().is_functional();
    let pts = args.points.resolve(surface.domain_bounds(), functional)?;
    let mut columns: Vec<String> = ["u", "v", "x", "y", "z"].map(String::from).to_vec();
    if args.derivatives {
        columns.extend(["xu", "yu", "zu", "xv", "yv", "zv"].map(String::from));
    }
    let derivatives = args.derivatives;
    let layout = TableLayout::choose(
        &columns,
        args.columns.as_deref(),
        args.raster,
        &pts,
        args.table.outside,
    )?;
    evaluate_table_as(
        &surface,
        &pts,
        &columns,
        &layout,
        args.table.outside,
        args.table.output.as_deref(),
        |j, row| {
            let j = &j.jet;
            row[0..3].copy_from_slice(j.value.as_slice());
            if derivatives {
                row[3..6].copy_from_slice(j.dx.as_slice());
                row[6..9].copy_from_slice(j.dy.as_slice());
            }
        },
    )
}
