//! The scene: named surface objects with visibility and a placement, saved as one JSON file
//! that embeds each surface in the library's file format (`docs/format.md`).

use std::path::Path;
use std::sync::Arc;

use nalgebra::{Matrix4, Rotation3, Vector3};
use pssurf::io::{
    Durability, SurfaceEncoding, atomic_write, atomic_write_bytes, is_binary_surface_file,
    write_surface,
};
use pssurf::subdivision::{Mesh, RefinedMesh};
use pssurf::surface::Surface;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use thiserror::Error;

/// The scene file's format name and version (defined with the library's scene files).
pub use pssurf::io::{SCENE_FORMAT, SCENE_VERSION};

/// A rigid placement with a uniform scale: p ↦ t + s R p (R from Euler angles in degrees,
/// applied about x, then y, then z).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Transform {
    /// Translation.
    pub translate: [f64; 3],
    /// Rotation about x, y, z in degrees.
    pub rotate_deg: [f64; 3],
    /// Uniform scale (> 0).
    pub scale: f64,
}

impl Default for Transform {
    fn default() -> Self {
        Transform {
            translate: [0.0; 3],
            rotate_deg: [0.0; 3],
            scale: 1.0,
        }
    }
}

impl Transform {
    /// The 4 × 4 matrix.
    pub fn matrix(&self) -> Matrix4<f64> {
        let [a, b, c] = self.rotate_deg.map(f64::to_radians);
        let r = Rotation3::from_euler_angles(a, b, c);
        Matrix4::new_translation(&Vector3::from(self.translate))
            * r.to_homogeneous()
            * Matrix4::new_scaling(self.scale)
    }

    /// Whether this is the identity.
    pub fn is_identity(&self) -> bool {
        *self == Transform::default()
    }
}

/// A surface material for the shaded view: a base colour and how glossy it is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Material {
    /// Matte light grey.
    #[default]
    Clay,
    /// Glossy blue plastic.
    Plastic,
    /// Shiny gold.
    Gold,
    /// Semi-glossy green.
    Jade,
}

impl Material {
    /// Every material.
    pub const ALL: [Material; 4] = [
        Material::Clay,
        Material::Plastic,
        Material::Gold,
        Material::Jade,
    ];

    /// The UI name.
    pub fn name(self) -> &'static str {
        match self {
            Material::Clay => "clay",
            Material::Plastic => "plastic",
            Material::Gold => "gold",
            Material::Jade => "jade",
        }
    }

    /// The vertex colour: RGB, and the glossiness in alpha (the shader's specular strength
    /// and exponent grow with it).
    pub fn color(self) -> [u8; 4] {
        match self {
            Material::Clay => [200, 200, 205, 40],
            Material::Plastic => [70, 120, 210, 150],
            Material::Gold => [212, 170, 60, 230],
            Material::Jade => [90, 170, 120, 110],
        }
    }
}

/// One object of the scene.
#[derive(Clone, Debug)]
pub struct SceneObject {
    /// The name shown in the scene tree.
    pub name: String,
    /// The group it belongs to in the scene tree ("" for none).
    pub group: String,
    /// How it is shaded.
    pub material: Material,
    /// Whether it is drawn.
    pub visible: bool,
    /// Its placement.
    pub transform: Transform,
    /// What it is: a surface (any kind) or a mesh, shared with the undo history: a snapshot
    /// of the scene copies the pointer, and an edit copies the surface only when a snapshot
    /// still holds it (see [`SceneObject::surface_mut`]).
    pub shape: Shape,
    /// A number that changes whenever the surface or transform changes (display caches key
    /// on it; it is not saved).
    pub revision: u64,
    /// Identifies the object for as long as the application runs (kept by copies, so
    /// through undo and redo; not saved): what refers to an object across edits that may
    /// move it in the list uses this, not its index.
    pub id: u64,
}

/// Why a mesh object refuses a control-point edit.
pub const NO_CONTROLS: &str = "a mesh object has no control points (subdivide it instead)";

/// What an object is.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A surface of any kind.
    Surface(Arc<Surface>),
    /// A triangle mesh, shown for reference and refined by a subdivision scheme.
    Mesh(Arc<MeshShape>),
}

/// The largest mesh file the application reads (1 GiB: a text OBJ of [`MAX_MESH_TRIANGLES`]
/// triangles takes about 200 MB, and reading holds a few times the file in memory).
pub const MAX_MESH_FILE_BYTES: u64 = 1 << 30;

/// The most triangles a mesh object may have after its subdivision (what the view draws of
/// one object; the same bound as a sampled surface).
pub const MAX_MESH_TRIANGLES: usize = 4_000_000;

/// A mesh object: the control mesh and its subdivision ([`RefinedMesh`]), with the refined
/// mesh, its normals and its discrete curvatures computed once.
#[derive(Clone, Debug)]
pub struct MeshShape {
    /// The control mesh and the subdivision applied to it.
    pub recipe: RefinedMesh,
    /// The refined mesh.
    pub refined: Mesh,
    /// Unit vertex normals of the refined mesh.
    pub normals: Vec<nalgebra::Vector3<f64>>,
    /// The discrete Gaussian and mean curvature per vertex (NaN on the boundary), when the
    /// refined mesh is manifold; else why not.
    pub curvature: Result<DiscreteCurvature, String>,
}

/// Discrete curvatures per vertex of a mesh (see `pssurf::subdivision::mesh::discrete_curvature`).
#[derive(Clone, Debug)]
pub struct DiscreteCurvature {
    /// Gaussian curvature K.
    pub gaussian: Vec<f64>,
    /// Mean curvature H.
    pub mean: Vec<f64>,
}

impl MeshShape {
    /// Refines the control mesh as the recipe says; an error in words when the control mesh
    /// is invalid, the scheme cannot run on it (not manifold) or the result would have more
    /// than [`MAX_MESH_TRIANGLES`] triangles.
    pub fn new(recipe: RefinedMesh) -> Result<MeshShape, String> {
        let after = recipe.triangles_after();
        if after > MAX_MESH_TRIANGLES as f64 {
            let what = match recipe.times {
                0 => format!("the mesh has {} triangles", recipe.control.triangles.len()),
                n => format!(
                    "{n} step(s) of {} would make about {} triangles",
                    recipe.scheme.name(),
                    crate::fields::compact(after)
                ),
            };
            return Err(format!(
                "{what}, more than the {} million a mesh object may have",
                MAX_MESH_TRIANGLES / 1_000_000
            ));
        }
        let refined = recipe.refine().map_err(|e| e.to_string())?;
        let normals = refined.vertex_normals();
        let curvature = pssurf::subdivision::mesh::discrete_curvature(&refined)
            .map(|(gaussian, mean)| DiscreteCurvature { gaussian, mean })
            .map_err(|e| e.to_string());
        Ok(MeshShape {
            recipe,
            refined,
            normals,
            curvature,
        })
    }
}

/// The largest scene or surface file the application opens (2 GiB: loading takes about
/// eight times its size in memory).
pub const MAX_FILE_BYTES: u64 = 2 << 30;
/// The most read from a file without a size (a pipe, a device such as `/dev/zero`).
pub const MAX_STREAM_BYTES: u64 = 64 << 20;

/// Whether `path` names a file of scattered points (extension `csv`, any case).
pub fn is_points_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
}

/// Whether `path` names an IGES file (extension `igs` or `iges`, any case).
pub fn is_iges_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("igs") || e.eq_ignore_ascii_case("iges"))
}

/// Whether `path` names a triangle mesh file (extension `obj`, `ply` or `stl`, any case).
pub fn is_mesh_path(path: &Path) -> bool {
    path.extension().is_some_and(|e| {
        ["obj", "ply", "stl"]
            .iter()
            .any(|m| e.eq_ignore_ascii_case(m))
    })
}

/// Whether `path` names a file the application imports rather than saves to (IGES, CSV
/// points, a mesh): opening one gives an untitled document.
pub fn is_import_path(path: &Path) -> bool {
    is_iges_path(path) || is_points_path(path) || is_mesh_path(path)
}

/// Reads a text file of bounded size: a regular file up to [`MAX_FILE_BYTES`] (checked
/// before reading), anything else up to [`MAX_STREAM_BYTES`] (an endless stream is refused
/// after that much).
pub fn read_bounded(path: &Path) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if meta.is_dir() {
        return Err(Error::new(ErrorKind::IsADirectory, "is a directory"));
    }
    let limit = if meta.is_file() {
        if meta.len() > MAX_FILE_BYTES {
            return Err(Error::new(
                ErrorKind::FileTooLarge,
                format!(
                    "{} bytes, more than the {MAX_FILE_BYTES} the application opens",
                    meta.len()
                ),
            ));
        }
        MAX_FILE_BYTES
    } else {
        MAX_STREAM_BYTES
    };
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(Error::new(
            ErrorKind::FileTooLarge,
            format!("longer than the {limit} bytes the application reads from it"),
        ));
    }
    String::from_utf8(bytes).map_err(|_| {
        Error::new(
            ErrorKind::InvalidData,
            "is not UTF-8 text (a pssurf file is JSON)",
        )
    })
}

/// A fresh revision number, never seen before in this process.
pub fn fresh_revision() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl SceneObject {
    /// A visible object with the identity placement.
    pub fn new(name: impl Into<String>, surface: Surface) -> Self {
        SceneObject::of_shape(name, Shape::Surface(Arc::new(surface)))
    }

    /// A visible mesh object with the identity placement.
    pub fn mesh(name: impl Into<String>, mesh: MeshShape) -> Self {
        SceneObject::of_shape(name, Shape::Mesh(Arc::new(mesh)))
    }

    /// A visible object of any shape with the identity placement.
    pub fn of_shape(name: impl Into<String>, shape: Shape) -> Self {
        SceneObject {
            name: name.into(),
            group: String::new(),
            material: Material::default(),
            visible: true,
            transform: Transform::default(),
            shape,
            revision: fresh_revision(),
            id: fresh_revision(),
        }
    }

    /// The surface, unless the object is a mesh.
    pub fn surface(&self) -> Option<&Arc<Surface>> {
        match &self.shape {
            Shape::Surface(s) => Some(s),
            Shape::Mesh(_) => None,
        }
    }

    /// The mesh, if the object is one.
    pub fn mesh_shape(&self) -> Option<&MeshShape> {
        match &self.shape {
            Shape::Mesh(m) => Some(m),
            Shape::Surface(_) => None,
        }
    }

    /// The number of control groups an edit can select (see `crate::edit`; 0 for a mesh).
    pub fn vertex_count(&self) -> usize {
        self.surface().map_or(0, |s| crate::edit::vertex_count(s))
    }

    /// What kind of object this is, in words (the surface kind's name, or "mesh").
    pub fn kind_name(&self) -> &'static str {
        match &self.shape {
            Shape::Surface(s) => s.kind().name(),
            Shape::Mesh(_) => "mesh",
        }
    }

    /// Replaces what the object is (marked as changed).
    pub fn set_shape(&mut self, shape: Shape) {
        self.shape = shape;
        self.touch();
    }

    /// Marks the object as changed.
    pub fn touch(&mut self) {
        self.revision = fresh_revision();
    }

    /// The surface for an edit, marked as changed: copied first if the undo history still
    /// shares it (copy on write), so the history keeps the surface as it was.
    /// None for a mesh object (nothing is marked then).
    pub fn surface_mut(&mut self) -> Option<&mut Surface> {
        match &mut self.shape {
            Shape::Surface(s) => {
                self.revision = fresh_revision();
                Some(Arc::make_mut(s))
            }
            Shape::Mesh(_) => None,
        }
    }
}

/// What a file holds: one surface in the library's format (`docs/format.md`), or a scene of
/// objects. A document keeps the kind of its file, so a surface stays a surface file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FileKind {
    /// One surface, in the library's format (what `pssurf` reads).
    Surface,
    /// A scene: objects with names, materials, visibility and placements.
    #[default]
    Scene,
}

impl FileKind {
    /// The name used in messages and dialogs.
    pub fn name(self) -> &'static str {
        match self {
            FileKind::Surface => "surface file",
            FileKind::Scene => "scene file",
        }
    }
}

/// The objects of a scene.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The objects in tree order.
    pub objects: Vec<SceneObject>,
}

/// A scene file could not be read or written.
#[derive(Debug, Error)]
pub enum SceneError {
    /// Reading or writing failed.
    #[error("{path}: {}", pssurf::io::io_cause(source))]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The file is not a valid scene or surface file.
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong, and where.
        message: String,
    },
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    format: String,
    version: u32,
    objects: Vec<ObjectFile>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectFile {
    name: String,
    #[serde(default, skip_serializing_if = "String::is_empty")]
    group: String,
    #[serde(default)]
    material: Material,
    #[serde(default = "yes")]
    visible: bool,
    #[serde(default)]
    transform: Transform,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    surface: Option<Value>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mesh: Option<Value>,
}

fn yes() -> bool {
    true
}

impl Scene {
    /// The index of the object with identity `id` (see [`SceneObject::id`]).
    pub fn index_of(&self, id: u64) -> Option<usize> {
        self.objects.iter().position(|o| o.id == id)
    }

    /// The visible objects with their indices.
    pub fn visible(&self) -> impl Iterator<Item = (usize, &SceneObject)> {
        self.objects.iter().enumerate().filter(|(_, o)| o.visible)
    }

    /// The scene as the JSON text of a scene file.
    pub fn to_json(&self) -> String {
        let file = SceneFile {
            format: SCENE_FORMAT.into(),
            version: SCENE_VERSION,
            objects: self
                .objects
                .iter()
                .map(|o| ObjectFile {
                    name: o.name.clone(),
                    group: o.group.clone(),
                    material: o.material,
                    visible: o.visible,
                    transform: o.transform,
                    surface: o.surface().map(|s| {
                        serde_json::from_str(&pssurf::io::to_json_string(s))
                            .expect("the library writes valid JSON")
                    }),
                    mesh: o.mesh_shape().map(|m| pssurf::io::mesh_to_value(&m.recipe)),
                })
                .collect(),
        };
        serde_json::to_string_pretty(&file).expect("scenes serialise")
    }

    /// Parses a scene file, or a single surface file (which becomes a one-object scene named
    /// `name`). Every surface is validated as on loading a surface file.
    pub fn from_json(text: &str, name: &str) -> Result<Scene, String> {
        Scene::parse(text, name).map(|(scene, _)| scene)
    }

    /// [`Scene::from_json`], also telling which kind of file the text was.
    pub fn parse(text: &str, name: &str) -> Result<(Scene, FileKind), String> {
        let value: Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
        if value.get("format").and_then(Value::as_str) != Some(SCENE_FORMAT) {
            let surface = pssurf::io::from_json_str(text).map_err(|e| e.to_string())?;
            let scene = Scene {
                objects: vec![SceneObject::new(name, surface)],
            };
            return Ok((scene, FileKind::Surface));
        }
        let file: SceneFile = serde_json::from_value(value).map_err(|e| e.to_string())?;
        if file.version != SCENE_VERSION {
            return Err(format!(
                "scene version {} is not supported (this build reads version {SCENE_VERSION})",
                file.version
            ));
        }
        let mut objects = Vec::with_capacity(file.objects.len());
        for (k, o) in file.objects.into_iter().enumerate() {
            let t = &o.transform;
            let finite = t
                .translate
                .iter()
                .chain(&t.rotate_deg)
                .all(|x| x.is_finite());
            let positive = t.scale > 0.0 && t.scale.is_finite();
            if !(finite && positive) {
                return Err(format!(
                    "object {k} ({}): the transform must be finite with a positive scale",
                    o.name
                ));
            }
            let at = |e: String| format!("object {k} ({}): {e}", o.name);
            let shape = match (&o.surface, &o.mesh) {
                (Some(surface), None) => Shape::Surface(Arc::new(
                    pssurf::io::from_json_str(&surface.to_string())
                        .map_err(|e| at(e.to_string()))?,
                )),
                (None, Some(mesh)) => {
                    let recipe = pssurf::io::mesh_from_value(mesh).map_err(at)?;
                    Shape::Mesh(Arc::new(MeshShape::new(recipe).map_err(at)?))
                }
                _ => {
                    return Err(at(
                        "an object needs a surface or a mesh (one of them)".into()
                    ));
                }
            };
            objects.push(SceneObject {
                name: o.name,
                group: o.group,
                material: o.material,
                visible: o.visible,
                transform: o.transform,
                shape,
                revision: fresh_revision(),
                id: fresh_revision(),
            });
        }
        Ok((Scene { objects }, FileKind::Scene))
    }

    /// Loads a scene or surface file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::load_file(path).map(|(scene, _)| scene)
    }

    /// Loads a scene or surface file, telling which it was; an IGES file (by its extension)
    /// is imported as a scene of its B-spline surfaces.
    pub fn load_file(path: &Path) -> Result<(Scene, FileKind), SceneError> {
        if is_binary_surface_file(path) {
            let surface = pssurf::io::load_limited(path, MAX_FILE_BYTES).map_err(|e| {
                SceneError::Invalid {
                    path: path.display().to_string(),
                    message: e.to_string(),
                }
            })?;
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let scene = Scene {
                objects: vec![SceneObject::new(&name, surface)],
            };
            return Ok((scene, FileKind::Surface));
        }
        if is_mesh_path(path) {
            return Scene::from_mesh_file(path).map(|scene| (scene, FileKind::Scene));
        }
        let text = read_bounded(path).map_err(|source| SceneError::Io {
            path: path.display().to_string(),
            source,
        })?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let invalid = |message| SceneError::Invalid {
            path: path.display().to_string(),
            message,
        };
        if is_iges_path(path) {
            return Scene::from_iges(&text, &name)
                .map(|scene| (scene, FileKind::Scene))
                .map_err(invalid);
        }
        if is_points_path(path) {
            return Scene::from_points(&text, &name)
                .map(|scene| (scene, FileKind::Scene))
                .map_err(invalid);
        }
        Scene::parse(&text, &name).map_err(invalid)
    }

    /// The PS-spline interpolating the scattered points of a CSV text (columns named x, y, z,
    /// or the first three; a header line is optional), as one functional object named
    /// `name (fit)`: `pssurf::scattered::interpolate` with locally estimated gradients, as
    /// `pssurf fit` does. Errors name the line.
    pub fn from_points(text: &str, name: &str) -> Result<Scene, String> {
        let (points, values) = read_points_csv(text)?;
        let fit = pssurf::scattered::interpolate(
            &points,
            &values,
            pssurf::scattered::GradientMethod::Local,
        )
        .map_err(|e| e.to_string())?;
        Ok(Scene {
            objects: vec![SceneObject::new(
                format!("{name} (fit)"),
                Surface::Functional(fit.spline),
            )],
        })
    }

    /// The triangle mesh of an OBJ, PLY or STL file as one mesh object named after the file,
    /// not subdivided (at most [`MAX_MESH_FILE_BYTES`] and [`MAX_MESH_TRIANGLES`] triangles).
    pub fn from_mesh_file(path: &Path) -> Result<Scene, SceneError> {
        let shown = path.display().to_string();
        let meta = std::fs::metadata(path).map_err(|source| SceneError::Io {
            path: shown.clone(),
            source,
        })?;
        let invalid = |message: String| SceneError::Invalid {
            path: shown.clone(),
            message,
        };
        if !meta.is_file() {
            return Err(invalid("is not a regular file".into()));
        }
        if meta.len() > MAX_MESH_FILE_BYTES {
            return Err(invalid(format!(
                "{} bytes, more than the {MAX_MESH_FILE_BYTES} of a mesh file the application opens (a mesh object has at most {MAX_MESH_TRIANGLES} triangles)",
                meta.len()
            )));
        }
        use pssurf_viz::import::ImportError;
        let mesh = pssurf_viz::import::read_mesh(path).map_err(|e| match e {
            ImportError::Read { message, .. } => invalid(message),
            ImportError::Format(_) => invalid("not a mesh file (use .obj, .ply or .stl)".into()),
        })?;
        let shape = MeshShape::new(RefinedMesh::new(mesh)).map_err(invalid)?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Ok(Scene {
            objects: vec![SceneObject::mesh(name, shape)],
        })
    }

    /// The B-spline surfaces of an IGES file's text as objects of group `group` (see
    /// `pssurf::iges`); an error when the file holds none.
    pub fn from_iges(text: &str, group: &str) -> Result<Scene, String> {
        let model = pssurf::iges::read_iges(text).map_err(|e| e.to_string())?;
        if model.surfaces.is_empty() {
            return Err("the IGES file holds no B-spline surfaces (entity 128)".into());
        }
        let objects = model
            .surfaces
            .into_iter()
            .map(|s| {
                let mut o = SceneObject::new(&s.name, Surface::Nurbs(s.surface));
                o.group = group.to_string();
                o
            })
            .collect();
        Ok(Scene { objects })
    }

    /// Why this scene cannot be written as a surface file (None when it can: exactly one
    /// object, in its own coordinates).
    pub fn surface_file_problem(&self) -> Option<String> {
        match self.objects.as_slice() {
            [o] if o.surface().is_none() => {
                Some("the object is a mesh, which a surface file cannot hold".into())
            }
            [o] if o.transform.is_identity() => None,
            [_] => Some(
                "the object is moved, turned or scaled, which a surface file cannot record".into(),
            ),
            objects => Some(format!(
                "a surface file holds one surface, and the scene has {} objects",
                objects.len()
            )),
        }
    }

    /// Saves as a scene file, atomically (a failed write leaves the previous file intact)
    /// and durably.
    pub fn save(&self, path: &Path) -> Result<(), SceneError> {
        self.save_as(path, FileKind::Scene)
    }

    /// Saves as a file of `kind`, atomically and durably; a surface file only when the scene
    /// is one object in its own coordinates.
    /// A surface file is binary when its name ends in `.psb`, else JSON.
    pub fn save_as(&self, path: &Path, kind: FileKind) -> Result<(), SceneError> {
        let name = path.display().to_string();
        let written = match kind {
            FileKind::Scene => {
                atomic_write_bytes(path, Durability::Durable, self.to_json().as_bytes())
            }
            FileKind::Surface => {
                if let Some(message) = self.surface_file_problem() {
                    return Err(SceneError::Invalid {
                        path: name,
                        message,
                    });
                }
                let encoding = SurfaceEncoding::for_path(path);
                atomic_write(path, Durability::Durable, |w| {
                    let surface = self.objects[0].surface().expect("checked above");
                    write_surface(surface, encoding, w)
                })
            }
        };
        written.map_err(|source| SceneError::Io { path: name, source })
    }
}

/// The points (x, y) and values z of a CSV text: the columns named x, y and z in a header
/// line, or the first three. At least three rows; every number finite.
fn read_points_csv(text: &str) -> Result<(Vec<nalgebra::Point2<f64>>, Vec<f64>), String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let split = |l: &str| -> Vec<String> {
        l.split([',', ';', '\t'])
            .map(|f| f.trim().trim_matches('"').to_string())
            .collect()
    };
    let Some((first_no, first)) = lines.next() else {
        return Err("the file holds no points".into());
    };
    let fields = split(first);
    let numeric = fields.iter().all(|f| f.parse::<f64>().is_ok());
    let columns = if numeric {
        [0, 1, 2]
    } else {
        let find = |name: &str| fields.iter().position(|f| f.eq_ignore_ascii_case(name));
        match (find("x"), find("y"), find("z")) {
            (Some(x), Some(y), Some(z)) => [x, y, z],
            _ => [0, 1, 2],
        }
    };
    let mut points = Vec::new();
    let mut values = Vec::new();
    let rows = if numeric {
        vec![(first_no, first)]
    } else {
        vec![]
    };
    for (no, line) in rows.into_iter().chain(lines) {
        let f = split(line);
        let get = |c: usize| -> Result<f64, String> {
            let t = f
                .get(c)
                .ok_or(format!("line {}: fewer than 3 columns", no + 1))?;
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && v.abs() <= pssurf::limits::MAX_VALUE)
                .ok_or(format!("line {}: `{t}` is not a finite number", no + 1))
        };
        points.push(nalgebra::Point2::new(get(columns[0])?, get(columns[1])?));
        values.push(get(columns[2])?);
    }
    if points.len() < 3 {
        return Err(format!(
            "{} points: a surface needs at least 3",
            points.len()
        ));
    }
    Ok((points, values))
}

#[cfg(test)]
mod fuzz {
    //! Issue 13: scene files with any number replaced by an extreme one, or any span cut
    //! out, are refused with a message or load into a scene that saves and loads again.

    use super::*;
    use proptest::prelude::*;

    const EXTREMES: [&str; 10] = [
        "0",
        "-0",
        "1e300",
        "-1e300",
        "1e-300",
        "1.7976931348623157e308",
        "1e309",
        "12345678901234567890",
        "-1",
        "4.9e-324",
    ];

    /// The byte ranges of the numbers in a JSON text.
    fn numbers(text: &str) -> Vec<(usize, usize)> {
        let b = text.as_bytes();
        let mut out = Vec::new();
        let mut k = 0;
        while k < b.len() {
            if b[k] == b'-' || b[k].is_ascii_digit() {
                let start = k;
                while k < b.len() && matches!(b[k], b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E')
                {
                    k += 1;
                }
                out.push((start, k));
            } else {
                k += 1;
            }
        }
        out
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        #[test]
        fn mutated_scene_files_load_or_fail_cleanly(
            edits in proptest::collection::vec((any::<usize>(), 0usize..EXTREMES.len()), 0..4),
            cut in proptest::option::of((any::<usize>(), 0usize..60)),
        ) {
            let mut text = crate::demo::scene().to_json();
            for (which, value) in edits {
                let spans = numbers(&text);
                let (a, b) = spans[which % spans.len()];
                text.replace_range(a..b, EXTREMES[value]);
            }
            if let Some((at, len)) = cut {
                let a = at % text.len();
                let b = (a + len).min(text.len());
                text.replace_range(a..b, "");
            }
            if let Ok(scene) = Scene::from_json(&text, "fuzz") {
                let again = Scene::from_json(&scene.to_json(), "fuzz");
                prop_assert!(again.is_ok(), "{:?}", again.err());
            }
        }

        /// Any text imported as points gives a scene or an error, never a panic.
        #[test]
        fn any_points_text_gives_a_scene_or_an_error(
            rows in proptest::collection::vec(
                proptest::collection::vec(
                    prop_oneof![
                        (-10.0f64..10.0).prop_map(|x| x.to_string()),
                        proptest::sample::select(EXTREMES.to_vec()).prop_map(str::to_string),
                        Just("x".to_string()),
                        Just(String::new()),
                    ],
                    0..5,
                ),
                0..12,
            )
        ) {
            let text: String = rows.iter().map(|r| r.join(",") + "\n").collect();
            let _ = Scene::from_points(&text, "fuzz");
        }
    }
}

#[cfg(test)]
mod binary_files {
    use super::*;

    /// A one-surface document saved under a `.psb` name is a binary surface file that the
    /// library loads; the application opens it again as the same surface file.
    #[test]
    fn surface_files_named_psb_are_binary_and_open_again() {
        let dir = tempfile::tempdir().unwrap();
        let scene = crate::demo::scene();
        let one = Scene {
            objects: vec![scene.objects[0].clone()],
        };
        let path = dir.path().join("one.psb");
        one.save_as(&path, FileKind::Surface).unwrap();
        assert!(pssurf::io::is_binary_surface_file(&path));
        let (back, kind) = Scene::load_file(&path).unwrap();
        assert_eq!(kind, FileKind::Surface);
        assert_eq!(back.objects[0].name, "one");
        assert_eq!(
            pssurf::io::to_json_string(back.objects[0].surface().unwrap()),
            pssurf::io::to_json_string(one.objects[0].surface().unwrap())
        );
        // A cut binary file is refused with its name.
        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
        let e = Scene::load_file(&path).unwrap_err().to_string();
        assert!(e.contains("one.psb") && e.contains("truncated"), "{e}");
    }
}

#[cfg(test)]
mod mesh_objects {
    use super::*;

    /// A subdivision beyond the mesh object's size is refused before anything is computed,
    /// with the count in the message.
    #[test]
    fn oversized_subdivisions_are_refused_in_words() {
        let recipe = RefinedMesh {
            control: Mesh::octahedron(),
            scheme: pssurf::subdivision::SurfaceScheme::Loop,
            times: 10,
        };
        let e = MeshShape::new(recipe).unwrap_err();
        assert!(
            e.contains("10 step(s) of loop") && e.contains("more than the 4 million"),
            "{e}"
        );
    }
}
