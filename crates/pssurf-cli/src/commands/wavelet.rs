//! `pssurf wavelet`: the UPS wavelet decomposition and its spectrum.

use std::path::PathBuf;

use anyhow::Result;
use pssurf::surface::{Surface, UpsDecomposition};
use serde_json::json;

use super::denoise::stats_table;
use super::uniform;

/// Arguments of `pssurf wavelet`.
#[derive(clap::Args, Debug)]
pub struct WaveletArgs {
    /// A UPS surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// The number of levels F.
    #[arg(long, value_name = "F", value_parser = clap::value_parser!(u32).range(1..=40))]
    pub levels: u32,
    /// Write the decomposition (the coarse surface and every detail triple with its lattice
    /// coordinates) as JSON.
    #[arg(short, long, value_name = "COEFFS.json")]
    pub output: Option<PathBuf>,
}

/// Runs `pssurf wavelet`.
pub fn run(args: &WaveletArgs) -> Result<()> {
    let file = crate::budget::load_surface(&args.surface)?;
    let u = uniform::require(&file, &args.surface, "wavelet")?;
    let json = report(&u.wavelet_transform(args.levels)?, u.coordinate_names())?;
    if let Some(path) = &args.output {
        let text = serde_json::to_string(&json)? + "\n";
        crate::output::write_output(path, pssurf::io::Durability::Atomic, |w| {
            Ok(w.write_all(text.as_bytes())?)
        })?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// Prints the spectrum and histograms; returns the decomposition as JSON.
fn report(dec: &UpsDecomposition, names: &[&str]) -> Result<serde_json::Value> {
    let spectrum = dec.spectrum();
    outln!(
        "UPS wavelet spectrum, {} levels (level 1 is the coarsest)",
        dec.levels()
    )?;
    outln!("{}", stats_table(&spectrum, names, false))?;
    outln!()?;
    outln!("histograms of |d| / max |d| per level and coordinate (10 bins):")?;
    for s in &spectrum {
        let d = dec.coefficients(s.level - 1, s.component);
        let mut bins = [0usize; 10];
        for x in &d {
            let r = if s.max_abs > 0.0 {
                x.abs() / s.max_abs
            } else {
                0.0
            };
            bins[((r * 10.0) as usize).min(9)] += 1;
        }
        let top = *bins.iter().max().unwrap_or(&1).max(&1);
        let bars: Vec<String> = bins
            .iter()
            .map(|&b| format!("{:<8}", "#".repeat((b * 8).div_ceil(top))))
            .collect();
        outln!(
            "level {} {:>2}  |{}|",
            s.level,
            names.get(s.component).copied().unwrap_or("?"),
            bars.join("|")
        )?;
    }
    let coarse_text = pssurf::io::to_json_string(&Surface::try_from(dec.coarse())?);
    let coarse: serde_json::Value = serde_json::from_str(&coarse_text).expect("our own JSON");
    let details: Vec<serde_json::Value> = (0..dec.levels())
        .map(|k| {
            let coeffs: Vec<serde_json::Value> = dec
                .detail_rows(k)
                .into_iter()
                .map(|row| json!({ "ij": row.ij, "d": row.d }))
                .collect();
            json!({ "level": k + 1, "base": dec.level_base(k), "coefficients": coeffs })
        })
        .collect();
    Ok(json!({
        "format": "pssurf-wavelet",
        "version": 1,
        "levels": dec.levels(),
        "coarse": coarse,
        "details": details,
    }))
}
