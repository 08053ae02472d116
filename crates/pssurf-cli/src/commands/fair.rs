//! `pssurf fair SURF.json [--weight w] -o OUT.json`: the fairest surface with the same
//! boundary, or (w > 0) a compromise between fairness and the original (issue 18, part 5).

use std::path::PathBuf;

use anyhow::Result;
use pssurf::ps::{Energy, FairOptions, fair};
use pssurf::text::Significant;

/// Which energy to minimise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EnergyArg {
    /// The jumps of the second derivatives across the PS refinement (thesis 5.4.3).
    Jumps,
    /// The thin-plate energy ∫ s_uu² + 2 s_uv² + s_vv².
    ThinPlate,
}

/// Arguments of `pssurf fair`.
#[derive(clap::Args, Debug)]
pub struct FairArgs {
    /// A PS, UPS or NURPS surface file.
    #[arg(value_name = "SURF.json")]
    pub input: PathBuf,
    /// How much to stay close to the original: 0 gives the fairest surface with this boundary;
    /// 1 weighs closeness and fairness about alike; larger values (up to 1e12) change less.
    #[arg(long, default_value_t = 0.1, allow_hyphen_values = true)]
    pub weight: f64,
    /// The energy to minimise.
    #[arg(long, value_enum, default_value_t = EnergyArg::Jumps)]
    pub energy: EnergyArg,
    /// The surface file to write (binary when it ends in `.psb`, else JSON; docs/format.md).
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// Runs `pssurf fair`.
pub fn run(args: &FairArgs) -> Result<()> {
    let surface = crate::budget::load_surface(&args.input)?;
    if let Some(b) = surface.ps_basis() {
        // The sparse factorisation's fill: measured 22 KB per vertex with the Hessian jumps
        // (2.2 GB peak at 100k vertices), half that with the thin-plate energy.
        let per_vertex: u64 = match args.energy {
            EnergyArg::Jumps => 24 << 10,
            EnergyArg::ThinPlate => 12 << 10,
        };
        let n = b.triangulation().vertex_count() as u64;
        crate::budget::Estimate {
            what: format!("fairing {}", args.input.display()),
            makes: format!("a sparse factorisation over {n} vertices"),
            memory: crate::budget::load_memory(0).saturating_add(per_vertex.saturating_mul(n)),
            output: 0,
        }
        .check()?;
    }
    let opts = FairOptions {
        weight: args.weight,
        energy: match args.energy {
            EnergyArg::Jumps => Energy::HessianJumps,
            EnergyArg::ThinPlate => Energy::ThinPlate,
        },
    };
    let f = fair(&surface, &opts)?;
    crate::output::save_surface(&f.surface, &args.output)?;
    eprintln!(
        "energy {} -> {}; moved {} control points (largest move {}), boundary kept; normal equations to {} ({}); wrote {}",
        Significant(f.energy_before, 6),
        Significant(f.energy_after, 6),
        f.moved,
        Significant(f.largest_move, 4),
        Significant(f.normal_residual, 2),
        f.solver,
        args.output.display()
    );
    Ok(())
}
