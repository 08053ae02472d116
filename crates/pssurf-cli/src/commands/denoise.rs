//! `pssurf denoise`: wavelet thresholding of a UPS surface (thesis 4.5.6).

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use pssurf::surface::Surface;
use pssurf::ups::threshold::{LevelStats, Shrink, ThresholdRule};

use super::uniform;

/// Hard or soft thresholding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Mode {
    /// Zero the small coefficients, keep the others.
    Hard,
    /// Zero the small coefficients, move the others towards zero by the threshold.
    Soft,
}

/// Automatic threshold rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Auto {
    /// σ √(2 ln n) with σ = median |d| / 0.6745, per level and coordinate.
    Universal,
    /// Minimises Stein's unbiased risk estimate (SureShrink).
    Sure,
    /// Minimises generalized cross validation.
    Gcv,
}

/// Arguments of `pssurf denoise`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("rule").required(true).args(["threshold", "auto", "per_level"])))]
pub struct DenoiseArgs {
    /// A UPS surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// The number of wavelet levels F (the polygon's corners must lie on the lattice of base
    /// 2^F·B; a surface subdivided F times always allows it).
    #[arg(long, value_name = "F", value_parser = clap::value_parser!(u32).range(1..=40))]
    pub levels: u32,
    /// One threshold for every level and coordinate: a percentage of the level's largest
    /// coefficient (`5%`) or an absolute value (`0.01`).
    #[arg(long, value_name = "5%|0.01", allow_hyphen_values = true)]
    pub threshold: Option<String>,
    /// An automatic threshold, chosen per level and coordinate from the coefficients.
    #[arg(long, value_enum)]
    pub auto: Option<Auto>,
    /// One threshold per level, coarsest first (`10%,5%,0.002`).
    #[arg(long, value_name = "a,b,c")]
    pub per_level: Option<String>,
    /// Soft (default) or hard thresholding.
    #[arg(long, value_enum, default_value_t = Mode::Soft)]
    pub mode: Mode,
    /// The surface file to write (binary when it ends in `.psb`, else JSON; docs/format.md).
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// Parses `5%` or `0.01`.
pub fn parse_threshold(s: &str) -> Result<ThresholdRule> {
    let s = s.trim();
    let rule = match s.strip_suffix('%') {
        Some(p) => ThresholdRule::PercentOfMax(
            p.trim()
                .parse()
                .with_context(|| format!("`{s}` is not a percentage"))?,
        ),
        None => ThresholdRule::Absolute(
            s.parse()
                .with_context(|| format!("`{s}` is not a number or a percentage"))?,
        ),
    };
    match rule {
        ThresholdRule::PercentOfMax(v) | ThresholdRule::Absolute(v)
            if !(v >= 0.0 && v.is_finite()) =>
        {
            bail!("thresholds must be finite and non-negative, not `{s}`")
        }
        r => Ok(r),
    }
}

/// Runs `pssurf denoise`.
pub fn run(args: &DenoiseArgs) -> Result<()> {
    let file = crate::budget::load_surface(&args.surface)?;
    let u = uniform::require(&file, &args.surface, "denoise")?;
    let rules: Vec<ThresholdRule> = match (&args.threshold, args.auto, &args.per_level) {
        (Some(t), _, _) => vec![parse_threshold(t)?; args.levels as usize],
        (_, Some(a), _) => vec![
            match a {
                Auto::Universal => ThresholdRule::Universal,
                Auto::Sure => ThresholdRule::Sure,
                Auto::Gcv => ThresholdRule::Gcv,
            };
            args.levels as usize
        ],
        (_, _, Some(list)) => {
            let r: Vec<ThresholdRule> = list
                .split(',')
                .map(parse_threshold)
                .collect::<Result<_>>()?;
            if r.len() != args.levels as usize {
                bail!(
                    "--per-level gives {} thresholds for {} levels",
                    r.len(),
                    args.levels
                );
            }
            r
        }
        _ => bail!("give --threshold, --auto or --per-level"),
    };
    let mode = match args.mode {
        Mode::Hard => Shrink::Hard,
        Mode::Soft => Shrink::Soft,
    };
    let names = u.coordinate_names();
    let (out, stats) = u.denoise(args.levels, |level, _| rules[level], mode)?;
    outln!("{}", stats_table(&stats, names, true))?;
    let removed: usize = stats.iter().map(|s| s.zeroed).sum();
    let total: usize = stats.iter().map(|s| s.count).sum();
    outln!(
        "rule: {} thresholding, {}; {removed} of {total} coefficients ({:.2}%) set to zero",
        match args.mode {
            Mode::Hard => "hard",
            Mode::Soft => "soft",
        },
        if rules.windows(2).all(|w| w[0] == w[1]) {
            format!("{} at every level", rules[0].name())
        } else {
            format!(
                "{} (coarsest first)",
                rules
                    .iter()
                    .map(|r| r.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        },
        100.0 * removed as f64 / total.max(1) as f64
    )?;
    crate::output::save_surface(&Surface::try_from(out)?, &args.output)?;
    eprintln!("wrote {}", args.output.display());
    Ok(())
}

/// The per-level table (the thesis' table after 4.5.6).
pub fn stats_table(stats: &[LevelStats], names: &[&str], thresholds: bool) -> String {
    let mut out = String::new();
    if thresholds {
        out += "level  coord     count     max |d|    threshold  zeroed\n";
    } else {
        out += "level  coord     count     max |d|     rms |d|       norm\n";
    }
    for s in stats {
        let name = names.get(s.component).copied().unwrap_or("?");
        if thresholds {
            out += &format!(
                "{:>5}  {:>5}  {:>8}  {:>10.3e}  {:>11.3e}  {:>6.2}%\n",
                s.level,
                name,
                s.count,
                s.max_abs,
                s.threshold,
                s.zeroed_percent()
            );
        } else {
            let rms = s.norm / (s.count.max(1) as f64).sqrt();
            out += &format!(
                "{:>5}  {:>5}  {:>8}  {:>10.3e}  {:>10.3e}  {:>9.3e}\n",
                s.level, name, s.count, s.max_abs, rms, s.norm
            );
        }
    }
    out.trim_end().to_string()
}
