//! `pssurf approx NURBS.json -o UPS.json`: a UPS surface approximating a NURBS surface
//! (thesis 6.4.2), with its deviation measured; `--tolerance` refines until it is met.

use std::path::PathBuf;

use anyhow::{Result, bail};
use pssurf::nurbs::{ApproxOptions, approximate};
use pssurf::surface::Surface;

/// Arguments of `pssurf approx`.
#[derive(clap::Args, Debug)]
pub struct ApproxArgs {
    /// A NURBS surface file, or a scene (then --object picks the surface).
    #[arg(value_name = "NURBS.json")]
    pub input: PathBuf,
    /// Which object of a scene: its index (from 0) or its name.
    #[arg(long, value_name = "K|NAME")]
    pub object: Option<String>,
    /// Triangles along the u side of the UPS domain (default: (√3/3) k_u − 1, thesis (6.9)).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=200))]
    pub nu: Option<u32>,
    /// Triangles along the v side.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=200))]
    pub nv: Option<u32>,
    /// Refine n_u, n_v until the largest deviation is at most this (model units).
    #[arg(long, value_name = "E")]
    pub tolerance: Option<f64>,
    /// The UPS surface file to write (binary when it ends in `.psb`, else JSON).
    #[arg(short, long, value_name = "UPS.json")]
    pub output: PathBuf,
}

/// Runs `pssurf approx`.
pub fn run(args: &ApproxArgs) -> Result<()> {
    let objects = super::info::load_named_surfaces(&args.input)?;
    let (name, surface) = match (&args.object, objects.len()) {
        (None, 1) => &objects[0],
        (None, n) => bail!(
            "{} holds {n} surfaces: choose one with --object K (0 to {}) or --object NAME",
            args.input.display(),
            n - 1
        ),
        (Some(k), n) => match k.parse::<usize>() {
            Ok(i) if i < n => &objects[i],
            Ok(i) => bail!("--object {i}: the scene has {n} objects (0 to {})", n - 1),
            Err(_) => objects
                .iter()
                .find(|(name, _)| name == k)
                .ok_or_else(|| anyhow::anyhow!("--object {k}: no object of that name"))?,
        },
    };
    let Surface::Nurbs(nurbs) = surface else {
        bail!(
            "{name} is a {} surface: approx reads NURBS surfaces",
            surface.kind().description()
        );
    };
    let counts = match (args.nu, args.nv) {
        (Some(u), Some(v)) => Some([u as usize, v as usize]),
        (None, None) => None,
        _ => bail!("give both --nu and --nv, or neither"),
    };
    let a = approximate(
        nurbs,
        &ApproxOptions {
            counts,
            tolerance: args.tolerance,
            ..ApproxOptions::default()
        },
    )?;
    let ups = Surface::try_from(a.surface.clone())?;
    crate::output::save_surface(&ups, &args.output)?;
    for (n, max, rms) in &a.tried {
        eprintln!(
            "n_u × n_v = {} × {}: max deviation {}, RMS {}",
            n[0],
            n[1],
            pssurf::text::Significant(*max, 4),
            pssurf::text::Significant(*rms, 4)
        );
    }
    eprintln!(
        "approximated {name} by a UPS surface of {} × {} triangles per side; wrote {}",
        a.counts[0],
        a.counts[1],
        args.output.display()
    );
    Ok(())
}
