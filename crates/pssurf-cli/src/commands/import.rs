//! `pssurf import FILE.igs -o SCENE.json`: the B-spline surfaces of an IGES file as a scene
//! (one object per surface, in millimetres), what was not imported listed with counts, and
//! optionally the trimming loops as curves.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use pssurf::iges::{IgesModel, read_iges};
use pssurf::interrogate::SurfaceCurve;
use pssurf::io::{Durability, SceneEntry, scene_to_json};
use pssurf::surface::{ParametricSurface, Surface};

/// Arguments of `pssurf import`.
#[derive(clap::Args, Debug)]
pub struct ImportArgs {
    /// The IGES file (IGES 5.3, fixed format).
    #[arg(value_name = "FILE.igs")]
    pub input: PathBuf,
    /// The scene file to write (one object per surface).
    #[arg(short, long, value_name = "SCENE.json")]
    pub output: PathBuf,
    /// Also write the trimming loops of trimmed surfaces as curves (curve,u,v,x,y,z), for
    /// `pssurf plot --lines` and `pssurf domain --lines` on the single surfaces.
    #[arg(long, value_name = "LOOPS.csv")]
    pub loops: Option<PathBuf>,
}

/// IGES text takes about 12 bytes of memory per byte of file once parsed (fields, lines and
/// the surfaces' nets).
const MEMORY_PER_BYTE: u64 = 12;

/// Runs `pssurf import`.
pub fn run(args: &ImportArgs) -> Result<()> {
    let text = read_text(&args.input)?;
    let model = read_iges(&text).map_err(|e| anyhow::anyhow!("{}: {e}", args.input.display()))?;
    if model.surfaces.is_empty() {
        bail!(
            "{}: no B-spline surfaces (entity 128) to import{}",
            args.input.display(),
            unknown_list(&model)
        );
    }
    let group = args
        .input
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let objects: Vec<SceneEntry> = model
        .surfaces
        .iter()
        .map(|s| SceneEntry {
            name: s.name.clone(),
            group: group.clone(),
            surface: Surface::Nurbs(s.surface.clone()),
        })
        .collect();
    let json = scene_to_json(&objects);
    // The loops first: if they cannot be written, the scene is not written either (a scene
    // written by a command that then fails would look like a success).
    if let Some(path) = &args.loops {
        let curves = loops(&model);
        crate::output::write_output(path, Durability::Atomic, |w| {
            Ok(pssurf::io::write_curves_csv(w, &curves)?)
        })?;
    }
    crate::output::write_output(&args.output, Durability::Atomic, |w| {
        Ok(w.write_all(json.as_bytes())?)
    })?;
    report(args, &model);
    Ok(())
}

/// Reads the IGES file within the memory budget (as text; bytes that are not UTF-8 become
/// replacement characters, which only strings may hold).
fn read_text(path: &Path) -> Result<String> {
    use std::io::Read;
    let meta =
        std::fs::metadata(path).with_context(|| format!("cannot read {}", path.display()))?;
    if meta.is_file() {
        crate::budget::Estimate {
            what: format!("importing {}", path.display()),
            makes: format!("a file of {}", crate::budget::Bytes(meta.len())),
            memory: crate::budget::base_memory()
                .saturating_add(meta.len().saturating_mul(MEMORY_PER_BYTE)),
            output: meta.len().saturating_mul(2),
        }
        .check()?;
    }
    let limit = crate::budget::Budget::current()
        .memory
        .saturating_sub(crate::budget::base_memory())
        / MEMORY_PER_BYTE;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .with_context(|| format!("cannot read {}", path.display()))?
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .with_context(|| format!("cannot read {}", path.display()))?;
    if bytes.len() as u64 > limit {
        bail!(
            "{}: longer than the memory budget allows (raise it with --max-memory)",
            path.display()
        );
    }
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The trimming loops of every surface, with their points on the surface.
fn loops(model: &IgesModel) -> Vec<SurfaceCurve> {
    let mut out = Vec::new();
    for s in &model.surfaces {
        for l in &s.loops {
            let mut c = SurfaceCurve::default();
            for uv in l {
                if let Ok(p) = s.surface.point(*uv) {
                    c.uvs.push(*uv);
                    c.points.push(p);
                }
            }
            if c.uvs.len() >= 2 {
                out.push(c);
            }
        }
    }
    out
}

fn unknown_list(model: &IgesModel) -> String {
    if model.unknown.is_empty() {
        return String::new();
    }
    let list: Vec<String> = model
        .unknown
        .iter()
        .map(|(t, n)| format!("{t}×{n}"))
        .collect();
    format!("; not imported: {}", list.join(" "))
}

fn report(args: &ImportArgs, model: &IgesModel) {
    let trimmed = model.surfaces.iter().filter(|s| s.trimmed).count();
    let loops: usize = model.surfaces.iter().map(|s| s.loops.len()).sum();
    eprintln!(
        "{}{}: {} B-spline surfaces ({trimmed} trimmed, {loops} trimming loops), {} curves; unit {} (× {} to mm){}",
        args.input.display(),
        if model.system.is_empty() {
            String::new()
        } else {
            format!(" (from {})", model.system.trim())
        },
        model.surfaces.len(),
        model.curves.len(),
        model.unit.0,
        model.unit.1,
        unknown_list(model)
    );
    for w in &model.warnings {
        eprintln!("warning: {w}");
    }
    eprintln!("wrote {}", args.output.display());
    if let Some(p) = &args.loops {
        eprintln!("wrote {}", p.display());
    }
}
