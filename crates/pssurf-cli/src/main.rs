//! `pssurf`: design and interrogate Powell–Sabin spline surfaces from the command line.

/// `println!` that returns the write's error instead of panicking on it; a reader that has
/// gone (`pssurf info f.json | head -1`) is no error ([`reader_gone_is_fine`]).
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        $crate::reader_gone_is_fine(writeln!(std::io::stdout().lock(), $($arg)*))
    }};
}

/// `print!` that returns the write's error (see `outln!`).
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        $crate::reader_gone_is_fine(write!(std::io::stdout().lock(), $($arg)*))
    }};
}

/// A report line's write, with a pipe whose reader has gone (`pssurf denoise … | head -1`)
/// taken as written: the command goes on to write its files. It stopped there with exit 0,
/// and the requested file was never written.
fn reader_gone_is_fine(written: std::io::Result<()>) -> std::io::Result<()> {
    match written {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

mod budget;
mod colors;
mod commands;
mod output;
mod points;
mod table;

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

// mimalloc keeps freed memory for reuse; with glibc's allocator every large fresh buffer
// (a subdivided surface, a million evaluated points) is page-faulted in again, which made
// UPS subdivision 3× slower on large surfaces (docs/performance.md).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Powell–Sabin spline surfaces: fit scattered data, evaluate, inspect.
///
/// A PS-spline is a C¹ piecewise quadratic on any triangulation, written in Dierckx's
/// normalized B-spline form: three control points per vertex forming a control triangle
/// tangent to the surface. Surfaces (PS, NURPS, UPS and Bézier triangles) are stored in
/// pssurf JSON files (docs/format.md). Wherever a command reads one surface, object K of a
/// scene file (`pssurf import`, `new sphere`) is named SCENE.json#K, K from 0.
#[derive(Parser, Debug)]
#[command(
    name = "pssurf",
    version,
    about,
    long_about,
    max_term_width = 100,
    after_long_help = TYPICAL_USE
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    #[command(flatten)]
    budget: budget::BudgetArgs,
}

/// Examples printed by `pssurf --help`, line by line.
const TYPICAL_USE: &str = "\
Typical use:
  pssurf fit data.csv -o surf.json          # interpolate x,y,z (and optional zx,zy)
  pssurf info surf.json                     # what the file holds, PS-triangle quality
  pssurf eval surf.json --grid 200x200 -o grid.npy --derivatives
  pssurf new ups --sides 6 --size 4 --height \"sin(x)*cos(y)\" -o ups.json
  pssurf subdivide ups.json --times 3 -o fine.json
  pssurf noise fine.json --amplitude 0.01 --seed 1 -o noisy.json
  pssurf denoise noisy.json --levels 3 --threshold 5% -o clean.json
  pssurf trace ups.json --level K=0,0.5 --level H=auto:10 -o lines.svg
  pssurf trace ups.json --curvature-lines --seeds 20 -o lines.csv
  pssurf plot ups.json --show mean --lines lines.csv -o lines.png
  pssurf trace ups.json --geodesic --from 4,2 --to 8,3 -o geodesic.csv
  pssurf probe ups.json --at 5,3 --json
  pssurf import part.igs -o part.json       # IGES B-spline surfaces as a scene
  pssurf approx part.json --object 0 --tolerance 0.01 -o ups.json";

#[derive(Subcommand, Debug)]
enum Command {
    /// Fit a functional PS-spline surface z = s(x, y) to scattered data: Hermite
    /// interpolation (Delaunay triangulation unless triangles are given), or with
    /// --approximate a smoothing least-squares fit on a coarser triangulation.
    Fit(commands::fit::FitArgs),
    /// Evaluate a surface (points, optionally first derivatives) at given parameters or on a
    /// grid, to CSV or .npy.
    Eval(commands::eval::EvalArgs),
    /// Show what a surface file holds: kind, counts, domain, PS-triangle quality, validity.
    Info(commands::info::InfoArgs),
    /// Create a surface: `pssurf new ups` makes a uniform PS surface on a lattice polygon;
    /// `pssurf new cylinder|cone|sphere` an exact quadric as NURPS patches.
    #[command(subcommand)]
    New(commands::new::NewWhat),
    /// Subdivide a UPS surface: the same surface on a finer triangulation.
    Subdivide(commands::subdivide::SubdivideArgs),
    /// Add reproducible noise to the control points (for denoising experiments).
    Noise(commands::noise::NoiseArgs),
    /// Remove noise from a UPS surface by wavelet thresholding; prints per-level statistics.
    Denoise(commands::denoise::DenoiseArgs),
    /// Show the UPS wavelet decomposition: per-level spectrum and histograms; optionally save it.
    Wavelet(commands::wavelet::WaveletArgs),
    /// Exact curvature (K, H, κ1, κ2, |κ1|+|κ2|, principal directions, piece) at points or
    /// on a grid, to CSV or .npy.
    Curvature(commands::curvature::CurvatureArgs),
    /// Trace curves on a surface: level lines of a field (K, H, k1, k2, kabs, z or a
    /// formula), lines of curvature, asymptotic lines, geodesics; to CSV, OBJ or an SVG of
    /// the domain with the lines.
    Trace(commands::trace::TraceArgs),
    /// Everything at one point: forms, K, H, κ1, κ2, principal directions, umbilic flag,
    /// cross-planes with their normal sections and osculating circles, Euler's formula, the
    /// torsion and Frenet frames of the coordinate curves.
    Probe(commands::probe::ProbeArgs),
    /// Approximate a NURBS surface by a UPS surface (thesis 6.4.2), reporting the deviation;
    /// --tolerance refines until it is met.
    Approx(commands::approx::ApproxArgs),
    /// Prescribe a curvature at a point (ku, kv, k1, k2, K, H): the control points nearby move
    /// by the smallest smooth change; `--graph-demo` runs the paper's polynomial method.
    Edit(commands::edit::EditArgs),
    /// Fair a PS, UPS or NURPS surface with its boundary fixed (thesis 5.4.3), with a weight
    /// between fairness and the original.
    Fair(commands::fair::FairArgs),
    /// Fill a hole bounded by 3 to 6 curves (or a gap between 2) with a UPS patch that meets
    /// the curves and the normals of the surrounding surfaces (thesis chapter 5).
    FillHole(commands::hole::FillHoleArgs),
    /// Compare Loop, √3, the butterfly and a PS-spline interpolant on one coarse mesh: their
    /// curvature plots side by side on an HTML page.
    CompareSubdivision(commands::compare::CompareArgs),
    /// Triangle meshes (OBJ, PLY, STL): subdivide them by Loop, √3 or the butterfly scheme.
    #[command(subcommand)]
    Mesh(commands::mesh::MeshWhat),
    /// Run a built-in hole-filling example of the thesis (hole-sphere, two-cylinders,
    /// prism-cap, two-curve-gap, degenerate-nurbs) and write its scene, patches and quality
    /// report.
    Example(commands::hole::ExampleArgs),
    /// Subdivide a polygon (CSV): Chaikin, cubic B-spline or the four-point scheme, open or
    /// closed.
    Curve(commands::curve::CurveArgs),
    /// Import the B-spline surfaces of an IGES file as a scene (one object per surface, in
    /// millimetres); other entities are listed with their counts.
    Import(commands::import::ImportArgs),
    /// Render a surface to PNG: shaded, a curvature plot with legend, zebra stripes or
    /// isophotes, with optional overlays.
    Plot(commands::plot::PlotArgs),
    /// Draw the parameter domain as SVG: triangulation, PS refinement, PS-points and
    /// PS-triangles, optionally coloured by curvature.
    Domain(commands::domain::DomainArgs),
    /// Fairness numbers: integrals of H², K, |K|, κ1² + κ2², thin-plate energy, and the
    /// distribution of every curvature quantity.
    Fairness(commands::fairness::FairnessArgs),
    /// Export a triangle mesh with curvature fields: PLY, OBJ, STL, glTF binary, VTK.
    Export(commands::export::ExportArgs),
    /// The main demonstration: noise on a UPS surface, removed by wavelet thresholding, and
    /// compared by curvature plots and numbers in a gallery (DIR/index.html).
    Showcase(commands::showcase::ShowcaseArgs),
    /// Open surfaces or a scene in the interactive application (pssurf-app).
    View(commands::view::ViewArgs),
}

/// The command line, with every option that takes one value accepting negative numbers
/// (`--smooth -1`): clap's default reads them as unknown options and advises `-- -1`, which
/// does not work for an option. (Options whose values may start with a hyphen otherwise,
/// points such as `--at -2,3` or formulas, say so themselves with `allow_hyphen_values`.)
fn command() -> clap::Command {
    fn negative_numbers(command: clap::Command) -> clap::Command {
        command
            .mut_args(|a| {
                if !a.is_positional() && a.get_action().takes_values() {
                    a.allow_negative_numbers(true)
                } else {
                    a
                }
            })
            .mut_subcommands(negative_numbers)
    }
    negative_numbers(Cli::command())
}

fn main() -> ExitCode {
    let cli = match command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    budget::Budget::from_args(&cli.budget).install();
    // On SIGINT or SIGTERM remove the temporary file of a write in progress (the file it
    // would replace is untouched), then end as interrupted.
    let _ = ctrlc::set_handler(|| {
        pssurf::io::remove_pending_temp_files();
        std::process::exit(130);
    });
    let result = match &cli.command {
        Command::Fit(a) => commands::fit::run(a),
        Command::Eval(a) => commands::eval::run(a),
        Command::Info(a) => commands::info::run(a),
        Command::New(a) => commands::new::run(a),
        Command::Subdivide(a) => commands::subdivide::run(a),
        Command::Noise(a) => commands::noise::run(a),
        Command::Denoise(a) => commands::denoise::run(a),
        Command::Wavelet(a) => commands::wavelet::run(a),
        Command::Curvature(a) => commands::curvature::run(a),
        Command::Trace(a) if a.curvature_lines || a.asymptotic || a.geodesic => {
            commands::trace_lines::run(a)
        }
        Command::Trace(a) => commands::trace::run(a),
        Command::Probe(a) => commands::probe::run(a),
        Command::Import(a) => commands::import::run(a),
        Command::Approx(a) => commands::approx::run(a),
        Command::Edit(a) => commands::edit::run(a),
        Command::Fair(a) => commands::fair::run(a),
        Command::FillHole(a) => commands::hole::run_fill(a),
        Command::Mesh(w) => commands::mesh::run(w),
        Command::CompareSubdivision(a) => commands::compare::run(a),
        Command::Example(a) => commands::hole::run_example(a),
        Command::Curve(a) => commands::curve::run(a),
        Command::Plot(a) => commands::plot::run(a),
        Command::Domain(a) => commands::domain::run(a),
        Command::Fairness(a) => commands::fairness::run(a),
        Command::Export(a) => commands::export::run(a),
        Command::Showcase(a) => commands::showcase::run(a),
        Command::View(a) => commands::view::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our standard output stopped reading (`| head`): not an error.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            // One line whatever the causes hold.
            let message = format!("{e:#}").replace(['\n', '\r'], " ");
            eprintln!("error: {}", pssurf::text::cut_line(&message));
            ExitCode::FAILURE
        }
    }
}

/// Reports a command-line error in one line (clap's message with what it lists, without its
/// usage hint) and
/// exits with status 2; help and version requests print as usual.
fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        e.exit();
    }
    // The message and what it lists (missing arguments come on the lines after it), up to the
    // usage hint, joined into one line.
    let text = e.render().to_string();
    let message: Vec<&str> = text
        .lines()
        .map(str::trim)
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .filter(|l| !l.is_empty())
        .collect();
    let line = if message.is_empty() {
        "error".to_string()
    } else {
        message.join(" ")
    };
    eprintln!("{}", pssurf::text::cut_line(&line));
    ExitCode::from(2)
}

/// Whether an error comes from writing into a pipe whose reader has gone.
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

#[cfg(test)]
mod parser_fuzz {
    //! Every parser of user input refuses bad input with an error, never a panic, whatever
    //! the bytes (issue 13).

    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn option_values_never_panic(s in "\\PC{0,40}|[-+0-9.eExX,%a-z ]{0,24}") {
            use std::str::FromStr;
            let _ = crate::budget::parse_size(&s);
            let _ = crate::points::GridSize::from_str(&s);
            let _ = crate::commands::plot::Size::from_str(&s);
            let _ = crate::commands::plot::Pair::from_str(&s);
            let _ = crate::commands::new::parse_polygon(&s);
            let _ = crate::commands::denoise::parse_threshold(&s);
            let _ = pssurf::expr::HeightFunction::parse(&s);
            let _ = crate::colors::quantity(&s);
        }

        #[test]
        fn csv_files_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300),
                                 text in "(x|y|z|zx|u|v|,|\\n|#|0|1e308|-|\\.|nan|inf| |\"|;|\\t){0,60}") {
            let dir = tempfile::tempdir().unwrap();
            for (k, content) in [bytes, text.into_bytes()].into_iter().enumerate() {
                let p = dir.path().join(format!("d{k}.csv"));
                std::fs::write(&p, content).unwrap();
                let _ = crate::table::Table::read(&p);
                let _ = crate::table::Table::read_columns(&p, Some(&["x", "y", "z"]));
                let _ = crate::table::read_triangles(&p, 10);
            }
        }
    }
}
