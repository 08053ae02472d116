//! The size budget. Every command that creates data estimates its peak memory and the size
//! of what it writes from its arguments, before allocating anything, and refuses a request
//! beyond the budget with one line that gives the estimate and the flag that raises it.
//!
//! The estimates are upper bounds built from per-item costs measured on this code
//! (docs/reliability.md, "The size budget"); they are meant to be pessimistic by at most a
//! small factor, never optimistic.

use std::fmt;
use std::path::Path;
use std::sync::OnceLock;

use anyhow::{Result, bail};

/// One kibibyte, mebibyte, gibibyte, tebibyte.
const KIB: u64 = 1 << 10;
const MIB: u64 = 1 << 20;
const GIB: u64 = 1 << 30;
const TIB: u64 = 1 << 40;

/// The memory budget when the machine's memory cannot be read.
const FALLBACK_MEMORY: u64 = 4 * GIB;
/// The default largest output file.
const DEFAULT_OUTPUT: u64 = 16 * GIB;
/// Memory any command needs besides its data, in bytes: 48 MB of code, buffers and loaded
/// input, and 8 MB per worker thread (stack and allocator arenas): 64 MB on 2 cores.
pub fn base_memory() -> u64 {
    (48 * MIB).saturating_add(mul(8 * MIB, rayon::current_num_threads() as u64))
}

/// The `--max-memory` / `--max-output` options, accepted by every command.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct BudgetArgs {
    /// The most memory a command may plan to use, e.g. 500M or 8G; larger requests are
    /// refused before they start [default: half of this machine's memory]
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
    /// The largest file a command may write, e.g. 100M or 50G [default: 16G]
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_size)]
    pub max_output: Option<u64>,
}

/// The limits in force for this run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// Peak memory, bytes.
    pub memory: u64,
    /// Size of one written file, bytes.
    pub output: u64,
}

static BUDGET: OnceLock<Budget> = OnceLock::new();

impl Budget {
    /// The budget from the command line (defaults filled in).
    pub fn from_args(args: &BudgetArgs) -> Budget {
        Budget {
            memory: args
                .max_memory
                .unwrap_or_else(|| machine_memory().map_or(FALLBACK_MEMORY, |m| m / 2)),
            output: args.max_output.unwrap_or(DEFAULT_OUTPUT),
        }
    }

    /// Makes `self` the budget of this run (the first call wins).
    pub fn install(self) {
        let _ = BUDGET.set(self);
    }

    /// The budget of this run (the defaults if none was installed).
    pub fn current() -> Budget {
        *BUDGET.get_or_init(|| Budget::from_args(&BudgetArgs::default()))
    }
}

/// What a request will cost.
#[derive(Clone, Debug)]
pub struct Estimate {
    /// The request in a few words ("a level-9 plot", "a 100000 × 100000 grid").
    pub what: String,
    /// What it makes, for the message ("113,246,208 triangles").
    pub makes: String,
    /// Peak memory, bytes (saturating).
    pub memory: u64,
    /// Bytes written (saturating; 0 if nothing is written).
    pub output: u64,
}

impl Estimate {
    /// Refuses the request if it exceeds the current budget.
    pub fn check(&self) -> Result<()> {
        self.check_against(Budget::current())
    }

    /// Refuses the request if it exceeds `budget`, in one line naming the estimate and the
    /// flag that raises the limit.
    pub fn check_against(&self, budget: Budget) -> Result<()> {
        let makes = if self.makes.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.makes)
        };
        if self.memory > budget.memory {
            bail!(
                "{}{makes} would need about {} of memory, over the budget of {} (raise it with --max-memory)",
                self.what,
                Bytes(self.memory),
                Bytes(budget.memory)
            );
        }
        if self.output > budget.output {
            bail!(
                "{}{makes} would write about {}, over the limit of {} (raise it with --max-output)",
                self.what,
                Bytes(self.output),
                Bytes(budget.output)
            );
        }
        Ok(())
    }
}

/// The cost of sampling a surface at a level, per mesh vertex and per mesh triangle (bytes),
/// for one kind of use.
#[derive(Clone, Copy, Debug)]
pub struct SampleCost {
    /// Peak memory per vertex.
    pub memory_per_vertex: u64,
    /// Peak memory per triangle.
    pub memory_per_triangle: u64,
    /// Bytes written per vertex.
    pub output_per_vertex: u64,
    /// Bytes written per triangle.
    pub output_per_triangle: u64,
}

/// Estimates sampling `surface` at `level` (`what`: "a level-9 plot") with per-item `cost`,
/// plus `extra_memory` (frame buffers), before any allocation.
pub fn sample_estimate(
    surface: &pssurf::surface::Surface,
    level: u32,
    what: String,
    cost: SampleCost,
    extra_memory: u64,
) -> Estimate {
    use pssurf::surface::PiecewiseSurface;
    let counts =
        pssurf::interrogate::sample_counts(surface.piece_kind(), surface.piece_count(), level);
    let Some(c) = counts else {
        return Estimate {
            what,
            makes: "more than 2^64 triangles".into(),
            memory: u64::MAX,
            output: u64::MAX,
        };
    };
    Estimate {
        what,
        makes: format!("{} triangles", count(c.triangles)),
        memory: base_memory()
            .saturating_add(mul(c.vertices, cost.memory_per_vertex))
            .saturating_add(mul(c.triangles, cost.memory_per_triangle))
            .saturating_add(extra_memory),
        output: mul(c.vertices, cost.output_per_vertex)
            .saturating_add(mul(c.triangles, cost.output_per_triangle)),
    }
}

/// Memory to load a surface file of `file_bytes` bytes: parsing JSON and building the
/// triangulation, PS basis and evaluation structures take at most 8 bytes per byte of file
/// (measured: 7.2 for a 1 GB UPS file, less for small ones), plus [`base_memory`].
pub fn load_memory(file_bytes: u64) -> u64 {
    base_memory().saturating_add(file_bytes.saturating_mul(8))
}

/// Checks that loading the file at `path` fits the budget and returns how many bytes may be
/// read (a device or pipe has no size: at most what the budget allows).
fn load_limit(path: &Path) -> Result<u64> {
    if let Ok(meta) = std::fs::metadata(path)
        && meta.is_file()
    {
        Estimate {
            what: format!("loading {}", path.display()),
            makes: format!("a file of {}", Bytes(meta.len())),
            memory: load_memory(meta.len()),
            output: 0,
        }
        .check()?;
    }
    Ok(Budget::current().memory.saturating_sub(base_memory()) / 8)
}

/// Checks that loading the surface file at `path` fits the budget, then loads it. One
/// surface of a scene file is named `SCENE.json#K` (object K, from 0); a scene named
/// without `#K` is refused with that advice.
pub fn load_surface(path: &Path) -> Result<pssurf::surface::Surface> {
    if !path.exists()
        && let Some((scene, k)) = scene_object_path(path)
    {
        return scene_object(&scene, k);
    }
    match pssurf::io::load_limited(path, load_limit(path)?) {
        Ok(s) => Ok(s),
        Err(
            e @ pssurf::io::FileError::Format {
                cause: pssurf::io::FormatError::NotPssurf | pssurf::io::FormatError::Foreign(_),
                ..
            },
        ) => match scene_objects(path)? {
            Some(c) => bail!(
                "{}: a scene of {} surfaces, not a surface file: name one as {}#K (K from 0 to {})",
                path.display(),
                c.surfaces.len(),
                path.display(),
                c.surfaces.len().saturating_sub(1)
            ),
            None => Err(e.into()),
        },
        Err(e) => Err(e.into()),
    }
}

/// `SCENE#K` split into the scene file (which exists) and K.
fn scene_object_path(path: &Path) -> Option<(std::path::PathBuf, usize)> {
    let text = path.to_str()?;
    let (file, k) = text.rsplit_once('#')?;
    let k = k.parse().ok()?;
    let file = std::path::PathBuf::from(file);
    file.is_file().then_some((file, k))
}

/// Object `k` of the scene file `scene`.
fn scene_object(scene: &Path, k: usize) -> Result<pssurf::surface::Surface> {
    let Some(mut c) = scene_objects(scene)? else {
        bail!(
            "{}: not a scene file, so #{k} names nothing",
            scene.display()
        );
    };
    let n = c.surfaces.len();
    if k >= n {
        bail!(
            "{}#{k}: the scene has {n} surfaces (objects 0 to {})",
            scene.display(),
            n.saturating_sub(1)
        );
    }
    Ok(c.surfaces.swap_remove(k).surface)
}

/// The objects of a scene file (`pssurf import` and the application write them), or `None`
/// for a surface file.
pub fn scene_objects(path: &std::path::Path) -> Result<Option<pssurf::io::SceneContents>> {
    use std::io::Read;
    let mut head = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(4096).read_to_end(&mut head);
    }
    if !String::from_utf8_lossy(&head).contains(&format!("\"{}\"", pssurf::io::SCENE_FORMAT)) {
        return Ok(None);
    }
    let text = crate::table::read_text(path)?;
    if !pssurf::io::is_scene(&text) {
        return Ok(None);
    }
    let objects = pssurf::io::scene_contents_from_json(&text)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok(Some(objects))
}

/// Loads a curve file within the memory budget (as [`load_surface`]).
pub fn load_curve(path: &Path) -> Result<pssurf::nurbs::NurbsCurve> {
    Ok(pssurf::io::load_curve_limited(path, load_limit(path)?)?)
}

/// The machine's memory in bytes: the smaller of the physical memory and this process's
/// control-group limit (Linux), or `None` where it cannot be read.
pub fn machine_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let total_kib: u64 = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemTotal:"))?
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    let total = total_kib.saturating_mul(KIB);
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    Some(cgroup.map_or(total, |c| c.min(total)))
}

/// Parses a size: a number of bytes with an optional suffix K, M, G or T (powers of 1024,
/// optionally followed by `B` or `iB`), e.g. `512M`, `1.5G`, `100000`.
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let upper = t.to_ascii_uppercase();
    let body = upper
        .strip_suffix("IB")
        .or_else(|| upper.strip_suffix('B'))
        .unwrap_or(&upper);
    let (number, unit) = match body.chars().last() {
        Some('K') => (&body[..body.len() - 1], KIB),
        Some('M') => (&body[..body.len() - 1], MIB),
        Some('G') => (&body[..body.len() - 1], GIB),
        Some('T') => (&body[..body.len() - 1], TIB),
        _ => (body, 1),
    };
    let value: f64 = number.trim().parse().map_err(|_| {
        format!(
            "`{}` is not a size such as 500M or 8G",
            pssurf::text::cut(t)
        )
    })?;
    let bytes = value * unit as f64;
    if !(1.0..1e19).contains(&bytes) {
        return Err(format!(
            "`{}` is not a size between 1 byte and 8E",
            pssurf::text::cut(t)
        ));
    }
    Ok(bytes as u64)
}

/// A byte count for people: `1.5 GB`, `320 MB`, `12 kB` (powers of 1024).
#[derive(Clone, Copy, Debug)]
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0 as f64;
        let (value, unit) = if self.0 >= TIB {
            (b / TIB as f64, "TB")
        } else if self.0 >= GIB {
            (b / GIB as f64, "GB")
        } else if self.0 >= MIB {
            (b / MIB as f64, "MB")
        } else if self.0 >= KIB {
            (b / KIB as f64, "kB")
        } else {
            return write!(f, "{} bytes", self.0);
        };
        if value >= 100.0 {
            write!(f, "{value:.0} {unit}")
        } else {
            write!(f, "{value:.1} {unit}")
        }
    }
}

/// A count for people, with thousands separators: `113,246,208`.
pub fn count(n: u64) -> String {
    if n == u64::MAX {
        return "more than 1.8e19".to_string();
    }
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `a × b` saturating at `u64::MAX`, for estimates from untrusted sizes.
pub fn mul(a: u64, b: u64) -> u64 {
    a.saturating_mul(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_suffixes() {
        assert_eq!(parse_size("512M"), Ok(512 * MIB));
        assert_eq!(parse_size("1.5g"), Ok(3 * GIB / 2));
        assert_eq!(parse_size("2GiB"), Ok(2 * GIB));
        assert_eq!(parse_size("100000"), Ok(100_000));
        assert_eq!(parse_size("1T"), Ok(TIB));
        for bad in ["", "M", "-1G", "nan", "1e300", "0", "12Q"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn refusals_name_the_estimate_and_the_flag() {
        let e = Estimate {
            what: "a level-9 plot".into(),
            makes: format!("{} triangles", count(113_246_208)),
            memory: 12 * GIB,
            output: 0,
        };
        let budget = Budget {
            memory: 8 * GIB,
            output: GIB,
        };
        let m = e.check_against(budget).unwrap_err().to_string();
        assert_eq!(
            m,
            "a level-9 plot (113,246,208 triangles) would need about 12.0 GB of memory, over the budget of 8.0 GB (raise it with --max-memory)"
        );
        let small = Estimate {
            memory: GIB,
            output: 2 * GIB,
            ..e
        };
        let m = small.check_against(budget).unwrap_err().to_string();
        assert!(m.contains("--max-output") && m.contains("2.0 GB"), "{m}");
        assert!(
            Estimate {
                output: 10,
                ..small
            }
            .check_against(budget)
            .is_ok()
        );
    }

    #[test]
    fn byte_counts_read_well() {
        assert_eq!(Bytes(12).to_string(), "12 bytes");
        assert_eq!(Bytes(1536).to_string(), "1.5 kB");
        assert_eq!(Bytes(320 * MIB).to_string(), "320 MB");
        assert_eq!(Bytes(u64::MAX).to_string(), "16777216 TB");
        assert_eq!(count(0), "0");
        assert_eq!(count(1000), "1,000");
        assert_eq!(count(113_246_208), "113,246,208");
    }
}
