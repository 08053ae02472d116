//! Scene files: named surfaces in one JSON file (`{"format": "pssurf-scene", "version": 1,
//! "objects": [{"name", "group", "surface"}, …]}`), each surface in the library's format. The
//! application adds placement, material and visibility to each object; readers that do not
//! need them (`pssurf info`) ignore them.

use serde_json::{Value, json};

use super::format::{FormatError, from_json_str, to_json_string};
use crate::surface::Surface;

/// The scene file's format name.
pub const SCENE_FORMAT: &str = "pssurf-scene";
/// The scene file version this build reads and writes.
pub const SCENE_VERSION: u32 = 1;

/// One object of a scene as the library writes and reads it.
#[derive(Clone, Debug)]
pub struct SceneEntry {
    /// The object's name.
    pub name: String,
    /// Its group (may be empty).
    pub group: String,
    /// Its surface.
    pub surface: Surface,
}

/// The text of a scene file holding `objects` (no placement: the identity, visible).
pub fn scene_to_json(objects: &[SceneEntry]) -> String {
    let objects: Vec<Value> = objects
        .iter()
        .map(|o| {
            let surface: Value =
                serde_json::from_str(&to_json_string(&o.surface)).expect("the library writes JSON");
            let mut v = json!({"name": o.name, "surface": surface});
            if !o.group.is_empty() {
                v["group"] = o.group.clone().into();
            }
            v
        })
        .collect();
    let mut text = serde_json::to_string_pretty(
        &json!({"format": SCENE_FORMAT, "version": SCENE_VERSION, "objects": objects}),
    )
    .expect("scenes serialise");
    text.push('\n');
    text
}

/// Whether a JSON text is a scene file (rather than a surface file).
pub fn is_scene(text: &str) -> bool {
    // The format field is near the start; parse only what is needed to see it.
    #[derive(serde::Deserialize)]
    struct Head {
        format: Option<String>,
    }
    serde_json::from_str::<Head>(text).is_ok_and(|h| h.format.as_deref() == Some(SCENE_FORMAT))
}

/// The objects of a scene file, every surface validated; the error names the object.
pub fn scene_from_json(text: &str) -> Result<Vec<SceneEntry>, FormatError> {
    let value: Value = serde_json::from_str(text).map_err(|e| FormatError::Syntax {
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    })?;
    if value.get("format").and_then(Value::as_str) != Some(SCENE_FORMAT) {
        return Err(FormatError::NotPssurf);
    }
    let invalid = |at: String, message: String| FormatError::Invalid { at, message };
    match value.get("version").and_then(Value::as_u64) {
        Some(v) if v == u64::from(SCENE_VERSION) => {}
        Some(v) => return Err(FormatError::UnsupportedVersion(v)),
        None => return Err(invalid("version".into(), "missing scene version".into())),
    }
    let objects = value
        .get("objects")
        .and_then(Value::as_array)
        .ok_or_else(|| invalid("objects".into(), "a scene needs a list of objects".into()))?;
    objects
        .iter()
        .enumerate()
        .map(|(k, o)| {
            let name = o
                .get("name")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string();
            let group = o
                .get("group")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string();
            let surface = o.get("surface").ok_or_else(|| {
                invalid(format!("objects[{k}]"), "an object needs a surface".into())
            })?;
            let surface = from_json_str(&surface.to_string())
                .map_err(|e| invalid(format!("objects[{k}] ({name})"), e.to_string()))?;
            Ok(SceneEntry {
                name,
                group,
                surface,
            })
        })
        .collect()
}
