//! `pssurf showcase`: the experiment of seed 000, section 4, as a gallery — a smooth UPS
//! surface, the same with noise, denoised by wavelet thresholding (hard 5 %, soft 5 %,
//! soft 10 %, and an automatic threshold), each shaded and as Gaussian and mean curvature
//! plots; the curvature plot of one PS B-spline basis function; domain pictures; and an
//! `index.html` with the numbers that compare them.

mod experiment;
mod html;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::io::Durability;
use pssurf::surface::{PiecewiseSurface, Surface};
use pssurf_viz::plot::{plot_sampled, range_scale};
use pssurf_viz::{Camera, ColorMap, ColorScale, DomainOptions, PlotOptions, Range, Show};

use super::plot::write_png;

/// Arguments of `pssurf showcase`.
#[derive(clap::Args, Debug)]
pub struct ShowcaseArgs {
    /// The directory to write the gallery into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Picture size of each plot.
    #[arg(long, value_name = "WxH", default_value = "640x480")]
    pub size: super::plot::Size,
}

/// One rendered row of the gallery.
pub struct Row {
    /// Caption.
    pub title: String,
    /// Picture file names: shaded, Gaussian, mean, zebra.
    pub pictures: [String; 4],
    /// Numbers (none for the original itself).
    pub comparison: experiment::Comparison,
    /// Wavelet coefficients zeroed, percent.
    pub zeroed_percent: Option<f64>,
}

/// The sampling level of the gallery's plots.
const LEVEL: u32 = 2;

/// Runs `pssurf showcase`.
pub fn run(args: &ShowcaseArgs) -> Result<()> {
    let started = std::time::Instant::now();
    let variants = experiment::variants();
    // The pictures are drawn one at a time: the budget is that of one plot.
    super::plot::estimate(&variants[0].surface, LEVEL, args.size).check()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let bar = progress_bar(variants.len() as u64 * 5 + 4);
    let original = &variants[0].surface;
    let points = experiment::sample_points(original, 4000);
    let seed = ColorMap::named("seed")?;
    let scales = SharedScales::of(original, &seed);
    let base = PlotOptions {
        width: args.size.0,
        height: args.size.1,
        level: LEVEL,
        camera: Camera::default(),
        colormap: seed.clone(),
        ..PlotOptions::default()
    };
    let mut rows = Vec::new();
    for v in &variants {
        let pictures = variant_pictures(v, &base, &scales, &args.out, &bar)?;
        bar.set_message(format!("{}: comparing", v.key));
        rows.push(Row {
            title: v.title.clone(),
            pictures,
            comparison: experiment::compare(original, &v.surface, &points),
            zeroed_percent: v.zeroed_percent,
        });
    }
    let basis_pictures = write_basis_and_domains(original, &base, &args.out, &bar)?;
    let page = html::page(
        &rows,
        &basis_pictures,
        &scales.gaussian,
        &scales.mean,
        started.elapsed().as_secs_f64(),
    );
    let index = args.out.join("index.html");
    crate::output::write_output(&index, Durability::Atomic, |w| {
        Ok(w.write_all(page.as_bytes())?)
    })?;
    bar.inc(1);
    bar.finish_and_clear();
    eprintln!(
        "showcase written in {:.1} s: open {}",
        started.elapsed().as_secs_f64(),
        index.display()
    );
    Ok(())
}

/// A progress bar of `steps` steps with the elapsed time and a message.
fn progress_bar(steps: u64) -> ProgressBar {
    ProgressBar::new(steps).with_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} {msg}")
            .expect("a valid template"),
    )
}

/// The colour scales of K and H shared by all pictures, taken from the original surface.
struct SharedScales {
    /// The scale of Gaussian curvature K.
    gaussian: ColorScale,
    /// The scale of mean curvature H.
    mean: ColorScale,
}

impl SharedScales {
    /// The automatic scales of `map` for the original's K and H (sampled at [`LEVEL`]).
    fn of(original: &Surface, map: &ColorMap) -> Self {
        let reference = sample_patches(original, LEVEL, true);
        let diameter = pssurf::surface::ParametricSurface::domain_bounds(original);
        let diameter = (diameter.1 - diameter.0).norm();
        let scale_of = |q| range_scale(Range::Auto, map, q, &reference.quantity(q), diameter);
        SharedScales {
            gaussian: scale_of(CurvatureQuantity::Gaussian),
            mean: scale_of(CurvatureQuantity::Mean),
        }
    }
}

/// Writes a variant's shaded, Gaussian, mean and zebra pictures; returns their file names.
fn variant_pictures(
    v: &experiment::Variant,
    base: &PlotOptions,
    scales: &SharedScales,
    dir: &Path,
    bar: &ProgressBar,
) -> Result<[String; 4]> {
    bar.set_message(format!("{}: sampling", v.key));
    let sampled = sample_patches(&v.surface, LEVEL, true);
    bar.inc(1);
    let mut pictures: [String; 4] = Default::default();
    for (k, (show, scale)) in [
        (Show::Shaded, None),
        (
            Show::Quantity(CurvatureQuantity::Gaussian),
            Some(scales.gaussian),
        ),
        (Show::Quantity(CurvatureQuantity::Mean), Some(scales.mean)),
        (Show::Zebra, None),
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!(
            "{}_{}.png",
            v.key,
            ["shaded", "gaussian", "mean", "zebra"][k]
        );
        bar.set_message(format!("{}: {name}", v.key));
        let opts = PlotOptions {
            show,
            range: fixed(scale),
            ..base.clone()
        };
        write_png(&plot_sampled(&sampled, &[], &opts), &dir.join(&name))?;
        pictures[k] = name;
        bar.inc(1);
    }
    Ok(pictures)
}

/// Writes the basis function's pictures and both domain SVGs; returns the pictures' names.
fn write_basis_and_domains(
    original: &Surface,
    base: &PlotOptions,
    dir: &Path,
    bar: &ProgressBar,
) -> Result<Vec<String>> {
    bar.set_message("basis function");
    let basis = experiment::basis_function();
    let basis_pictures = basis_pictures(&basis, base, dir)?;
    bar.inc(2);
    bar.set_message("domain pictures");
    write_domain(
        original,
        Some(CurvatureQuantity::Mean),
        &dir.join("domain_original.svg"),
    )?;
    write_domain(&basis, None, &dir.join("domain_basis.svg"))?;
    bar.inc(1);
    Ok(basis_pictures)
}

fn fixed(scale: Option<ColorScale>) -> Range {
    match scale {
        Some(ColorScale::Contrast { c }) => Range::Contrast(c),
        Some(ColorScale::Linear { lo, hi }) => Range::Fixed(lo, hi),
        None => Range::Auto,
    }
}

/// The basis function's pictures: shaded, Gaussian and mean curvature.
fn basis_pictures(s: &Surface, base: &PlotOptions, dir: &Path) -> Result<Vec<String>> {
    let level = (0..=5)
        .find(|&l| s.piece_count() << (2 * l) >= 100_000)
        .unwrap_or(5);
    let sampled = sample_patches(s, level, true);
    let mut names = Vec::new();
    for (show, key) in [
        (Show::Shaded, "shaded"),
        (Show::Quantity(CurvatureQuantity::Gaussian), "gaussian"),
        (Show::Quantity(CurvatureQuantity::Mean), "mean"),
    ] {
        let name = format!("basis_{key}.png");
        let opts = PlotOptions {
            show,
            level,
            camera: Camera {
                elevation_deg: 40.0,
                ..Camera::default()
            },
            ..base.clone()
        };
        write_png(&plot_sampled(&sampled, &[], &opts), &dir.join(&name))?;
        names.push(name);
    }
    Ok(names)
}

fn write_domain(s: &Surface, color: Option<CurvatureQuantity>, path: &Path) -> Result<()> {
    let opts = DomainOptions {
        color,
        ps_points: color.is_none(),
        colormap: ColorMap::named("coolwarm")?,
        width: 640.0,
        ..DomainOptions::default()
    };
    let svg = pssurf_viz::domain_svg(s, &opts);
    crate::output::write_output(path, Durability::Atomic, |w| {
        Ok(w.write_all(svg.as_bytes())?)
    })
}
