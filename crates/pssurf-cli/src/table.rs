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
        let mut rdr = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_path(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let headers: Vec<String> = rdr
            .headers()
            .with_context(|| format!("{}: cannot read the header line", path.display()))?
            .iter()
            .map(|h| h.to_string())
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
            for (cell, name) in rec.iter().zip(&headers) {
                let v: f64 = cell.parse().map_err(|_| {
                    anyhow::anyhow!(
                        "{}: row {row}, column {name}: `{cell}` is not a number",
                        path.display()
                    )
                })?;
                if !v.is_finite() {
                    bail!(
                        "{}: row {row}, column {name}: `{cell}` is not a finite number",
                        path.display()
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

/// Reads triangles as rows `i,j,k` of zero-based vertex indices, with or without a header.
pub fn read_triangles(path: &Path, vertex_count: usize) -> Result<Vec<[usize; 3]>> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_path(path)
        .with_context(|| format!("cannot read {}", path.display()))?;
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
            _ if k == 0 => continue, // a header line
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
