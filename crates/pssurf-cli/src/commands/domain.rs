//! `pssurf domain`: the parameter domain as SVG — triangulation, PS refinement, PS-points,
//! PS-triangles, optionally coloured by curvature.

use std::path::PathBuf;

use anyhow::{Result, bail};
use pssurf::interrogate::CurvatureQuantity;
use pssurf::io::Durability;
use pssurf_viz::DomainOptions;

use crate::budget::{SampleCost, sample_estimate};
use crate::colors::{ColorArgs, quantity};

/// What a domain picture can show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Layer {
    /// The triangles of Δ.
    Triangulation,
    /// The split lines of the refinement Δ*.
    Refinement,
    /// The PS-points of every vertex.
    PsPoints,
    /// The PS-triangles.
    PsTriangles,
    /// Vertex numbers.
    Labels,
}

/// Arguments of `pssurf domain`.
#[derive(clap::Args, Debug)]
pub struct DomainArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// The layers to draw (comma-separated).
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [Layer::Triangulation, Layer::Refinement, Layer::PsTriangles])]
    pub show: Vec<Layer>,
    /// Colour the sub-triangles by a curvature quantity (K, H, k1, k2, kabs), piece by piece.
    #[arg(long, value_name = "QUANTITY", value_parser = quantity)]
    pub color: Option<CurvatureQuantity>,
    /// Colours for --color.
    #[command(flatten)]
    pub colors: ColorArgs,
    /// Sampling level for --color: each sub-triangle becomes 4^L cells. Levels up to 20 are
    /// accepted; the budget (--max-memory, --max-output) decides what runs.
    #[arg(long, value_name = "L", default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=20))]
    pub level: u32,
    /// Draw curves traced on the surface (a `pssurf trace` CSV), each in its own colour.
    /// Repeatable.
    #[arg(long, value_name = "LINES.csv")]
    pub lines: Vec<PathBuf>,
    /// Picture width in pixels.
    #[arg(long, default_value_t = 900.0)]
    pub width: f64,
    /// The SVG file to write.
    #[arg(short, long, value_name = "OUT.svg")]
    pub output: PathBuf,
}

/// Runs `pssurf domain`.
pub fn run(args: &DomainArgs) -> Result<()> {
    if !(100.0..=20000.0).contains(&args.width) {
        bail!("--width must be between 100 and 20000");
    }
    let surface = crate::budget::load_surface(&args.surface)?;
    if args.color.is_some() {
        // Measured at level 6: 800 bytes of memory and 94 bytes of SVG per coloured cell.
        let cost = SampleCost {
            memory_per_vertex: 0,
            memory_per_triangle: 1000,
            output_per_vertex: 0,
            output_per_triangle: 120,
        };
        let what = format!("a domain picture coloured at level {}", args.level);
        sample_estimate(&surface, args.level, what, cost, 0).check()?;
    }
    let has = |l| args.show.contains(&l);
    let q = args.color.unwrap_or(CurvatureQuantity::Mean);
    let opts = DomainOptions {
        triangulation: has(Layer::Triangulation),
        refinement: has(Layer::Refinement),
        ps_points: has(Layer::PsPoints),
        ps_triangles: has(Layer::PsTriangles),
        vertex_labels: has(Layer::Labels),
        color: args.color,
        colormap: args.colors.map(q)?,
        range: args.colors.range()?,
        level: args.level,
        width: args.width,
        curves: read_domain_curves(&args.lines)?,
    };
    let svg = pssurf_viz::domain_svg(&surface, &opts);
    crate::output::write_output(&args.output, Durability::Atomic, |w| {
        Ok(w.write_all(svg.as_bytes())?)
    })?;
    eprintln!("wrote {}", args.output.display());
    Ok(())
}

/// The curves of `--lines` files, coloured in turn.
fn read_domain_curves(paths: &[PathBuf]) -> Result<Vec<pssurf_viz::DomainCurve>> {
    let mut out = Vec::new();
    for path in paths {
        for c in super::plot::read_lines(path)? {
            let color = super::trace::PALETTE[out.len() % super::trace::PALETTE.len()];
            out.push(pssurf_viz::DomainCurve {
                uvs: c.uvs,
                closed: c.closed,
                color,
            });
        }
    }
    Ok(out)
}
