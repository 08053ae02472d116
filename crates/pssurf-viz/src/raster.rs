//! A software rasteriser with deferred shading: triangles go into a G-buffer (nearest
//! triangle and its barycentric coordinates per pixel), then every pixel is shaded once from
//! the attributes of its triangle. Both passes run in parallel over horizontal bands.

use rayon::prelude::*;

/// No triangle covers the pixel.
pub const EMPTY: u32 = u32::MAX;

/// Rows per band of parallel work.
const BAND: usize = 16;

/// A vertex on the screen.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenVertex {
    /// Pixel column (continuous; pixel centres at k + 0.5).
    pub x: f32,
    /// Pixel row (continuous).
    pub y: f32,
    /// Depth key: larger is nearer. It must be affine in screen space over a triangle
    /// (the view depth for orthographic views, 1/w for perspective ones).
    pub z: f32,
    /// 1/w for perspective-correct interpolation (1 for orthographic views).
    pub inv_w: f32,
}

/// For every pixel, the nearest triangle and where in it the pixel centre lies.
#[derive(Clone, Debug)]
pub struct GBuffer {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The depth key of the nearest surface (−∞ where empty).
    pub depth: Vec<f32>,
    /// The nearest triangle, or [`EMPTY`].
    pub triangle: Vec<u32>,
    /// Perspective-correct barycentric coordinates (b1, b2) of the pixel centre in that
    /// triangle (b0 = 1 − b1 − b2).
    pub bary: Vec<[f32; 2]>,
}

impl GBuffer {
    /// The barycentric coordinates (b0, b1, b2) at pixel `k`.
    #[inline]
    pub fn bary3(&self, k: usize) -> [f32; 3] {
        let [b1, b2] = self.bary[k];
        [1.0 - b1 - b2, b1, b2]
    }
}

/// Rasterises triangles (both orientations are drawn) into a G-buffer of `width` × `height`.
pub fn rasterize(
    vertices: &[ScreenVertex],
    triangles: &[[u32; 3]],
    width: usize,
    height: usize,
) -> GBuffer {
    let n = width * height;
    let mut g = GBuffer {
        width,
        height,
        depth: vec![f32::NEG_INFINITY; n],
        triangle: vec![EMPTY; n],
        bary: vec![[0.0; 2]; n],
    };
    if n == 0 {
        return g;
    }
    let bands = height.div_ceil(BAND);
    let bins = bin_by_band(vertices, triangles, width, height, bands);
    g.depth
        .par_chunks_mut(BAND * width)
        .zip(g.triangle.par_chunks_mut(BAND * width))
        .zip(g.bary.par_chunks_mut(BAND * width))
        .enumerate()
        .for_each(|(band, ((depth, tri), bary))| {
            let y_start = band * BAND;
            let rows = depth.len() / width;
            let mut target = Band {
                width,
                y_start,
                rows,
                depth,
                tri,
                bary,
            };
            for &t in &bins[band] {
                let [a, b, c] = triangles[t as usize];
                let v = [
                    vertices[a as usize],
                    vertices[b as usize],
                    vertices[c as usize],
                ];
                target.triangle(t, &v);
            }
        });
    g
}

/// The triangles overlapping each band, in input order (so ties in depth resolve the same way
/// whatever the number of threads).
fn bin_by_band(
    vertices: &[ScreenVertex],
    triangles: &[[u32; 3]],
    width: usize,
    height: usize,
    bands: usize,
) -> Vec<Vec<u32>> {
    let chunk = 1 << 16;
    let partial: Vec<Vec<Vec<u32>>> = triangles
        .par_chunks(chunk)
        .enumerate()
        .map(|(c, tris)| {
            let mut bins = vec![Vec::new(); bands];
            for (k, t) in tris.iter().enumerate() {
                let v = t.map(|i| vertices[i as usize]);
                let (x0, x1) = (
                    v[0].x.min(v[1].x).min(v[2].x),
                    v[0].x.max(v[1].x).max(v[2].x),
                );
                let (y0, y1) = (
                    v[0].y.min(v[1].y).min(v[2].y),
                    v[0].y.max(v[1].y).max(v[2].y),
                );
                // Finite and on screen (pixel centres k + 0.5 inside the box).
                if !(x1 >= 0.5
                    && x0 <= width as f32 - 0.5
                    && y1 >= 0.5
                    && y0 <= height as f32 - 0.5)
                {
                    continue;
                }
                let (r0, r1) = (
                    (y0 - 0.5).ceil().max(0.0) as usize,
                    ((y1 - 0.5).floor() as usize).min(height - 1),
                );
                if r0 > r1 {
                    continue;
                }
                for band in r0 / BAND..=r1 / BAND {
                    bins[band].push((c * chunk + k) as u32);
                }
            }
            bins
        })
        .collect();
    let mut bins: Vec<Vec<u32>> = (0..bands)
        .map(|b| Vec::with_capacity(partial.iter().map(|p| p[b].len()).sum()))
        .collect();
    for p in partial {
        for (band, list) in p.into_iter().enumerate() {
            bins[band].extend(list);
        }
    }
    bins
}

/// One band of the G-buffer being written by one thread.
struct Band<'a> {
    width: usize,
    y_start: usize,
    rows: usize,
    depth: &'a mut [f32],
    tri: &'a mut [u32],
    bary: &'a mut [[f32; 2]],
}

impl Band<'_> {
    fn triangle(&mut self, id: u32, v: &[ScreenVertex; 3]) {
        let area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
        if !(area.abs() > 0.0) {
            return;
        }
        let inv_area = 1.0 / area;
        let (x0, x1) = (
            v[0].x.min(v[1].x).min(v[2].x),
            v[0].x.max(v[1].x).max(v[2].x),
        );
        let (y0, y1) = (
            v[0].y.min(v[1].y).min(v[2].y),
            v[0].y.max(v[1].y).max(v[2].y),
        );
        let col0 = (x0 - 0.5).ceil().max(0.0) as usize;
        let col1 = ((x1 - 0.5).floor().min(self.width as f32 - 1.0)) as isize;
        let row0 = ((y0 - 0.5).ceil().max(self.y_start as f32)) as usize;
        let row1 = ((y1 - 0.5)
            .floor()
            .min((self.y_start + self.rows) as f32 - 1.0)) as isize;
        if col1 < col0 as isize || row1 < row0 as isize {
            return;
        }
        let perspective = v[0].inv_w != 1.0 || v[1].inv_w != 1.0 || v[2].inv_w != 1.0;
        for row in row0..=row1 as usize {
            let py = row as f32 + 0.5;
            let base = (row - self.y_start) * self.width;
            for col in col0..=col1 as usize {
                let px = col as f32 + 0.5;
                // Edge functions: barycentric coordinates times the signed area.
                let w1 = ((px - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (py - v[0].y))
                    * inv_area;
                let w2 = ((v[1].x - v[0].x) * (py - v[0].y) - (px - v[0].x) * (v[1].y - v[0].y))
                    * inv_area;
                let w0 = 1.0 - w1 - w2;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * v[0].z + w1 * v[1].z + w2 * v[2].z;
                let k = base + col;
                if z > self.depth[k] {
                    self.depth[k] = z;
                    self.tri[k] = id;
                    self.bary[k] = if perspective {
                        let (q0, q1, q2) = (w0 * v[0].inv_w, w1 * v[1].inv_w, w2 * v[2].inv_w);
                        let s = 1.0 / (q0 + q1 + q2);
                        [q1 * s, q2 * s]
                    } else {
                        [w1, w2]
                    };
                }
            }
        }
    }
}

/// Shades every covered pixel in parallel: `shade(triangle, [b0, b1, b2])` gives its colour;
/// empty pixels are left as they are in `image` (RGB, row-major, `width × height`).
pub fn shade_pixels(
    g: &GBuffer,
    image: &mut [[u8; 3]],
    shade: impl Fn(u32, [f32; 3]) -> [u8; 3] + Sync,
) {
    image
        .par_chunks_mut(g.width)
        .enumerate()
        .for_each(|(row, pixels)| {
            for (col, px) in pixels.iter_mut().enumerate() {
                let k = row * g.width + col;
                let t = g.triangle[k];
                if t != EMPTY {
                    *px = shade(t, g.bary3(k));
                }
            }
        });
}

/// Draws a segment between two screen points over the picture, hidden where the surface
/// in the G-buffer is nearer than the segment by more than `tolerance` (in depth-key units).
/// `thickness` 1 or 2 pixels.
pub fn draw_segment(
    g: &GBuffer,
    image: &mut [[u8; 3]],
    a: ScreenVertex,
    b: ScreenVertex,
    color: [u8; 3],
    thickness: usize,
    tolerance: f32,
) {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let steps = dx.abs().max(dy.abs()).ceil().max(1.0);
    if !steps.is_finite() || steps > 1e6 {
        return;
    }
    let steps = steps as usize;
    for s in 0..=steps {
        let t = s as f32 / steps as f32;
        let (x, y, z) = (a.x + t * dx, a.y + t * dy, a.z + t * (b.z - a.z));
        for (ox, oy) in [(0i64, 0i64), (1, 0), (0, 1), (1, 1)]
            .iter()
            .take(if thickness > 1 { 4 } else { 1 })
        {
            let (col, row) = ((x - 0.5).round() as i64 + ox, (y - 0.5).round() as i64 + oy);
            if col < 0 || row < 0 || col >= g.width as i64 || row >= g.height as i64 {
                continue;
            }
            let k = row as usize * g.width + col as usize;
            if z + tolerance >= g.depth[k] {
                image[k] = color;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sv(x: f32, y: f32, z: f32) -> ScreenVertex {
        ScreenVertex {
            x,
            y,
            z,
            inv_w: 1.0,
        }
    }

    #[test]
    fn a_square_of_two_triangles_covers_its_pixels_once_and_the_nearer_wins() {
        let v = vec![
            sv(2.0, 2.0, 0.0),
            sv(12.0, 2.0, 0.0),
            sv(12.0, 12.0, 0.0),
            sv(2.0, 12.0, 0.0),
        ];
        // Counter-clockwise and clockwise triangles both draw.
        let t = vec![[0, 1, 2], [0, 3, 2]];
        let g = rasterize(&v, &t, 40, 40);
        let covered = g.triangle.iter().filter(|&&t| t != EMPTY).count();
        assert_eq!(covered, 100);
        for row in 0..40 {
            for col in 0..40 {
                let inside = (2..12).contains(&row) && (2..12).contains(&col);
                assert_eq!(g.triangle[row * 40 + col] != EMPTY, inside, "{row} {col}");
            }
        }
        // A nearer triangle on top (added first or last) wins.
        let mut v2 = v.clone();
        v2.extend([sv(0.0, 0.0, 1.0), sv(30.0, 0.0, 1.0), sv(0.0, 30.0, 1.0)]);
        for t in [vec![[4, 5, 6], [0, 1, 2]], vec![[0, 1, 2], [4, 5, 6]]] {
            let g = rasterize(&v2, &t, 40, 40);
            let near = t.iter().position(|x| x[0] == 4).unwrap() as u32;
            assert_eq!(g.triangle[5 * 40 + 5], near);
        }
    }

    #[test]
    fn barycentric_coordinates_interpolate_exactly() {
        let v = vec![sv(0.0, 0.0, 0.0), sv(64.0, 0.0, 1.0), sv(0.0, 64.0, 2.0)];
        let g = rasterize(&v, &[[0, 1, 2]], 70, 70);
        for row in (0..60).step_by(7) {
            for col in (0..60 - row).step_by(5) {
                let k = row * 70 + col;
                let b = g.bary3(k);
                let (x, y) = (b[1] * 64.0, b[2] * 64.0);
                assert!(
                    (x - (col as f32 + 0.5)).abs() < 1e-4 && (y - (row as f32 + 0.5)).abs() < 1e-4
                );
                assert!((g.depth[k] - (b[1] + 2.0 * b[2])).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn many_bands_and_threads_give_the_same_picture() {
        // A fan of thin triangles across all bands.
        let mut v = vec![sv(100.0, 100.0, 0.0)];
        let mut t = Vec::new();
        for k in 0..=360 {
            let a = (k as f32).to_radians();
            v.push(sv(
                100.0 + 95.0 * a.cos(),
                100.0 + 95.0 * a.sin(),
                (k % 7) as f32,
            ));
            if k > 0 {
                t.push([0, k as u32, k as u32 + 1]);
            }
        }
        let g = rasterize(&v, &t, 200, 200);
        let single = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| rasterize(&v, &t, 200, 200));
        assert_eq!(g.triangle, single.triangle);
        // Every pixel well inside the disc is covered.
        for (row, col) in [(100, 100), (30, 100), (100, 170), (160, 140)] {
            assert_ne!(g.triangle[row * 200 + col], EMPTY);
        }
    }
}
