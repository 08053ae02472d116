//! `pssurf subdivide`: the same UPS surface on a finer triangulation.

use std::path::PathBuf;

use anyhow::Result;
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
    /// The surface file to write (binary when it ends in `.psb`, else JSON; docs/format.md).
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// Runs `pssurf subdivide`.
pub fn run(args: &SubdivideArgs) -> Result<()> {
    let file = crate::budget::load_surface(&args.surface)?;
    let u = uniform::require(&file, &args.surface, "subdivide")?;
    let before = u.grid().vertex_count() as u64;
    // Each step doubles the lattice coordinates: V·4^T bounds the vertices (Pick's theorem)
    // and 4^T the block-matrix slots.
    let growth = 1u128
        .checked_shl(2 * args.times.min(63))
        .unwrap_or(u128::MAX);
    crate::commands::uniform::creation_estimate(
        format!("{} subdivision steps", args.times),
        (before as u128).saturating_mul(growth),
        (u.grid().polygon().block_slots()).saturating_mul(growth),
    )
    .check()?;
    let out = u.subdivide_times(args.times as usize);
    let after = out.grid().vertex_count();
    crate::output::save_surface(&Surface::try_from(out)?, &args.output)?;
    eprintln!(
        "subdivided {} times: {before} → {after} vertices; wrote {}",
        args.times,
        args.output.display()
    );
    Ok(())
}
