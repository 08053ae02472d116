//! `pssurf fill-hole` and `pssurf example`: filling polygonal holes with UPS patches
//! (thesis chapter 5, issue 18).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, anyhow, bail};
use pssurf::hole::examples::{EXAMPLES, example};
use pssurf::hole::{
    DynCurve, FillOptions, FilledHole, HoleBoundary, HoleError, Interior, MAX_ITERATIONS,
    QualityReport, SurfaceEdge, fill_hole,
};
use pssurf::io::{Durability, SceneEntry, scene_to_json};
use pssurf::surface::{Surface, UniformSurface, UpsSurface};
use pssurf::text::Significant;

/// The interior method (thesis 5.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum InteriorArg {
    /// The initial solution subdivided at each step, its boundary overwritten by the latest
    /// fit (the thesis' cheap recommendation).
    Instant,
    /// The initial solution subdivided, only the boundary replaced.
    Copy,
    /// Rings from the boundary inwards, each triangle the mean of its six neighbours.
    Average,
    /// Bridges of k-subdivision between opposite boundary triangles, three directions
    /// averaged.
    Subdivision,
    /// The instant update smoothed by wavelet thresholding, boundary rings kept.
    Threshold,
    /// Constrained fairing: least squares on the second-derivative jumps (sparse Cholesky).
    Fair,
}

impl InteriorArg {
    fn method(self) -> Interior {
        Interior::from_name(match self {
            InteriorArg::Instant => "instant",
            InteriorArg::Copy => "copy",
            InteriorArg::Average => "average",
            InteriorArg::Subdivision => "subdivision",
            InteriorArg::Threshold => "threshold",
            InteriorArg::Fair => "fair",
        })
        .expect("every argument names a method")
    }
}

/// How to iterate (shared by `fill-hole` and `example`).
#[derive(clap::Args, Debug)]
pub struct IterationArgs {
    /// The interior method.
    #[arg(long, value_enum, default_value_t = InteriorArg::Instant)]
    pub interior: InteriorArg,
    /// Refine until the patch is within this fraction of the model size of the curves (at
    /// the middles and quarter points of the boundary edges).
    #[arg(long, default_value_t = 1e-4, conflicts_with = "iterations")]
    pub tolerance: f64,
    /// ... and its normals within this many degrees of the given ones.
    #[arg(long, default_value_t = 0.25, conflicts_with = "iterations")]
    pub angle_tolerance: f64,
    /// Refine exactly this many times instead (at most 9).
    #[arg(long)]
    pub iterations: Option<usize>,
    /// The most refinement steps when refining to the tolerance.
    #[arg(long, default_value_t = 8)]
    pub max_iterations: usize,
}

impl IterationArgs {
    fn options(&self) -> Result<FillOptions> {
        if self.max_iterations > MAX_ITERATIONS {
            bail!(HoleError::TooManyIterations {
                requested: self.max_iterations
            });
        }
        Ok(FillOptions {
            tolerance: self.tolerance,
            angle_tolerance: self.angle_tolerance,
            iterations: self.iterations,
            max_iterations: self.max_iterations,
            interior: self.interior.method(),
        })
    }
}

/// Arguments of `pssurf fill-hole`.
#[derive(clap::Args, Debug)]
pub struct FillHoleArgs {
    /// A hole specification (kind "hole": 3 to 6 curves with normals, or 2 for a gap).
    #[arg(value_name = "SPEC.json", required_unless_present = "scene")]
    pub spec: Option<PathBuf>,
    /// Take the boundary from edges of the surfaces in this scene (or surface) file.
    #[arg(long, value_name = "SCENE.json", conflicts_with = "spec")]
    pub scene: Option<PathBuf>,
    /// The edges: OBJECT:SIDE,… with objects and sides numbered from 1 (`--list-edges`
    /// shows them); 3 to 6 edges bound a hole, 2 a gap (filled by two patches).
    #[arg(long, value_name = "O:S,…", value_delimiter = ',', requires = "scene")]
    pub edges: Vec<String>,
    /// List the sides of every object of the scene and stop.
    #[arg(long, requires = "scene")]
    pub list_edges: bool,
    #[command(flatten)]
    pub iteration: IterationArgs,
    /// The patch file to write (a scene of two patches for a two-curve gap).
    #[arg(
        short,
        long,
        value_name = "PATCH.json",
        required_unless_present = "list_edges"
    )]
    pub output: Option<PathBuf>,
    /// Also write the quality report as JSON.
    #[arg(long, value_name = "REPORT.json")]
    pub report: Option<PathBuf>,
}

/// Runs `pssurf fill-hole`.
pub fn run_fill(args: &FillHoleArgs) -> Result<()> {
    let holes = match (&args.spec, &args.scene) {
        (Some(spec), _) => holes_from_spec(spec)?,
        (None, Some(scene)) => {
            let objects = scene_surfaces(scene)?;
            if args.list_edges {
                return list_edges(&objects);
            }
            holes_from_edges(&objects, &args.edges)?
        }
        (None, None) => bail!("give a hole specification or --scene"),
    };
    let output = args
        .output
        .as_ref()
        .context("give the output file with -o")?;
    let opts = args.iteration.options()?;
    let filled = fill_all(holes, &opts)?;
    write_patches(&filled, output, "patch")?;
    if let Some(path) = &args.report {
        write_report(&filled, path)?;
    }
    eprintln!("wrote {}", output.display());
    Ok(())
}

/// Fills every hole, printing the residual per iteration and the quality report.
fn fill_all(holes: Vec<HoleBoundary>, opts: &FillOptions) -> Result<Vec<FilledHole>> {
    let count = holes.len();
    let sides: Vec<usize> = holes.iter().map(|h| h.len()).collect();
    fill_estimate(&sides, opts).check()?;
    let mut out = Vec::new();
    for (k, hole) in holes.into_iter().enumerate() {
        let filled = fill_hole(hole, opts)?;
        if count > 1 {
            eprintln!("patch {} of {count}:", k + 1);
        }
        print_report(&filled.report, opts.interior);
        if !filled.converged {
            eprintln!(
                "warning: the tolerance was not met after {} iterations (raise --max-iterations up to {MAX_ITERATIONS}, or loosen --tolerance)",
                filled.report.iterations.len() - 1
            );
        }
        out.push(filled);
    }
    Ok(out)
}

/// Peak memory per vertex of the finest patches, bytes: the fill's UPS surfaces, the
/// patch's general form, its quality report, and the patches kept for writing (measured
/// 3.4 kB for one 3-sided hole at 8 and 9 steps: 149 and 452 MB for 33,153 and 131,841
/// vertices; 4.5 kB for the three holes of `example prism-cap` at 8 steps), with a margin.
const FILL_MEMORY_PER_VERTEX: u64 = 5 * 1024;

/// Bytes of the written patch per vertex (three control points in JSON; 348 measured).
const FILL_OUTPUT_PER_VERTEX: u64 = 400;

/// The cost of filling holes of `sides` curves each as far as `opts` may refine them (the
/// fixed number of steps, or the most steps towards the tolerance); all patches are kept
/// until they are written.
fn fill_estimate(sides: &[usize], opts: &FillOptions) -> crate::budget::Estimate {
    let level = opts
        .iterations
        .unwrap_or(opts.max_iterations)
        .min(MAX_ITERATIONS);
    let vertices = sides
        .iter()
        .map(|&n| {
            pssurf::ups::LatticePolygon::standard(n, 1 << level).map_or(0, |p| {
                u64::try_from(p.lattice_point_count()).unwrap_or(u64::MAX)
            })
        })
        .fold(0u64, u64::saturating_add);
    let holes = match sides {
        [n] => format!("a {n}-sided hole"),
        _ => format!("{} holes", sides.len()),
    };
    crate::budget::Estimate {
        what: format!("filling {holes} with up to {level} refinement steps"),
        makes: format!("{} vertices", crate::budget::count(vertices)),
        memory: crate::budget::load_memory(0)
            .saturating_add(vertices.saturating_mul(FILL_MEMORY_PER_VERTEX)),
        output: vertices.saturating_mul(FILL_OUTPUT_PER_VERTEX),
    }
}

/// The residual per iteration and the quality numbers.
pub fn print_report(r: &QualityReport, interior: Interior) {
    eprintln!("iteration  vertices  deviation   normal angle  fitted  subdivided");
    for it in &r.iterations {
        eprintln!(
            "{:>9}  {:>8}  {:>10}  {:>11}°  {:>6}  {:>10}",
            it.level,
            it.vertices,
            Significant(it.max_deviation, 3).to_string(),
            Significant(it.max_angle, 3).to_string(),
            it.fitted,
            it.subdivided
        );
    }
    eprintln!(
        "quality ({} interior): G0 max {} rms {} ({} of the model size {}); G1 max {}° rms {}°; ∫H² dA {}; thin plate {}",
        interior.name(),
        Significant(r.g0_max, 3),
        Significant(r.g0_rms, 3),
        Significant(r.g0_max / r.model_size, 2),
        Significant(r.model_size, 4),
        Significant(r.g1_max_degrees, 3),
        Significant(r.g1_rms_degrees, 3),
        Significant(r.mean_curvature_squared, 5),
        Significant(r.thin_plate, 5),
    );
    for c in &r.singular_corners {
        eprintln!(
            "singular corner between curves {} and {}: the surrounding normals are {}° off the plane of the tangents (no tangent plane there, as at a cone's apex); G1 is measured away from its boundary edges",
            c.curve_in,
            c.curve_out,
            Significant(c.degrees, 3)
        );
    }
}

/// The boundaries of a hole specification: one hole, or two for a two-curve gap (bisected
/// automatically).
fn holes_from_spec(path: &Path) -> Result<Vec<HoleBoundary>> {
    let text = crate::table::read_text(path)?;
    let curves =
        pssurf::io::hole_from_json(&text).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    if curves.len() == 2 {
        let mut it = curves.into_iter();
        let (a, b) = (it.next().expect("two"), it.next().expect("two"));
        let [first, second] = pssurf::hole::gap_between(Arc::new(a), Arc::new(b))?;
        return Ok(vec![first, second]);
    }
    let curves: Vec<DynCurve> = curves
        .into_iter()
        .map(|c| Box::new(c) as DynCurve)
        .collect();
    Ok(vec![HoleBoundary::new(curves)?])
}

/// Whether a scene object's placement (written by the application) moves, turns or scales it.
fn is_placed(object: &serde_json::Value) -> bool {
    let Some(t) = object.get("transform") else {
        return false;
    };
    let zeros = |key: &str| {
        t.get(key)
            .and_then(|v| v.as_array())
            .is_none_or(|a| a.iter().all(|x| x.as_f64() == Some(0.0)))
    };
    !(zeros("translate")
        && zeros("rotate_deg")
        && t.get("scale").is_none_or(|s| s.as_f64() == Some(1.0)))
}

/// The surfaces of a scene or surface file. Objects the application placed elsewhere are
/// refused: the hole's curves are taken in each surface's own coordinates.
fn scene_surfaces(path: &Path) -> Result<Vec<(String, Arc<Surface>)>> {
    Ok(match crate::budget::scene_objects(path)? {
        Some(contents) => {
            let objects = contents.surfaces;
            let text = crate::table::read_text(path)?;
            let raw: serde_json::Value = serde_json::from_str(&text)?;
            let placed = raw["objects"]
                .as_array()
                // The surface objects, in the order the library reads them (meshes aside).
                .map(|a| {
                    (a.iter())
                        .filter(|o| o.get("surface").is_some())
                        .map(is_placed)
                        .collect::<Vec<_>>()
                })
                .unwrap_or_default();
            if let Some(k) = placed.iter().position(|&p| p) {
                bail!(
                    "{}: object {} ({}) is moved, turned or scaled in the scene; fill-hole takes surfaces at their own place (reset the placement in the application)",
                    path.display(),
                    k + 1,
                    objects[k].name
                );
            }
            objects
                .into_iter()
                .map(|o| (o.name, Arc::new(o.surface)))
                .collect()
        }
        None => vec![(
            "surface".to_string(),
            Arc::new(crate::budget::load_surface(path)?),
        )],
    })
}

/// Prints every side of every object: its number and 3D end points (a closed pipe ends the
/// listing quietly).
fn list_edges(objects: &[(String, Arc<Surface>)]) -> Result<()> {
    use pssurf::hole::BoundaryCurve;
    use std::fmt::Write as _;
    use std::io::Write as _;
    let mut text = String::new();
    for (k, (name, s)) in objects.iter().enumerate() {
        let _ = writeln!(text, "object {} ({name}):", k + 1);
        for (j, e) in SurfaceEdge::sides(s.clone()).iter().enumerate() {
            let (a, b) = (e.point(0.0), e.point(1.0));
            let _ = writeln!(
                text,
                "  {}:{}  from ({}, {}, {}) to ({}, {}, {})",
                k + 1,
                j + 1,
                Significant(a.x, 6),
                Significant(a.y, 6),
                Significant(a.z, 6),
                Significant(b.x, 6),
                Significant(b.y, 6),
                Significant(b.z, 6)
            );
        }
    }
    match std::io::stdout().write_all(text.as_bytes()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(anyhow!(
            "cannot write the listing: {}",
            pssurf::io::io_cause(&e)
        )),
        _ => Ok(()),
    }
}

/// The boundary made of the named sides.
fn holes_from_edges(
    objects: &[(String, Arc<Surface>)],
    edges: &[String],
) -> Result<Vec<HoleBoundary>> {
    let mut curves: Vec<SurfaceEdge> = Vec::new();
    for e in edges {
        let (o, s) = e
            .split_once(':')
            .with_context(|| format!("edge \"{e}\" is not OBJECT:SIDE (e.g. 1:2)"))?;
        let o: usize = o
            .trim()
            .parse()
            .ok()
            .filter(|&o| (1..=objects.len()).contains(&o))
            .with_context(|| {
                format!(
                    "edge \"{e}\": there is no object {o} (1 to {})",
                    objects.len()
                )
            })?;
        let sides = SurfaceEdge::sides(objects[o - 1].1.clone());
        let s: usize = s
            .trim()
            .parse()
            .ok()
            .filter(|&s| (1..=sides.len()).contains(&s))
            .with_context(|| {
                format!(
                    "edge \"{e}\": object {o} has sides 1 to {}, not {s}",
                    sides.len()
                )
            })?;
        curves.push(sides[s - 1].clone());
    }
    if let [a, b] = &curves[..] {
        let [first, second] = pssurf::hole::gap_between(Arc::new(a.clone()), Arc::new(b.clone()))?;
        return Ok(vec![first, second]);
    }
    Ok(vec![HoleBoundary::new(
        curves
            .into_iter()
            .map(|c| Box::new(c) as DynCurve)
            .collect(),
    )?])
}

/// The patch of a filled hole as a surface.
fn patch_surface(f: &FilledHole) -> Result<Surface> {
    Ok(Surface::Uniform(UniformSurface::new(
        UpsSurface::Parametric(f.patch.clone()),
    )?))
}

/// Writes one patch as a surface file, several as a scene.
fn write_patches(filled: &[FilledHole], output: &Path, name: &str) -> Result<()> {
    if let [one] = filled {
        return crate::output::save_surface(&patch_surface(one)?, output);
    }
    let objects: Vec<SceneEntry> = filled
        .iter()
        .enumerate()
        .map(|(k, f)| {
            Ok(SceneEntry {
                name: format!("{name} {}", k + 1),
                group: name.to_string(),
                surface: patch_surface(f)?,
            })
        })
        .collect::<Result<_>>()?;
    write_scene(&objects, output)
}

fn write_scene(objects: &[SceneEntry], output: &Path) -> Result<()> {
    let json = scene_to_json(objects);
    crate::output::write_output(output, Durability::Durable, |w| {
        Ok(w.write_all(json.as_bytes())?)
    })
}

fn write_report(filled: &[FilledHole], path: &Path) -> Result<()> {
    let reports: Vec<&QualityReport> = filled.iter().map(|f| &f.report).collect();
    let json = serde_json::to_string_pretty(&reports)?;
    crate::output::write_output(path, Durability::Durable, |w| {
        Ok(w.write_all(json.as_bytes())?)
    })
}

/// Arguments of `pssurf example`.
#[derive(clap::Args, Debug)]
pub struct ExampleArgs {
    /// The example: hole-sphere (thesis 5.4), two-cylinders (5.6.1), prism-cap (5.6.2),
    /// two-curve-gap, or degenerate-nurbs (6.4.1: a triangular patch instead of a NURBS
    /// patch with a collapsed edge).
    #[arg(value_parser = clap::builder::PossibleValuesParser::new(EXAMPLES))]
    pub name: String,
    #[command(flatten)]
    pub iteration: IterationArgs,
    /// Also fill with every other interior method, for comparison (one file each).
    #[arg(long)]
    pub all_methods: bool,
    /// The folder to write into (created if missing).
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,
}

/// Runs `pssurf example`: writes DIR/NAME.json (the surroundings and the patches as a scene),
/// DIR/NAME-patch-K.json (each patch), DIR/NAME-report.json and, with --all-methods,
/// DIR/NAME-METHOD-patch-K.json for every interior method.
pub fn run_example(args: &ExampleArgs) -> Result<()> {
    let opts = args.iteration.options()?;
    // Refused before anything is written or printed.
    let holes = example(&args.name).expect("a known example")?.holes;
    fill_estimate(&holes.iter().map(|h| h.len()).collect::<Vec<_>>(), &opts).check()?;
    crate::output::create_folder(&args.output)?;
    let methods: Vec<Interior> = if args.all_methods {
        Interior::ALL.to_vec()
    } else {
        vec![opts.interior]
    };
    for method in methods {
        let ex = example(&args.name).expect("a known example")?;
        let opts = FillOptions {
            interior: method,
            ..opts
        };
        eprintln!("{} with the {} interior:", args.name, method.name());
        let filled = fill_all(ex.holes, &opts)?;
        let stem = if method == args.iteration.interior.method() {
            args.name.clone()
        } else {
            format!("{}-{}", args.name, method.name())
        };
        for (k, f) in filled.iter().enumerate() {
            let path = args.output.join(format!("{stem}-patch-{}.json", k + 1));
            crate::output::save_surface(&patch_surface(f)?, &path)?;
        }
        let mut objects: Vec<SceneEntry> = ex
            .surroundings
            .into_iter()
            .enumerate()
            .map(|(k, s)| SceneEntry {
                name: format!("given {}", k + 1),
                group: "surroundings".into(),
                surface: s,
            })
            .collect();
        for (k, f) in filled.iter().enumerate() {
            objects.push(SceneEntry {
                name: format!("patch {}", k + 1),
                group: "patches".into(),
                surface: patch_surface(f)?,
            });
        }
        write_scene(&objects, &args.output.join(format!("{stem}.json")))?;
        write_report(&filled, &args.output.join(format!("{stem}-report.json")))?;
    }
    eprintln!("wrote {}", args.output.display());
    Ok(())
}
