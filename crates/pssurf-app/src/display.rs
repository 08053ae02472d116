//! What the 3D view draws and the meshes it draws: each visible object sampled piece by
//! piece (so curvature jumps across PS split lines stay visible), coloured on the CPU by the
//! library's colour maps, plus overlay lines.

use nalgebra::{Point3, Vector3};
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::surface::PatchwiseSurface;
use pssurf_viz::colormap::{ColorMap, ColorScale};
use pssurf_viz::plot::{Overlays, Range, overlay_lines, range_scale};

use crate::scene::SceneObject;

/// What colours the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewMode {
    /// Lit, neutral material.
    Shaded,
    /// A curvature plot.
    Curvature(CurvatureQuantity),
    /// Zebra stripes (reflection lines).
    Zebra,
}

/// The view's display settings.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplaySettings {
    /// Shaded, curvature or zebra.
    pub mode: ViewMode,
    /// The colour map name (see `pssurf_viz::ColorMap::NAMES`).
    pub colormap: String,
    /// The colour range.
    pub range: Range,
    /// Sampling level: each PS piece becomes 4^level triangles.
    pub level: u32,
    /// Flat (per-triangle) instead of smooth normals.
    pub flat: bool,
    /// Overlays: triangulation, PS refinement, control triangles, boundary.
    pub overlays: Overlays,
    /// Zebra band width in degrees.
    pub zebra_width_deg: f32,
}

impl Default for DisplaySettings {
    fn default() -> Self {
        DisplaySettings {
            mode: ViewMode::Shaded,
            colormap: "coolwarm".into(),
            range: Range::Auto,
            level: 2,
            flat: false,
            overlays: Overlays::default(),
            zebra_width_deg: 6.0,
        }
    }
}

/// One vertex for the GPU: position, normal, colour (sRGB bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuVertex {
    /// Position in the scene.
    pub position: [f32; 3],
    /// Unit normal (zero where undefined).
    pub normal: [f32; 3],
    /// Colour RGBA.
    pub color: [u8; 4],
}

/// One line vertex for the GPU.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineVertex {
    /// Position in the scene.
    pub position: [f32; 3],
    /// Colour RGBA.
    pub color: [u8; 4],
}

/// The drawable form of one object.
#[derive(Clone, Debug, Default)]
pub struct ObjectMesh {
    /// Surface vertices.
    pub vertices: Vec<GpuVertex>,
    /// Triangles (indices into `vertices`).
    pub indices: Vec<u32>,
    /// The parameters (u, v) of each vertex, for picking.
    pub uvs: Vec<[f64; 2]>,
    /// Overlay line segments (pairs of vertices).
    pub lines: Vec<LineVertex>,
    /// The curvature values per vertex, when coloured by curvature.
    pub values: Vec<f64>,
}

/// The colour scale used for a curvature plot of the given values (see
/// `pssurf_viz::plot::range_scale`).
pub fn scale_for(
    settings: &DisplaySettings,
    q: CurvatureQuantity,
    values: &[f64],
    diameter: f64,
) -> ColorScale {
    range_scale(settings.range, &color_map(settings), q, values, diameter)
}

/// The neutral surface colour.
pub const NEUTRAL: [u8; 4] = [200, 200, 205, 255];

/// Samples an object for display, in a neutral colour (see [`colorize`]).
pub fn object_mesh(o: &SceneObject, settings: &DisplaySettings) -> ObjectMesh {
    let surface = o.surface.general();
    let level = settings.level.min(max_level(surface.patch_count()));
    let curvature = matches!(settings.mode, ViewMode::Curvature(_));
    let sampled = sample_patches(surface, level, curvature);
    let m = o.transform.matrix();
    let rot = m.fixed_view::<3, 3>(0, 0).into_owned();
    let values = match settings.mode {
        ViewMode::Curvature(q) => sampled.quantity(q),
        _ => Vec::new(),
    };
    let vertices = sampled
        .mesh
        .positions
        .iter()
        .zip(&sampled.mesh.normals)
        .map(|(p, n)| {
            let p = m.transform_point(&Point3::from(*p));
            let n = (rot * n)
                .try_normalize(1e-300)
                .unwrap_or_else(Vector3::zeros);
            GpuVertex {
                position: p.coords.map(|x| x as f32).into(),
                normal: n.map(|x| x as f32).into(),
                color: NEUTRAL,
            }
        })
        .collect();
    let lines = overlay_lines(surface, &settings.overlays, level.min(3))
        .into_iter()
        .flat_map(|pl| {
            let c = [pl.color[0], pl.color[1], pl.color[2], 255];
            let pts: Vec<[f32; 3]> = pl
                .points
                .iter()
                .map(|p| {
                    m.transform_point(&Point3::from(*p))
                        .coords
                        .map(|x| x as f32)
                        .into()
                })
                .collect();
            pts.windows(2)
                .flat_map(|w| {
                    [
                        LineVertex {
                            position: w[0],
                            color: c,
                        },
                        LineVertex {
                            position: w[1],
                            color: c,
                        },
                    ]
                })
                .collect::<Vec<_>>()
        })
        .collect();
    ObjectMesh {
        vertices,
        indices: sampled.mesh.triangles.iter().flatten().copied().collect(),
        uvs: sampled.mesh.uvs.iter().map(|p| [p.x, p.y]).collect(),
        lines,
        values,
    }
}

/// Colours the meshes of a curvature plot with one scale fitted to all their values
/// (returned for the legend); other modes get the neutral colour.
pub fn colorize(
    meshes: &mut [&mut ObjectMesh],
    settings: &DisplaySettings,
    diameter: f64,
) -> Option<ColorScale> {
    let ViewMode::Curvature(q) = settings.mode else {
        for m in meshes.iter_mut() {
            m.vertices.iter_mut().for_each(|v| v.color = NEUTRAL);
        }
        return None;
    };
    let all: Vec<f64> = meshes
        .iter()
        .flat_map(|m| m.values.iter().copied())
        .collect();
    let scale = scale_for(settings, q, &all, diameter);
    let map = color_map(settings);
    for m in meshes.iter_mut() {
        for (v, x) in m.vertices.iter_mut().zip(&m.values) {
            let [r, g, b] = map.at(scale.position(*x));
            v.color = [r, g, b, 255];
        }
    }
    Some(scale)
}

/// The colour map of the settings (coolwarm if the name is unknown).
pub fn color_map(settings: &DisplaySettings) -> ColorMap {
    ColorMap::named(&settings.colormap)
        .unwrap_or_else(|_| ColorMap::named("coolwarm").expect("built in"))
}

/// The highest level that keeps one object under about 4 million triangles.
fn max_level(pieces: usize) -> u32 {
    let mut level = 0;
    while level < 6 && pieces << (2 * (level + 1)) <= 4_000_000 {
        level += 1;
    }
    level
}

/// The axis-aligned bounds of meshes, or None when empty.
pub fn bounds<'a>(
    meshes: impl IntoIterator<Item = &'a ObjectMesh>,
) -> Option<(Vector3<f32>, Vector3<f32>)> {
    let mut lo = Vector3::repeat(f32::INFINITY);
    let mut hi = Vector3::repeat(f32::NEG_INFINITY);
    for m in meshes {
        for v in &m.vertices {
            let p = Vector3::from(v.position);
            if p.iter().all(|x| x.is_finite()) {
                lo = lo.inf(&p);
                hi = hi.sup(&p);
            }
        }
    }
    (lo.x <= hi.x).then_some((lo, hi))
}
