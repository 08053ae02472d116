//! `pssurf noise`: perturb the control points, for denoising experiments.

use std::path::PathBuf;

use anyhow::{Result, bail};
use pssurf::noise::NoiseKind;

/// The distribution of the noise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Distribution {
    /// Uniform on [−A, A].
    Uniform,
    /// Normal with standard deviation A.
    Gaussian,
}

/// Arguments of `pssurf noise`.
#[derive(clap::Args, Debug)]
pub struct NoiseArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// The amplitude A of the noise added to every coordinate of every control point.
    #[arg(long, value_name = "A")]
    pub amplitude: f64,
    /// Uniform on [−A, A] or Gaussian with standard deviation A.
    #[arg(long, value_enum, default_value_t = Distribution::Uniform)]
    pub distribution: Distribution,
    /// The random seed: the same seed gives the same noise.
    #[arg(long, value_name = "S")]
    pub seed: u64,
    /// The surface file to write (binary when it ends in `.psb`, else JSON; docs/format.md).
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// Runs `pssurf noise`.
pub fn run(args: &NoiseArgs) -> Result<()> {
    if !(args.amplitude.is_finite() && args.amplitude >= 0.0) {
        bail!("the amplitude must be a finite non-negative number");
    }
    let kind = match args.distribution {
        Distribution::Uniform => NoiseKind::Uniform,
        Distribution::Gaussian => NoiseKind::Gaussian,
    };
    let (a, seed) = (args.amplitude, args.seed);
    let file = crate::budget::load_surface(&args.surface)?;
    let out = file.with_noise(a, kind, seed).map_err(|e| {
        anyhow::anyhow!(
            "noise of amplitude {} would make the surface invalid: {e}",
            pssurf::text::Short(a)
        )
    })?;
    crate::output::save_surface(&out, &args.output)?;
    let name = match args.distribution {
        Distribution::Uniform => "uniform",
        Distribution::Gaussian => "Gaussian",
    };
    eprintln!(
        "added {name} noise of amplitude {} (seed {seed}); wrote {}",
        pssurf::text::Short(a),
        args.output.display()
    );
    Ok(())
}
