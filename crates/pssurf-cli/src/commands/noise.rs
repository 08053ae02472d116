//! `pssurf noise`: perturb the control points, for denoising experiments.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Result, bail};
use pssurf::noise::{NoiseKind, perturb};
use pssurf::ps::{Nurps, PsSpline};
use pssurf::surface::{PsSurface, Surface, UpsSurface};

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
    /// The surface file to write.
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
    let file = pssurf::io::load(&args.surface)?;
    let out: Surface = match &file {
        Surface::Uniform(u, _) => match u {
            UpsSurface::Functional(s) => UpsSurface::Functional(s.with_noise(a, kind, seed)).into(),
            UpsSurface::Parametric(s) => UpsSurface::Parametric(s.with_noise(a, kind, seed)).into(),
            UpsSurface::Rational(_) => bail!(
                "noise on rational surfaces is not supported (their weights would be ambiguous)"
            ),
        },
        Surface::General(g) => match g {
            PsSurface::Functional(s) => {
                let mut c = s.coefficients().to_vec();
                perturb(c.iter_mut().flatten(), a, kind, seed);
                PsSurface::Functional(PsSpline::new(Arc::clone(s.basis()), c)?).into()
            }
            PsSurface::Parametric(s) => {
                let mut c = s.coefficients().to_vec();
                perturb(c.iter_mut().flatten(), a, kind, seed);
                PsSurface::Parametric(PsSpline::new(Arc::clone(s.basis()), c)?).into()
            }
            PsSurface::Rational(s) => {
                let mut c = s.points().to_vec();
                perturb(c.iter_mut().flatten(), a, kind, seed);
                PsSurface::Rational(Nurps::new(Arc::clone(s.basis()), c, s.weights().to_vec())?)
                    .into()
            }
        },
    };
    pssurf::io::save(&out, &args.output)?;
    let name = match args.distribution {
        Distribution::Uniform => "uniform",
        Distribution::Gaussian => "Gaussian",
    };
    eprintln!(
        "added {name} noise of amplitude {a} (seed {seed}); wrote {}",
        args.output.display()
    );
    Ok(())
}
