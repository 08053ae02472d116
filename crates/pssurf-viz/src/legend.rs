//! The legend: a colour bar with numeric ticks and the quantity's name.

use crate::colormap::{ColorMap, ColorScale, DataRange};
use crate::text::{Align, TextStyle, draw_text, text_width};
use pssurf::text::Significant;

/// A rectangle in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Left edge.
    pub x: f32,
    /// Top edge.
    pub y: f32,
    /// Width.
    pub w: f32,
    /// Height.
    pub h: f32,
}

/// A "nice" step (1, 2 or 5 times a power of ten) close to `raw`.
pub fn nice_step(raw: f64) -> f64 {
    if !(raw > 0.0 && raw.is_finite()) {
        return 1.0;
    }
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    p * if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    }
}

/// A tick label: as many decimals as the step needs, scientific notation for very large or
/// small steps.
pub fn format_tick(v: f64, step: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !(1e-4..1e5).contains(&step) {
        return format!("{v:.1e}");
    }
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// The most ticks a scale gets (a nice step of a fifth of the range gives 4 to 11; more only
/// when the range is not a range of numbers, and then none are drawn).
const MAX_TICKS: usize = 100;

/// The tick values of a scale, with positions in [0, 1].
pub fn ticks(scale: &ColorScale) -> Vec<(f64, f64)> {
    let (lo, hi) = match *scale {
        ColorScale::Linear { lo, hi } => (lo, hi),
        // The contrast curve reaches κ_norm = 0.9 at ln 10 / C: tick up to there.
        // (Capped: a contrast below about 1e-307 would put it at infinity.)
        ColorScale::Contrast { c } => {
            let m = (std::f64::consts::LN_10 / c).min(f64::MAX / 2.0);
            (-m, m)
        }
    };
    // hi/5 − lo/5: a range wider than the largest float (−9e307 … 9e307) has a finite step.
    let step = nice_step(hi / 5.0 - lo / 5.0);
    let (first, last) = ((lo / step).ceil(), (hi / step).floor());
    if !(first.is_finite() && last.is_finite() && last - first <= MAX_TICKS as f64) {
        return Vec::new();
    }
    (first as i64..=last as i64)
        .map(|k| k as f64 * step)
        .map(|v| (v, scale.position(v)))
        .filter(|(_, t)| (0.0..=1.0).contains(t))
        .collect()
}

/// The legend's ink: title, frame, tick marks and labels.
const INK: [u8; 3] = [20, 20, 20];

/// Draws the legend into `area` of the picture: the title (wrapped at spaces) at the top, a
/// vertical colour bar (value increasing upwards) with tick marks and labels.
pub fn draw_legend(
    image: &mut [[u8; 3]],
    width: usize,
    area: Rect,
    title: &str,
    map: &ColorMap,
    scale: &ColorScale,
) {
    draw_legend_data(image, width, area, title, map, scale, None);
}

/// [`draw_legend`], with the data's true maximum above the bar and minimum below it, each
/// marked with an arrow (▲, ▼) when the scale clips values on that side.
pub fn draw_legend_data(
    image: &mut [[u8; 3]],
    width: usize,
    area: Rect,
    title: &str,
    map: &ColorMap,
    scale: &ColorScale,
    data: Option<&DataRange>,
) {
    let font = (area.w / 9.0).clamp(11.0, 18.0);
    let style = TextStyle {
        size: font,
        color: INK,
        align: Align::Left,
    };
    let mut y = draw_title(image, width, area, title, &style);
    let mut bottom = area.y + area.h;
    if let Some(d) = data {
        let (top, low) = extreme_labels(d);
        y += 0.3 * font;
        draw_text(image, width, area.x + 2.0, y, &top, &style);
        y += 0.3 * font;
        draw_text(
            image,
            width,
            area.x + 2.0,
            bottom - 0.3 * font,
            &low,
            &style,
        );
        bottom -= 1.4 * font;
    }
    let bar = Rect {
        x: area.x + 4.0,
        y: y + 0.5 * font,
        w: (area.w * 0.18).clamp(10.0, 24.0),
        h: (bottom - y - 1.5 * font).max(10.0),
    };
    let height = image.len() / width.max(1);
    let pixels = BarPixels::of(&bar);
    fill_bar(image, width, height, pixels, map);
    draw_frame(image, width, height, pixels);
    draw_ticks(image, width, height, &bar, scale, &style);
}

/// The labels of the data's maximum and minimum: `▲ max 26.3` when values above the scale
/// are clipped, else `max 0.98`; likewise `▼ min …`.
pub fn extreme_labels(d: &DataRange) -> (String, String) {
    let mark = |clipped: usize, arrow: &'static str| if clipped > 0 { arrow } else { " " };
    (
        format!("{} max {}", mark(d.above, "▲"), Significant(d.max, 4)),
        format!("{} min {}", mark(d.below, "▼"), Significant(d.min, 4)),
    )
}

/// The words of `title` in lines at most `max_width` wide at font size `font`.
fn wrap_title(title: &str, font: f32, max_width: f32) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in title.split_whitespace() {
        match lines.last_mut() {
            Some(l) if text_width(&format!("{l} {word}"), font) <= max_width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Draws the title wrapped to the area's width at its top; returns the baseline below it.
fn draw_title(
    image: &mut [[u8; 3]],
    width: usize,
    area: Rect,
    title: &str,
    style: &TextStyle,
) -> f32 {
    let font = style.size;
    let mut y = area.y + font;
    for l in &wrap_title(title, font, area.w - 4.0) {
        draw_text(image, width, area.x + 2.0, y, l, style);
        y += font * 1.2;
    }
    y
}

/// The colour bar's edges rounded to whole pixels: columns `x0..x1`, rows `y0..y1`.
#[derive(Clone, Copy, Debug)]
struct BarPixels {
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
}

impl BarPixels {
    /// The pixel edges of the bar's rectangle.
    fn of(bar: &Rect) -> Self {
        BarPixels {
            x0: bar.x.round() as usize,
            x1: (bar.x + bar.w).round() as usize,
            y0: bar.y.round() as usize,
            y1: (bar.y + bar.h).round() as usize,
        }
    }
}

/// Fills the bar with the colour map, from its end at the top to its start at the bottom.
fn fill_bar(image: &mut [[u8; 3]], width: usize, height: usize, bar: BarPixels, map: &ColorMap) {
    let BarPixels { x0, x1, y0, y1 } = bar;
    for row in y0..y1.min(height) {
        let t = 1.0 - (row - y0) as f64 / (y1 - y0).max(1) as f64;
        let c = map.at(t);
        for col in x0..x1.min(width) {
            image[row * width + col] = c;
        }
    }
}

/// Draws a thin frame of ink one pixel outside the bar.
fn draw_frame(image: &mut [[u8; 3]], width: usize, height: usize, bar: BarPixels) {
    let BarPixels { x0, x1, y0, y1 } = bar;
    for row in y0.saturating_sub(1)..(y1 + 1).min(height) {
        for col in [x0.saturating_sub(1), x1] {
            if col < width {
                image[row * width + col] = INK;
            }
        }
    }
    for col in x0.saturating_sub(1)..(x1 + 1).min(width) {
        for row in [y0.saturating_sub(1), y1] {
            if row < height {
                image[row * width + col] = INK;
            }
        }
    }
}

/// Draws the scale's ticks right of the bar: a 5-pixel mark and the value's label at each.
fn draw_ticks(
    image: &mut [[u8; 3]],
    width: usize,
    height: usize,
    bar: &Rect,
    scale: &ColorScale,
    style: &TextStyle,
) {
    let x1 = BarPixels::of(bar).x1;
    let ticks = ticks(scale);
    let step = if ticks.len() > 1 {
        ticks[1].0 - ticks[0].0
    } else {
        1.0
    };
    for (v, t) in ticks {
        let row = (bar.y + (1.0 - t as f32) * bar.h).round();
        for col in x1..(x1 + 5).min(width) {
            if (row as usize) < height {
                image[row as usize * width + col] = INK;
            }
        }
        draw_text(
            image,
            width,
            bar.x + bar.w + 8.0,
            row + 0.35 * style.size,
            &format_tick(v, step),
            style,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A range wider than the largest float (its width overflows) and a contrast whose tick
    /// range is infinite asked for 2⁶⁴ ticks: plot and domain aborted allocating them.
    #[test]
    fn ranges_beyond_the_largest_float_get_a_few_ticks() {
        for (lo, hi) in [(-9e307, 9e307), (-1.7e308, 1e308), (-f64::MAX, f64::MAX)] {
            let t = ticks(&ColorScale::Linear { lo, hi });
            assert!((3..=11).contains(&t.len()), "{lo} … {hi}: {t:?}");
            assert!(
                t.iter()
                    .all(|(v, p)| v.is_finite() && (0.0..=1.0).contains(p))
            );
            // Positions spread over the bar, and back to their values.
            assert!(t[0].1 < 0.25 && t[t.len() - 1].1 > 0.75, "{t:?}");
            let scale = ColorScale::Linear { lo, hi };
            for &(v, p) in &t {
                assert!(
                    (scale.value_at(p) - v).abs() <= 1e-12 * v.abs().max(hi),
                    "{v} {p}"
                );
            }
        }
        for c in [1e-308, 5e-324] {
            let t = ticks(&ColorScale::Contrast { c });
            assert!(t.len() <= MAX_TICKS, "contrast {c}: {} ticks", t.len());
        }
    }

    #[test]
    fn nice_ticks() {
        assert_eq!(nice_step(0.23), 0.2);
        assert_eq!(nice_step(4.0), 5.0);
        assert_eq!(nice_step(0.0013), 0.001);
        let t = ticks(&ColorScale::Linear { lo: -1.3, hi: 1.3 });
        let v: Vec<f64> = t.iter().map(|x| x.0).collect();
        assert_eq!(v, vec![-1.0, -0.5, 0.0, 0.5, 1.0]);
        assert_eq!(format_tick(0.5, 0.5), "0.5");
        assert_eq!(format_tick(-2.0, 1.0), "-2");
        assert_eq!(format_tick(3e-6, 1e-6), "3.0e-6");
        // Contrast scale: symmetric about the middle of the bar.
        let t = ticks(&ColorScale::Contrast { c: 1.0 });
        assert!(t.iter().any(|&(v, p)| v == 0.0 && (p - 0.5).abs() < 1e-15));
        for &(v, p) in &t {
            assert!(
                t.iter()
                    .any(|&(w, q)| w == -v && (p + q - 1.0).abs() < 1e-12)
            );
        }
    }
}
