//! `pssurf plot`: a picture of a surface (shaded, curvature, zebra, isophotes) as PNG.

use std::path::PathBuf;
use std::str::FromStr;

use anyhow::{Result, bail};
use pssurf::interrogate::CurvatureQuantity;
use pssurf::io::Durability;
use pssurf::surface::{PiecewiseSurface, Surface};
use pssurf_viz::plot::Bands;
use pssurf_viz::{Camera, Overlays, PlotOptions, Projection, Shading, Show};

use crate::budget::{Estimate, SampleCost, mul, sample_estimate};
use crate::colors::ColorArgs;

/// What to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ShowArg {
    /// The lit surface.
    Shaded,
    /// Gaussian curvature K.
    Gaussian,
    /// Mean curvature H.
    Mean,
    /// The larger principal curvature κ1.
    K1,
    /// The smaller principal curvature κ2.
    K2,
    /// Absolute curvature |κ1| + |κ2|.
    Absolute,
    /// Zebra stripes (reflection lines).
    Zebra,
    /// Isophotes (bands of equal light).
    Isophotes,
}

impl ShowArg {
    /// The library's choice.
    pub fn show(self) -> Show {
        match self {
            ShowArg::Shaded => Show::Shaded,
            ShowArg::Gaussian => Show::Quantity(CurvatureQuantity::Gaussian),
            ShowArg::Mean => Show::Quantity(CurvatureQuantity::Mean),
            ShowArg::K1 => Show::Quantity(CurvatureQuantity::K1),
            ShowArg::K2 => Show::Quantity(CurvatureQuantity::K2),
            ShowArg::Absolute => Show::Quantity(CurvatureQuantity::Absolute),
            ShowArg::Zebra => Show::Zebra,
            ShowArg::Isophotes => Show::Isophotes,
        }
    }
}

/// A pair of numbers `a,b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pair(pub f64, pub f64);

impl FromStr for Pair {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (a, b) = s
            .split_once(',')
            .ok_or_else(|| format!("`{s}` is not of the form a,b"))?;
        let p = |t: &str| {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("`{t}` is not a number"))
        };
        Ok(Pair(p(a)?, p(b)?))
    }
}

/// A picture size `WxH`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size(pub usize, pub usize);

impl FromStr for Size {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (a, b) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("`{s}` is not of the form WxH, e.g. 1600x1200"))?;
        let p = |t: &str| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("`{t}` is not a whole number"))
        };
        let (w, h) = (p(a)?, p(b)?);
        if !(16..=16384).contains(&w) || !(16..=16384).contains(&h) {
            return Err("width and height must be between 16 and 16384".into());
        }
        Ok(Size(w, h))
    }
}

/// Arguments of `pssurf plot`.
#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// What to show.
    #[arg(long, value_enum, default_value_t = ShowArg::Shaded)]
    pub show: ShowArg,
    /// Colours for curvature.
    #[command(flatten)]
    pub colors: ColorArgs,
    /// Sampling level: each PS sub-triangle becomes 4^L mesh triangles. Default: the
    /// smallest level giving at least 200 000 triangles (at most 5). Levels up to 20 are
    /// accepted; the memory budget (--max-memory) decides what runs.
    #[arg(long, value_name = "L", value_parser = clap::value_parser!(u32).range(0..=20))]
    pub level: Option<u32>,
    /// Picture size in pixels.
    #[arg(long, value_name = "WxH", default_value = "1200x900")]
    pub size: Size,
    /// Camera azimuth and elevation in degrees (azimuth 0 looks from +x, elevation 90 from
    /// above).
    #[arg(
        long,
        value_name = "AZ,EL",
        default_value = "-50,35",
        allow_hyphen_values = true
    )]
    pub view: Pair,
    /// Magnification (1 fits the surface into the picture).
    #[arg(long, default_value_t = 1.0)]
    pub zoom: f64,
    /// Perspective projection with this vertical field of view in degrees (default:
    /// orthographic).
    #[arg(long, value_name = "FOV")]
    pub perspective: Option<f64>,
    /// How normals are interpolated for lighting.
    #[arg(long, value_enum, default_value_t = ShadingArg::Smooth)]
    pub shading: ShadingArg,
    /// Draw the triangulation's edges on the surface.
    #[arg(long)]
    pub wire: bool,
    /// Draw the Powell–Sabin refinement (split lines) on the surface.
    #[arg(long)]
    pub refinement: bool,
    /// Draw the control triangles.
    #[arg(long)]
    pub control: bool,
    /// Draw curvature combs on the sides of the boundary (the longest tooth a tenth of the
    /// surface's size).
    #[arg(long)]
    pub combs: bool,
    /// Draw the boundary.
    #[arg(long)]
    pub boundary: bool,
    /// Light the curvature colours too (default: flat colours).
    #[arg(long)]
    pub lit: bool,
    /// Leave out the legend.
    #[arg(long)]
    pub no_legend: bool,
    /// Draw curves traced on the surface (a `pssurf trace` CSV: curve,u,v,x,y,z), each
    /// curve in its own colour. Repeatable.
    #[arg(long, value_name = "LINES.csv")]
    pub lines: Vec<PathBuf>,
    /// Zebra / isophote band width in degrees.
    #[arg(long, value_name = "DEG", default_value_t = 5.0)]
    pub band_width: f64,
    /// Zebra band direction on the screen in degrees (0: vertical bands).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub band_angle: f64,
    /// The PNG file to write.
    #[arg(short, long, value_name = "OUT.png")]
    pub output: PathBuf,
}

/// Normal interpolation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ShadingArg {
    /// Per-pixel normals (Phong).
    Smooth,
    /// Per-vertex lighting (Gouraud).
    Gouraud,
    /// Per-triangle normals.
    Flat,
}

/// The smallest level at which the surfaces have at least `target` mesh triangles, at most 5.
pub fn auto_level(surfaces: &[Surface], target: usize) -> u32 {
    let pieces = surfaces
        .iter()
        .map(|s| s.piece_count())
        .sum::<usize>()
        .max(1);
    (0..=5).find(|&l| pieces << (2 * l) >= target).unwrap_or(5)
}

/// What a plot costs: the sampled mesh with its projections, colours and curvature (at most
/// 100 bytes per vertex and 16 per triangle; measured 89 and 12 at level 9) and the frame
/// buffers (16 bytes per pixel; measured 14 at 8000 × 8000).
pub fn estimate(surface: &Surface, level: u32, size: Size) -> Estimate {
    let pixels = mul(size.0 as u64, size.1 as u64);
    let mut e = sample_estimate(
        surface,
        level,
        format!("a level-{level} plot at {}x{}", size.0, size.1),
        SAMPLED_MESH_COST,
        mul(pixels, FRAME_BYTES_PER_PIXEL),
    );
    e.output = png_bound(pixels);
    e
}

/// Memory of a sampled mesh drawn in a plot: at most 100 bytes per vertex and 16 per
/// triangle (measured 89 and 12 at level 9).
pub const SAMPLED_MESH_COST: SampleCost = SampleCost {
    memory_per_vertex: 100,
    memory_per_triangle: 16,
    output_per_vertex: 0,
    output_per_triangle: 0,
};

/// Memory of a plot's frame buffers per pixel (measured 14 at 8000 × 8000).
pub const FRAME_BYTES_PER_PIXEL: u64 = 16;

/// The largest PNG of `pixels` pixels: never larger than its raw RGBA pixels, plus headers.
pub fn png_bound(pixels: u64) -> u64 {
    mul(pixels, 4).saturating_add(1 << 16)
}

/// The plot options of the arguments, for the surfaces drawn together.
pub fn options(args: &PlotArgs, surfaces: &[Surface]) -> Result<PlotOptions> {
    let show = args.show.show();
    let q = match show {
        Show::Quantity(q) => q,
        _ => CurvatureQuantity::Mean,
    };
    if !(args.zoom > 0.0 && args.zoom.is_finite()) {
        bail!("--zoom must be positive");
    }
    if !(args.band_width > 0.0 && args.band_width < 180.0) {
        bail!("--band-width must be between 0 and 180 degrees");
    }
    let projection = match args.perspective {
        None => Projection::Orthographic,
        Some(f) if f > 0.0 && f < 170.0 => Projection::Perspective { fov_deg: f },
        Some(f) => bail!(
            "--perspective wants a field of view between 0 and 170 degrees (got {})",
            pssurf::text::Short(f)
        ),
    };
    let level = args.level.unwrap_or_else(|| auto_level(surfaces, 200_000));
    // The frame buffers once, the meshes of every surface.
    let mut total = estimate(&surfaces[0], level, args.size);
    for s in &surfaces[1..] {
        let e = estimate(s, level, args.size);
        total.memory = total
            .memory
            .saturating_add(e.memory.saturating_sub(crate::budget::base_memory()));
    }
    total.check()?;
    Ok(PlotOptions {
        show,
        colormap: args.colors.map(q)?,
        range: args.colors.range()?,
        level,
        width: args.size.0,
        height: args.size.1,
        camera: Camera {
            azimuth_deg: args.view.0,
            elevation_deg: args.view.1,
            zoom: args.zoom,
            projection,
        },
        shading: match args.shading {
            ShadingArg::Smooth => Shading::Smooth,
            ShadingArg::Gouraud => Shading::Gouraud,
            ShadingArg::Flat => Shading::Flat,
        },
        overlays: Overlays {
            wire: args.wire,
            refinement: args.refinement,
            control: args.control,
            boundary: args.boundary,
            combs: args.combs,
        },
        legend: !args.no_legend,
        lit: args.lit,
        bands: Bands {
            angle_deg: args.band_angle,
            width_deg: args.band_width,
        },
        background: [255, 255, 255],
    })
}

/// Runs `pssurf plot`.
pub fn run(args: &PlotArgs) -> Result<()> {
    let surfaces = super::info::load_surfaces(&args.surface)?;
    let opts = options(args, &surfaces)?;
    let mut extra = Vec::new();
    for path in &args.lines {
        let curves = read_lines(path)?;
        let first = extra.len();
        extra.extend(curves.into_iter().enumerate().map(|(i, c)| {
            let k = first + i;
            let mut points = c.points;
            if c.closed
                && let Some(first) = points.first()
            {
                points.push(*first);
            }
            pssurf_viz::Polyline {
                points,
                color: super::trace::PALETTE[k % super::trace::PALETTE.len()],
                thickness: 2,
            }
        }));
    }
    let picture = pssurf_viz::plot_surfaces(&surfaces, &opts, extra);
    write_png(&picture, &args.output)?;
    eprintln!(
        "drew {} triangles (level {}) at {}x{}; wrote {}",
        picture.triangles,
        opts.level,
        picture.width,
        picture.height,
        args.output.display()
    );
    Ok(())
}

/// Reads a curves CSV (`curve,u,v,x,y,z`), within the memory budget.
pub fn read_lines(path: &std::path::Path) -> Result<Vec<pssurf::interrogate::SurfaceCurve>> {
    let text = crate::table::read_text(path)?;
    pssurf::io::read_curves_csv(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

/// Writes a picture as PNG, atomically; a name with another extension (`.jpg`) is refused
/// rather than given PNG bytes.
pub fn write_png(picture: &pssurf_viz::Picture, path: &std::path::Path) -> Result<()> {
    if let Some(ext) = path.extension().and_then(|e| e.to_str())
        && !ext.eq_ignore_ascii_case("png")
    {
        anyhow::bail!(
            "{}: pictures are written as PNG; give a name ending in .png",
            path.display()
        );
    }
    crate::output::write_output(path, Durability::Atomic, |w| {
        picture.write_png(w).map_err(|e| anyhow::anyhow!(e))
    })
}
