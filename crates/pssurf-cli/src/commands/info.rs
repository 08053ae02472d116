//! `pssurf info`: what a surface, scene or curve file holds.

use std::path::PathBuf;

use anyhow::Result;
use pssurf::ps::PsBasis;
use pssurf::ps::ps_triangles::{quality, quality_for};
use pssurf::surface::{ControlId, ControlNet, Domain, PiecewiseSurface, Surface, UpsSurface};
use pssurf::ups::fixed_ps_triangle;
use serde::Serialize;

/// Arguments of `pssurf info`.
#[derive(clap::Args, Debug)]
pub struct InfoArgs {
    /// The surface, scene or curve file.
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

/// What every kind reports.
#[derive(Serialize)]
struct Info {
    file: String,
    valid: bool,
    kind: &'static str,
    description: &'static str,
    pieces: usize,
    domain_min: [f64; 2],
    domain_max: [f64; 2],
    domain_area: f64,
    domain_holes: usize,
    control_points: usize,
    control_min: [f64; 3],
    control_max: [f64; 3],
    weights: Option<Stats>,
    #[serde(flatten)]
    ps: Option<PsInfo>,
    degree: usize,
    uniform: Option<UniformInfo>,
    nurbs: Option<NurbsInfo>,
}

/// A NURBS surface's structure.
#[derive(Serialize)]
struct NurbsInfo {
    /// Degrees [p, q].
    degrees: [usize; 2],
    /// The net's size [n_u, n_v].
    net: [usize; 2],
    /// Non-empty knot spans in u and v.
    spans: [usize; 2],
    /// Whether it has weights.
    rational: bool,
}

/// The PS structure: triangulation, refinement, PS-triangles.
#[derive(Serialize)]
struct PsInfo {
    vertices: usize,
    triangles: usize,
    edges: usize,
    boundary_vertices: usize,
    basis_functions: usize,
    split: String,
    molecule_number: Stats,
    ps_triangle_area_ratio: Stats,
    ps_triangle_min_angle_deg: Stats,
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
    if is_curve_file(&args.surface) {
        return curve_info(args);
    }
    if let Some(contents) = crate::budget::scene_objects(&args.surface)? {
        let infos: Vec<Info> = (contents.surfaces)
            .iter()
            .enumerate()
            .map(|(k, o)| {
                collect(
                    &o.surface,
                    format!("{} object {k}: {}", args.surface.display(), o.name),
                )
            })
            .collect();
        let meshes: Vec<MeshInfo> = contents.meshes.iter().map(MeshInfo::of).collect();
        if args.json {
            if meshes.is_empty() {
                outln!("{}", serde_json::to_string_pretty(&infos)?)?;
            } else {
                let both = serde_json::json!({"surfaces": infos, "meshes": meshes});
                outln!("{}", serde_json::to_string_pretty(&both)?)?;
            }
        } else {
            outln!(
                "scene {}: {} objects",
                args.surface.display(),
                infos.len() + meshes.len()
            )?;
            for info in &infos {
                outln!()?;
                print_table(info)?;
            }
            for m in &meshes {
                outln!()?;
                outln!(
                    "mesh {}: {} vertices, {} triangles; shown after {} × {} ({} triangles)",
                    m.name,
                    m.vertices,
                    m.triangles,
                    m.times,
                    m.scheme,
                    m.refined_triangles
                )?;
            }
        }
        return Ok(());
    }
    let s = crate::budget::load_surface(&args.surface)?;
    let info = collect(&s, args.surface.display().to_string());
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&info)?)?;
    } else {
        print_table(&info)?;
    }
    Ok(())
}

/// What a scene's mesh object reports.
#[derive(serde::Serialize)]
struct MeshInfo {
    name: String,
    vertices: usize,
    triangles: usize,
    scheme: &'static str,
    times: u32,
    refined_triangles: f64,
}

impl MeshInfo {
    fn of(m: &pssurf::io::SceneMesh) -> MeshInfo {
        MeshInfo {
            name: m.name.clone(),
            vertices: m.mesh.control.positions.len(),
            triangles: m.mesh.control.triangles.len(),
            scheme: m.mesh.scheme.name(),
            times: m.mesh.times,
            refined_triangles: m.mesh.triangles_after(),
        }
    }
}

/// What a curve file reports.
#[derive(Serialize)]
struct CurveInfo {
    file: String,
    valid: bool,
    kind: &'static str,
    degree: usize,
    control_points: usize,
    rational: bool,
    knots: usize,
    spans: usize,
    parameter_domain: [f64; 2],
    control_min: [f64; 3],
    control_max: [f64; 3],
    /// The arc length (adaptive Gauss–Legendre to 1e-12 of the control polygon's extent).
    length: f64,
    /// The inflection points' parameters, for a planar curve (None for a space curve).
    inflections: Option<Vec<f64>>,
    /// The ranges of curvature and torsion at 32 samples per knot span.
    curvature_torsion: pssurf::interrogate::curve_shape::CurvatureTorsion,
}

/// Whether the file's first 4 KiB name it a pssurf curve file.
fn is_curve_file(path: &std::path::Path) -> bool {
    use std::io::Read;
    let mut head = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(4096).read_to_end(&mut head);
    }
    let head = String::from_utf8_lossy(&head);
    head.contains(&format!("\"{}\"", pssurf::io::CURVE_KIND)) && head.contains("\"kind\"")
}

/// `pssurf info` on a curve file.
fn curve_info(args: &InfoArgs) -> Result<()> {
    let c = crate::budget::load_curve(&args.surface)?;
    let k = c.knot_vector();
    let pts = c.points();
    let lo = pts.iter().fold(pts[0], |a, p| a.inf(p));
    let hi = pts.iter().fold(pts[0], |a, p| a.sup(p));
    let size = (hi - lo).norm();
    let length = pssurf::interrogate::curve_shape::arc_length(&c, 1e-12 * size.max(1e-300)).length;
    let knots = k.knots();
    let inflections =
        plane_normal(pts).map(|n| pssurf::interrogate::curve_shape::inflections(&c, n, 32));
    let (a, b) = c.domain();
    let info = CurveInfo {
        file: args.surface.display().to_string(),
        valid: true,
        kind: "curve",
        degree: k.degree(),
        control_points: pts.len(),
        rational: c.is_rational(),
        knots: knots.len(),
        spans: k.spans().len(),
        parameter_domain: [a, b],
        control_min: lo.into(),
        control_max: hi.into(),
        length,
        inflections,
        curvature_torsion: pssurf::interrogate::curve_shape::curvature_torsion_ranges(&c, 32),
    };
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&info)?)?;
        return Ok(());
    }
    outln!("file                 {}", info.file)?;
    outln!("status               valid (every check passed on loading)")?;
    outln!(
        "kind                 curve ({}NURBS curve of degree {})",
        if info.rational { "rational " } else { "" },
        info.degree
    )?;
    outln!(
        "control points       {}: x [{}, {}], y [{}, {}], z [{}, {}]",
        info.control_points,
        lo.x,
        hi.x,
        lo.y,
        hi.y,
        lo.z,
        hi.z
    )?;
    outln!(
        "knots                {} ({} spans) on [{a}, {b}]",
        info.knots,
        info.spans
    )?;
    outln!("length               {}", info.length)?;
    match &info.inflections {
        Some(t) if t.is_empty() => outln!("inflections          none (a planar curve)")?,
        Some(t) => outln!(
            "inflections          {} at t = {}",
            t.len(),
            t.iter()
                .map(|x| format!("{x}"))
                .collect::<Vec<_>>()
                .join(", ")
        )?,
        None => outln!("inflections          - (a space curve)")?,
    }
    let ct = info.curvature_torsion;
    if ct.curvature[0] <= ct.curvature[1] {
        outln!(
            "curvature            {} to {} (32 samples per span)",
            ct.curvature[0],
            ct.curvature[1]
        )?;
    } else {
        // No sample had a defined curvature (min > max: the empty range).
        outln!("curvature            undefined (the curve does not move: zero speed everywhere)")?;
    }
    match ct.torsion {
        Some([a, b]) => outln!("torsion              {a} to {b}")?,
        None => outln!("torsion              - (no osculating plane: a straight line)")?,
    }
    Ok(())
}

/// The normal of the plane that holds all the control points (to 1e-12 of their extent), if
/// there is one; a straight curve's plane is taken as (x, y)'s if it lies in it.
fn plane_normal(pts: &[nalgebra::Vector3<f64>]) -> Option<nalgebra::Vector3<f64>> {
    let o = pts[0];
    let size = pts.iter().map(|p| (p - o).norm()).fold(0.0, f64::max);
    let mut normal = None;
    'find: for a in &pts[1..] {
        for b in pts {
            if let Some(n) = (a - o).cross(&(b - o)).try_normalize(1e-9 * size * size) {
                normal = Some(n);
                break 'find;
            }
        }
    }
    let n = normal.unwrap_or_else(nalgebra::Vector3::z);
    pts.iter()
        .all(|p| (p - o).dot(&n).abs() <= 1e-12 * size.max(1e-300))
        .then_some(n)
}

/// The surfaces of a surface file (one, named by the file) or of a scene file, with names.
pub fn load_named_surfaces(path: &std::path::Path) -> Result<Vec<(String, Surface)>> {
    Ok(match crate::budget::scene_objects(path)? {
        Some(c) if c.surfaces.is_empty() => {
            anyhow::bail!("{}: the scene has no surfaces", path.display())
        }
        Some(c) => (c.surfaces.into_iter())
            .map(|o| (o.name, o.surface))
            .collect(),
        None => vec![(
            path.display().to_string(),
            crate::budget::load_surface(path)?,
        )],
    })
}

/// The surfaces of a surface file (one) or of a scene file (every object's).
pub fn load_surfaces(path: &std::path::Path) -> Result<Vec<Surface>> {
    Ok(match crate::budget::scene_objects(path)? {
        Some(c) if c.surfaces.is_empty() => {
            anyhow::bail!("{}: the scene has no surfaces", path.display())
        }
        Some(c) => c.surfaces.into_iter().map(|o| o.surface).collect(),
        None => vec![crate::budget::load_surface(path)?],
    })
}

fn collect(s: &Surface, file: String) -> Info {
    // Bounds of the control points without collecting them (millions for a fine UPS).
    let count = s.control_count();
    let (lo, hi) = (0..count)
        .filter_map(|k| s.control_point(ControlId(k)))
        .fold(
            ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
            |(mut lo, mut hi), p| {
                for d in 0..3 {
                    lo[d] = lo[d].min(p.position[d]);
                    hi[d] = hi[d].max(p.position[d]);
                }
                (lo, hi)
            },
        );
    // A UPS surface is described from its lattice: building its general form (a PS basis of
    // every vertex) would take seconds for millions of control points.
    let (domain, ps) = match s.uniform() {
        Some(u) => (
            uniform_domain(u).unwrap_or_else(|| s.domain()),
            Some(uniform_ps_info(u)),
        ),
        None => (s.domain(), s.ps_basis().map(|b| ps_info(b))),
    };
    let (dlo, dhi) = domain.bounds();
    Info {
        file,
        valid: true,
        kind: s.kind().name(),
        description: s.kind().description(),
        pieces: s.piece_count(),
        domain_min: [dlo.x, dlo.y],
        domain_max: [dhi.x, dhi.y],
        domain_area: domain.area(),
        domain_holes: domain.hole_count(),
        control_points: count,
        control_min: lo,
        control_max: hi,
        weights: s.is_rational().then(|| {
            stats(
                (0..count)
                    .filter_map(|k| s.control_point(ControlId(k)))
                    .map(|p| p.weight)
                    .collect(),
            )
        }),
        ps,
        degree: s.piece_degree(),
        nurbs: match s {
            Surface::Nurbs(n) => Some(NurbsInfo {
                degrees: n.degree(),
                net: n.counts(),
                spans: [
                    n.knot_vectors()[0].spans().len(),
                    n.knot_vectors()[1].spans().len(),
                ],
                rational: n.is_rational(),
            }),
            _ => None,
        },
        uniform: s.uniform().map(uniform_info),
    }
}

fn ps_info(basis: &PsBasis) -> PsInfo {
    let t = basis.triangulation();
    let n = t.vertex_count();
    let q: Vec<_> = (0..n)
        .map(|i| quality(t, basis.refinement(), i, basis.ps_triangle(i)))
        .collect();
    PsInfo {
        vertices: n,
        triangles: t.triangle_count(),
        edges: t.edge_count(),
        boundary_vertices: (0..n).filter(|&i| t.is_boundary_vertex(i)).count(),
        basis_functions: basis.dimension(),
        split: match basis.refinement().rule() {
            Some(r) => format!("{r:?}").to_lowercase(),
            None => "given points".into(),
        },
        molecule_number: stats((0..n).map(|i| t.molecule_number(i) as f64).collect()),
        ps_triangle_area_ratio: stats(q.iter().map(|q| q.area_ratio).collect()),
        ps_triangle_min_angle_deg: stats(q.iter().map(|q| q.min_angle_deg).collect()),
    }
}

/// The domain of a UPS surface: its lattice polygon (`None` if the polygon is refused as a
/// domain, which a validated polygon never is).
fn uniform_domain(u: &UpsSurface) -> Option<Domain> {
    let g = u.grid();
    let corners = g
        .polygon()
        .vertices()
        .iter()
        .map(|&c| g.lattice().point(c))
        .collect();
    Domain::from_loops(vec![corners]).ok()
}

/// What [`ps_info`] reports of the general form, read off the lattice: the same counts, the
/// molecule numbers, and the quality of the fixed PS-triangles t(6) against each vertex's
/// PS-points.
fn uniform_ps_info(u: &UpsSurface) -> PsInfo {
    let g = u.grid();
    let lattice = g.lattice();
    let slots = g.real_slots();
    // A vertex's PS-points relative to it depend only on which of its six sectors are
    // triangles: one quality per pattern (at most 64), computed at its first vertex.
    let mut by_pattern = std::collections::HashMap::new();
    let q: Vec<_> = slots
        .iter()
        .map(|&s| {
            *by_pattern.entry(g.sectors(s)).or_insert_with(|| {
                let v = lattice.point(g.lattice_point(s));
                quality_for(&g.ps_points(s), &fixed_ps_triangle(lattice, v))
            })
        })
        .collect();
    PsInfo {
        vertices: g.vertex_count(),
        triangles: g.triangle_count(),
        // Each edge once, from the end it leaves in direction 0°, 60° or 120°.
        edges: slots
            .iter()
            .map(|&s| (0..3).filter(|&k| g.has_edge(s, k)).count())
            .sum(),
        boundary_vertices: slots.iter().filter(|&&s| g.is_boundary(s)).count(),
        basis_functions: 3 * g.vertex_count(),
        split: "incenter".into(),
        molecule_number: stats(slots.iter().map(|&s| g.molecule_number(s) as f64).collect()),
        ps_triangle_area_ratio: stats(q.iter().map(|q| q.area_ratio).collect()),
        ps_triangle_min_angle_deg: stats(q.iter().map(|q| q.min_angle_deg).collect()),
    }
}

fn uniform_info(u: &UpsSurface) -> UniformInfo {
    let g = u.grid();
    UniformInfo {
        base: g.lattice().base,
        origin: [g.lattice().origin.x, g.lattice().origin.y],
        polygon: g.polygon().vertices().to_vec(),
        wavelet_levels_available: g.coarsening_levels(),
    }
}

fn print_table(info: &Info) -> Result<()> {
    let st = |s: &Stats| format!("min {:.4}, median {:.4}, max {:.4}", s.min, s.median, s.max);
    outln!("file                 {}", info.file)?;
    outln!("status               valid (every check passed on loading)")?;
    outln!("kind                 {} ({})", info.kind, info.description)?;
    if let Some(ps) = &info.ps {
        outln!(
            "vertices             {} ({} on the boundary)",
            ps.vertices,
            ps.boundary_vertices
        )?;
        outln!(
            "triangles            {} ({} edges; {} PS sub-triangles)",
            ps.triangles,
            ps.edges,
            info.pieces
        )?;
        outln!("basis functions      {}", ps.basis_functions)?;
        outln!("split points         {}", ps.split)?;
    }
    match &info.nurbs {
        Some(n) => outln!(
            "pieces               {} knot rectangles ({} × {}) of degrees {} × {}; net {} × {}{}",
            info.pieces,
            n.spans[0],
            n.spans[1],
            n.degrees[0],
            n.degrees[1],
            n.net[0],
            n.net[1],
            if n.rational { ", rational" } else { "" }
        )?,
        None => outln!(
            "pieces               {} of degree {}",
            info.pieces,
            info.degree
        )?,
    }
    let (dlo, dhi) = (info.domain_min, info.domain_max);
    outln!(
        "domain               [{}, {}] × [{}, {}], area {}{}",
        dlo[0],
        dhi[0],
        dlo[1],
        dhi[1],
        info.domain_area,
        match info.domain_holes {
            0 => String::new(),
            1 => ", 1 hole".into(),
            h => format!(", {h} holes"),
        }
    )?;
    if let Some(ps) = &info.ps {
        outln!("molecule numbers     {}", st(&ps.molecule_number))?;
        outln!(
            "PS-triangle quality  area / hull of PS-points: {}",
            st(&ps.ps_triangle_area_ratio)
        )?;
        outln!(
            "                     smallest angle (degrees): {}",
            st(&ps.ps_triangle_min_angle_deg)
        )?;
    }
    let (lo, hi) = (info.control_min, info.control_max);
    outln!(
        "control points       {}: x [{}, {}], y [{}, {}], z [{}, {}]",
        info.control_points,
        lo[0],
        hi[0],
        lo[1],
        hi[1],
        lo[2],
        hi[2]
    )?;
    if let Some(w) = &info.weights {
        outln!("weights              {}", st(w))?;
    }
    if let Some(u) = &info.uniform {
        let corners: Vec<String> = u
            .polygon
            .iter()
            .map(|p| format!("{},{}", p[0], p[1]))
            .collect();
        outln!(
            "uniform (UPS)        base {}, origin ({}, {}), lattice polygon {}",
            u.base,
            u.origin[0],
            u.origin[1],
            corners.join(" ")
        )?;
        outln!(
            "                     up to {} wavelet levels",
            u.wavelet_levels_available.min(62)
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The report of a UPS surface read off its lattice equals the report of its general
    /// form (counts exactly, statistics to rounding), on several polygons.
    #[test]
    fn uniform_reports_equal_the_general_forms() {
        use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface};
        for (sides, size) in [(3, 4), (4, 3), (5, 2), (6, 3)] {
            let lattice = Lattice {
                base: 0.7,
                origin: nalgebra::Point2::new(-2.0, 1.5),
            };
            let polygon = LatticePolygon::standard(sides, size).unwrap();
            let grid = UpsGrid::new(lattice, polygon).unwrap();
            let u = graph_surface(grid, GraphKind::Functional, |p| pssurf::ps::Hermite {
                value: p.x * p.y,
                dx: p.y,
                dy: p.x,
            });
            let general = u.to_general().unwrap();
            let (a, b) = (uniform_ps_info(&u), ps_info(general.ps_basis().unwrap()));
            let tag = format!("{sides}-gon of size {size}");
            assert_eq!(
                (
                    a.vertices,
                    a.triangles,
                    a.edges,
                    a.boundary_vertices,
                    a.basis_functions
                ),
                (
                    b.vertices,
                    b.triangles,
                    b.edges,
                    b.boundary_vertices,
                    b.basis_functions
                ),
                "{tag}"
            );
            assert_eq!(a.split, b.split, "{tag}");
            for (x, y) in [
                (&a.molecule_number, &b.molecule_number),
                (&a.ps_triangle_area_ratio, &b.ps_triangle_area_ratio),
                (&a.ps_triangle_min_angle_deg, &b.ps_triangle_min_angle_deg),
            ] {
                for (p, q) in [(x.min, y.min), (x.median, y.median), (x.max, y.max)] {
                    assert!((p - q).abs() <= 1e-12 * q.abs(), "{tag}: {p} vs {q}");
                }
            }
            let (d, e) = (uniform_domain(&u).unwrap(), general.domain());
            assert!((d.area() - e.area()).abs() <= 1e-12 * e.area(), "{tag}");
            assert_eq!(d.bounds(), e.bounds(), "{tag}");
        }
    }
}
