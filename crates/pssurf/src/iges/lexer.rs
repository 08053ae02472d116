//! The fixed-format layer of IGES 5.3: 80-column records sorted into the Start, Global,
//! Directory, Parameter and Terminate sections, the Global section's delimiters, the
//! free-format parameter fields (numbers with `E` or `D` exponents, Hollerith strings `nH…`
//! that may contain delimiters, empty fields), and the directory entries.

use super::IgesError;

/// One physical record of a section: its text (columns 1–72) and its line in the file.
#[derive(Clone, Debug)]
pub(crate) struct Record<'a> {
    pub text: &'a str,
    pub line: usize,
}

/// The records of a file by section.
#[derive(Debug, Default)]
pub(crate) struct Sections<'a> {
    pub start: Vec<Record<'a>>,
    pub global: Vec<Record<'a>>,
    pub directory: Vec<Record<'a>>,
    pub parameter: Vec<Record<'a>>,
    /// Whether the file ends with its Terminate record (one cut short does not).
    pub terminated: bool,
    /// Where the Terminate record's counts differ from the records read (a warning: files
    /// with a broken header are read all the same).
    pub miscount: Option<String>,
}

/// Splits the file into sections by the letter in column 73. Blank lines are skipped; a line
/// shorter than 73 columns or with text beyond column 80, an unknown section letter,
/// sections out of order, a compressed file and a second Terminate record are errors;
/// whether the Terminate record is there, and counts in it that are not the sections', are
/// noted for the caller.
pub(crate) fn sections(text: &str) -> Result<Sections<'_>, IgesError> {
    let mut out = Sections::default();
    let mut order = 0;
    let mut terminate: Option<Record<'_>> = None;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let raw = raw.trim_end_matches('\r');
        if raw.trim().is_empty() {
            continue;
        }
        if !raw.is_char_boundary(72) || raw.len() < 73 {
            return Err(IgesError::at(
                line,
                format!(
                    "a record must have 80 columns with the section letter in column 73 (this one has {})",
                    raw.chars().count()
                ),
            ));
        }
        let (body, rest) = raw.split_at(72);
        if rest.chars().skip(8).any(|c| !c.is_whitespace()) {
            return Err(IgesError::at(
                line,
                format!(
                    "a record must have 80 columns (this one has {})",
                    raw.trim_end().chars().count()
                ),
            ));
        }
        let letter = rest.chars().next().unwrap_or(' ');
        let (rank, list) = match letter {
            'S' => (0, &mut out.start),
            'G' => (1, &mut out.global),
            'D' => (2, &mut out.directory),
            'P' => (3, &mut out.parameter),
            'T' => (4, &mut out.start), // the Terminate record is not used
            'C' | 'B' => {
                return Err(IgesError::at(
                    line,
                    "compressed and binary IGES files are not supported",
                ));
            }
            c => {
                return Err(IgesError::at(
                    line,
                    format!("unknown section letter `{c}` in column 73"),
                ));
            }
        };
        if rank < order {
            return Err(IgesError::at(
                line,
                format!("section `{letter}` after a later section"),
            ));
        }
        order = rank;
        if letter != 'T' {
            list.push(Record { text: body, line });
        } else if terminate.is_some() {
            return Err(IgesError::at(line, "a second Terminate record"));
        } else {
            terminate = Some(Record { text: body, line });
        }
    }
    if out.directory.is_empty() {
        return Err(IgesError::at(0, "the file has no Directory Entry section"));
    }
    out.terminated = terminate.is_some();
    out.miscount = terminate.and_then(|t| miscount(&out, &t));
    Ok(out)
}

/// The Terminate record names how many records each section has (columns 2–8, 10–16, 18–24
/// and 26–32 after the letters S, G, D, P): where it differs from the records read, what it
/// says, naming its line.
fn miscount(sections: &Sections<'_>, terminate: &Record<'_>) -> Option<String> {
    let found = [
        ('S', sections.start.len()),
        ('G', sections.global.len()),
        ('D', sections.directory.len()),
        ('P', sections.parameter.len()),
    ];
    found.into_iter().enumerate().find_map(|(k, (letter, count))| {
        let field = terminate.text.get(8 * k..8 * k + 8).unwrap_or("");
        let said = field
            .strip_prefix(letter)
            .and_then(|n| n.trim().parse::<usize>().ok());
        (said != Some(count)).then(|| {
            format!(
                "line {}: the Terminate record gives `{}` where the file has {count} `{letter}` records (edited by hand?)",
                terminate.line,
                field.trim()
            )
        })
    })
}

/// A free-format field: empty (defaulted), a number, or a string.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Field {
    Empty,
    Number(f64),
    Text(String),
}

/// A field with the line it starts on.
#[derive(Clone, Debug)]
pub(crate) struct Located {
    pub field: Field,
    pub line: usize,
}

/// The delimiters of the free-format sections.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Delimiters {
    pub parameter: char,
    pub record: char,
}

impl Default for Delimiters {
    fn default() -> Self {
        Delimiters {
            parameter: ',',
            record: ';',
        }
    }
}

/// The text of `records` joined, with the line of each character (only the first `width`
/// columns of each record: 72 in the Global section, 64 in the Parameter section).
fn joined(records: &[Record<'_>], width: usize) -> (Vec<char>, Vec<usize>) {
    let mut chars = Vec::new();
    let mut lines = Vec::new();
    for r in records {
        for c in r.text.chars().take(width) {
            chars.push(c);
            lines.push(r.line);
        }
    }
    (chars, lines)
}

/// The Global section's delimiters: its first two fields, each a Hollerith `1Hx` or empty
/// (the defaults `,` and `;`).
pub(crate) fn global_delimiters(records: &[Record<'_>]) -> Result<Delimiters, IgesError> {
    let (chars, lines) = joined(records, 72);
    let line_at = |k: usize| lines.get(k).copied().unwrap_or(0);
    let mut d = Delimiters::default();
    let mut k = 0;
    // Field 1: the parameter delimiter.
    if chars.get(k) == Some(&',') {
        k += 1;
    } else if chars
        .get(k..k + 3)
        .is_some_and(|s| s[0] == '1' && s[1] == 'H')
    {
        d.parameter = chars[k + 2];
        k += 3;
        if chars.get(k) != Some(&d.parameter) {
            return Err(IgesError::at(
                line_at(k),
                "the Global section's first field must be followed by the parameter delimiter",
            ));
        }
        k += 1;
    } else if !chars.is_empty() {
        return Err(IgesError::at(
            line_at(0),
            "the Global section must start with the parameter delimiter (`1H,` or an empty field)",
        ));
    }
    // Field 2: the record delimiter.
    if chars
        .get(k..k + 3)
        .is_some_and(|s| s[0] == '1' && s[1] == 'H')
    {
        d.record = chars[k + 2];
    } else if chars
        .get(k)
        .is_some_and(|c| *c != d.parameter && *c != d.record)
    {
        return Err(IgesError::at(
            line_at(k),
            "the Global section's second field must be the record delimiter (`1H;` or empty)",
        ));
    }
    if d.parameter == d.record || d.parameter.is_whitespace() || d.record.is_whitespace() {
        return Err(IgesError::at(
            line_at(0),
            "the parameter and record delimiters must differ and not be blanks",
        ));
    }
    Ok(d)
}

/// The fields of one free-format record (Global: the whole section; Parameter: one entity)
/// up to its record delimiter; what follows the record delimiter is a comment.
pub(crate) fn fields(
    records: &[Record<'_>],
    width: usize,
    d: Delimiters,
) -> Result<Vec<Located>, IgesError> {
    let (chars, lines) = joined(records, width);
    let line_at = |k: usize| lines.get(k).or(lines.last()).copied().unwrap_or(0);
    let mut out = Vec::new();
    let mut k = 0;
    loop {
        // Skip blanks before a field.
        while k < chars.len() && chars[k] == ' ' {
            k += 1;
        }
        let start = k;
        if k >= chars.len() {
            return Err(IgesError::at(
                line_at(k),
                format!(
                    "the record ends without its record delimiter `{}`",
                    d.record
                ),
            ));
        }
        let (field, end) = if chars[k] == d.parameter || chars[k] == d.record {
            (Field::Empty, k)
        } else {
            // Digits then H: a Hollerith string of that many characters.
            let mut j = k;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
            if j > k && j < chars.len() && (chars[j] == 'H' || chars[j] == 'h') {
                let n: usize = chars[k..j]
                    .iter()
                    .collect::<String>()
                    .parse()
                    .map_err(|_| IgesError::at(line_at(k), "a Hollerith length is too large"))?;
                let from = j + 1;
                let to = from
                    .checked_add(n)
                    .filter(|&t| t <= chars.len())
                    .ok_or_else(|| {
                        IgesError::at(
                            line_at(k),
                            format!("the string {n}H… runs past the end of the section"),
                        )
                    })?;
                (Field::Text(chars[from..to].iter().collect()), to)
            } else {
                let mut j = k;
                while j < chars.len() && chars[j] != d.parameter && chars[j] != d.record {
                    j += 1;
                }
                let text: String = chars[k..j].iter().collect();
                (number(text.trim(), line_at(k))?, j)
            }
        };
        out.push(Located {
            field,
            line: line_at(start),
        });
        // After the field: blanks, then a delimiter.
        let mut j = end;
        while j < chars.len() && chars[j] == ' ' {
            j += 1;
        }
        match chars.get(j) {
            Some(c) if *c == d.parameter => k = j + 1,
            Some(c) if *c == d.record => return Ok(out),
            Some(c) => {
                return Err(IgesError::at(
                    line_at(j),
                    format!(
                        "unexpected `{c}` after a field (expected `{}` or `{}`)",
                        d.parameter, d.record
                    ),
                ));
            }
            None => {
                return Err(IgesError::at(
                    line_at(j),
                    format!(
                        "the record ends without its record delimiter `{}`",
                        d.record
                    ),
                ));
            }
        }
    }
}

/// An integer or real, with `E` or `D` exponents (Fortran `1.0D0`).
fn number(text: &str, line: usize) -> Result<Field, IgesError> {
    let t = text.replace(['D', 'd'], "E");
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(Field::Number(x)),
        Ok(_) => Err(IgesError::at(
            line,
            format!("`{text}` is not a finite number"),
        )),
        Err(_) => Err(IgesError::at(line, format!("`{text}` is not a number"))),
    }
}

/// A directory entry: the two 80-column records of one entity.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    /// The entity type.
    pub kind: i64,
    /// The first Parameter record (1-based sequence number).
    pub parameter: usize,
    /// The directory entry of the transformation matrix (0: none).
    pub transform: usize,
    /// The number of Parameter records.
    pub parameter_lines: usize,
    /// The form number.
    pub form: i64,
    /// The entity label (columns 57–64 of the second record).
    pub label: String,
    /// The line of the first record in the file.
    pub line: usize,
    /// Its sequence number in the Directory section (2k + 1 for entry k).
    pub de: usize,
}

/// The directory entries, in order (the entity with sequence number 2k + 1 is entry k).
pub(crate) fn directory(records: &[Record<'_>]) -> Result<Vec<Entry>, IgesError> {
    if !records.len().is_multiple_of(2) {
        let last = records.last().map_or(0, |r| r.line);
        return Err(IgesError::at(
            last,
            "the Directory Entry section has an odd number of records (two per entity)",
        ));
    }
    records
        .chunks(2)
        .enumerate()
        .map(|(k, pair)| {
            fn field<'a>(r: &Record<'a>, k: usize) -> &'a str {
                r.text.get(8 * k..8 * k + 8).unwrap_or("").trim()
            }
            let int = |r: &Record<'_>, k: usize, name: &str| -> Result<i64, IgesError> {
                let f = field(r, k);
                if f.is_empty() {
                    return Ok(0);
                }
                f.parse::<i64>().map_err(|_| {
                    IgesError::at(r.line, format!("the {name} field `{f}` is not an integer"))
                })
            };
            let (a, b) = (&pair[0], &pair[1]);
            let kind = int(a, 0, "entity type")?;
            let pointer = |v: i64, name: &str| -> Result<usize, IgesError> {
                usize::try_from(v).map_err(|_| {
                    IgesError::at(a.line, format!("the {name} pointer {v} is negative"))
                })
            };
            Ok(Entry {
                kind,
                parameter: pointer(int(a, 1, "parameter data")?, "parameter data")?,
                // A negative transformation pointer is not allowed either.
                transform: pointer(int(a, 6, "transformation matrix")?, "transformation")?,
                parameter_lines: pointer(
                    int(b, 3, "parameter line count")?,
                    "parameter line count",
                )?,
                form: int(b, 4, "form number")?,
                label: field(b, 7).to_string(),
                line: a.line,
                de: 2 * k + 1,
            })
        })
        .collect()
}
