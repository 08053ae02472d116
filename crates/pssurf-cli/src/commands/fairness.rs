//! `pssurf fairness`: integrals of curvature and its distribution, to compare surfaces.

use std::path::PathBuf;

use anyhow::{Result, bail};
use pssurf::interrogate::fairness::PERCENTILES;
use pssurf::interrogate::{DEFAULT_QUADRATURE_DEGREE, Fairness, fairness};

/// Arguments of `pssurf fairness`.
#[derive(clap::Args, Debug)]
pub struct FairnessArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// The per-piece quadrature is exact for polynomials of this total degree.
    #[arg(long, default_value_t = DEFAULT_QUADRATURE_DEGREE)]
    pub degree: usize,
}

/// Runs `pssurf fairness`.
pub fn run(args: &FairnessArgs) -> Result<()> {
    if !(1..=40).contains(&args.degree) {
        bail!("--degree must be between 1 and 40");
    }
    let surface = crate::budget::load_surface(&args.surface)?;
    let f = fairness(&surface, args.degree);
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&f)?)?;
    } else {
        out!("{}", table(&f))?;
    }
    Ok(())
}

/// The fairness numbers as a text table.
pub fn table(f: &Fairness) -> String {
    use std::fmt::Write;
    let i = &f.integrals;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "integrals over the surface (Gauss quadrature on every piece, {} nodes)",
        f.nodes
    );
    for (name, v) in [
        ("area  ∫ dA", i.area),
        ("∫ H² dA", i.mean_squared),
        ("∫ K dA", i.gaussian),
        ("∫ |K| dA", i.gaussian_abs),
        ("∫ (κ1² + κ2²) dA", i.principal_squared),
        ("thin plate ∫∫ |s_uu|² + 2|s_uv|² + |s_vv|²", i.thin_plate),
    ] {
        let _ = writeln!(s, "  {name:<44} {v:>14.6e}");
    }
    if f.singular_nodes > 0 {
        let _ = writeln!(s, "  ({} singular nodes left out)", f.singular_nodes);
    }
    let _ = writeln!(s, "\ndistribution (area-weighted percentiles)");
    let _ = write!(s, "  {:<5} {:>12} {:>12} {:>12}", "", "min", "max", "mean");
    for p in PERCENTILES {
        let _ = write!(s, " {:>12}", format!("p{p}"));
    }
    let _ = writeln!(s);
    for (name, q) in &f.stats {
        let _ = write!(
            s,
            "  {name:<5} {:>12.4e} {:>12.4e} {:>12.4e}",
            q.min, q.max, q.mean
        );
        for p in q.percentiles {
            let _ = write!(s, " {p:>12.4e}");
        }
        let _ = writeln!(s);
    }
    s
}
