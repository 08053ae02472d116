//! Files: the versioned pssurf JSON format (see `docs/format.md`) and atomic writing.

mod atomic;
mod format;

pub use atomic::{
    Durability, atomic_write, atomic_write_bytes, io_cause, remove_pending_temp_files,
};
pub use format::{
    FORMAT_VERSION, FileError, FormatError, from_json_str, load, load_limited, save, to_json_string,
};

#[cfg(test)]
mod tests;
