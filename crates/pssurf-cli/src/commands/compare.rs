//! `pssurf compare-subdivision MESH -o DIR`: one coarse mesh refined by Loop, √3 and the
//! butterfly scheme and, where it is a height field over a planar triangulation, interpolated
//! by a PS-spline; their curvature plots side by side on one HTML page (issue 20, part 4).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Result, anyhow};
use nalgebra::Point2;
use pssurf::interrogate::{CurvatureQuantity, PrincipalCurvatures, SampledSurface};
use pssurf::io::Durability;
use pssurf::mesh::TriMesh;
use pssurf::scattered::{GradientMethod, data_basis, estimate_gradients_by, hermite_spline};
use pssurf::subdivision::mesh::discrete_curvature;
use pssurf::subdivision::{Mesh, SurfaceScheme};
use pssurf::surface::Surface;
use pssurf::triangulation::Triangulation;
use pssurf_viz::{PlotOptions, Range, Show};

use crate::commands::plot::{FRAME_BYTES_PER_PIXEL, SAMPLED_MESH_COST, png_bound};

/// Arguments of `pssurf compare-subdivision`.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The coarse control mesh (.obj, .ply or .stl).
    #[arg(value_name = "MESH")]
    pub input: PathBuf,
    /// Subdivision steps of Loop and the butterfly (4^N triangles per triangle); √3 gets the
    /// number of steps whose 3^M is nearest, M = round(N log 4 / log 3).
    #[arg(long, default_value_t = 3)]
    pub times: u32,
    /// The quantity to compare.
    #[arg(long, value_enum, default_value_t = QuantityArg::Gaussian)]
    pub show: QuantityArg,
    /// Picture size in pixels.
    #[arg(long, value_name = "WxH", default_value = "640x480")]
    pub size: crate::commands::plot::Size,
    /// The folder to write into (created if missing).
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,
}

/// The quantities.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum QuantityArg {
    /// Gaussian curvature K.
    Gaussian,
    /// Mean curvature H.
    Mean,
}

/// One panel of the page.
struct Panel {
    file: String,
    title: String,
    note: &'static str,
    sampled: SampledSurface,
}

/// A subdivided mesh as a sampled surface with its discrete curvatures.
fn sampled_mesh(mesh: Mesh) -> Result<SampledSurface> {
    let (k, h) = discrete_curvature(&mesh)?;
    let normals = mesh.vertex_normals();
    let curvature = (k.iter().zip(&h))
        .map(|(&k, &h)| PrincipalCurvatures::from_gaussian_mean(k, h))
        .collect();
    Ok(SampledSurface {
        patch: vec![0; mesh.positions.len()],
        curvature,
        mesh: TriMesh {
            uvs: vec![Point2::origin(); mesh.positions.len()],
            normals,
            positions: mesh.positions,
            triangles: mesh.triangles,
        },
    })
}

/// The PS-spline interpolating the mesh as a height field z(x, y) over its own triangulation
/// (gradients estimated locally), if the mesh is one.
fn ps_interpolant(mesh: &Mesh) -> Option<Surface> {
    let points: Vec<Point2<f64>> = mesh
        .positions
        .iter()
        .map(|p| Point2::new(p.x, p.y))
        .collect();
    let triangles: Vec<[usize; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| v as usize))
        .collect();
    let tri = Triangulation::try_new(points, triangles).ok()?;
    let basis = Arc::new(data_basis(tri, pssurf::ps::SplitRule::Incenter).ok()?);
    let z: Vec<f64> = mesh.positions.iter().map(|p| p.z).collect();
    let (gradients, _) = estimate_gradients_by(&basis, &z, GradientMethod::Local).ok()?;
    hermite_spline(basis, &z, &gradients)
        .ok()
        .map(Surface::Functional)
}

/// The √3 steps whose refinement 3^M is nearest to 4^N: M = round(N log 4 / log 3).
fn sqrt3_steps(n: u32) -> u32 {
    (n as f64 * 4f64.ln() / 3f64.ln()).round() as u32
}

/// Runs `pssurf compare-subdivision`.
pub fn run(args: &CompareArgs) -> Result<()> {
    let coarse = pssurf_viz::import::read_mesh(&args.input).map_err(|e| anyhow!(e))?;
    coarse
        .topology()
        .map_err(|e| anyhow!("{}: {e}", args.input.display()))?;
    let t = coarse.triangles.len() as u64;
    let sqrt3_times = sqrt3_steps(args.times);
    let fin = 4u64
        .checked_pow(args.times)
        .max(3u64.checked_pow(sqrt3_times))
        .and_then(|f| f.checked_mul(t))
        .unwrap_or(u64::MAX);
    // The PS panel samples every piece (six per triangle) at level 3, as a plot does; the
    // pictures are drawn one at a time and each written as a PNG. Leaving these out let a
    // 51k-triangle mesh take 2.1 GB against a 512 MB budget.
    let ps_panel = pssurf::interrogate::sample_counts(
        pssurf::surface::PieceKind::Triangle,
        usize::try_from(t.saturating_mul(6)).unwrap_or(usize::MAX),
        3,
    )
    .map_or(u64::MAX, |c| {
        crate::budget::mul(c.vertices, SAMPLED_MESH_COST.memory_per_vertex).saturating_add(
            crate::budget::mul(c.triangles, SAMPLED_MESH_COST.memory_per_triangle),
        )
    });
    let pixels = crate::budget::mul(args.size.0 as u64, args.size.1 as u64);
    crate::budget::Estimate {
        what: format!(
            "comparing {} steps at {}x{}",
            args.times, args.size.0, args.size.1
        ),
        makes: format!(
            "three meshes of about {} triangles",
            crate::budget::count(fin)
        ),
        memory: crate::budget::load_memory(0)
            .saturating_add(fin.saturating_mul(3 * 300))
            .saturating_add(ps_panel)
            .saturating_add(crate::budget::mul(pixels, FRAME_BYTES_PER_PIXEL)),
        // Three subdivided panels and the PS one.
        output: fin
            .saturating_mul(3 * 60)
            .saturating_add(png_bound(pixels).saturating_mul(4)),
    }
    .check()?;
    crate::output::create_folder(&args.output)?;
    let schemes = [
        (
            SurfaceScheme::Loop,
            args.times,
            "approximating; C² where the mesh is regular (the quartic box spline), C¹ at extraordinary vertices",
        ),
        (
            SurfaceScheme::Sqrt3,
            sqrt3_times,
            "approximating; C² where regular, C¹ at extraordinary vertices; its steps chosen so that 3^M is nearest to Loop's 4^N triangles per triangle",
        ),
        (
            SurfaceScheme::Butterfly,
            args.times,
            "interpolating the control points; C¹ (the modified rule at extraordinary vertices), never C²",
        ),
    ];
    let mut panels = Vec::new();
    for (scheme, times, note) in schemes {
        let mut m = coarse.clone();
        for _ in 0..times {
            m = scheme.step(&m)?;
        }
        panels.push(Panel {
            file: format!("{}.png", scheme.name()),
            title: format!("{} × {times}", scheme.name()),
            note,
            sampled: sampled_mesh(m)?,
        });
    }
    let quantity = match args.show {
        QuantityArg::Gaussian => CurvatureQuantity::Gaussian,
        QuantityArg::Mean => CurvatureQuantity::Mean,
    };
    let ps = ps_interpolant(&coarse);
    if let Some(s) = &ps {
        let sampled = pssurf::interrogate::sample_patches(s, 3, true);
        panels.push(Panel {
            file: "ps.png".into(),
            title: "PS-spline interpolant".into(),
            note: "interpolating the control points as a height field z(x, y) over the mesh's own triangulation (gradients estimated); C¹, with curvature jumps across the edges of the PS refinement",
            sampled,
        });
    }
    // One colour range for all: the 98th percentile of |q| over everything.
    let mut all: Vec<f64> = panels
        .iter()
        .flat_map(|p| p.sampled.quantity(quantity))
        .filter(|v| v.is_finite())
        .map(f64::abs)
        .collect();
    all.sort_by(f64::total_cmp);
    let r = all
        .get(((all.len() as f64 * 0.98) as usize).min(all.len().saturating_sub(1)))
        .copied()
        .unwrap_or(1.0)
        .max(1e-12);
    let opts = PlotOptions {
        show: Show::Quantity(quantity),
        range: Range::Fixed(-r, r),
        width: args.size.0,
        height: args.size.1,
        ..PlotOptions::default()
    };
    for p in &panels {
        let picture = pssurf_viz::plot::plot_sampled(&p.sampled, &[], &opts);
        let path = args.output.join(&p.file);
        crate::output::write_output(&path, Durability::Atomic, |w| {
            picture.write_png(w).map_err(|e| anyhow!(e))
        })?;
    }
    let html = page(args, &panels, quantity, r, ps.is_some());
    crate::output::write_output(&args.output.join("index.html"), Durability::Atomic, |w| {
        Ok(w.write_all(html.as_bytes())?)
    })?;
    eprintln!(
        "{} panels ({}), colour range ±{}; wrote {}",
        panels.len(),
        panels
            .iter()
            .map(|p| p.title.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        pssurf::text::Short(r),
        args.output.join("index.html").display()
    );
    Ok(())
}

/// The HTML page.
fn page(
    args: &CompareArgs,
    panels: &[Panel],
    q: CurvatureQuantity,
    r: f64,
    height_field: bool,
) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>Subdivision schemes compared</title>\n\
<style>body{{font-family:sans-serif;max-width:1400px;margin:auto}} .grid{{display:flex;flex-wrap:wrap;gap:16px}} figure{{margin:0;width:{}px}} img{{width:100%}}</style></head><body>\n\
<h1>Subdivision schemes compared</h1>\n<p>The control mesh <code>{}</code> ({} vertices, {} triangles) refined by each scheme; {} plotted with one colour range, ±{:.4}. Curvatures of subdivided meshes are discrete estimates (angle deficit, cotangent Laplacian).</p>\n<div class=\"grid\">\n",
        args.size.0,
        html_escape(&args.input.display().to_string()),
        panels.first().map_or(0, |p| p.sampled.mesh.positions.len()),
        panels.first().map_or(0, |p| p.sampled.mesh.triangles.len()),
        q.titled(),
        r
    );
    for p in panels {
        let _ = writeln!(
            s,
            "<figure><img src=\"{}\" alt=\"{}\"><figcaption><b>{}</b>: {}</figcaption></figure>",
            p.file, p.title, p.title, p.note
        );
    }
    s.push_str("</div>\n");
    if !height_field {
        s.push_str("<p>The mesh is not a height field over a planar triangulation (or its PS interpolant could not be built), so there is no PS-spline panel.</p>\n");
    }
    s.push_str("</body></html>\n");
    s
}

fn html_escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
