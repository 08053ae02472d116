//! `pssurf mesh subdivide`: the classic subdivision surface schemes on triangle meshes read
//! from OBJ, PLY or STL (issue 20, part 3).

use std::path::PathBuf;

use anyhow::{Context, Result, anyhow, bail};
use nalgebra::Point2;
use pssurf::io::Durability;
use pssurf::mesh::TriMesh;
use pssurf::subdivision::mesh::discrete_curvature;
use pssurf::subdivision::{SurfaceScheme, loop_limit_normals, loop_limit_positions};
use pssurf_viz::{FieldMesh, MeshFormat};

/// What to do with a mesh.
#[derive(clap::Subcommand, Debug)]
pub enum MeshWhat {
    /// Subdivide a triangle mesh by Loop, √3 or the butterfly scheme and write it with a
    /// discrete curvature estimate per vertex (K and H, for PLY and VTK).
    Subdivide(SubdivideMeshArgs),
}

/// The schemes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SchemeArg {
    /// Loop (approximating, the quartic box spline where regular).
    Loop,
    /// √3 of Kobbelt (approximating, 3 triangles for 1).
    Sqrt3,
    /// The modified butterfly (interpolating).
    Butterfly,
}

/// Arguments of `pssurf mesh subdivide`.
#[derive(clap::Args, Debug)]
pub struct SubdivideMeshArgs {
    /// The mesh: .obj, .ply or .stl (polygons are split into triangles).
    #[arg(value_name = "MESH")]
    pub input: PathBuf,
    /// The scheme.
    #[arg(long, value_enum)]
    pub scheme: SchemeArg,
    /// How many steps.
    #[arg(long, default_value_t = 1)]
    pub times: u32,
    /// Move the vertices to their limit positions with limit normals (Loop; the butterfly
    /// interpolates, so its vertices are on the limit surface already).
    #[arg(long)]
    pub limit: bool,
    /// The mesh to write: .obj, .ply, .stl, .vtk or .glb.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
}

/// Runs `pssurf mesh …`.
pub fn run(what: &MeshWhat) -> Result<()> {
    match what {
        MeshWhat::Subdivide(a) => subdivide(a),
    }
}

fn subdivide(args: &SubdivideMeshArgs) -> Result<()> {
    let scheme = match args.scheme {
        SchemeArg::Loop => SurfaceScheme::Loop,
        SchemeArg::Sqrt3 => SurfaceScheme::Sqrt3,
        SchemeArg::Butterfly => SurfaceScheme::Butterfly,
    };
    if args.limit && scheme == SurfaceScheme::Sqrt3 {
        bail!("--limit is available for loop (and butterfly, which interpolates), not for sqrt3");
    }
    let ext = args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default();
    let format = MeshFormat::parse(ext).with_context(|| {
        format!(
            "{}: write .obj, .ply, .stl, .vtk or .glb",
            args.output.display()
        )
    })?;
    let bytes = std::fs::metadata(&args.input)
        .map(|m| m.len())
        .with_context(|| format!("cannot read {}", args.input.display()))?;
    crate::budget::Estimate {
        what: format!("reading {}", args.input.display()),
        makes: format!("a mesh from {} bytes", bytes),
        memory: crate::budget::load_memory(bytes),
        output: 0,
    }
    .check()?;
    let mut mesh = pssurf_viz::import::read_mesh(&args.input).map_err(|e| anyhow!(e))?;
    let input_triangles = mesh.triangles.len();
    estimate(input_triangles, scheme, args.times, &args.output)?.check()?;
    mesh.topology()
        .map_err(|e| anyhow!("{}: {e}", args.input.display()))?;
    for _ in 0..args.times {
        mesh = scheme.step(&mesh)?;
    }
    let normals = if args.limit && scheme == SurfaceScheme::Loop {
        let n = loop_limit_normals(&mesh)?;
        mesh.positions = loop_limit_positions(&mesh)?;
        n
    } else {
        mesh.vertex_normals()
    };
    let (k, h) = discrete_curvature(&mesh)?;
    let fields = vec![("K".to_string(), k), ("H".to_string(), h)];
    let tri = TriMesh {
        uvs: vec![Point2::origin(); mesh.positions.len()],
        positions: mesh.positions,
        normals,
        triangles: mesh.triangles,
    };
    let fm = FieldMesh {
        mesh: &tri,
        fields: if format.carries_fields() {
            &fields
        } else {
            &[]
        },
        colors: None,
        lines: &[],
    };
    crate::output::write_output(&args.output, Durability::Atomic, |w| {
        pssurf_viz::write_mesh(w, format, &fm).map_err(|e| anyhow!(e))
    })?;
    eprintln!(
        "{} × {}: {} triangles -> {} triangles, {} vertices{}; wrote {}",
        scheme.name(),
        args.times,
        input_triangles,
        tri.triangles.len(),
        tri.positions.len(),
        if args.limit { " (limit positions)" } else { "" },
        args.output.display()
    );
    Ok(())
}

/// Memory and output of `times` steps: about 4^N (Loop, butterfly) or 3^N (√3) times the
/// triangles, each costing up to 300 bytes at the end besides the base (positions, topology,
/// normals, fields, the sort of the last step; measured 255 for Loop at 524,288 triangles
/// and 179 for √3 at 1.4M, peaks including the base) and up to 120 bytes of file (OBJ, the
/// largest).
fn estimate(
    triangles: usize,
    scheme: SurfaceScheme,
    times: u32,
    output: &std::path::Path,
) -> Result<crate::budget::Estimate> {
    let factor: u64 = match scheme {
        SurfaceScheme::Sqrt3 => 3,
        _ => 4,
    };
    let fin = factor
        .checked_pow(times)
        .and_then(|f| f.checked_mul(triangles as u64))
        .unwrap_or(u64::MAX);
    if fin > pssurf::subdivision::mesh::MAX_TRIANGLES as u64 {
        bail!(
            "{} steps of {} make {} triangles, more than the {} a mesh may have",
            times,
            scheme.name(),
            crate::budget::count(fin),
            crate::budget::count(pssurf::subdivision::mesh::MAX_TRIANGLES as u64)
        );
    }
    Ok(crate::budget::Estimate {
        what: format!("{times} steps of {}", scheme.name()),
        makes: format!(
            "{} triangles in {}",
            crate::budget::count(fin),
            output.display()
        ),
        memory: crate::budget::load_memory(0).saturating_add(fin.saturating_mul(300)),
        output: fin.saturating_mul(120),
    })
}
