//! `pssurf eval`: points (and derivatives) of a surface at given parameters.

use std::path::PathBuf;

use anyhow::Result;
use pssurf::surface::ParametricSurface;

use crate::points::{PointArgs, TableOutputArgs, evaluate_table};

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
    evaluate_table(
        &surface,
        &pts,
        &columns,
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
