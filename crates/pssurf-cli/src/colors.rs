//! The colour options shared by `plot`, `domain` and `export`.

use anyhow::{Result, bail};
use pssurf::interrogate::CurvatureQuantity;
use pssurf_viz::{ColorMap, Range};

/// A colour map, a range and a contrast.
#[derive(clap::Args, Clone, Debug)]
pub struct ColorArgs {
    /// The colour map: seed (the thesis' green–black–red), coolwarm, rdbu, viridis, turbo,
    /// inferno, magma, plasma, cividis, spectral, greys, blues — or a file of stops (lines
    /// `position colour`, or JSON `[[0, "#3b4cc0"], …, [1, "#b40426"]]`). Default: coolwarm
    /// for signed quantities, viridis for absolute curvature.
    #[arg(long, value_name = "NAME|FILE")]
    pub colormap: Option<String>,
    /// The value range: `auto` (symmetric ±98th percentile of |q| for signed quantities,
    /// 1st–99th percentile otherwise) or `a,b`.
    #[arg(
        long,
        value_name = "auto|a,b",
        default_value = "auto",
        allow_hyphen_values = true
    )]
    pub range: String,
    /// Use the seed's contrast curve κ_norm = sign(κ)(1 − e^(−C|κ|)) with this C instead of a
    /// linear range (with --colormap seed and no --contrast, C is chosen automatically).
    #[arg(long, value_name = "C", allow_hyphen_values = true)]
    pub contrast: Option<f64>,
}

impl ColorArgs {
    /// The colour map for a quantity.
    pub fn map(&self, q: CurvatureQuantity) -> Result<ColorMap> {
        let name = self.colormap.clone().unwrap_or_else(|| {
            if q.is_signed() {
                "coolwarm".into()
            } else {
                "viridis".into()
            }
        });
        Ok(ColorMap::named_or_file(&name)?)
    }

    /// The range choice.
    pub fn range(&self) -> Result<Range> {
        if let Some(c) = self.contrast {
            if !(c > 0.0 && c.is_finite()) {
                bail!(
                    "--contrast must be a positive number (got {})",
                    pssurf::text::Short(c)
                );
            }
            return Ok(Range::Contrast(c));
        }
        if self.range.eq_ignore_ascii_case("auto") {
            return Ok(Range::Auto);
        }
        let parts: Vec<&str> = self.range.split(',').collect();
        let nums: Vec<f64> = parts.iter().filter_map(|t| t.trim().parse().ok()).collect();
        match nums.as_slice() {
            [a, b] if a.is_finite() && b.is_finite() && a < b && parts.len() == 2 => {
                Ok(Range::Fixed(*a, *b))
            }
            _ => bail!(
                "--range must be `auto` or two increasing numbers `a,b` (got `{}`)",
                self.range
            ),
        }
    }
}

/// Parses a quantity name for the command line.
pub fn quantity(s: &str) -> Result<CurvatureQuantity, String> {
    CurvatureQuantity::parse(s).ok_or_else(|| {
        format!(
            "`{s}` is not a curvature quantity (K, H, k1, k2, kabs; or gaussian, mean, absolute)"
        )
    })
}
