//! `pssurf curve POLYGON.csv --subdivide chaikin|cubic|four-point --times N [--closed]
//! -o OUT.csv`: subdivision curves (issue 20, part 2; `pssurf::subdivision::curves`).

use std::path::PathBuf;

use anyhow::{Result, bail};
use nalgebra::Vector3;
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
    /// The polygon: a CSV file with columns x, y and optionally z, one point per row.
    #[arg(value_name = "POLYGON.csv")]
    pub input: PathBuf,
    /// The subdivision scheme.
    #[arg(long, value_enum)]
    pub subdivide: SchemeArg,
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
    /// The CSV file to write (x,y,z).
    #[arg(short, long, value_name = "OUT.csv")]
    pub output: PathBuf,
}

/// Runs `pssurf curve`.
pub fn run(args: &CurveArgs) -> Result<()> {
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
    let scheme = match args.subdivide {
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
