//! Writing outputs: any file atomically or to standard output (`-o -`), surfaces, and numeric
//! tables as CSV or NumPy `.npy` in chunks.

use std::io::Write;
use std::path::Path;

use anyhow::Result;
use npyz::WriterBuilder;
use pssurf::io::Durability;

/// Whether an output path means standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// An error of the producer of an output (not of writing it), passed through unchanged.
#[derive(Debug)]
struct Produce(anyhow::Error);

impl std::fmt::Display for Produce {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:#}", self.0)
    }
}

impl std::error::Error for Produce {}

/// Marks an error of the producer of an output (not of writing it): [`write_output`] returns
/// it as it is instead of as a failure to write the file.
pub fn producer_error(e: anyhow::Error) -> anyhow::Error {
    anyhow::Error::new(Produce(e))
}

/// Writes what `fill` produces to `path`: standard output for `-`, otherwise through
/// [`pssurf::io::atomic_write`] (a failure leaves any previous file untouched and no temporary
/// file). Errors say which file could not be written and why, in a few words, except those
/// `fill` marks with [`producer_error`].
pub fn write_output(
    path: &Path,
    durability: Durability,
    fill: impl FnOnce(&mut dyn Write) -> Result<()>,
) -> Result<()> {
    let result = if is_stdout(path) {
        let stdout = std::io::stdout();
        let mut lock = std::io::BufWriter::with_capacity(1 << 20, stdout.lock());
        fill(&mut lock).and_then(|()| Ok(lock.flush()?))
    } else {
        pssurf::io::atomic_write(path, durability, fill)
    };
    result.map_err(|e| match e.downcast::<Produce>() {
        Ok(Produce(inner)) => inner,
        Err(e) if crate::is_broken_pipe(&e) => e,
        Err(e) => {
            let name = if is_stdout(path) {
                "standard output".to_string()
            } else {
                path.display().to_string()
            };
            anyhow::anyhow!("cannot write {name}: {}", io_cause(&e))
        }
    })
}

/// The cause of a write error in a few words (`no space left on the device`), without the OS
/// error number.
fn io_cause(e: &anyhow::Error) -> String {
    match e.chain().find_map(|c| c.downcast_ref::<std::io::Error>()) {
        Some(io) => pssurf::io::io_cause(io),
        None => {
            let text = format!("{e:#}");
            match text.find(" (os error") {
                Some(k) => text[..k].to_string(),
                None => text,
            }
        }
    }
}

/// Writes a surface file (durably: it is the user's source of truth), or to standard output.
pub fn save_surface(surface: &pssurf::surface::Surface, path: &Path) -> Result<()> {
    let encoding = pssurf::io::SurfaceEncoding::for_path(path);
    write_output(path, Durability::Durable, |w| {
        Ok(pssurf::io::write_surface(surface, encoding, w)?)
    })
}

/// The output formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header line.
    Csv,
    /// A NumPy float64 2-D array.
    Npy,
}

impl Format {
    /// The format for a path: `.npy` means NumPy, anything else CSV.
    pub fn of(path: Option<&Path>) -> Format {
        match path {
            Some(p) if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("npy")) => Format::Npy,
            _ => Format::Csv,
        }
    }
}

/// Receives the rows of a table, a chunk at a time.
pub struct TableSink<'w> {
    w: &'w mut dyn Write,
    format: Format,
    width: usize,
    /// The column of the next number (CSV lines may span chunks).
    column: usize,
    text: String,
    bytes: Vec<u8>,
    /// The header, written with the first rows: a table that fails before its first rows
    /// (a point outside in the first chunk) leaves nothing on standard output, where files
    /// are discarded anyway.
    pending: Vec<u8>,
}

impl TableSink<'_> {
    /// Writes the header if it is still pending.
    fn flush_pending(&mut self) -> Result<()> {
        if !self.pending.is_empty() {
            self.w.write_all(&self.pending)?;
            self.pending.clear();
        }
        Ok(())
    }

    /// Appends numbers row by row (`width` to a row; a chunk need not end a row).
    pub fn rows(&mut self, data: &[f64]) -> Result<()> {
        self.flush_pending()?;
        match self.format {
            Format::Csv => {
                use std::fmt::Write as _;
                self.text.clear();
                for v in data {
                    if self.column > 0 {
                        self.text.push(',');
                    }
                    // Shortest round-trip representation; NaN as `nan`.
                    if v.is_nan() {
                        self.text.push_str("nan");
                    } else {
                        let _ = write!(self.text, "{v:?}");
                    }
                    self.column += 1;
                    if self.column == self.width {
                        self.text.push('\n');
                        self.column = 0;
                    }
                    if self.text.len() >= 1 << 16 {
                        self.w.write_all(self.text.as_bytes())?;
                        self.text.clear();
                    }
                }
                self.w.write_all(self.text.as_bytes())?;
            }
            Format::Npy => {
                self.bytes.clear();
                self.bytes.reserve(8 * data.len());
                for v in data {
                    self.bytes.extend_from_slice(&v.to_le_bytes());
                }
                self.w.write_all(&self.bytes)?;
            }
        }
        Ok(())
    }
}

/// Writes a table of `rows` rows with the given columns to `path` (`.npy` or CSV), or as CSV
/// to standard output when `path` is `None`; `produce` feeds the rows in chunks. Files are
/// written atomically: on failure no partial file is left and an existing file is kept.
pub fn write_streamed(
    path: Option<&Path>,
    columns: &[String],
    rows: usize,
    produce: impl FnOnce(&mut TableSink<'_>) -> Result<()>,
) -> Result<()> {
    write_table(path, Some(columns), [rows, columns.len()], produce)
}

/// Writes one number per grid point as a raster of `ny` rows of `nx` numbers (v outer, u
/// inner): a 2-D `.npy` array of shape (ny, nx), or CSV lines of `nx` numbers without a
/// header; `produce` feeds the numbers in grid order, in chunks.
pub fn write_raster(
    path: Option<&Path>,
    ny: usize,
    nx: usize,
    produce: impl FnOnce(&mut TableSink<'_>) -> Result<()>,
) -> Result<()> {
    write_table(path, None, [ny, nx], produce)
}

/// A table of `shape` (rows, numbers per row), with a CSV header line when `header` names the
/// columns.
fn write_table(
    path: Option<&Path>,
    header: Option<&[String]>,
    [rows, width]: [usize; 2],
    produce: impl FnOnce(&mut TableSink<'_>) -> Result<()>,
) -> Result<()> {
    let format = Format::of(path);
    let run = |w: &mut dyn Write| -> Result<()> {
        let mut pending = Vec::new();
        match format {
            Format::Csv => {
                if let Some(columns) = header {
                    writeln!(pending, "{}", columns.join(","))?
                }
            }
            Format::Npy => {
                let shape = [rows as u64, width as u64];
                npyz::WriteOptions::<f64>::new()
                    .default_dtype()
                    .shape(&shape)
                    .writer(&mut pending)
                    .write_header_only()?;
            }
        }
        let mut sink = TableSink {
            w,
            format,
            width,
            column: 0,
            text: String::new(),
            bytes: Vec::new(),
            pending,
        };
        produce(&mut sink).map_err(|e| {
            if e.chain()
                .any(|c| c.downcast_ref::<std::io::Error>().is_some())
            {
                e
            } else {
                producer_error(e)
            }
        })?;
        sink.flush_pending()
    };
    write_output(path.unwrap_or(Path::new("-")), Durability::Atomic, run)
}

/// Creates the folder `path` (and its parents) for a command that writes several files; a
/// path that exists and is not a folder, or one that cannot be created, is one clear error.
pub fn create_folder(path: &Path) -> Result<()> {
    if path.exists() && !path.is_dir() {
        anyhow::bail!("{} exists and is not a folder", path.display());
    }
    std::fs::create_dir_all(path).map_err(|e| {
        anyhow::anyhow!(
            "cannot create the folder {}: {}",
            path.display(),
            pssurf::io::io_cause(&e)
        )
    })
}
