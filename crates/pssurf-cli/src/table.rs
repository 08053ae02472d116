//! Reading CSV tables with named columns, with errors that name the row and column.

use std::path::Path;

use anyhow::{Context, Result, bail};

/// A numeric table read from a CSV file with a header row.
pub struct Table {
    /// Column names as in the header (trimmed).
    pub headers: Vec<String>,
    /// Rows of numbers.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// Reads a CSV file whose first line names the columns; every cell must be a finite number.
    pub fn read(path: &Path) -> Result<Table> {
        Self::read_columns(path, None)
    }

    /// Reads a CSV file whose first line names the columns; the cells of the columns named in
    /// `used` (case-insensitive; all columns when `None`) must be finite numbers, the others
    /// are not read (they hold NaN). Duplicate column names and a header that is not
    /// comma-separated are errors.
    pub fn read_columns(path: &Path, used: Option<&[&str]>) -> Result<Table> {
        // A row of w cells takes at least 2w bytes of text and at most 40 + 8w bytes of
        // memory: at most 24 bytes per byte of file.
        check_reading(path)?;
        let mut rdr = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            // Rows of another length are reported below, by row and count.
            .flexible(true)
            .from_reader(open_bounded(path)?);
        let headers: Vec<String> = rdr
            .headers()
            .with_context(|| format!("{}: cannot read the header line", path.display()))?
            .iter()
            .map(|h| h.to_string())
            .collect();
        check_headers(path, &headers)?;
        let read: Vec<bool> = headers
            .iter()
            .map(|h| used.is_none_or(|u| u.iter().any(|n| h.eq_ignore_ascii_case(n))))
            .collect();
        let mut rows = Vec::new();
        for (k, rec) in rdr.records().enumerate() {
            let row = k + 1;
            let rec = rec.with_context(|| format!("{}: row {row}", path.display()))?;
            if rec.len() != headers.len() {
                bail!(
                    "{}: row {row} has {} fields, the header has {}",
                    path.display(),
                    rec.len(),
                    headers.len()
                );
            }
            let mut vals = Vec::with_capacity(rec.len());
            for ((cell, name), &wanted) in rec.iter().zip(&headers).zip(&read) {
                if !wanted {
                    vals.push(f64::NAN);
                    continue;
                }
                let v: f64 = cell.parse().map_err(|_| {
                    anyhow::anyhow!(
                        "{}: row {row}, column {}: `{}` is not a number",
                        path.display(),
                        short(name),
                        short(cell)
                    )
                })?;
                if !v.is_finite() {
                    bail!(
                        "{}: row {row}, column {}: `{}` is not a finite number",
                        path.display(),
                        short(name),
                        short(cell)
                    );
                }
                vals.push(v);
            }
            rows.push(vals);
        }
        if rows.is_empty() {
            bail!("{}: no data rows", path.display());
        }
        Ok(Table { headers, rows })
    }

    /// The index of the column named `name` (case-insensitive), if any.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.headers
            .iter()
            .position(|h| h.eq_ignore_ascii_case(name))
    }
}

/// Refuses repeated column names (case-insensitive) and a one-column header that holds tabs
/// or semicolons (a file separated by something other than commas).
fn check_headers(path: &Path, headers: &[String]) -> Result<()> {
    if let Some(first) = headers.first()
        && first.trim_start_matches('\u{feff}').starts_with(['{', '['])
    {
        bail!(
            "{}: a JSON file, where a CSV table is expected (a header line naming the columns, then one row per point)",
            path.display()
        );
    }
    if let [only] = headers
        && (only.contains('\t') || only.contains(';'))
    {
        bail!(
            "{}: columns must be separated by commas (the header is `{}`)",
            path.display(),
            short(only)
        );
    }
    // A set, not a comparison of each name with every earlier one: a header line of
    // 200,000 names took 78 s that way.
    let mut seen = std::collections::HashSet::with_capacity(headers.len());
    for h in headers {
        if !seen.insert(h.to_ascii_lowercase()) {
            bail!(
                "{}: the column name `{}` appears twice",
                path.display(),
                short(h)
            );
        }
    }
    Ok(())
}

/// A cell or name cut to its first 40 characters for a message.
pub fn short(text: &str) -> String {
    pssurf::text::cut(text)
}

/// A reader that fails, rather than stops, after `left` bytes: a device or pipe (`/dev/zero`)
/// has no size to check against the budget, and must not be read without end.
struct Bounded<R> {
    inner: R,
    left: u64,
}

impl<R: std::io::Read> std::io::Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.left = self.left.checked_sub(n as u64).ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::FileTooLarge,
                "longer than the memory budget allows (raise it with --max-memory)",
            )
        })?;
        Ok(n)
    }
}

/// Opens a CSV file for reading at most what the memory budget allows (24 bytes of memory per
/// byte of text at most, see [`Table::read_columns`]).
fn open_bounded(path: &Path) -> Result<Bounded<std::io::BufReader<std::fs::File>>> {
    let file = std::fs::File::open(path).map_err(|e| {
        anyhow::anyhow!(
            "cannot read {}: {}",
            path.display(),
            pssurf::io::io_cause(&e)
        )
    })?;
    let budget = crate::budget::Budget::current().memory;
    Ok(Bounded {
        inner: std::io::BufReader::new(file),
        left: budget.saturating_sub(crate::budget::base_memory()) / 24,
    })
}

/// Checks that reading the text file at `path` fits the budget: at most 24 bytes of memory
/// per byte of text.
fn check_reading(path: &Path) -> Result<()> {
    if let Ok(meta) = std::fs::metadata(path)
        && meta.is_file()
    {
        crate::budget::Estimate {
            what: format!("reading {}", path.display()),
            makes: format!("a file of {}", crate::budget::Bytes(meta.len())),
            memory: crate::budget::base_memory().saturating_add(meta.len().saturating_mul(24)),
            output: 0,
        }
        .check()?;
    }
    Ok(())
}

/// Reads a whole text file within the memory budget (a curves CSV becomes at most 24 bytes of
/// memory per byte of text).
pub fn read_text(path: &Path) -> Result<String> {
    use std::io::Read;
    check_reading(path)?;
    let mut text = String::new();
    open_bounded(path)?
        .read_to_string(&mut text)
        .with_context(|| format!("cannot read {} as text", path.display()))?;
    Ok(text)
}

/// Reads triangles as rows `i,j,k` of zero-based vertex indices, with or without a header
/// (a first line with a letter in it).
pub fn read_triangles(path: &Path, vertex_count: usize) -> Result<Vec<[usize; 3]>> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(open_bounded(path)?);
    let mut out = Vec::new();
    for (k, rec) in rdr.records().enumerate() {
        let rec = rec.with_context(|| format!("{}: line {}", path.display(), k + 1))?;
        let parsed: Option<Vec<usize>> = rec.iter().map(|c| c.parse().ok()).collect();
        match parsed {
            Some(v) if v.len() == 3 => {
                if let Some(&bad) = v.iter().find(|&&i| i >= vertex_count) {
                    bail!(
                        "{}: triangle {} (line {}) refers to vertex {bad}, but there are {vertex_count} data points (indices are zero-based)",
                        path.display(),
                        out.len(),
                        k + 1
                    );
                }
                out.push([v[0], v[1], v[2]]);
            }
            _ if k == 0 && rec.iter().any(|c| c.chars().any(|ch| ch.is_alphabetic())) => {
                continue; // a header line
            }
            _ => bail!(
                "{}: line {} is not three vertex indices `i,j,k`",
                path.display(),
                k + 1
            ),
        }
    }
    if out.is_empty() {
        bail!("{}: no triangles", path.display());
    }
    Ok(out)
}
