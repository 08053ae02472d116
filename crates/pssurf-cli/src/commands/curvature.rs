//! `pssurf curvature`: exact curvature at given parameters or on a grid.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::Result;
use pssurf::interrogate::Curvature;
use pssurf::surface::ParametricSurface;

use crate::points::{PointArgs, TableOutputArgs, evaluate_table};

/// The output columns.
pub const COLUMNS: [&str; 17] = [
    "u", "v", "x", "y", "z", "K", "H", "k1", "k2", "kabs", "d1x", "d1y", "d1z", "d2x", "d2y",
    "d2z", "patch",
];

/// Arguments of `pssurf curvature`.
#[derive(clap::Args, Debug)]
pub struct CurvatureArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// Where to evaluate.
    #[command(flatten)]
    pub points: PointArgs,
    /// Where the table goes and what happens to points outside the domain.
    #[command(flatten)]
    pub table: TableOutputArgs,
}

/// Runs `pssurf curvature`.
pub fn run(args: &CurvatureArgs) -> Result<()> {
    let surface = crate::budget::load_surface(&args.surface)?;
    let pts = args
        .points
        .resolve(surface.domain_bounds(), surface.kind().is_functional())?;
    let columns: Vec<String> = COLUMNS.map(String::from).to_vec();
    let singular = AtomicUsize::new(0);
    evaluate_table(
        &surface,
        &pts,
        &columns,
        args.table.outside,
        args.table.output.as_deref(),
        |j, row| {
            row[0..3].copy_from_slice(j.jet.value.as_slice());
            row[14] = j.piece as f64;
            match Curvature::from_jet(&j.jet) {
                Ok(c) => {
                    row[3..8].copy_from_slice(&[c.gaussian, c.mean, c.k1, c.k2, c.absolute()]);
                    row[8..11].copy_from_slice(c.dir1.as_slice());
                    row[11..14].copy_from_slice(c.dir2.as_slice());
                }
                // Undefined at a singular point (s_u × s_v = 0), and said so below.
                Err(_) => {
                    singular.fetch_add(1, Ordering::Relaxed);
                    row[3..14].fill(f64::NAN);
                }
            }
        },
    )?;
    let singular = singular.into_inner();
    if singular > 0 {
        eprintln!(
            "warning: the surface is singular (s_u × s_v vanishes to working precision) at {singular} of the {} points: curvature is undefined there, and their columns K … d2z hold nan",
            pts.len()
        );
    }
    Ok(())
}
