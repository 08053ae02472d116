//! `pssurf subdivide`: the same UPS surface on a finer triangulation.

use std::path::PathBuf;

use anyhow::{Result, bail};
use pssurf::surface::Surface;

use super::uniform;

/// Arguments of `pssurf subdivide`.
#[derive(clap::Args, Debug)]
pub struct SubdivideArgs {
    /// A UPS surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// How many dyadic subdivision steps (each halves the base and quadruples the triangles;
    /// the surface itself does not change).
    #[arg(long, value_name = "T")]
    pub times: u32,
    /// The surface file to write.
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// The largest number of vertices a command may create.
pub const MAX_VERTICES: u64 = 1 << 27;

/// Runs `pssurf subdivide`.
pub fn run(args: &SubdivideArgs) -> Result<()> {
    let file = pssurf::io::load(&args.surface)?;
    let u = uniform::require(&file, &args.surface, "subdivide")?;
    let before = u.grid().vertex_count() as u64;
    let estimate = (before as f64) * 4f64.powi(args.times as i32);
    if estimate > MAX_VERTICES as f64 {
        bail!(
            "{} subdivision steps would make about {:.0} vertices (at most {MAX_VERTICES} are supported)",
            args.times,
            estimate
        );
    }
    let out = u.subdivide_times(args.times as usize);
    let after = out.grid().vertex_count();
    pssurf::io::save(&Surface::from(out), &args.output)?;
    eprintln!(
        "subdivided {} times: {before} → {after} vertices; wrote {}",
        args.times,
        args.output.display()
    );
    Ok(())
}
