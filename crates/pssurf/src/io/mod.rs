//! Files: the versioned pssurf JSON format (see `docs/format.md`) and atomic writing.

mod atomic;
mod curves;
mod format;

pub use atomic::{
    Durability, atomic_write, atomic_write_bytes, io_cause, remove_pending_temp_files,
};
pub use curves::{
    CURVES_HEADER, CurvesError, MAX_CURVE_POINTS, read_curves_csv, write_curves_csv,
    write_curves_obj,
};
pub use format::{
    FORMAT_VERSION, FileError, FormatError, from_json_str, load, load_limited, save, to_json_string,
};

#[cfg(test)]
mod tests;
