//! `pssurf eval`: points (and derivatives) of a surface at given parameters.

use std::path::PathBuf;

use anyhow::{Result, bail};
use pssurf::surface::{ParametricSurface, jets};

use crate::output::{NumTable, write_table};
use crate::points::{Outside, PointArgs};

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
    /// Output file: `.npy` (float64 array) or anything else for CSV; standard output (CSV)
    /// when absent.
    #[arg(short, long, value_name = "OUT.csv|OUT.npy")]
    pub output: Option<PathBuf>,
    /// Points outside the domain: an error naming the point (default), NaN values, or skipped.
    #[arg(long, value_enum, default_value_t = Outside::Error)]
    pub outside: Outside,
}

/// Runs `pssurf eval`.
pub fn run(args: &EvalArgs) -> Result<()> {
    let surface = pssurf::io::load(&args.surface)?;
    let functional = matches!(surface, pssurf::surface::PsSurface::Functional(_));
    let pts = args.points.resolve(surface.domain_bounds(), functional)?;
    let results = jets(&surface, &pts);
    let mut columns: Vec<String> = ["u", "v", "x", "y", "z"].map(String::from).to_vec();
    if args.derivatives {
        columns.extend(["xu", "yu", "zu", "xv", "yv", "zv"].map(String::from));
    }
    let mut data = Vec::with_capacity(pts.len() * columns.len());
    for (k, (p, r)) in pts.iter().zip(&results).enumerate() {
        match r {
            Ok(j) => {
                let j = &j.jet;
                data.extend([p.x, p.y, j.value.x, j.value.y, j.value.z]);
                if args.derivatives {
                    data.extend([j.dx.x, j.dx.y, j.dx.z, j.dy.x, j.dy.y, j.dy.z]);
                }
            }
            Err(_) => match args.outside {
                Outside::Error => bail!(
                    "{} lies outside the domain (use --outside nan|skip to continue)",
                    crate::describe_point(&args.points, k, *p)
                ),
                Outside::Skip => {}
                Outside::Nan => {
                    data.extend([p.x, p.y]);
                    data.extend(std::iter::repeat_n(f64::NAN, columns.len() - 2));
                }
            },
        }
    }
    write_table(&NumTable { columns, data }, args.output.as_deref())
}
