//! `pssurf info`: what a surface file holds.

use std::path::PathBuf;

use anyhow::Result;
use pssurf::ps::ps_triangles::quality;
use pssurf::surface::PsSurface;
use serde::Serialize;

/// Arguments of `pssurf info`.
#[derive(clap::Args, Debug)]
pub struct InfoArgs {
    /// The surface file.
    #[arg(value_name = "SURF.json")]
    pub surface: PathBuf,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Summary statistics (min, median, max) of a list.
#[derive(Serialize)]
struct Stats {
    min: f64,
    median: f64,
    max: f64,
}

fn stats(mut v: Vec<f64>) -> Stats {
    v.sort_by(f64::total_cmp);
    Stats {
        min: v[0],
        median: v[v.len() / 2],
        max: v[v.len() - 1],
    }
}

#[derive(Serialize)]
struct Info {
    file: String,
    valid: bool,
    kind: &'static str,
    vertices: usize,
    triangles: usize,
    edges: usize,
    boundary_vertices: usize,
    basis_functions: usize,
    split: String,
    domain_min: [f64; 2],
    domain_max: [f64; 2],
    domain_area: f64,
    molecule_number: Stats,
    ps_triangle_area_ratio: Stats,
    ps_triangle_min_angle_deg: Stats,
    control_min: [f64; 3],
    control_max: [f64; 3],
    weights: Option<Stats>,
    uniform: Option<UniformInfo>,
}

#[derive(Serialize)]
struct UniformInfo {
    base: f64,
    origin: [f64; 2],
    polygon: Vec<[i64; 2]>,
    wavelet_levels_available: u32,
}

/// Runs `pssurf info`.
pub fn run(args: &InfoArgs) -> Result<()> {
    let file = pssurf::io::load(&args.surface)?;
    let s = file.general();
    let basis = s.basis();
    let t = basis.triangulation();
    let n = t.vertex_count();
    let q: Vec<_> = (0..n)
        .map(|i| quality(t, basis.refinement(), i, basis.ps_triangle(i)))
        .collect();
    let cps = s.control_points();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in cps.iter().flatten() {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let (dlo, dhi) = t.bounds();
    let info = Info {
        file: args.surface.display().to_string(),
        valid: true,
        kind: s.kind_name(),
        vertices: n,
        triangles: t.triangle_count(),
        edges: t.edge_count(),
        boundary_vertices: (0..n).filter(|&i| t.is_boundary_vertex(i)).count(),
        basis_functions: basis.dimension(),
        split: match basis.refinement().rule() {
            Some(r) => format!("{r:?}").to_lowercase(),
            None => "given points".into(),
        },
        domain_min: [dlo.x, dlo.y],
        domain_max: [dhi.x, dhi.y],
        domain_area: t.area(),
        molecule_number: stats((0..n).map(|i| t.molecule_number(i) as f64).collect()),
        ps_triangle_area_ratio: stats(q.iter().map(|q| q.area_ratio).collect()),
        ps_triangle_min_angle_deg: stats(q.iter().map(|q| q.min_angle_deg).collect()),
        control_min: lo,
        control_max: hi,
        weights: match &s {
            PsSurface::Rational(r) => Some(stats(r.weights().iter().flatten().copied().collect())),
            _ => None,
        },
        uniform: file.uniform().map(|u| {
            let g = u.grid();
            UniformInfo {
                base: g.lattice().base,
                origin: [g.lattice().origin.x, g.lattice().origin.y],
                polygon: g.polygon().vertices().to_vec(),
                wavelet_levels_available: g.coarsening_levels(),
            }
        }),
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&info)?);
        return Ok(());
    }
    let st = |s: &Stats| format!("min {:.4}, median {:.4}, max {:.4}", s.min, s.median, s.max);
    println!("file                 {}", info.file);
    println!("status               valid (every check passed on loading)");
    println!("kind                 {}", info.kind);
    println!(
        "vertices             {} ({} on the boundary)",
        info.vertices, info.boundary_vertices
    );
    println!(
        "triangles            {} ({} edges; {} PS sub-triangles)",
        info.triangles,
        info.edges,
        6 * info.triangles
    );
    println!("basis functions      {}", info.basis_functions);
    println!("split points         {}", info.split);
    println!(
        "domain               [{}, {}] × [{}, {}], area {}",
        dlo.x, dhi.x, dlo.y, dhi.y, info.domain_area
    );
    println!("molecule numbers     {}", st(&info.molecule_number));
    println!(
        "PS-triangle quality  area / hull of PS-points: {}",
        st(&info.ps_triangle_area_ratio)
    );
    println!(
        "                     smallest angle (degrees): {}",
        st(&info.ps_triangle_min_angle_deg)
    );
    println!(
        "control points       x [{}, {}], y [{}, {}], z [{}, {}]",
        lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
    );
    if let Some(w) = &info.weights {
        println!("weights              {}", st(w));
    }
    if let Some(u) = &info.uniform {
        let corners: Vec<String> = u
            .polygon
            .iter()
            .map(|p| format!("{},{}", p[0], p[1]))
            .collect();
        println!(
            "uniform (UPS)        base {}, origin ({}, {}), lattice polygon {}",
            u.base,
            u.origin[0],
            u.origin[1],
            corners.join(" ")
        );
        println!(
            "                     up to {} wavelet levels",
            u.wavelet_levels_available.min(62)
        );
    }
    Ok(())
}
