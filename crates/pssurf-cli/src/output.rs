//! Writing numeric tables as CSV or NumPy `.npy`, atomically.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};
use npyz::WriterBuilder;

/// A table of numbers with column names, row-major.
pub struct NumTable {
    /// Column names.
    pub columns: Vec<String>,
    /// Row-major values, `columns.len()` per row.
    pub data: Vec<f64>,
}

impl NumTable {
    /// The number of rows.
    pub fn rows(&self) -> usize {
        self.data.len() / self.columns.len().max(1)
    }
}

/// Writes the table to `path` (by its extension: `.npy` → a float64 2-D array, otherwise
/// CSV with a header), or as CSV to standard output when `path` is `None`. Files are written
/// atomically: on failure no partial file is left and an existing file is kept.
pub fn write_table(table: &NumTable, path: Option<&Path>) -> Result<()> {
    match path {
        None => {
            let stdout = std::io::stdout();
            let mut lock = std::io::BufWriter::new(stdout.lock());
            write_csv(table, &mut lock)?;
            lock.flush()?;
            Ok(())
        }
        Some(p) => {
            let npy = p.extension().is_some_and(|e| e.eq_ignore_ascii_case("npy"));
            pssurf::io::atomic_write(p, |w| {
                if npy {
                    write_npy(table, w)
                } else {
                    write_csv(table, w)
                }
            })
            .with_context(|| format!("cannot write {}", p.display()))
        }
    }
}

fn write_csv(table: &NumTable, w: &mut dyn Write) -> Result<()> {
    writeln!(w, "{}", table.columns.join(","))?;
    let k = table.columns.len();
    let mut buf = ryu_line::Line::default();
    for row in table.data.chunks(k) {
        buf.clear();
        for (j, v) in row.iter().enumerate() {
            if j > 0 {
                buf.push(',');
            }
            buf.push_f64(*v);
        }
        buf.push('\n');
        w.write_all(buf.as_bytes())?;
    }
    Ok(())
}

fn write_npy(table: &NumTable, w: &mut dyn Write) -> Result<()> {
    let shape = [table.rows() as u64, table.columns.len() as u64];
    let mut writer = npyz::WriteOptions::<f64>::new()
        .default_dtype()
        .shape(&shape)
        .writer(w)
        .begin_nd()?;
    writer.extend(table.data.iter().copied())?;
    writer.finish()?;
    Ok(())
}

/// A reusable line buffer with shortest round-trip float formatting.
mod ryu_line {
    /// The buffer.
    #[derive(Default)]
    pub struct Line(String);

    impl Line {
        pub fn clear(&mut self) {
            self.0.clear();
        }
        pub fn push(&mut self, c: char) {
            self.0.push(c);
        }
        /// Appends a float so that it parses back to the same value (NaN as `nan`).
        pub fn push_f64(&mut self, v: f64) {
            use std::fmt::Write;
            if v.is_nan() {
                self.0.push_str("nan");
            } else {
                let _ = write!(self.0, "{v:?}");
            }
        }
        pub fn as_bytes(&self) -> &[u8] {
            self.0.as_bytes()
        }
    }
}
