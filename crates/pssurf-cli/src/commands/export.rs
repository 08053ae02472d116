//! `pssurf export`: the surface as a triangle mesh with curvature fields.

use std::path::PathBuf;

use anyhow::{Result, anyhow, bail};
use pssurf::interrogate::{CurvatureQuantity, SampledSurface, sample_patches};
use pssurf::io::Durability;
use pssurf::surface::Surface;
use pssurf_viz::plot::range_scale;
use pssurf_viz::{FieldMesh, MeshFormat};

use crate::budget::{Estimate, SampleCost, sample_estimate};
use crate::colors::{ColorArgs, quantity};

/// Arguments of `pssurf export`.
#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// ply, obj, stl, glb or vtk (default: from the output's extension).
    #[arg(long, value_name = "FORMAT")]
    pub format: Option<String>,
    /// Sampling level: each PS sub-triangle becomes 4^L triangles. Levels up to 20 are
    /// accepted; the budget (--max-memory, --max-output) decides what runs.
    #[arg(long, value_name = "L", default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=20))]
    pub level: u32,
    /// The curvature fields to store (comma-separated: K,H,k1,k2,kabs); by default all of
    /// them go into the formats that carry fields (PLY, GLB, VTK). `--fields none` for none.
    #[arg(long, value_delimiter = ',', value_name = "K,H,...")]
    pub fields: Option<Vec<String>>,
    /// Colour the vertices by this quantity (PLY, OBJ, GLB, VTK).
    #[arg(long, value_name = "QUANTITY", default_value = "H", value_parser = quantity)]
    pub color_by: CurvatureQuantity,
    /// Colours for --color-by.
    #[command(flatten)]
    pub colors: ColorArgs,
    /// The mesh file to write.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Curves traced on the surface (a `pssurf trace` CSV) to write with the mesh: PLY
    /// edges, VTK lines or OBJ line elements. Repeatable.
    #[arg(long, value_name = "LINES.csv")]
    pub lines: Vec<PathBuf>,
}

/// Runs `pssurf export`.
pub fn run(args: &ExportArgs) -> Result<()> {
    let name = format_name(args);
    let format = MeshFormat::parse(&name).ok_or_else(|| anyhow!("unknown mesh format `{name}` (ply, obj, stl, glb, vtk); give --format or a known extension"))?;
    let fields = requested_fields(args, format, &name)?;
    if !args.lines.is_empty() && !format.carries_lines() {
        bail!("--lines: {name} cannot hold lines; use ply, vtk or obj");
    }
    let surface = crate::budget::load_surface(&args.surface)?;
    estimate(&surface, args.level, format, fields.len()).check()?;
    let mut lines = Vec::new();
    for path in &args.lines {
        for c in super::plot::read_lines(path)? {
            let mut points = c.points;
            if c.closed
                && let Some(first) = points.first()
            {
                points.push(*first);
            }
            lines.push(points);
        }
    }
    let sampled = sample_patches(&surface, args.level, true);
    let field_values: Vec<(String, Vec<f64>)> = if format.carries_fields() {
        fields
            .iter()
            .map(|&q| (q.short_name().to_string(), sampled.quantity(q)))
            .collect()
    } else {
        Vec::new()
    };
    let colors = if format.carries_colors() {
        Some(vertex_colors(args, &surface, &sampled)?)
    } else {
        None
    };
    let mesh = FieldMesh {
        mesh: &sampled.mesh,
        fields: &field_values,
        colors: colors.as_deref(),
        lines: &lines,
    };
    crate::output::write_output(&args.output, Durability::Atomic, |w| {
        pssurf_viz::write_mesh(w, format, &mesh).map_err(|e| anyhow!(e))
    })?;
    eprintln!("{}", summary(args, &sampled, &field_values));
    Ok(())
}

/// What an export costs, per mesh vertex (triangles are about twice as many): the sampled
/// mesh, its fields and the encoder's buffers (at most 450 bytes plus 8 per field; measured
/// 390 for glb at level 7), and the file (measured per vertex at level 7 with five fields:
/// PLY 72, OBJ 163, STL 98, glb 71, VTK 122 bytes; the estimate adds 30 %).
fn estimate(surface: &Surface, level: u32, format: MeshFormat, fields: usize) -> Estimate {
    let fields = fields as u64;
    let written = match format {
        MeshFormat::Ply => 95 + 8 * fields,
        MeshFormat::Obj => 215,
        MeshFormat::Stl => 130,
        MeshFormat::Glb => 95 + 8 * fields,
        MeshFormat::Vtk => 160 + 16 * fields,
    };
    let cost = SampleCost {
        memory_per_vertex: 450 + 8 * fields,
        memory_per_triangle: 0,
        output_per_vertex: written,
        output_per_triangle: 0,
    };
    sample_estimate(surface, level, format!("a level-{level} export"), cost, 0)
}

/// The format's name: `--format`, else the output's extension.
fn format_name(args: &ExportArgs) -> String {
    match &args.format {
        Some(f) => f.clone(),
        None => args
            .output
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_string(),
    }
}

/// The fields asked for by `--fields` (default all); an error if the format cannot store them.
fn requested_fields(
    args: &ExportArgs,
    format: MeshFormat,
    name: &str,
) -> Result<Vec<CurvatureQuantity>> {
    let fields: Vec<CurvatureQuantity> = match &args.fields {
        None => CurvatureQuantity::ALL.to_vec(),
        Some(v) if v.len() == 1 && v[0] == "none" => Vec::new(),
        Some(v) => v
            .iter()
            .map(|s| quantity(s).map_err(|e| anyhow!(e)))
            .collect::<Result<_>>()?,
    };
    if let Some((k, q)) = fields
        .iter()
        .enumerate()
        .find(|(k, q)| fields[..*k].contains(q))
    {
        bail!(
            "--fields names {} twice (field {}); list each at most once",
            q.short_name(),
            k + 1
        );
    }
    if !format.carries_fields() && args.fields.is_some() && !fields.is_empty() {
        bail!("{name} files cannot store scalar fields; use ply, glb or vtk (or --fields none)");
    }
    Ok(fields)
}

/// The vertex colours: the `--color-by` quantity through the colour map and range.
fn vertex_colors(
    args: &ExportArgs,
    surface: &Surface,
    sampled: &SampledSurface,
) -> Result<Vec<[u8; 3]>> {
    let values = sampled.quantity(args.color_by);
    let map = args.colors.map(args.color_by)?;
    let (lo, hi) = pssurf::surface::ParametricSurface::domain_bounds(surface);
    let scale = range_scale(
        args.colors.range()?,
        &map,
        args.color_by,
        &values,
        (hi - lo).norm(),
    );
    Ok(values
        .iter()
        .map(|&v| map.at(scale.position(v)))
        .collect::<Vec<_>>())
}

/// The report line: the file written, its vertex and triangle counts and its fields.
fn summary(
    args: &ExportArgs,
    sampled: &SampledSurface,
    field_values: &[(String, Vec<f64>)],
) -> String {
    format!(
        "wrote {} ({} vertices, {} triangles{})",
        args.output.display(),
        sampled.mesh.positions.len(),
        sampled.mesh.triangles.len(),
        if field_values.is_empty() {
            String::new()
        } else {
            format!(
                ", fields {}",
                field_values
                    .iter()
                    .map(|f| f.0.as_str())
                    .collect::<Vec<_>>()
                    .join(",")
            )
        }
    )
}
