//! `pssurf new ups`: a UPS surface on a lattice polygon, interpolating the graph of a formula;
//! `pssurf new cylinder|cone|sphere`: a quadric as a scene of exact NURPS patches (thesis 3.6).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use nalgebra::Point2;
use pssurf::expr::HeightFunction;
use pssurf::io::{Durability, SceneEntry, scene_to_json};
use pssurf::ps::quadrics::Quadric;
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface_from_formula};

/// What to create.
#[derive(clap::Subcommand, Debug)]
pub enum NewWhat {
    /// A uniform PS (UPS) surface on a lattice polygon of the isometric grid.
    Ups(NewUpsArgs),
    /// A cylinder x² + y² = r², 0 ≤ z ≤ h, exactly, as eight NURPS patches (a scene file).
    Cylinder(NewQuadricArgs),
    /// A cone x² + y² = ((h − z) r / h)², 0 ≤ z ≤ h, exactly, as six NURPS patches meeting at
    /// the apex (a scene file).
    Cone(NewQuadricArgs),
    /// The sphere x² + y² + z² = r² as 2n exact NURPS patches, leaving two thin bands next to
    /// the equator open (no surface of rational quadratic triangles closes a sphere); more
    /// sectors, thinner bands (a scene file).
    Sphere(NewSphereArgs),
}

/// What each patch of a quadric becomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PatchForm {
    /// A NURPS surface on an equilateral triangle (the optimal representation, thesis 3.5.2).
    Nurps,
    /// The rational quadratic Bézier triangle itself.
    Bezier,
}

/// Arguments of `pssurf new cylinder` and `pssurf new cone`.
#[derive(clap::Args, Debug)]
pub struct NewQuadricArgs {
    /// The radius r (of the base for a cone).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub radius: f64,
    /// The height h.
    #[arg(long, default_value_t = 2.0, allow_hyphen_values = true)]
    pub height: f64,
    /// NURPS patches or rational Bézier triangles.
    #[arg(long, value_enum, default_value_t = PatchForm::Nurps)]
    pub form: PatchForm,
    /// The scene file to write (one object per patch, grouped).
    #[arg(short, long, value_name = "SCENE.json")]
    pub output: PathBuf,
}

/// Arguments of `pssurf new sphere`.
#[derive(clap::Args, Debug)]
pub struct NewSphereArgs {
    /// The radius r.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub radius: f64,
    /// The number n of patches around each hemisphere, each spanning 360°/n (3 to 720); the
    /// open bands are r sin²(π/n) / (cos²(π/n) + 1) high (thesis (3.124)).
    #[arg(long, default_value_t = 6, value_name = "N")]
    pub sectors: usize,
    /// NURPS patches or rational Bézier triangles.
    #[arg(long, value_enum, default_value_t = PatchForm::Nurps)]
    pub form: PatchForm,
    /// The scene file to write (one object per patch, grouped).
    #[arg(short, long, value_name = "SCENE.json")]
    pub output: PathBuf,
}

/// The kind of surface to create.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Kind {
    /// Control points in R³ (x, y, z).
    Parametric,
    /// One control value per PS-triangle corner: z = s(x, y).
    Functional,
}

/// Arguments of `pssurf new ups`.
#[derive(clap::Args, Debug)]
pub struct NewUpsArgs {
    /// A standard polygon: 3 = triangle of side N, 4 = rhombus of side N, 5 = pentagon with
    /// sides N, N, 2N, 2N, N (a triangle of side 3N without two corners), 6 = regular hexagon
    /// of side N.
    #[arg(long, value_parser = clap::value_parser!(u8).range(3..=6), required_unless_present = "polygon", conflicts_with = "polygon")]
    pub sides: Option<u8>,
    /// The number of triangles along each (shorter) side of the standard polygon.
    #[arg(long, value_name = "N", required_unless_present = "polygon", value_parser = clap::value_parser!(i64).range(1..=1 << 20))]
    pub size: Option<i64>,
    /// Your own polygon: corners in lattice coordinates "i,j i,j ...", each edge along a grid
    /// line (steps in multiples of (1,0), (0,1) or (1,−1)); lattice point (i, j) lies at
    /// B·(i + j/2, j·√3/2).
    #[arg(long, value_name = "\"i,j i,j ...\"", allow_hyphen_values = true)]
    pub polygon: Option<String>,
    /// The base B: the edge length of the triangles.
    #[arg(long, default_value_t = 1.0)]
    pub base: f64,
    /// The height z = EXPR(x, y): numbers, x, y, + - * / ^, parentheses, sin cos tan exp ln
    /// sqrt abs, PI, E. The surface interpolates its value and tangent plane at every vertex
    /// (Hermite interpolation, thesis (4.9)).
    #[arg(
        long,
        value_name = "EXPR",
        default_value = "0",
        allow_hyphen_values = true
    )]
    pub height: String,
    /// A parametric surface (default) or a functional one.
    #[arg(long, value_enum, default_value_t = Kind::Parametric)]
    pub kind: Kind,
    /// The surface file to write (binary when it ends in `.psb`, else JSON; docs/format.md).
    #[arg(short, long, value_name = "SURF.json")]
    pub output: PathBuf,
}

/// Parses "i,j i,j ..." into lattice points.
pub(crate) fn parse_polygon(s: &str) -> Result<Vec<[i64; 2]>> {
    s.split_whitespace()
        .enumerate()
        .map(|(k, pair)| {
            let (a, b) = pair
                .split_once(',')
                .with_context(|| format!("corner {k} `{pair}` is not of the form i,j"))?;
            let p = |t: &str| {
                t.trim()
                    .parse::<i64>()
                    .with_context(|| format!("corner {k}: `{t}` is not an integer"))
            };
            Ok([p(a)?, p(b)?])
        })
        .collect()
}

/// Runs `pssurf new`.
pub fn run(what: &NewWhat) -> Result<()> {
    match what {
        NewWhat::Ups(args) => new_ups(args),
        NewWhat::Cylinder(a) | NewWhat::Cone(a) => {
            let (radius, height) = (a.radius, a.height);
            let q = if matches!(what, NewWhat::Cylinder(_)) {
                Quadric::Cylinder { radius, height }
            } else {
                Quadric::Cone { radius, height }
            };
            new_quadric(&q, a.form, &a.output)
        }
        NewWhat::Sphere(a) => {
            let q = Quadric::Sphere {
                radius: a.radius,
                sectors: a.sectors,
            };
            new_quadric(&q, a.form, &a.output)
        }
    }
}

/// Writes the patches of a quadric as a scene, one object per patch in a group named after it.
fn new_quadric(q: &Quadric, form: PatchForm, output: &Path) -> Result<()> {
    let surfaces: Vec<Surface> = match form {
        PatchForm::Nurps => q.nurps_patches()?.into_iter().map(Surface::Nurps).collect(),
        PatchForm::Bezier => (q.bezier_patches()?.into_iter())
            .map(Surface::RationalBezier)
            .collect(),
    };
    let objects: Vec<SceneEntry> = surfaces
        .into_iter()
        .enumerate()
        .map(|(k, surface)| SceneEntry {
            name: format!("{} {}", q.name(), k + 1),
            group: q.name().to_string(),
            surface,
        })
        .collect();
    let json = scene_to_json(&objects);
    crate::output::write_output(output, Durability::Durable, |w| {
        Ok(w.write_all(json.as_bytes())?)
    })?;
    let form = match form {
        PatchForm::Nurps => "NURPS patches",
        PatchForm::Bezier => "rational Bézier triangles",
    };
    let gap = match q {
        Quadric::Sphere { .. } => format!(
            "; two bands {} high next to the equator stay open",
            pssurf::text::Short(q.gap())
        ),
        _ => String::new(),
    };
    eprintln!(
        "created a {} of {} {form}{gap}; wrote {}",
        q.name(),
        objects.len(),
        output.display()
    );
    Ok(())
}

/// Runs `pssurf new ups`.
fn new_ups(args: &NewUpsArgs) -> Result<()> {
    let polygon = match (&args.polygon, args.sides, args.size) {
        (Some(p), _, _) => LatticePolygon::new(parse_polygon(p)?)?,
        (None, Some(s), Some(n)) => LatticePolygon::standard(s as usize, n)?,
        _ => bail!("give --sides and --size, or --polygon"),
    };
    crate::commands::uniform::creation_estimate(
        "a new UPS surface".to_string(),
        polygon.lattice_point_count(),
        polygon.block_slots(),
    )
    .check()?;
    let lattice = Lattice {
        base: args.base,
        origin: Point2::origin(),
    };
    let grid = UpsGrid::new(lattice, polygon)?;
    let f = HeightFunction::parse(&args.height)?;
    let kind = match args.kind {
        Kind::Parametric => GraphKind::Parametric,
        Kind::Functional => GraphKind::Functional,
    };
    let ups = graph_surface_from_formula(grid, kind, &f)?;
    let g = ups.grid();
    let (vertices, triangles) = (g.vertex_count(), g.triangle_count());
    crate::output::save_surface(&Surface::try_from(ups)?, &args.output)?;
    eprintln!(
        "created a {} UPS surface: {vertices} vertices, {triangles} triangles; wrote {}",
        match args.kind {
            Kind::Parametric => "parametric",
            Kind::Functional => "functional",
        },
        args.output.display()
    );
    Ok(())
}
