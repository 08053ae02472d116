//! Files: the versioned pssurf JSON format (see `docs/format.md`) for surfaces and curves,
//! scene files of named surfaces, curves as CSV or OBJ, and atomic writing.

mod atomic;
mod curve_file;
mod curves;
mod format;
mod hole_spec;
mod scene;

pub use atomic::{
    Durability, atomic_write, atomic_write_bytes, io_cause, remove_pending_temp_files,
};
pub use curve_file::{curve_from_json, curve_to_json, is_curve, load_curve_limited, save_curve};
pub use curves::{
    CURVES_HEADER, CurvesError, MAX_CURVE_POINTS, read_curves_csv, write_curves_csv,
    write_curves_obj,
};
pub use format::{
    BINARY_EXTENSION, CURVE_KIND, FORMAT_VERSION, FileError, FormatError, SurfaceEncoding,
    from_json_str, is_binary_surface_file, load, load_limited, save, to_json_string, write_surface,
};
pub use hole_spec::{HOLE_KIND, hole_from_json};
pub use scene::{
    SCENE_FORMAT, SCENE_VERSION, SceneContents, SceneEntry, SceneMesh, is_scene, mesh_from_value,
    mesh_to_value, scene_contents_from_json, scene_from_json, scene_to_json,
};

#[cfg(test)]
mod tests;
