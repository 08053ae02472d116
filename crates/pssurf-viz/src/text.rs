//! Anti-aliased text on RGB pictures (the Hack typeface, embedded).

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};

/// The embedded typeface.
fn font() -> FontRef<'static> {
    FontRef::try_from_slice(epaint_default_fonts::HACK_REGULAR).expect("the embedded font is valid")
}

/// Where a text is anchored horizontally.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Align {
    /// `x` is the left end.
    Left,
    /// `x` is the middle.
    Center,
    /// `x` is the right end.
    Right,
}

/// The width in pixels of `text` at `size` pixels.
pub fn text_width(text: &str, size: f32) -> f32 {
    let f = font();
    let s = f.as_scaled(PxScale::from(size));
    text.chars().map(|c| s.h_advance(f.glyph_id(c))).sum()
}

/// How a text looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextStyle {
    /// Height in pixels.
    pub size: f32,
    /// Colour.
    pub color: [u8; 3],
    /// Horizontal anchoring.
    pub align: Align,
}

/// Draws `text` with its baseline at `y`, blending its colour over the picture (RGB,
/// row-major, `width` pixels per row). Returns the drawn width.
pub fn draw_text(
    image: &mut [[u8; 3]],
    width: usize,
    x: f32,
    y: f32,
    text: &str,
    style: &TextStyle,
) -> f32 {
    let TextStyle { size, color, align } = *style;
    let f = font();
    let scale = PxScale::from(size);
    let scaled = f.as_scaled(scale);
    let w = text_width(text, size);
    let mut caret = match align {
        Align::Left => x,
        Align::Center => x - 0.5 * w,
        Align::Right => x - w,
    };
    let height = image.len() / width.max(1);
    for c in text.chars() {
        let id = f.glyph_id(c);
        let glyph = id.with_scale_and_position(scale, point(caret, y));
        caret += scaled.h_advance(id);
        let Some(outline) = f.outline_glyph(glyph) else {
            continue;
        };
        let b = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (px, py) = (b.min.x as i64 + gx as i64, b.min.y as i64 + gy as i64);
            if px < 0 || py < 0 || px >= width as i64 || py >= height as i64 {
                return;
            }
            let p = &mut image[py as usize * width + px as usize];
            let a = coverage.clamp(0.0, 1.0);
            for k in 0..3 {
                p[k] = (p[k] as f32 * (1.0 - a) + color[k] as f32 * a).round() as u8;
            }
        });
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_leaves_ink_where_it_is_drawn() {
        let (w, h) = (120, 40);
        let mut img = vec![[255u8; 3]; w * h];
        let style = TextStyle {
            size: 20.0,
            color: [0, 0, 0],
            align: Align::Left,
        };
        let drawn = draw_text(&mut img, w, 10.0, 28.0, "K = 1.5", &style);
        assert!(drawn > 50.0 && drawn < 110.0, "{drawn}");
        let ink = img.iter().filter(|p| p[0] < 128).count();
        assert!(ink > 40, "{ink}");
        // Nothing left of x = 9 or right of the text.
        for row in 0..h {
            for col in (0..9).chain((12 + drawn as usize)..w) {
                assert_eq!(img[row * w + col], [255; 3]);
            }
        }
        assert!((text_width("abc", 20.0) - 3.0 * text_width("a", 20.0)).abs() < 1e-3);
    }
}
