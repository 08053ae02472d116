//! The binary encoding of surface files (`.psb`, docs/format.md, "Binary files"): the same
//! document as the JSON encoding, with its large arrays moved out of the JSON header into
//! little-endian chunks, each with a CRC-32. Reading checks the magic number, the header,
//! every chunk's size against the file's before allocating, and every checksum, then builds
//! the surface with the JSON reader's own validation — so both encodings of a surface load to
//! bitwise-identical surfaces. A uniform (UPS) surface is written without its general form
//! (its lattice and polygon determine it).

use std::io::{BufReader, Read, Write};
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{FORMAT_NAME, FORMAT_VERSION, FileError, FileV1, FormatError, Surface, build, invalid};

/// The first eight bytes of a binary surface file as written: `PSSURFB` and the layout's
/// version, 2 (the header has a CRC-32 of its own; version 1, still read, had none).
pub const MAGIC: &[u8; 8] = b"PSSURFB\x02";

/// The first seven bytes of every binary surface file, before the layout's version.
pub const MAGIC_PREFIX: &[u8; 7] = b"PSSURFB";

/// The layout versions this build reads: 1 (no header checksum) and 2.
pub const LAYOUTS: [u8; 2] = [1, 2];

/// The largest JSON header accepted (the arrays are outside it).
const MAX_HEADER: u64 = 64 << 20;

/// Bytes converted per block while reading or writing a chunk.
const BLOCK: usize = 1 << 16;

/// The JSON header: the document without its large arrays, and the list of chunks.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    format: String,
    version: u64,
    encoding: String,
    chunks: Vec<Chunk>,
    document: FileV1,
}

/// One array stored as binary: which field, its element type, `rows` rows of `width`
/// numbers, and the CRC-32 (IEEE) of its bytes.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
struct Chunk {
    field: String,
    dtype: String,
    rows: u64,
    width: u64,
    crc32: u32,
}

/// The arrays that go into chunks: field name, element type and row width.
const FIELDS: [(&str, &str, u64); 7] = [
    ("domain.vertices", "f64", 2),
    ("domain.triangles", "u32", 3),
    ("domain.split_points", "f64", 2),
    ("ps_triangles", "f64", 6),
    ("control", "f64", 3),
    ("control_points", "f64", 9),
    ("weights", "f64", 3),
];

/// A chunk's data while writing.
enum Data {
    /// Floating-point numbers.
    F64(Vec<f64>),
    /// Indices.
    U32(Vec<u32>),
}

impl Data {
    /// Calls `f` with the little-endian bytes, a block at a time.
    fn for_each_block(
        &self,
        mut f: impl FnMut(&[u8]) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        let mut buf = Vec::with_capacity(BLOCK);
        macro_rules! blocks {
            ($v:expr, $size:expr) => {
                for part in $v.chunks(BLOCK / $size) {
                    buf.clear();
                    for x in part {
                        buf.extend_from_slice(&x.to_le_bytes());
                    }
                    f(&buf)?;
                }
            };
        }
        match self {
            Data::F64(v) => blocks!(v, 8),
            Data::U32(v) => blocks!(v, 4),
        }
        Ok(())
    }

    /// Its CRC-32.
    fn crc32(&self) -> u32 {
        let mut h = crc32fast::Hasher::new();
        self.for_each_block(|b| {
            h.update(b);
            Ok(())
        })
        .expect("hashing does not fail");
        h.finalize()
    }
}

/// Moves the large arrays out of `file`: (field, data, rows) in the order of [`FIELDS`].
fn take_arrays(file: &mut FileV1) -> Vec<(&'static str, Data, u64)> {
    let mut out = Vec::new();
    let flat2 = |v: Vec<[f64; 2]>| v.into_iter().flatten().collect::<Vec<f64>>();
    if let Some(d) = file.domain.as_mut() {
        let v = std::mem::take(&mut d.vertices);
        out.push(("domain.vertices", v.len() as u64, Data::F64(flat2(v))));
        let t = std::mem::take(&mut d.triangles);
        let idx = t
            .iter()
            .flatten()
            .map(|&i| u32::try_from(i).expect("vertex indices fit in 32 bits"))
            .collect();
        out.push(("domain.triangles", t.len() as u64, Data::U32(idx)));
        if let Some(s) = d.split_points.take() {
            out.push(("domain.split_points", s.len() as u64, Data::F64(flat2(s))));
        }
    }
    if let Some(p) = file.ps_triangles.take() {
        let n = p.len() as u64;
        out.push((
            "ps_triangles",
            n,
            Data::F64(p.into_iter().flatten().flatten().collect()),
        ));
    }
    if let Some(c) = file.control.take() {
        let n = c.len() as u64;
        out.push(("control", n, Data::F64(c.into_iter().flatten().collect())));
    }
    if let Some(c) = file.control_points.take() {
        let n = c.len() as u64;
        out.push((
            "control_points",
            n,
            Data::F64(c.into_iter().flatten().flatten().collect()),
        ));
    }
    if let Some(w) = file.weights.take() {
        let n = w.len() as u64;
        out.push(("weights", n, Data::F64(w.into_iter().flatten().collect())));
    }
    out.into_iter().map(|(f, n, d)| (f, d, n)).collect()
}

/// Writes `file` in the binary encoding.
pub(super) fn write(mut file: FileV1, w: &mut dyn Write) -> std::io::Result<()> {
    if file.uniform.is_some() {
        // Rebuilt from the lattice and polygon on load.
        file.domain = None;
        file.ps_triangles = None;
    }
    let arrays = take_arrays(&mut file);
    let chunks = arrays
        .iter()
        .map(|(field, data, rows)| {
            let (_, dtype, width) = spec(field).expect("a chunk field");
            Chunk {
                field: field.to_string(),
                dtype: dtype.to_string(),
                rows: *rows,
                width,
                crc32: data.crc32(),
            }
        })
        .collect();
    let header = Header {
        format: FORMAT_NAME.to_string(),
        version: FORMAT_VERSION as u64,
        encoding: "binary".to_string(),
        chunks,
        document: file,
    };
    let json = serde_json::to_vec(&header).expect("finite numbers serialise");
    let mut w = std::io::BufWriter::with_capacity(BLOCK, w);
    w.write_all(MAGIC)?;
    w.write_all(&(json.len() as u64).to_le_bytes())?;
    w.write_all(&crc32fast::hash(&json).to_le_bytes())?;
    w.write_all(&[0u8; 4])?;
    w.write_all(&json)?;
    w.write_all(&[0u8; 8][..padding(json.len() as u64) as usize])?;
    for (_, data, _) in &arrays {
        data.for_each_block(|b| w.write_all(b))?;
        let bytes = match data {
            Data::F64(v) => v.len() as u64 * 8,
            Data::U32(v) => v.len() as u64 * 4,
        };
        w.write_all(&[0u8; 8][..padding(bytes) as usize])?;
    }
    w.flush()
}

/// Zero bytes after `len` bytes up to the next multiple of 8.
fn padding(len: u64) -> u64 {
    (8 - len % 8) % 8
}

/// The specification of a chunk field.
fn spec(field: &str) -> Option<(&'static str, &'static str, u64)> {
    FIELDS.iter().copied().find(|(f, _, _)| *f == field)
}

/// Reads the rest of a binary surface file (after its magic number) and builds the surface.
pub(super) fn read(
    reader: BufReader<std::fs::File>,
    layout: u8,
    path: &Path,
    max_bytes: u64,
) -> Result<Surface, FileError> {
    let size = reader
        .get_ref()
        .metadata()
        .ok()
        .filter(|m| m.is_file())
        .map(|m| m.len());
    let format = |cause| FileError::Format {
        path: path.to_path_buf(),
        cause,
    };
    let io = |cause| FileError::Io {
        path: path.to_path_buf(),
        cause,
    };
    if size.is_some_and(|s| s > max_bytes) {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!("longer than the {max_bytes} bytes allowed"),
        )));
    }
    let mut r = Limited {
        inner: reader,
        left: size.unwrap_or(max_bytes).saturating_sub(MAGIC.len() as u64),
    };
    let file = read_document(&mut r, layout).map_err(|e| match e {
        ReadError::Format(e) => format(e),
        ReadError::Io(e) => io(e),
    })?;
    build(file).map_err(format)
}

/// A reader that knows how many bytes are left (the file's size, or the byte limit for a
/// stream), so that sizes claimed by the header are checked before allocating.
struct Limited {
    inner: BufReader<std::fs::File>,
    left: u64,
}

impl Limited {
    /// Reads exactly `buf.len()` bytes, or reports the file as truncated.
    fn fill(&mut self, buf: &mut [u8], what: &str) -> Result<(), ReadError> {
        if (buf.len() as u64) > self.left {
            return Err(truncated(what));
        }
        self.inner.read_exact(buf).map_err(|e| match e.kind() {
            std::io::ErrorKind::UnexpectedEof => truncated(what),
            _ => ReadError::Io(e),
        })?;
        self.left -= buf.len() as u64;
        Ok(())
    }

    /// Checks that `bytes` more bytes are there.
    fn claim(&self, bytes: u64, what: &str) -> Result<(), ReadError> {
        if bytes > self.left {
            return Err(truncated(what));
        }
        Ok(())
    }
}

/// Why reading failed.
enum ReadError {
    Format(FormatError),
    Io(std::io::Error),
}

impl From<FormatError> for ReadError {
    fn from(e: FormatError) -> Self {
        ReadError::Format(e)
    }
}

/// The file ends before `what`.
fn truncated(what: &str) -> ReadError {
    ReadError::Format(invalid(
        what,
        "the binary file is truncated (it ends before this part)",
    ))
}

/// Reads the header and every chunk into the document.
fn read_document(r: &mut Limited, layout: u8) -> Result<FileV1, ReadError> {
    let mut len = [0u8; 8];
    r.fill(&mut len, "header")?;
    let len = u64::from_le_bytes(len);
    if len > MAX_HEADER {
        return Err(invalid(
            "header",
            format!("claims {len} bytes (at most {MAX_HEADER})"),
        )
        .into());
    }
    // Layout 2: the header's CRC-32 and four zero bytes.
    let mut check = [0u8; 8];
    if layout >= 2 {
        r.fill(&mut check, "header")?;
        if check[4..] != [0u8; 4] {
            return Err(
                invalid("header", "checksum field corrupted: the file is corrupted").into(),
            );
        }
    }
    r.claim(len, "header")?;
    let mut json = vec![0u8; len as usize];
    r.fill(&mut json, "header")?;
    if layout >= 2 && crc32fast::hash(&json).to_le_bytes() != check[..4] {
        return Err(invalid("header", "checksum mismatch: the file is corrupted").into());
    }
    let header: Header = serde_json::from_slice(&json).map_err(super::syntax)?;
    if header.format != FORMAT_NAME {
        return Err(FormatError::NotPssurf.into());
    }
    if header.version != FORMAT_VERSION as u64 {
        return Err(FormatError::UnsupportedVersion(header.version).into());
    }
    if header.encoding != "binary" {
        return Err(invalid(
            "encoding",
            format!("expected \"binary\", not {:?}", header.encoding),
        )
        .into());
    }
    skip_padding(r, len, "header")?;
    let mut file = header.document;
    // The embedded document's own fields are checked as in a JSON file.
    if file.format != FORMAT_NAME {
        return Err(FormatError::NotPssurf.into());
    }
    if file.version != FORMAT_VERSION as u64 {
        return Err(FormatError::UnsupportedVersion(file.version).into());
    }
    let mut seen: Vec<&str> = Vec::new();
    for chunk in &header.chunks {
        let (field, dtype, width) = spec(&chunk.field)
            .ok_or_else(|| invalid("chunks", format!("unknown field `{}`", chunk.field)))?;
        if seen.contains(&field) {
            return Err(invalid(field, "stored twice").into());
        }
        seen.push(field);
        if chunk.dtype != dtype || chunk.width != width {
            return Err(invalid(
                field,
                format!(
                    "expected {dtype} rows of {width}, not {} rows of {}",
                    chunk.dtype, chunk.width
                ),
            )
            .into());
        }
        put(&mut file, chunk, r)?;
    }
    if r.left > 0 {
        return Err(invalid("chunks", format!("{} bytes after the last chunk", r.left)).into());
    }
    Ok(file)
}

/// Reads the zero bytes after a part of `len` bytes.
fn skip_padding(r: &mut Limited, len: u64, what: &str) -> Result<(), ReadError> {
    let mut pad = [0u8; 8];
    let pad = &mut pad[..padding(len) as usize];
    r.fill(pad, what)?;
    if pad.iter().any(|&b| b != 0) {
        return Err(invalid(
            what,
            "the padding after it is not zero: the file is corrupted",
        )
        .into());
    }
    Ok(())
}

/// A row kept as it is.
fn same<const W: usize>(row: [f64; W]) -> [f64; W] {
    row
}

/// Reads `chunk`'s rows into its field of `file`, which must not hold it already.
fn put(file: &mut FileV1, chunk: &Chunk, r: &mut Limited) -> Result<(), ReadError> {
    let field = chunk.field.as_str();
    let twice = || invalid(field, "given both in the header and as a chunk");
    match field {
        "domain.vertices" | "domain.triangles" | "domain.split_points" => {
            let d = file
                .domain
                .as_mut()
                .ok_or_else(|| invalid(field, "a chunk for a document without `domain`"))?;
            match field {
                "domain.vertices" if d.vertices.is_empty() => d.vertices = rows(r, chunk, same)?,
                "domain.triangles" if d.triangles.is_empty() => {
                    d.triangles = indices(r, chunk)?;
                }
                "domain.split_points" if d.split_points.is_none() => {
                    d.split_points = Some(rows(r, chunk, same)?);
                }
                _ => return Err(twice().into()),
            }
        }
        "ps_triangles" if file.ps_triangles.is_none() => {
            file.ps_triangles = Some(rows(r, chunk, |t: [f64; 6]| {
                [[t[0], t[1]], [t[2], t[3]], [t[4], t[5]]]
            })?);
        }
        "control" if file.control.is_none() => file.control = Some(rows(r, chunk, same)?),
        "control_points" if file.control_points.is_none() => {
            file.control_points = Some(rows(r, chunk, |t: [f64; 9]| {
                [[t[0], t[1], t[2]], [t[3], t[4], t[5]], [t[6], t[7], t[8]]]
            })?);
        }
        "weights" if file.weights.is_none() => file.weights = Some(rows(r, chunk, same)?),
        _ => return Err(twice().into()),
    }
    Ok(())
}

/// The number of rows of `chunk`, after checking that its bytes (rows × `row_bytes`) are
/// still in the file: called before anything is allocated for it.
fn claimed_rows(r: &Limited, chunk: &Chunk, row_bytes: u64) -> Result<usize, ReadError> {
    let field = chunk.field.as_str();
    let bytes = chunk
        .rows
        .checked_mul(row_bytes)
        .ok_or_else(|| invalid(field, "absurd size"))?;
    r.claim(bytes, field)?;
    usize::try_from(chunk.rows).map_err(|_| invalid(field, "absurd size").into())
}

/// Reads the `rows` rows of `row_bytes` bytes of `chunk` in blocks of whole rows, checking its
/// CRC-32 and padding after, and decodes each row with `decode`.
fn read_chunk(
    r: &mut Limited,
    chunk: &Chunk,
    rows: usize,
    row_bytes: usize,
    mut decode: impl FnMut(&[u8]),
) -> Result<(), ReadError> {
    let field = chunk.field.as_str();
    let bytes = (rows * row_bytes) as u64;
    let mut hasher = crc32fast::Hasher::new();
    let block = (BLOCK / row_bytes).max(1) * row_bytes;
    let mut buf = vec![0u8; block];
    let mut left = bytes;
    while left > 0 {
        let n = left.min(block as u64) as usize;
        r.fill(&mut buf[..n], field)?;
        hasher.update(&buf[..n]);
        buf[..n].chunks_exact(row_bytes).for_each(&mut decode);
        left -= n as u64;
    }
    if hasher.finalize() != chunk.crc32 {
        return Err(invalid(field, "checksum mismatch: the file is corrupted").into());
    }
    skip_padding(r, bytes, field)
}

/// A chunk of rows of W f64 numbers, each turned into a `T` by `make` as it is read (no
/// intermediate copy of the array).
fn rows<T, const W: usize>(
    r: &mut Limited,
    chunk: &Chunk,
    make: impl Fn([f64; W]) -> T,
) -> Result<Vec<T>, ReadError> {
    let n = claimed_rows(r, chunk, 8 * W as u64)?;
    let mut out = Vec::with_capacity(n);
    read_chunk(r, chunk, n, 8 * W, |row| {
        out.push(make(std::array::from_fn(|k| {
            f64::from_le_bytes(row[8 * k..8 * k + 8].try_into().expect("8 bytes"))
        })));
    })?;
    Ok(out)
}

/// A chunk of u32 index triples.
fn indices(r: &mut Limited, chunk: &Chunk) -> Result<Vec<[usize; 3]>, ReadError> {
    let n = claimed_rows(r, chunk, 12)?;
    let mut out = Vec::with_capacity(n);
    read_chunk(r, chunk, n, 12, |row| {
        out.push(std::array::from_fn(|k| {
            u32::from_le_bytes(row[4 * k..4 * k + 4].try_into().expect("4 bytes")) as usize
        }));
    })?;
    Ok(out)
}
