//! What views and panels may ask of the application. They read the application through a
//! [`ViewContext`] and emit [`Command`]s; the application applies them after the frame, in
//! order. So no view changes the document, the view state or the runtime while another view
//! is drawing, and every change has one place where it happens (`App::apply`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use nalgebra::Point2;
use pssurf::surface::{ControlId, ControlPoint, Surface, UpsSurface};
use pssurf_viz::MeshFormat;

use crate::camera::OrbitCamera;
use crate::display::{DisplaySettings, Light};
use crate::document::{Document, Selection};
use crate::edit::VertexControl;
use crate::files::{Answer, Purpose};
use crate::probe::{Probe, ProbeSettings};
use crate::runtime::{RegionMark, Runtime};
use crate::scene::{FileKind, Material, MeshShape, SceneObject, Transform};
use crate::state::ViewState;

/// A change to one object's properties (each one undo step).
#[derive(Clone, Debug, PartialEq)]
pub enum ObjectEdit {
    /// A new name.
    Rename(String),
    /// A new group ("" for none).
    Group(String),
    /// A new material.
    Material(Material),
    /// A new placement.
    Transform(Transform),
}

/// Which part of the scene to fit into the 3D view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameTarget {
    /// Every visible object.
    All,
    /// The selected object (everything when nothing visible is selected).
    Selection,
}

/// What the "New surface" dialog makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// z = the formula.
    Formula,
    /// z = a x² + b xy + c y².
    Quadric,
    /// The cylinder as eight exact NURPS patches (thesis 3.6.1).
    Cylinder,
    /// The cone as six exact NURPS patches (thesis 3.6.2).
    Cone,
    /// The sphere as 2n exact NURPS patches with two thin open bands (thesis 3.6.3).
    Sphere,
}

impl Shape {
    /// Whether the shape is a closed quadric made of NURPS patches (not a UPS graph).
    pub fn is_solid_quadric(self) -> bool {
        matches!(self, Shape::Cylinder | Shape::Cone | Shape::Sphere)
    }
}

/// What to export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportKind {
    /// The selected object's mesh.
    Mesh,
    /// The 3D view as a PNG picture.
    Picture,
    /// The selected object's surface as a surface file.
    Surface,
}

/// Work for another thread: a computation that takes longer than a frame and ends in the
/// command to apply (see [`Command::InBackground`]). Cloning shares it; it runs once.
#[derive(Clone)]
pub struct BackgroundWork(Arc<std::sync::Mutex<Option<BoxedWork>>>);

/// The computation of a [`BackgroundWork`].
type BoxedWork = Box<dyn FnOnce() -> Command + Send>;

impl BackgroundWork {
    /// Wraps a computation.
    pub fn new(work: impl FnOnce() -> Command + Send + 'static) -> Self {
        BackgroundWork(Arc::new(std::sync::Mutex::new(Some(Box::new(work)))))
    }

    /// The computation, the first time it is asked for.
    pub fn take(&self) -> Option<BoxedWork> {
        self.0.lock().ok()?.take()
    }
}

impl std::fmt::Debug for BackgroundWork {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("BackgroundWork")
    }
}

/// A request from a view or panel, applied after the frame.
#[derive(Clone, Debug)]
pub enum Command {
    /// Run `work` on another thread, with a spinner saying `what` in the status bar, and
    /// apply the command it ends in (one task at a time: another is refused meanwhile).
    InBackground {
        /// What runs, for the busy indicator ("subdividing: loop × 4").
        what: String,
        /// The computation.
        work: BackgroundWork,
    },
    /// Select an object and possibly one of its vertices.
    Select(Selection),
    /// Put the probe on an object at parameters `uv` (removes it outside the domain).
    SetProbe {
        /// The object's index.
        object: usize,
        /// The parameters.
        uv: Point2<f64>,
    },
    /// Remove the probe.
    RemoveProbe,
    /// Trace curves on an object (kept and drawn until cleared; they follow edits).
    TraceCurves {
        /// The object's index.
        object: usize,
        /// What to trace.
        request: crate::curves::CurveRequest,
    },
    /// Remove the traced curves of one object (by identity), or all of them.
    ClearCurves(Option<u64>),
    /// Set a vertex's control points as one undoable edit.
    SetVertex {
        /// The object's index.
        object: usize,
        /// The vertex (control group).
        vertex: usize,
        /// The new control points.
        control: VertexControl,
    },
    /// Set several control points of an object as one undoable edit named `what` (an edit by
    /// curvature).
    SetControls {
        /// The object's index.
        object: usize,
        /// The edit's name for the Edit menu.
        what: &'static str,
        /// The new control points.
        changes: Vec<(ControlId, ControlPoint)>,
    },
    /// A step of a drag that sets several control points (after [`Command::StartDrag`]).
    DragControls {
        /// The object's index.
        object: usize,
        /// The new control points.
        changes: Vec<(ControlId, ControlPoint)>,
    },
    /// Show (or clear) the region of an edit by curvature in the domain view.
    MarkRegion(Option<RegionMark>),
    /// Start dragging a control point: one undo step for the whole drag, and the colour
    /// scales hold still until it ends.
    StartDrag,
    /// The drag ended: the colour scales are fitted to the data again.
    EndDrag,
    /// A step of a drag: set a vertex's control points without an undo step of its own.
    DragVertex {
        /// The object's index.
        object: usize,
        /// The vertex (control group).
        vertex: usize,
        /// The new control points.
        control: VertexControl,
    },
    /// Change an object's properties.
    EditObject {
        /// The object's index.
        object: usize,
        /// What changes.
        edit: ObjectEdit,
    },
    /// Show the hidden and hide the shown among these objects.
    ToggleVisible(Vec<usize>),
    /// Delete an object.
    Delete(usize),
    /// Add objects as one undoable edit and select the first.
    Add(Vec<SceneObject>),
    /// Replace the surfaces of several objects as one undoable edit (the patches of one
    /// hole-filling step).
    ReplaceSurfaces {
        /// (object index, new surface) pairs.
        surfaces: Vec<(usize, Box<pssurf::surface::Surface>)>,
        /// The edit's name for the Edit menu.
        what: &'static str,
        /// The status line afterwards.
        status: String,
    },
    /// Add objects where they are (not beside the others: a filling patch belongs in its
    /// hole) as one undoable edit named `what`, and select the first.
    Insert {
        /// The objects.
        objects: Vec<SceneObject>,
        /// The edit's name for the Edit menu.
        what: &'static str,
    },
    /// Replace an object's surface (a panel's result) as one undoable edit.
    ReplaceSurface {
        /// The object's index.
        object: usize,
        /// The edit's name for the Edit menu.
        what: &'static str,
        /// The new surface.
        surface: Box<Surface>,
        /// The status message on success.
        status: String,
    },
    /// Replace a mesh object's mesh (a new subdivision) as one undoable edit.
    ReplaceMesh {
        /// The object's identity ([`SceneObject::id`]: the result of a background task must
        /// find its object even if others were added or deleted meanwhile).
        id: u64,
        /// The edit's name for the Edit menu.
        what: &'static str,
        /// The new mesh.
        mesh: Arc<MeshShape>,
        /// The status message on success.
        status: String,
    },
    /// Fit part of the scene into the 3D view.
    Frame(FrameTarget),
    /// Open a scene or surface file, replacing the document (asking first about unsaved
    /// changes).
    Open(PathBuf),
    /// Start an empty scene (asking first about unsaved changes).
    New,
    /// Close the application (asking first about unsaved changes).
    Quit,
    /// Add the objects of a scene or surface file to the scene.
    AddFile(PathBuf),
    /// Open the file chooser for a purpose.
    Choose(Purpose),
    /// Open the autosaved scene as a new, unnamed document.
    RecoverAutosave,
    /// Save the document to its file, or ask where (Save As) when it has none or its file
    /// cannot hold it.
    Save,
    /// Save the document to `path` as a file of `kind`; it becomes the document's file.
    SaveTo {
        /// The file.
        path: PathBuf,
        /// Surface or scene file.
        kind: FileKind,
    },
    /// The user closed a Save As chooser without choosing.
    SaveCancelled,
    /// The answer to the unsaved-changes question.
    Answer(Answer),
    /// The Export dialog's file, chosen in the file chooser.
    SetExportPath(PathBuf),
    /// Undo the last edit.
    Undo,
    /// Redo the last undone edit.
    Redo,
    /// New display settings.
    SetDisplay(DisplaySettings),
    /// A new light.
    SetLight(Light),
    /// New probe settings.
    SetProbeSettings(ProbeSettings),
    /// A new camera.
    SetCamera(OrbitCamera),
    /// Open the "New surface" dialog on a shape.
    OpenNewSurface(Shape),
    /// Open the Export dialog with a suggested file name.
    OpenExport(ExportKind),
    /// Write the selected object's mesh.
    ExportMesh {
        /// The file.
        path: PathBuf,
        /// Its format.
        format: MeshFormat,
    },
    /// Render the 3D view to a PNG file.
    ExportPicture {
        /// The file.
        path: PathBuf,
        /// The picture's size in pixels.
        size: [u32; 2],
    },
    /// Write the selected object's surface as a surface file.
    ExportSurface {
        /// The file.
        path: PathBuf,
    },
    /// A message for the status bar.
    Status(String),
    /// A problem shown in a window until dismissed.
    Error(String),
}

/// What a view or panel sees of the application while it draws, and where its requests go.
pub struct ViewContext<'a> {
    /// The document (scene, selection, history).
    pub doc: &'a Document,
    /// The view settings.
    pub view: &'a ViewState,
    /// The drawable geometry, the probe and the GPU.
    pub runtime: &'a Runtime,
    /// Where autosaves go, if anywhere.
    pub autosave: Option<&'a Path>,
    commands: &'a mut Vec<Command>,
}

impl<'a> ViewContext<'a> {
    /// A context whose commands go to `commands`.
    pub fn new(
        doc: &'a Document,
        view: &'a ViewState,
        runtime: &'a Runtime,
        autosave: Option<&'a Path>,
        commands: &'a mut Vec<Command>,
    ) -> Self {
        ViewContext {
            doc,
            view,
            runtime,
            autosave,
            commands,
        }
    }

    /// Asks the application for something (applied after the frame).
    pub fn emit(&mut self, command: Command) {
        self.commands.push(command);
    }

    /// Sets the status bar's message.
    pub fn status(&mut self, message: impl Into<String>) {
        self.emit(Command::Status(message.into()));
    }

    /// The selected object's index, if it exists.
    pub fn selected(&self) -> Option<usize> {
        let i = self.doc.selection.object?;
        (i < self.doc.scene.objects.len()).then_some(i)
    }

    /// The selected object.
    pub fn object(&self) -> Option<&'a SceneObject> {
        let doc: &'a Document = self.doc;
        self.selected().map(|i| &doc.scene.objects[i])
    }

    /// The selected object's surface, unless it is a mesh.
    pub fn surface(&self) -> Option<&'a Arc<Surface>> {
        self.object().and_then(|o| o.surface())
    }

    /// The selected object's mesh, if it is one.
    pub fn mesh(&self) -> Option<&'a MeshShape> {
        self.object().and_then(|o| o.mesh_shape())
    }

    /// The selected object's uniform (UPS) form, if it has one.
    pub fn uniform(&self) -> Option<&'a UpsSurface> {
        self.surface().and_then(|s| s.uniform())
    }

    /// The probe, if one is set.
    pub fn probe(&self) -> Option<&'a Probe> {
        let runtime: &'a Runtime = self.runtime;
        runtime.probe.probe.as_ref()
    }
}
