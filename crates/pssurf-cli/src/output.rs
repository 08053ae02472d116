//! Writing numeric tables as CSV or NumPy `.npy`, atomically and in chunks.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};
use npyz::WriterBuilder;

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
    text: String,
    bytes: Vec<u8>,
}

impl TableSink<'_> {
    /// Appends rows (row-major, `width` numbers each).
    pub fn rows(&mut self, data: &[f64]) -> Result<()> {
        match self.format {
            Format::Csv => {
                use std::fmt::Write as _;
                for row in data.chunks(self.width) {
                    self.text.clear();
                    for (j, v) in row.iter().enumerate() {
                        if j > 0 {
                            self.text.push(',');
                        }
                        // Shortest round-trip representation; NaN as `nan`.
                        if v.is_nan() {
                            self.text.push_str("nan");
                        } else {
                            let _ = write!(self.text, "{v:?}");
                        }
                    }
                    self.text.push('\n');
                    self.w.write_all(self.text.as_bytes())?;
                }
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
    let format = Format::of(path);
    let run = |w: &mut dyn Write| -> Result<()> {
        match format {
            Format::Csv => writeln!(w, "{}", columns.join(","))?,
            Format::Npy => {
                let shape = [rows as u64, columns.len() as u64];
                let mut header = Vec::new();
                npyz::WriteOptions::<f64>::new()
                    .default_dtype()
                    .shape(&shape)
                    .writer(&mut header)
                    .write_header_only()?;
                w.write_all(&header)?;
            }
        }
        let mut sink = TableSink {
            w,
            format,
            width: columns.len(),
            text: String::new(),
            bytes: Vec::new(),
        };
        produce(&mut sink)
    };
    match path {
        None => {
            let stdout = std::io::stdout();
            let mut lock = std::io::BufWriter::new(stdout.lock());
            run(&mut lock)?;
            lock.flush()?;
            Ok(())
        }
        Some(p) => pssurf::io::atomic_write(p, pssurf::io::Durability::Atomic, run)
            .with_context(|| format!("cannot write {}", p.display())),
    }
}
