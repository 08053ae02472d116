//! The library's errors as Python exceptions: invalid input and contents are `ValueError`,
//! the operating system's refusals are `OSError`; the message is the library's own.

use pssurf::io::FileError;
use pyo3::PyErr;
use pyo3::exceptions::{PyMemoryError, PyOSError, PyValueError};

/// A `ValueError` with the message of `e`.
pub fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// An `OSError` when the system refused, a `ValueError` when the file's contents are invalid.
pub fn file_error(e: FileError) -> PyErr {
    match e {
        FileError::Io { .. } => PyOSError::new_err(e.to_string()),
        FileError::Format { .. } => PyValueError::new_err(e.to_string()),
    }
}

/// A `MemoryError` refusing a request whose estimated memory exceeds the budget.
pub fn too_large(what: &str, bytes: u128) -> PyErr {
    PyMemoryError::new_err(format!(
        "{what} would need about {} of memory, more than this process may plan to use ({}); refused before allocating",
        human(bytes),
        human(memory_budget() as u128)
    ))
}

/// The most memory one call may plan to use: half of the machine's memory (4 GiB when it
/// cannot be read), as the command-line tool's default budget.
pub fn memory_budget() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(4 << 30, |kib| kib.saturating_mul(1024) / 2)
}

/// Refuses (with [`too_large`]) a request estimated at `bytes`.
pub fn check_budget(what: &str, bytes: u128) -> Result<(), PyErr> {
    if bytes > memory_budget() as u128 {
        return Err(too_large(what, bytes));
    }
    Ok(())
}

/// Bytes in words: "1.5 GB".
fn human(bytes: u128) -> String {
    let b = bytes as f64;
    match b {
        b if b >= 1e12 => format!("{:.1} TB", b / 1e12),
        b if b >= 1e9 => format!("{:.1} GB", b / 1e9),
        b if b >= 1e6 => format!("{:.1} MB", b / 1e6),
        b => format!("{:.0} kB", b / 1e3),
    }
}

/// A non-negative integer argument (a count, a level, a size). Negative, too large and
/// non-integer values are a `ValueError` naming the value, where pyo3's own conversion to
/// an unsigned type would raise `OverflowError` or `TypeError`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count<T>(pub T);

impl<'a, 'py, T: TryFrom<i128>> pyo3::FromPyObject<'a, 'py> for Count<T> {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, pyo3::PyAny>) -> Result<Self, Self::Error> {
        use pyo3::types::PyAnyMethods;
        let refuse = || {
            let shown = obj
                .repr()
                .map_or_else(|_| "this value".to_string(), |r| r.to_string());
            value_error(format!(
                "expected a non-negative integer within range, not {shown}"
            ))
        };
        if obj.is_instance_of::<pyo3::types::PyBool>() {
            return Err(refuse());
        }
        let v: i128 = obj.extract().map_err(|_| refuse())?;
        if v < 0 {
            return Err(refuse());
        }
        T::try_from(v).map(Count).map_err(|_| refuse())
    }
}
