//! `pssurf new ups`: a UPS surface on a lattice polygon, interpolating the graph of a formula.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use nalgebra::Point2;
use pssurf::expr::HeightFunction;
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface_from_formula};

/// What to create.
#[derive(clap::Subcommand, Debug)]
pub enum NewWhat {
    /// A uniform PS (UPS) surface on a lattice polygon of the isometric grid.
    Ups(NewUpsArgs),
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
    /// The surface file to write.
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
    let NewWhat::Ups(args) = what;
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
    crate::output::save_surface(&Surface::from(ups), &args.output)?;
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
