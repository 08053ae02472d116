//! Colour maps and the scales that bring a quantity to [0, 1] before colouring.
//!
//! A [`ColorMap`] is a table of 1024 colours built once from a `colorgrad` gradient (the
//! perceptual maps of matplotlib and ColorBrewer, Moreland's cool–warm, the seed's
//! green–black–red) or from user stops. A [`ColorScale`] maps values to [0, 1]: linearly
//! over a range, or by the seed's contrast curve κ_norm = sign(κ)(1 − e^(−C|κ|)).

use std::path::Path;

use colorgrad::{BlendMode, Color, Gradient, GradientBuilder, LinearGradient};
use thiserror::Error;

/// Entries in a colour table: odd, so that the middle t = 1/2 (zero on a symmetric range)
/// is one entry and not a rounding tie between two.
const TABLE: usize = 1025;

/// A colour map as a table of 1025 RGB colours over [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct ColorMap {
    name: String,
    table: Vec<[u8; 3]>,
}

/// A colour map could not be made.
#[derive(Debug, Error)]
pub enum ColorMapError {
    /// No built-in map has this name.
    #[error("unknown colour map '{0}' (built-in: {list}; or give a file of stops)", list = ColorMap::NAMES.join(", "))]
    Unknown(String),
    /// A file of stops could not be read.
    #[error("{path}: {message}")]
    BadFile {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

impl ColorMap {
    /// The names of the built-in maps.
    pub const NAMES: [&'static str; 12] = [
        "seed", "viridis", "coolwarm", "rdbu", "turbo", "inferno", "magma", "plasma", "cividis",
        "spectral", "greys", "blues",
    ];

    /// A built-in map by name (case-insensitive):
    ///
    /// - `seed`: green (0) – black (½) – red (1), linear in RGB: seed 000's map, where green
    ///   means κ_norm = −1 and red κ_norm = +1;
    /// - `viridis`, `inferno`, `magma`, `plasma`, `cividis`, `turbo`: sequential perceptual
    ///   maps; `greys`, `blues`: ColorBrewer sequential;
    /// - `coolwarm`: Moreland's diverging cool–warm (blue – light grey – red), interpolated in
    ///   CIELAB through its published control colours; `rdbu` (reversed so that red is
    ///   positive), `spectral`: ColorBrewer diverging.
    pub fn named(name: &str) -> Result<Self, ColorMapError> {
        use colorgrad::preset;
        let lower = name.to_ascii_lowercase();
        let table = match lower.as_str() {
            "seed" => from_stops(
                &[(0.0, [0, 255, 0]), (0.5, [0, 0, 0]), (1.0, [255, 0, 0])],
                BlendMode::Rgb,
            ),
            "coolwarm" => from_stops(
                &[
                    (0.0, [59, 76, 192]),
                    (0.25, [141, 176, 254]),
                    (0.5, [221, 221, 221]),
                    (0.75, [244, 154, 123]),
                    (1.0, [180, 4, 38]),
                ],
                BlendMode::Lab,
            ),
            "viridis" => tabulate(&preset::viridis()),
            "turbo" => tabulate(&preset::turbo()),
            "inferno" => tabulate(&preset::inferno()),
            "magma" => tabulate(&preset::magma()),
            "plasma" => tabulate(&preset::plasma()),
            "cividis" => tabulate(&preset::cividis()),
            "spectral" => tabulate(&preset::spectral()),
            "greys" => tabulate(&preset::greys()),
            "blues" => tabulate(&preset::blues()),
            "rdbu" => {
                let mut t = tabulate(&preset::rd_bu());
                t.reverse();
                t
            }
            _ => return Err(ColorMapError::Unknown(name.to_string())),
        };
        Ok(ColorMap { name: lower, table })
    }

    /// A built-in name, or else a file of stops (see [`ColorMap::from_stops_text`]).
    pub fn named_or_file(spec: &str) -> Result<Self, ColorMapError> {
        match Self::named(spec) {
            Ok(m) => Ok(m),
            Err(_) if Path::new(spec).is_file() => {
                let text = std::fs::read_to_string(spec).map_err(|io| ColorMapError::BadFile {
                    path: spec.to_string(),
                    message: io.to_string(),
                })?;
                Self::from_stops_text(&text).map_err(|message| ColorMapError::BadFile {
                    path: spec.to_string(),
                    message,
                })
            }
            Err(e) => Err(e),
        }
    }

    /// A user map from text: either JSON, `[[position, "#rrggbb"], …]` or
    /// `{"stops": [[position, "#rrggbb"], …], "blend": "rgb"|"lab"|"oklab"}`, or plain lines
    /// `position colour` (colour as `#rrggbb` or a CSS name; lines starting with `#` are
    /// comments). Positions must not decrease and run from 0 to 1; at least two stops.
    pub fn from_stops_text(text: &str) -> Result<Self, String> {
        let trimmed = text.trim_start();
        let (stops, blend): (Vec<(f64, String)>, BlendMode) = if trimmed.starts_with('[')
            || trimmed.starts_with('{')
        {
            parse_json_stops(trimmed)?
        } else {
            let mut stops = Vec::new();
            for (n, line) in text.lines().enumerate() {
                let line = line.trim();
                // A line starts with its position, so one starting with '#' is a comment.
                if line.is_empty() || line.starts_with('#') {
                    continue;
                }
                let mut parts = line.split_whitespace();
                let (Some(p), Some(c), None) = (parts.next(), parts.next(), parts.next()) else {
                    return Err(format!("line {}: expected 'position colour'", n + 1));
                };
                let p: f64 = p
                    .parse()
                    .map_err(|_| format!("line {}: '{p}' is not a number", n + 1))?;
                stops.push((p, c.to_string()));
            }
            (stops, BlendMode::Rgb)
        };
        if stops.len() < 2 {
            return Err("a colour map needs at least two stops".into());
        }
        if stops.first().map(|s| s.0) != Some(0.0) || stops.last().map(|s| s.0) != Some(1.0) {
            return Err("stop positions must run from 0 to 1".into());
        }
        if let Some(w) = stops.windows(2).position(|w| !(w[1].0 >= w[0].0)) {
            return Err(format!("stop {} is not after stop {}", w + 2, w + 1));
        }
        let mut colors = Vec::with_capacity(stops.len());
        for (k, (_, c)) in stops.iter().enumerate() {
            let color = c
                .parse::<Color>()
                .map_err(|_| format!("stop {}: '{c}' is not a colour", k + 1))?;
            colors.push(color);
        }
        let positions: Vec<f32> = stops.iter().map(|s| s.0 as f32).collect();
        let g = GradientBuilder::new()
            .colors(&colors)
            .domain(&positions)
            .mode(blend)
            .build::<LinearGradient>()
            .map_err(|e| e.to_string())?;
        Ok(ColorMap {
            name: "custom".into(),
            table: tabulate(&g),
        })
    }

    /// The map's name ("custom" for user maps).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The colour at t ∈ [0, 1] (clamped; NaN gives grey).
    #[inline]
    pub fn at(&self, t: f64) -> [u8; 3] {
        if t.is_nan() {
            return [128, 128, 128];
        }
        let k = (t.clamp(0.0, 1.0) * (TABLE - 1) as f64).round() as usize;
        self.table[k]
    }
}

fn tabulate(g: &impl Gradient) -> Vec<[u8; 3]> {
    let (a, b) = g.domain();
    (0..TABLE)
        .map(|k| {
            let t = a + (b - a) * k as f32 / (TABLE - 1) as f32;
            let [r, g, b, _] = g.at(t).to_rgba8();
            [r, g, b]
        })
        .collect()
}

fn from_stops(stops: &[(f32, [u8; 3])], mode: BlendMode) -> Vec<[u8; 3]> {
    let colors: Vec<Color> = stops
        .iter()
        .map(|s| Color::from_rgba8(s.1[0], s.1[1], s.1[2], 255))
        .collect();
    let positions: Vec<f32> = stops.iter().map(|s| s.0).collect();
    let g = GradientBuilder::new()
        .colors(&colors)
        .domain(&positions)
        .mode(mode)
        .build::<LinearGradient>()
        .expect("built-in stops are valid");
    tabulate(&g)
}

fn parse_json_stops(text: &str) -> Result<(Vec<(f64, String)>, BlendMode), String> {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Full {
        stops: Vec<(f64, String)>,
        #[serde(default)]
        blend: Option<String>,
    }
    let located = |e: serde_json::Error| format!("line {}, column {}: {e}", e.line(), e.column());
    if text.starts_with('[') {
        let stops: Vec<(f64, String)> = serde_json::from_str(text).map_err(located)?;
        return Ok((stops, BlendMode::Rgb));
    }
    let full: Full = serde_json::from_str(text).map_err(located)?;
    let mode = match full.blend.as_deref().unwrap_or("rgb") {
        "rgb" => BlendMode::Rgb,
        "lab" => BlendMode::Lab,
        "oklab" => BlendMode::Oklab,
        "linear-rgb" => BlendMode::LinearRgb,
        other => {
            return Err(format!(
                "unknown blend '{other}' (rgb, lab, oklab, linear-rgb)"
            ));
        }
    };
    Ok((full.stops, mode))
}

/// How values are brought to [0, 1] for a colour map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ColorScale {
    /// Linear from `lo` (0) to `hi` (1), clamped outside.
    Linear {
        /// The value shown with colour 0.
        lo: f64,
        /// The value shown with colour 1.
        hi: f64,
    },
    /// Seed 000's contrast curve: t = (1 + κ_norm)/2 with κ_norm = sign(κ)(1 − e^(−C|κ|)),
    /// so 0 is the map's middle and ±∞ its ends.
    Contrast {
        /// The contrast factor C > 0 (in the quantity's inverse units).
        c: f64,
    },
}

impl ColorScale {
    /// The position in [0, 1] of a value (NaN stays NaN).
    #[inline]
    pub fn position(&self, v: f64) -> f64 {
        match *self {
            ColorScale::Linear { lo, hi } => {
                // Halved first: hi − lo overflows on ranges like −9e307 … 9e307.
                if hi > lo {
                    ((v / 2.0 - lo / 2.0) / (hi / 2.0 - lo / 2.0)).clamp(0.0, 1.0)
                } else {
                    0.5 + 0.0 * v
                }
            }
            ColorScale::Contrast { c } => 0.5 * (1.0 + v.signum() * (1.0 - (-c * v.abs()).exp())),
        }
    }

    /// The value at position t ∈ (0, 1) (the inverse of [`ColorScale::position`], for legends).
    pub fn value_at(&self, t: f64) -> f64 {
        match *self {
            ColorScale::Linear { lo, hi } => 2.0 * (lo / 2.0 + t * (hi / 2.0 - lo / 2.0)),
            ColorScale::Contrast { c } => {
                let n = 2.0 * t - 1.0;
                -n.signum() * (1.0 - n.abs()).ln() / c
            }
        }
    }

    /// An automatic scale for the values (NaN ignored). Signed quantities get a range
    /// symmetric about 0, ±(98th percentile of |v|); others [1st, 99th percentile]. With
    /// `contrast`, the contrast curve with C such that the 95th percentile of |v| maps to
    /// κ_norm = 0.9 (C = ln 10 / p95). Magnitudes below `negligible` count as zero, so that
    /// rounding noise on a plane is not stretched over the whole map.
    pub fn auto(values: &[f64], signed: bool, contrast: bool, negligible: f64) -> ColorScale {
        let mut finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        if finite.is_empty() {
            return ColorScale::Linear { lo: -1.0, hi: 1.0 };
        }
        if contrast || signed {
            for v in &mut finite {
                *v = v.abs();
            }
        }
        finite.sort_unstable_by(f64::total_cmp);
        let pct = |p: f64| finite[((p / 100.0) * (finite.len() - 1) as f64).round() as usize];
        let floor = negligible.max(f64::MIN_POSITIVE);
        if contrast {
            let p95 = pct(95.0).max(floor);
            return ColorScale::Contrast {
                c: std::f64::consts::LN_10 / p95,
            };
        }
        if signed {
            let m = pct(98.0).max(floor);
            ColorScale::Linear { lo: -m, hi: m }
        } else {
            let (lo, hi) = (pct(1.0), pct(99.0));
            if hi - lo > floor {
                ColorScale::Linear { lo, hi }
            } else {
                let mid = 0.5 * (lo + hi);
                let half = floor.max(mid.abs() * 0.5).max(f64::MIN_POSITIVE);
                ColorScale::Linear {
                    lo: mid - half,
                    hi: mid + half,
                }
            }
        }
    }
}

/// The `p`-th percentile (0 … 100, nearest rank) of finite values, reordering them
/// (O(n): selection, not sorting). None when there are none.
pub fn percentile(values: &mut [f64], p: f64) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let k = ((p.clamp(0.0, 100.0) / 100.0) * (values.len() - 1) as f64).round() as usize;
    let (_, x, _) = values.select_nth_unstable_by(k, f64::total_cmp);
    Some(*x)
}

impl ColorScale {
    /// A linear scale over the robust range of the values (NaN and infinities ignored): from
    /// the `tail`-th to the (100 − `tail`)-th percentile, so that a few outliers do not
    /// stretch the scale (the values beyond it take the end colours; [`DataRange`] counts
    /// them). With `symmetric`, the range is ±(the larger magnitude of the two), so that 0 is
    /// the middle of a diverging map. A range narrower than `negligible` is widened to it,
    /// so that rounding noise on a plane is not stretched over the whole map.
    pub fn robust(values: &[f64], tail: f64, symmetric: bool, negligible: f64) -> ColorScale {
        let mut finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        let tail = tail.clamp(0.0, 49.0);
        let floor = negligible.max(f64::MIN_POSITIVE);
        let (Some(lo), Some(hi)) = (
            percentile(&mut finite, tail),
            percentile(&mut finite, 100.0 - tail),
        ) else {
            return ColorScale::Linear { lo: -1.0, hi: 1.0 };
        };
        if symmetric {
            let m = lo.abs().max(hi.abs()).max(floor);
            return ColorScale::Linear { lo: -m, hi: m };
        }
        if hi - lo > floor {
            return ColorScale::Linear { lo, hi };
        }
        let mid = 0.5 * (lo + hi);
        let half = floor.max(mid.abs() * 0.5).max(f64::MIN_POSITIVE);
        ColorScale::Linear {
            lo: mid - half,
            hi: mid + half,
        }
    }

    /// The values at the ends of the scale (for a contrast curve, where it reaches
    /// κ_norm = ∓0.9).
    pub fn ends(&self) -> (f64, f64) {
        match *self {
            ColorScale::Linear { lo, hi } => (lo, hi),
            ColorScale::Contrast { c } => {
                let m = std::f64::consts::LN_10 / c;
                (-m, m)
            }
        }
    }
}

/// The data behind a colour scale: the true extremes and how many values the scale clips.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DataRange {
    /// The smallest finite value.
    pub min: f64,
    /// The largest finite value.
    pub max: f64,
    /// How many finite values lie below the scale's low end (shown in its first colour).
    pub below: usize,
    /// How many lie above its high end (shown in its last colour).
    pub above: usize,
    /// How many values are finite.
    pub finite: usize,
    /// How many are not (undefined curvature, drawn in the middle colour).
    pub undefined: usize,
}

impl DataRange {
    /// The range of `values` under `scale`; None when no value is finite. A contrast curve
    /// clips nothing (it maps all reals into the map).
    pub fn of(values: &[f64], scale: &ColorScale) -> Option<DataRange> {
        let (lo, hi) = match scale {
            ColorScale::Linear { lo, hi } => (*lo, *hi),
            ColorScale::Contrast { .. } => (f64::NEG_INFINITY, f64::INFINITY),
        };
        let mut r = DataRange {
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            below: 0,
            above: 0,
            finite: 0,
            undefined: 0,
        };
        for &v in values {
            if !v.is_finite() {
                r.undefined += 1;
                continue;
            }
            r.finite += 1;
            r.min = r.min.min(v);
            r.max = r.max.max(v);
            r.below += usize::from(v < lo);
            r.above += usize::from(v > hi);
        }
        (r.finite > 0).then_some(r)
    }

    /// The share of finite values that the scale clips, in percent.
    pub fn clipped_percent(&self) -> f64 {
        100.0 * (self.below + self.above) as f64 / self.finite.max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 14: one outlier (or a few, up to the tail) does not stretch the scale, and the
    /// data range reports it as clipped.
    #[test]
    fn robust_ranges_ignore_outliers_and_report_them() {
        // 1000 values uniform in [-1, 1], then 5 outliers at 26.
        let mut v: Vec<f64> = (0..1000).map(|k| -1.0 + 2.0 * k as f64 / 999.0).collect();
        v.extend([26.0; 5]);
        let s = ColorScale::robust(&v, 1.0, true, 1e-9);
        let (lo, hi) = s.ends();
        assert!(lo == -hi && hi < 1.0 && hi > 0.97, "{s:?}");
        let r = DataRange::of(&v, &s).unwrap();
        assert_eq!((r.min, r.max), (-1.0, 26.0));
        // The outliers and at most the 1 % tail above, at most the 1 % tail below.
        assert!((5..=16).contains(&r.above) && r.below <= 11, "{r:?}");
        // Not symmetric: the 1st and 99th percentiles themselves, exactly (nearest rank).
        let s = ColorScale::robust(&v, 1.0, false, 1e-9);
        let mut sorted = v.clone();
        sorted.sort_by(f64::total_cmp);
        let rank = |p: f64| sorted[((p / 100.0) * (sorted.len() - 1) as f64).round() as usize];
        assert_eq!(
            s,
            ColorScale::Linear {
                lo: rank(1.0),
                hi: rank(99.0)
            }
        );
        // Min/max: tail 0.
        assert_eq!(
            ColorScale::robust(&v, 0.0, false, 1e-9),
            ColorScale::Linear { lo: -1.0, hi: 26.0 }
        );
        // Undefined values are counted, not used; none finite gives no range.
        let r = DataRange::of(&[f64::NAN, 1.0, f64::INFINITY], &s).unwrap();
        assert_eq!((r.finite, r.undefined), (1, 2));
        assert!(DataRange::of(&[f64::NAN], &s).is_none());
        // A plane's rounding noise does not fill the map.
        let noise = [1e-17, -2e-17, 0.0];
        assert_eq!(
            ColorScale::robust(&noise, 1.0, true, 1e-9),
            ColorScale::Linear {
                lo: -1e-9,
                hi: 1e-9
            }
        );
    }

    /// The selection percentile agrees with sorting on random data.
    #[test]
    fn percentile_by_selection_matches_sorting() {
        let mut x = 0.123_f64;
        for n in [1usize, 2, 3, 10, 101, 1000] {
            let v: Vec<f64> = (0..n)
                .map(|_| {
                    x = (x * 9301.0 + 0.4929).fract();
                    x * 100.0 - 50.0
                })
                .collect();
            let mut sorted = v.clone();
            sorted.sort_by(f64::total_cmp);
            for p in [0.0, 1.0, 37.5, 50.0, 99.0, 100.0] {
                let want = sorted[((p / 100.0) * (n - 1) as f64).round() as usize];
                assert_eq!(percentile(&mut v.clone(), p), Some(want), "n {n} p {p}");
            }
        }
        assert_eq!(percentile(&mut [], 50.0), None);
    }

    #[test]
    fn the_seed_map_runs_green_black_red() {
        let m = ColorMap::named("seed").unwrap();
        assert_eq!(m.at(0.0), [0, 255, 0]);
        assert_eq!(m.at(0.5), [0, 0, 0]);
        assert_eq!(m.at(1.0), [255, 0, 0]);
        let c = ColorScale::Contrast { c: 2.0 };
        assert_eq!(c.position(0.0), 0.5);
        // κ_norm = 1 − e^{−C|κ|}: κ = ln 2 / C gives κ_norm = 1/2.
        let k = 2f64.ln() / 2.0;
        assert!((c.position(k) - 0.75).abs() < 1e-15);
        assert!((c.position(-k) - 0.25).abs() < 1e-15);
        for t in [0.1, 0.3, 0.5, 0.77, 0.95] {
            assert!((c.position(c.value_at(t)) - t).abs() < 1e-12);
        }
    }

    #[test]
    fn every_named_map_exists_and_is_a_gradient() {
        for name in ColorMap::NAMES {
            let m = ColorMap::named(name).unwrap();
            assert_eq!(m.table.len(), TABLE);
            assert_ne!(m.at(0.0), m.at(1.0), "{name}");
        }
        let e = ColorMap::named("nope").unwrap_err().to_string();
        assert!(e.contains("viridis"), "{e}");
        // Viridis starts dark purple and ends yellow.
        let v = ColorMap::named("viridis").unwrap();
        assert!(v.at(0.0)[2] > v.at(0.0)[1] && v.at(1.0)[0] > 200);
        // Red means positive in the diverging maps.
        for name in ["coolwarm", "rdbu"] {
            let m = ColorMap::named(name).unwrap();
            assert!(
                m.at(1.0)[0] > m.at(1.0)[2] && m.at(0.0)[2] > m.at(0.0)[0],
                "{name}"
            );
        }
    }

    #[test]
    fn user_maps_from_text_and_json() {
        let m = ColorMap::from_stops_text("0 #000000\n0.5 red\n1 #ffffff\n").unwrap();
        assert_eq!(m.at(0.0), [0, 0, 0]);
        assert_eq!(m.at(0.5), [255, 0, 0]);
        assert_eq!(m.at(1.0), [255, 255, 255]);
        let j = ColorMap::from_stops_text(
            r##"{"stops": [[0, "#0000ff"], [1, "#ff0000"]], "blend": "lab"}"##,
        )
        .unwrap();
        assert_eq!(j.at(0.0), [0, 0, 255]);
        let bare = ColorMap::from_stops_text(r##"[[0, "black"], [1, "white"]]"##).unwrap();
        assert_eq!(bare.at(1.0), [255, 255, 255]);
        for (bad, why) in [
            ("0 #000\n", "two stops"),
            ("0 #000\n0.5 #fff\n", "from 0 to 1"),
            ("0 #000\n0.7 #fff\n0.5 #fff\n1 #000", "not after"),
            ("0 #000\n1 notacolour\n", "not a colour"),
            ("0 #000 extra\n1 #fff", "expected"),
            ("[[0, \"#000\"], [1]]", "line 1"),
        ] {
            let e = ColorMap::from_stops_text(bad).unwrap_err();
            assert!(e.contains(why), "{bad:?}: {e}");
        }
    }

    #[test]
    fn automatic_scales() {
        let v: Vec<f64> = (-100..=100)
            .map(|k| k as f64 / 100.0)
            .chain([f64::NAN, 50.0])
            .collect();
        let ColorScale::Linear { lo, hi } = ColorScale::auto(&v, true, false, 0.0) else {
            panic!()
        };
        assert_eq!(lo, -hi);
        assert!(hi > 0.9 && hi <= 1.0, "{hi}");
        let ColorScale::Linear { lo, hi } = ColorScale::auto(&v, false, false, 0.0) else {
            panic!()
        };
        assert!(lo < -0.9 && hi > 0.9 && hi < 2.0);
        let ColorScale::Contrast { c } = ColorScale::auto(&v, true, true, 0.0) else {
            panic!()
        };
        let p95 = 0.95;
        assert!((1.0 - (-c * p95).exp() - 0.9).abs() < 0.02, "{c}");
        // Rounding noise stays in the middle of the map.
        let noise = [1e-17, -3e-16, 2e-16];
        let s = ColorScale::auto(&noise, true, false, 1e-9);
        assert!(noise.iter().all(|&v| (s.position(v) - 0.5).abs() < 1e-6));
        // A constant quantity still gets a usable range.
        let ColorScale::Linear { lo, hi } = ColorScale::auto(&[2.0; 10], false, false, 1e-9) else {
            panic!()
        };
        assert!(lo < 2.0 && hi > 2.0);
    }
}

#[cfg(test)]
mod fuzz {
    //! Issue 13: colour-map files and value ranges never make the colour code panic.

    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn colour_map_texts_and_values_never_panic(
            text in "\\PC{0,60}|\\[(\\[(-?[0-9.e]{1,6}|1e400|NaN), \"#[0-9a-fA-F]{0,7}\"\\],? ?){0,5}\\]",
            values in proptest::collection::vec(prop_oneof![any::<f64>(), Just(f64::NAN), Just(f64::INFINITY), Just(1e308), Just(-0.0)], 0..20),
        ) {
            if let Ok(map) = ColorMap::from_stops_text(&text) {
                for t in [f64::NAN, f64::NEG_INFINITY, -1.0, 0.0, 0.5, 1.0, 2.0, f64::INFINITY] {
                    let _ = map.at(t);
                }
            }
            let _ = ColorMap::named_or_file(&text);
            for signed in [false, true] {
                let scale = ColorScale::auto(&values, signed, true, 1e-12);
                for &v in &values {
                    let p = scale.position(v);
                    prop_assert!(p.is_nan() || (0.0..=1.0).contains(&p), "{v} -> {p}");
                }
            }
        }
    }
}
