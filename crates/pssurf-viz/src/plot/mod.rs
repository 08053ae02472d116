//! Pictures of surfaces: shaded, coloured by a curvature quantity, zebra stripes or
//! isophotes, with overlays (triangulation, PS refinement, control triangles, boundary) and a
//! legend — rendered in software, so no GPU or display is needed.

use nalgebra::{Point2, Vector3};
use pssurf::interrogate::{CurvatureQuantity, SampledSurface, sample_patches};
use pssurf::mesh::TriMesh;
use pssurf::surface::Surface;
use rayon::prelude::*;

use crate::camera::{Camera, Projection, View};
use crate::colormap::{ColorMap, ColorScale};
use crate::legend::Rect;
use crate::raster::{GBuffer, ScreenVertex, draw_segment, rasterize, shade_pixels};

mod overlay;
pub use overlay::{
    cell_of_piece, cell_overlay, cell_pieces, comb_overlay, control_net_overlay, control_overlay,
    overlay_cells, overlay_lines,
};

/// What the picture shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Show {
    /// The lit surface in a neutral colour (back faces warmer).
    Shaded,
    /// A curvature quantity through a colour map, with a legend.
    Quantity(CurvatureQuantity),
    /// Zebra stripes: the reflection of a striped environment (bands of latitude around an
    /// axis in the screen plane); stripes run smoothly where the surface is C², kink where it
    /// is only C¹ (curvature jumps), break where it is only C⁰.
    Zebra,
    /// Isophotes: bands of equal illumination n·L.
    Isophotes,
}

/// How normals are interpolated for lighting.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// Per-pixel interpolated normals (Phong shading).
    Smooth,
    /// Colours lit at the vertices and interpolated (Gouraud shading).
    Gouraud,
    /// One normal per mesh triangle.
    Flat,
}

/// Lines drawn over the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Overlays {
    /// The triangulation Δ (its edges on the surface).
    pub wire: bool,
    /// The Powell–Sabin refinement Δ* (the split lines inside each triangle).
    pub refinement: bool,
    /// The control triangles (Definition 2.24).
    pub control: bool,
    /// The boundary of the surface.
    pub boundary: bool,
    /// Curvature combs on the sides of the boundary (teeth along the principal normal,
    /// the longest a tenth of the surface's size).
    pub combs: bool,
}

/// How the colour range is chosen.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Range {
    /// Automatic: symmetric about 0 for signed quantities (98th percentile of |q|), 1st–99th
    /// percentile otherwise; with the `seed` map, the contrast curve with automatic C.
    Auto,
    /// A fixed linear range.
    Fixed(f64, f64),
    /// The seed's contrast curve with this C.
    Contrast(f64),
}

/// Zebra and isophote band settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bands {
    /// The direction of the bands' axis on the screen, in degrees (0: the axis points right
    /// and the bands run up and down).
    pub angle_deg: f64,
    /// The angular width of one band, in degrees.
    pub width_deg: f64,
}

impl Default for Bands {
    fn default() -> Self {
        Bands {
            angle_deg: 0.0,
            width_deg: 5.0,
        }
    }
}

/// Everything that decides a picture.
#[derive(Clone, Debug)]
pub struct PlotOptions {
    /// What to show.
    pub show: Show,
    /// The colour map for quantities.
    pub colormap: ColorMap,
    /// The colour range.
    pub range: Range,
    /// Sampling level: each PS sub-triangle is split into 4^level mesh triangles.
    pub level: u32,
    /// Picture width in pixels.
    pub width: usize,
    /// Picture height in pixels.
    pub height: usize,
    /// The camera.
    pub camera: Camera,
    /// Normal interpolation.
    pub shading: Shading,
    /// Overlays.
    pub overlays: Overlays,
    /// Draw a legend for quantities.
    pub legend: bool,
    /// Also light the curvature colours (off: flat colours, as curvature plots usually are).
    pub lit: bool,
    /// Zebra / isophote bands.
    pub bands: Bands,
    /// Background colour.
    pub background: [u8; 3],
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            show: Show::Shaded,
            colormap: ColorMap::named("coolwarm").expect("built-in"),
            range: Range::Auto,
            level: 2,
            width: 800,
            height: 600,
            camera: Camera::default(),
            shading: Shading::Smooth,
            overlays: Overlays::default(),
            legend: true,
            lit: false,
            bands: Bands::default(),
            background: [255, 255, 255],
        }
    }
}

/// A rendered picture.
#[derive(Clone, Debug)]
pub struct Picture {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// RGB pixels, row-major.
    pub pixels: Vec<[u8; 3]>,
    /// The colour scale used (for quantities).
    pub scale: Option<ColorScale>,
    /// The number of mesh triangles drawn.
    pub triangles: usize,
}

impl Picture {
    /// The picture as an `image` buffer.
    pub fn to_image(&self) -> image::RgbImage {
        let raw: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        image::RgbImage::from_raw(self.width as u32, self.height as u32, raw).expect("sizes agree")
    }

    /// Encodes the picture as PNG.
    pub fn write_png(&self, w: &mut dyn std::io::Write) -> image::ImageResult<()> {
        let mut bytes = Vec::new();
        self.to_image().write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )?;
        w.write_all(&bytes).map_err(image::ImageError::IoError)
    }
}

/// A polyline in space drawn over the surface.
#[derive(Clone, Debug)]
pub struct Polyline {
    /// The points.
    pub points: Vec<Vector3<f64>>,
    /// The colour.
    pub color: [u8; 3],
    /// 1 or 2 pixels.
    pub thickness: usize,
}

/// Renders a surface of any kind.
pub fn plot(surface: &Surface, opts: &PlotOptions) -> Picture {
    plot_with_lines(surface, opts, Vec::new())
}

/// Renders a surface with extra polylines drawn over it (curves traced on the surface).
pub fn plot_with_lines(surface: &Surface, opts: &PlotOptions, extra: Vec<Polyline>) -> Picture {
    plot_surfaces(std::slice::from_ref(surface), opts, extra)
}

/// Renders several surfaces in one picture (a scene: the parts of an imported model), with
/// one colour scale and extra polylines.
pub fn plot_surfaces(surfaces: &[Surface], opts: &PlotOptions, extra: Vec<Polyline>) -> Picture {
    let need_curvature = matches!(opts.show, Show::Quantity(_));
    let mut sampled = SampledSurface::default();
    let mut lines = Vec::new();
    for surface in surfaces {
        sampled.append(sample_patches(surface, opts.level, need_curvature));
        lines.extend(overlay_lines(surface, &opts.overlays, opts.level));
    }
    lines.extend(extra);
    plot_sampled(&sampled, &lines, opts)
}

/// Renders a sampled surface with lines.
pub fn plot_sampled(sampled: &SampledSurface, lines: &[Polyline], opts: &PlotOptions) -> Picture {
    let (width, height) = (opts.width.max(1), opts.height.max(1));
    let mesh = &sampled.mesh;
    let values = match opts.show {
        Show::Quantity(q) => Some(sampled.quantity(q)),
        _ => None,
    };
    let diameter = surface_diameter(&mesh.positions);
    let scale = values.as_ref().map(|v| resolve_scale(opts, v, diameter));
    let legend_w = legend_width(width, scale.is_some() && opts.legend);
    let area_w = width as f64 - legend_w;
    let extent = scene_extent(&mesh.positions, lines);
    let view = View::fit(
        &opts.camera,
        &extent,
        area_w,
        height as f64,
        Point2::new(0.5 * area_w, 0.5 * height as f64),
    );
    let projection = opts.camera.projection;
    let screen: Vec<ScreenVertex> = mesh
        .positions
        .par_iter()
        .map(|p| screen_vertex(projection, &view.project(p)))
        .collect();
    let g = rasterize(&screen, &mesh.triangles, width, height);
    let mut pixels = vec![opts.background; width * height];
    let light = Light::new(&view);
    shade(
        &g,
        &mut pixels,
        sampled,
        values.as_deref(),
        scale.as_ref(),
        opts,
        &view,
        &light,
    );
    draw_lines(&g, &mut pixels, lines, &view, projection, &extent);
    if let (Some(s), true, Show::Quantity(q)) = (&scale, opts.legend, opts.show) {
        let area = Rect {
            x: area_w as f32 + 6.0,
            y: 8.0,
            w: legend_w as f32 - 12.0,
            h: height as f32 - 16.0,
        };
        // The data's true min and max, with arrows when the scale clips them (as the
        // application's legend).
        let data = values
            .as_deref()
            .and_then(|v| crate::colormap::DataRange::of(v, s));
        crate::legend::draw_legend_data(
            &mut pixels,
            width,
            area,
            &q.titled(),
            &opts.colormap,
            s,
            data.as_ref(),
        );
    }
    Picture {
        width,
        height,
        pixels,
        scale,
        triangles: mesh.triangles.len(),
    }
}

/// The diagonal of the bounding box of the surface's points (1 when there are none).
fn surface_diameter(positions: &[Vector3<f64>]) -> f64 {
    let c = bounding_corners(positions.iter());
    if c.is_empty() {
        1.0
    } else {
        (c[7] - c[0]).norm().max(1e-300)
    }
}

/// The width in pixels kept for the legend at the right of the picture (0 without one).
fn legend_width(width: usize, with_legend: bool) -> f64 {
    if with_legend {
        (width as f64 * 0.17)
            .clamp(110.0, 240.0)
            .min(width as f64 * 0.5)
    } else {
        0.0
    }
}

/// The bounding-box corners of the surface and the lines (the origin when nothing is finite).
fn scene_extent(positions: &[Vector3<f64>], lines: &[Polyline]) -> Vec<Vector3<f64>> {
    let mut extent: Vec<Vector3<f64>> = bounding_corners(
        positions
            .iter()
            .chain(lines.iter().flat_map(|l| l.points.iter())),
    );
    if extent.is_empty() {
        extent.push(Vector3::zeros());
    }
    extent
}

/// A projected point as a screen vertex, keyed by view depth (orthographic) or 1/w (perspective).
fn screen_vertex(projection: Projection, q: &crate::camera::Projected) -> ScreenVertex {
    let z = match projection {
        Projection::Orthographic => q.depth as f32,
        Projection::Perspective { .. } => q.inv_w as f32,
    };
    ScreenVertex {
        x: q.x as f32,
        y: q.y as f32,
        z,
        inv_w: q.inv_w as f32,
    }
}

/// Draws the lines over the surface, hidden behind nearer parts (tolerance: 0.4 % of the scene).
fn draw_lines(
    g: &GBuffer,
    pixels: &mut [[u8; 3]],
    lines: &[Polyline],
    view: &View,
    projection: Projection,
    extent: &[Vector3<f64>],
) {
    let diameter = (extent[extent.len() - 1] - extent[0]).norm().max(1e-300);
    let tolerance = match projection {
        Projection::Orthographic => 0.004 * diameter,
        Projection::Perspective { .. } => {
            let q = view.project(&(0.5 * (extent[0] + extent[extent.len() - 1])));
            0.004 * diameter * q.inv_w * q.inv_w
        }
    } as f32;
    for l in lines {
        for w in l.points.windows(2) {
            let sa = screen_vertex(projection, &view.project(&w[0]));
            let sb = screen_vertex(projection, &view.project(&w[1]));
            draw_segment(g, pixels, sa, sb, l.color, l.thickness, tolerance);
        }
    }
}

/// The two extreme corners (min, max) of the bounding box of the points (finite ones only).
fn bounding_corners<'a>(points: impl Iterator<Item = &'a Vector3<f64>>) -> Vec<Vector3<f64>> {
    let (mut lo, mut hi) = (
        Vector3::repeat(f64::INFINITY),
        Vector3::repeat(f64::NEG_INFINITY),
    );
    let mut any = false;
    for p in points.filter(|p| p.iter().all(|x| x.is_finite())) {
        lo = lo.inf(p);
        hi = hi.sup(p);
        any = true;
    }
    if !any {
        return Vec::new();
    }
    (0..8)
        .map(|k| {
            Vector3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect()
}

/// The colour scale for the options and the values of a surface of the given diameter
/// (curvatures below 10⁻⁹ of 1/diameter, or 1/diameter² for K, count as zero).
pub fn resolve_scale(opts: &PlotOptions, values: &[f64], diameter: f64) -> ColorScale {
    let q = match opts.show {
        Show::Quantity(q) => q,
        _ => CurvatureQuantity::Mean,
    };
    range_scale(opts.range, &opts.colormap, q, values, diameter)
}

/// The colour scale of a range choice for a quantity's values (see [`resolve_scale`]).
pub fn range_scale(
    range: Range,
    map: &ColorMap,
    q: CurvatureQuantity,
    values: &[f64],
    diameter: f64,
) -> ColorScale {
    let unit = 1.0 / diameter;
    let negligible = 1e-9
        * if q == CurvatureQuantity::Gaussian {
            unit * unit
        } else {
            unit
        };
    match range {
        Range::Fixed(lo, hi) => ColorScale::Linear { lo, hi },
        Range::Contrast(c) => ColorScale::Contrast { c },
        Range::Auto => ColorScale::auto(
            values,
            q.is_signed(),
            map.name() == "seed" && q.is_signed(),
            negligible,
        ),
    }
}

/// A directional light fixed to the camera (above, right, in front), with ambient and
/// specular terms.
struct Light {
    dir: Vector3<f64>,
}

impl Light {
    fn new(view: &View) -> Light {
        Light {
            dir: (0.35 * view.right + 0.55 * view.up + 0.75 * view.to_eye).normalize(),
        }
    }

    /// The brightness factor and the specular highlight for a normal facing the eye.
    #[inline]
    fn light(&self, n: Vector3<f64>, to_eye: Vector3<f64>) -> (f64, f64) {
        let diffuse = n.dot(&self.dir).max(0.0);
        let h = (self.dir + to_eye).normalize();
        let spec = n.dot(&h).max(0.0).powi(48);
        (0.12 + 0.95 * diffuse, 0.3 * spec)
    }

    /// The colour `base` lit at `p` with normal `n`; seen from the back, FRONT becomes BACK.
    fn lit_color(&self, view: &View, base: [f64; 3], n: Vector3<f64>, p: &Vector3<f64>) -> [u8; 3] {
        let to_eye = -view.view_direction(p);
        let (n, back) = if n.dot(&to_eye) >= 0.0 {
            (n, false)
        } else {
            (-n, true)
        };
        let (b, s) = self.light(n, to_eye);
        let base = if back && base == FRONT { BACK } else { base };
        base.map(|c| (c * b + 255.0 * s).clamp(0.0, 255.0) as u8)
    }
}

const FRONT: [f64; 3] = [150.0, 170.0, 205.0];
const BACK: [f64; 3] = [205.0, 170.0, 140.0];

/// Colours every pixel that the G-buffer covers by what the picture shows.
#[allow(clippy::too_many_arguments)]
fn shade(
    g: &GBuffer,
    pixels: &mut [[u8; 3]],
    sampled: &SampledSurface,
    values: Option<&[f64]>,
    scale: Option<&ColorScale>,
    opts: &PlotOptions,
    view: &View,
    light: &Light,
) {
    let mesh = &sampled.mesh;
    // Gouraud: light the vertices once.
    let vertex_colors: Vec<[u8; 3]> =
        if opts.shading == Shading::Gouraud && matches!(opts.show, Show::Shaded) {
            mesh.positions
                .par_iter()
                .zip(&mesh.normals)
                .map(|(p, n)| light.lit_color(view, FRONT, *n, p))
                .collect()
        } else {
            Vec::new()
        };
    // The zebra environment: bands of latitude around an axis in the screen plane, along the
    // screen's right for angle 0 (the bands then run up and down the picture).
    let band_axis = {
        let a = opts.bands.angle_deg.to_radians();
        view.right * a.cos() + view.up * a.sin()
    };
    let shader = PixelShader {
        mesh,
        values,
        scale,
        opts,
        view,
        light,
        vertex_colors,
        band_axis,
        band_width: opts.bands.width_deg.to_radians().max(1e-6),
    };
    shade_pixels(g, pixels, |t, b| shader.pixel(t, b));
}

/// Colours pixels from the mesh, its values, the options, the view and the light.
struct PixelShader<'a> {
    mesh: &'a TriMesh,
    values: Option<&'a [f64]>,
    scale: Option<&'a ColorScale>,
    opts: &'a PlotOptions,
    view: &'a View,
    light: &'a Light,
    /// The colours lit at the vertices for Gouraud shading (empty otherwise).
    vertex_colors: Vec<[u8; 3]>,
    /// The axis of the zebra environment's bands of latitude.
    band_axis: Vector3<f64>,
    /// The angular width of one zebra or isophote band, in radians.
    band_width: f64,
}

impl PixelShader<'_> {
    /// The colour of the point with barycentric coordinates `b` in mesh triangle `t`.
    fn pixel(&self, t: u32, b: [f32; 3]) -> [u8; 3] {
        let corners = self.mesh.triangles[t as usize].map(|x| x as usize);
        let [i, j, k] = corners;
        let b = b.map(|x| x as f64);
        let p = self.mesh.positions[i] * b[0]
            + self.mesh.positions[j] * b[1]
            + self.mesh.positions[k] * b[2];
        match self.opts.show {
            Show::Shaded => self.shaded(corners, b, &p),
            Show::Quantity(_) => self.quantity(corners, b, &p),
            Show::Zebra => self.zebra(corners, b, &p),
            Show::Isophotes => self.isophote(corners, b, &p),
        }
    }

    /// The unit normal at `b` in a triangle: its own (flat shading) or the vertex normals blended.
    fn normal(&self, [i, j, k]: [usize; 3], b: [f64; 3]) -> Vector3<f64> {
        let mesh = self.mesh;
        match self.opts.shading {
            Shading::Flat => {
                let (a, bb, c) = (mesh.positions[i], mesh.positions[j], mesh.positions[k]);
                (bb - a)
                    .cross(&(c - a))
                    .try_normalize(0.0)
                    .unwrap_or_default()
            }
            _ => (mesh.normals[i] * b[0] + mesh.normals[j] * b[1] + mesh.normals[k] * b[2])
                .try_normalize(0.0)
                .unwrap_or_default(),
        }
    }

    /// The lit neutral colour at `p`: Gouraud vertex colours blended, or lit per pixel.
    fn shaded(&self, corners: [usize; 3], b: [f64; 3], p: &Vector3<f64>) -> [u8; 3] {
        if !self.vertex_colors.is_empty() {
            let [ci, cj, ck] = corners.map(|v| self.vertex_colors[v]);
            std::array::from_fn(|c| {
                (ci[c] as f64 * b[0] + cj[c] as f64 * b[1] + ck[c] as f64 * b[2]).round() as u8
            })
        } else {
            self.light
                .lit_color(self.view, FRONT, self.normal(corners, b), p)
        }
    }

    /// The colour map's colour of the interpolated quantity at `p`, lit if asked.
    fn quantity(&self, [i, j, k]: [usize; 3], b: [f64; 3], p: &Vector3<f64>) -> [u8; 3] {
        let v = self.values.expect("values for quantities");
        let q = v[i] * b[0] + v[j] * b[1] + v[k] * b[2];
        let s = self.scale.expect("a scale for quantities");
        let c = self.opts.colormap.at(s.position(q));
        if self.opts.lit {
            let to_eye = -self.view.view_direction(p);
            let n = self.normal([i, j, k], b);
            let n = if n.dot(&to_eye) >= 0.0 { n } else { -n };
            let (br, sp) = self.light.light(n, to_eye);
            c.map(|x| (x as f64 * (0.35 + 0.65 * br) + 255.0 * sp * 0.5).clamp(0.0, 255.0) as u8)
        } else {
            c
        }
    }

    /// The zebra stripe at `p`: dark or light by the band the reflected view ray points into.
    fn zebra(&self, corners: [usize; 3], b: [f64; 3], p: &Vector3<f64>) -> [u8; 3] {
        let d = self.view.view_direction(p);
        let n = self.normal(corners, b);
        let n = if n.dot(&d) <= 0.0 { n } else { -n };
        let r = d - 2.0 * d.dot(&n) * n;
        // Bands of latitude around the axis: the reflection of a striped environment.
        let theta = r.dot(&self.band_axis).clamp(-1.0, 1.0).acos();
        if (theta / self.band_width).floor() as i64 % 2 == 0 {
            [20, 20, 20]
        } else {
            [245, 245, 245]
        }
    }

    /// The isophote band at `p`: dark or light by the angle between the normal and the light.
    fn isophote(&self, corners: [usize; 3], b: [f64; 3], p: &Vector3<f64>) -> [u8; 3] {
        let to_eye = -self.view.view_direction(p);
        let n = self.normal(corners, b);
        let n = if n.dot(&to_eye) >= 0.0 { n } else { -n };
        let theta = n.dot(&self.light.dir).clamp(-1.0, 1.0).acos();
        if (theta / self.band_width).floor() as i64 % 2 == 0 {
            [30, 30, 90]
        } else {
            [235, 235, 200]
        }
    }
}

#[cfg(test)]
mod tests;
