//! Scene files: named surfaces in one JSON file (`{"format": "pssurf-scene", "version": 1,
//! "objects": [{"name", "group", "surface"}, …]}`), each surface in the library's format (or
//! a `"mesh"` in place of the surface: a reference mesh and its subdivision). The
//! application adds placement, material and visibility to each object; readers that do not
//! need them (`pssurf info`) ignore them.

use nalgebra::Vector3;
use serde_json::{Value, json};

use super::format::{FormatError, from_json_str, to_json_string};
use crate::subdivision::mesh::MAX_TRIANGLES;
use crate::subdivision::{Mesh, RefinedMesh, SurfaceScheme};
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

/// The surfaces of a scene file, every one validated; the error names the object. Mesh
/// objects (see [`scene_contents_from_json`]) are checked and left out.
pub fn scene_from_json(text: &str) -> Result<Vec<SceneEntry>, FormatError> {
    scene_contents_from_json(text).map(|c| c.surfaces)
}

/// A mesh object of a scene: a control mesh and its subdivision (the application shows
/// reference meshes and subdivides them).
#[derive(Clone, Debug)]
pub struct SceneMesh {
    /// The object's name.
    pub name: String,
    /// Its group (may be empty).
    pub group: String,
    /// The mesh and its subdivision.
    pub mesh: RefinedMesh,
}

/// Everything a scene file holds: its surfaces and its meshes, in file order within each.
#[derive(Clone, Debug, Default)]
pub struct SceneContents {
    /// The surface objects.
    pub surfaces: Vec<SceneEntry>,
    /// The mesh objects.
    pub meshes: Vec<SceneMesh>,
}

/// The JSON value of a mesh object's `"mesh"` field: `{"positions": [[x, y, z], …],
/// "triangles": [[a, b, c], …], "scheme": "loop" | "sqrt3" | "butterfly", "times": N}`.
pub fn mesh_to_value(m: &RefinedMesh) -> Value {
    let positions: Vec<[f64; 3]> = m
        .control
        .positions
        .iter()
        .map(|p| [p.x, p.y, p.z])
        .collect();
    json!({
        "positions": positions,
        "triangles": m.control.triangles,
        "scheme": m.scheme.name(),
        "times": m.times,
    })
}

/// The mesh object of a `"mesh"` field ([`mesh_to_value`]), checked: valid indices, finite
/// coordinates ([`Mesh::check`]) and a subdivision within [`MAX_TRIANGLES`] triangles.
pub fn mesh_from_value(v: &Value) -> Result<RefinedMesh, String> {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct MeshFile {
        positions: Vec<[f64; 3]>,
        triangles: Vec<[u32; 3]>,
        #[serde(default = "loop_name")]
        scheme: String,
        #[serde(default)]
        times: u32,
    }
    fn loop_name() -> String {
        "loop".into()
    }
    let file: MeshFile = serde_json::from_value(v.clone()).map_err(|e| e.to_string())?;
    let scheme = SurfaceScheme::parse(&file.scheme).ok_or_else(|| {
        format!(
            "unknown scheme `{}` (use loop, sqrt3 or butterfly)",
            file.scheme
        )
    })?;
    let mesh = RefinedMesh {
        control: Mesh {
            positions: file.positions.into_iter().map(Vector3::from).collect(),
            triangles: file.triangles,
        },
        scheme,
        times: file.times,
    };
    mesh.control.check().map_err(|e| e.to_string())?;
    if mesh.triangles_after() > MAX_TRIANGLES as f64 {
        return Err(format!(
            "{} steps of {} make more than the {MAX_TRIANGLES} triangles a mesh may have",
            mesh.times,
            scheme.name()
        ));
    }
    Ok(mesh)
}

/// The objects of a scene file, every surface and mesh validated; the error names the
/// object. An object holds a `"surface"` or a `"mesh"` ([`mesh_to_value`]).
pub fn scene_contents_from_json(text: &str) -> Result<SceneContents, FormatError> {
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
    let mut contents = SceneContents::default();
    for (k, o) in objects.iter().enumerate() {
        let text = |key: &str| o.get(key).and_then(Value::as_str).unwrap_or("").to_string();
        let (name, group) = (text("name"), text("group"));
        let at = || format!("objects[{k}] ({name})");
        match (o.get("surface"), o.get("mesh")) {
            (Some(surface), None) => {
                let surface = from_json_str(&surface.to_string())
                    .map_err(|e| invalid(at(), e.to_string()))?;
                contents.surfaces.push(SceneEntry {
                    name,
                    group,
                    surface,
                });
            }
            (None, Some(mesh)) => {
                let mesh = mesh_from_value(mesh).map_err(|e| invalid(at(), e))?;
                contents.meshes.push(SceneMesh { name, group, mesh });
            }
            _ => {
                return Err(invalid(
                    format!("objects[{k}]"),
                    "an object needs a surface or a mesh (one of them)".into(),
                ));
            }
        }
    }
    Ok(contents)
}
