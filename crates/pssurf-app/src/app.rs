//! The application: the document, the saved view state, the runtime resources and the views,
//! and the one place where commands change them.
//!
//! Each frame the views draw from a read-only [`ViewContext`] and emit [`Command`]s; after
//! the frame [`App::apply`] applies them in order. The layout: menu bar; scene tree and
//! properties on the left; the 3D view in the centre; the domain view, display and probe
//! settings and the algorithm panels on the right; a status bar below.

use std::path::PathBuf;
use std::sync::Arc;

use egui::Rect;
use nalgebra::Point2;
use pssurf::interrogate::CurvatureQuantity;
use pssurf::surface::{ControlId, ControlNet, ControlPoint};
use pssurf_viz::MeshFormat;

use crate::command::{Command, FrameTarget, ObjectEdit, ViewContext};
use crate::create::NewSurface;
use crate::display::{ObjectMesh, ViewMode};
use crate::document::{Document, Selection};
use crate::domain_view::DomainView;
use crate::edit::{self, VertexControl};
use crate::export::ExportDialog;
use crate::files::{Answer, Files, Intent, Purpose};
use crate::menu::MenuBar;
use crate::panels::{Panel, default_panels};
use crate::probe::Probe;
use crate::properties::Properties;
use crate::runtime::Runtime;
use crate::scene::{FileKind, NO_CONTROLS, Scene, SceneObject, Shape};
use crate::scene_tree::SceneTree;
use crate::state::ViewState;
use crate::view_settings::{DisplayPanel, ProbePanel};
use crate::view3d::View3d;

/// The views and dialogs, each with its own transient state.
pub struct Views {
    /// The menu bar.
    pub menu: MenuBar,
    /// The scene tree.
    pub scene_tree: SceneTree,
    /// The selected object's properties and control points.
    pub properties: Properties,
    /// The domain view.
    pub domain: DomainView,
    /// The 3D view.
    pub view3d: View3d,
    /// The display settings.
    pub display: DisplayPanel,
    /// The probe's settings and values.
    pub probe: ProbePanel,
    /// The "New surface" dialog.
    pub new_surface: NewSurface,
    /// The Export dialog.
    pub export: ExportDialog,
    /// The algorithm panels.
    pub panels: Vec<Box<dyn Panel>>,
    /// The file chooser.
    pub files: Files,
}

impl Default for Views {
    fn default() -> Self {
        Views {
            menu: MenuBar,
            scene_tree: SceneTree,
            properties: Properties::default(),
            domain: DomainView::default(),
            view3d: View3d::default(),
            display: DisplayPanel,
            probe: ProbePanel,
            new_surface: NewSurface::default(),
            export: ExportDialog::default(),
            panels: default_panels(),
            files: Files::default(),
        }
    }
}

/// The application.
pub struct App {
    /// The open document: scene, selection, history.
    pub doc: Document,
    /// The view settings saved between sessions.
    pub view: ViewState,
    /// The drawable geometry, the probe and the GPU.
    pub runtime: Runtime,
    /// The views and dialogs.
    pub views: Views,
    /// The status bar's message.
    pub status: String,
    /// An error shown in a window until dismissed.
    pub error: Option<String>,
    /// Where autosaves go (None: no autosave).
    pub autosave: Option<PathBuf>,
    /// Where the view settings are saved on exit (None: not saved).
    pub view_file: Option<PathBuf>,
    /// What waits for the answer to the unsaved-changes question.
    pub pending: Option<Intent>,
    /// What to do once the document is saved (the question was answered "Save").
    after_save: Option<Intent>,
    /// Set when the window may close (the question was answered, or nothing was unsaved).
    closing: bool,
    /// The window title last sent.
    title_sent: String,
    /// Where the parts of the window were drawn in the last frame.
    pub layout: Layout,
    pending_frame: Option<FrameTarget>,
    last_autosave: f64,
}

impl App {
    /// An application showing `scene`, with default view settings.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        App::with_document(Document::new(scene, path))
    }

    /// An application showing the file `path` (a surface or scene file, `kind`) holding
    /// `scene`.
    pub fn from_file(scene: Scene, path: PathBuf, kind: FileKind) -> Self {
        App::with_document(Document::from_file(scene, path, kind))
    }

    fn with_document(doc: Document) -> Self {
        let views = Views::default();
        App {
            doc,
            view: ViewState::default(),
            runtime: Runtime::default(),
            views,
            status: String::new(),
            error: None,
            autosave: None,
            view_file: None,
            pending: None,
            after_save: None,
            closing: false,
            title_sent: String::new(),
            layout: Layout::default(),
            pending_frame: Some(FrameTarget::All),
            last_autosave: 0.0,
        }
    }

    /// The built-in demo: a curvature-coloured UPS patch and a NURPS paraboloid.
    pub fn demo() -> Self {
        let mut app = App::new(crate::demo::scene(), None);
        app.view.display.mode = ViewMode::Curvature(CurvatureQuantity::Mean);
        app.status =
            "demo scene: a UPS wave patch coloured by mean curvature, and a NURPS paraboloid"
                .into();
        app
    }

    /// Takes over saved view settings, the panels' included.
    pub fn restore_view(&mut self, view: ViewState) {
        for p in &mut self.views.panels {
            if let Some(s) = view.panels.get(p.title()) {
                p.restore(s);
            }
        }
        self.view = view;
    }

    /// The view settings to save, the panels' included.
    pub fn view_state(&self) -> ViewState {
        let mut view = self.view.clone();
        for p in &self.views.panels {
            if let Some(s) = p.settings() {
                view.panels.insert(p.title().to_string(), s);
            }
        }
        view
    }

    /// Installs the 3D view's GPU resources and keeps the device for offscreen pictures.
    pub fn attach_gpu(&mut self, state: eframe::egui_wgpu::RenderState) {
        crate::gpu::ViewResources::install(&state);
        self.runtime.gpu = Some(state);
    }

    /// The window title: the document's name, `*` first when it has unsaved changes.
    pub fn title(&self) -> String {
        let mark = if self.doc.dirty { "*" } else { "" };
        format!("{mark}{} — pssurf", self.doc.name())
    }

    /// Asks for `intent`. When it would replace a document with unsaved changes, the
    /// question (save, discard, cancel) is asked first and the intent waits for its answer.
    pub fn request(&mut self, intent: Intent) {
        if self.doc.dirty {
            self.pending = Some(intent);
        } else {
            self.carry_out(intent);
        }
    }

    fn carry_out(&mut self, intent: Intent) {
        match intent {
            Intent::Open(path) => self.open(path),
            Intent::New => {
                self.doc = Document::default();
                self.runtime.probe.clear();
                self.error = None;
                self.status = "new scene".into();
            }
            Intent::Quit => self.closing = true,
        }
    }

    /// Goes on with what waited for the unsaved-changes question.
    pub fn answer(&mut self, answer: Answer) {
        let Some(intent) = self.pending.take() else {
            return;
        };
        match answer {
            Answer::Cancel => self.status = "cancelled: the changes are kept".into(),
            Answer::Discard => self.carry_out(intent),
            Answer::Save => {
                self.after_save = Some(intent);
                self.save();
            }
        }
    }

    /// Opens a scene or surface file, replacing the document (without asking: see
    /// [`App::request`]); a bad file leaves the document unchanged and says why.
    pub fn open(&mut self, path: PathBuf) {
        match Scene::load_file(&path) {
            Ok((scene, kind)) => {
                // An imported file (IGES, points, a mesh) becomes an untitled scene: saving
                // must not write JSON over it.
                self.doc = if crate::scene::is_import_path(&path) {
                    Document::new(scene, None)
                } else {
                    Document::from_file(scene, path.clone(), kind)
                };
                self.runtime.probe.clear();
                crate::files::remember(&mut self.view.recent, &path);
                self.error = None;
                self.status = format!("opened {} ({})", path.display(), kind.name());
                self.pending_frame = Some(FrameTarget::All);
            }
            Err(e) => {
                self.status = format!("could not open {}", path.display());
                self.error = Some(format!("Could not open the file.\n\n{e}"));
            }
        }
    }

    /// Adds the objects of a scene or surface file to the scene (one undo step), beside the
    /// objects already there.
    pub fn add_file(&mut self, path: &std::path::Path) {
        match Scene::load(path) {
            Ok(loaded) => {
                let n = loaded.objects.len();
                self.add_objects(loaded.objects, "add file");
                self.error = None;
                self.status = format!("added {n} object(s) from {}", path.display());
            }
            Err(e) => {
                self.status = format!("could not add {}", path.display());
                self.error = Some(format!("Could not add the file.\n\n{e}"));
            }
        }
    }

    /// Saves the document to its file, of its kind. Asks where (Save As) when it has no file
    /// yet, or when its file is a surface file that cannot hold the scene any more.
    pub fn save(&mut self) {
        let fits = self.doc.scene.surface_file_problem();
        match (self.doc.path.clone(), self.doc.kind, fits) {
            (Some(path), FileKind::Scene, _) => self.save_to(path, FileKind::Scene),
            (Some(path), FileKind::Surface, None) => self.save_to(path, FileKind::Surface),
            (Some(_), FileKind::Surface, Some(why)) => {
                self.status = format!("{why}: choose where to save it as a scene");
                self.save_as(FileKind::Scene);
            }
            (None, kind, _) => self.save_as(kind),
        }
    }

    /// Opens the chooser to save as a file of `kind` (a scene when a surface file cannot
    /// hold the scene).
    pub fn save_as(&mut self, kind: FileKind) {
        let kind = match self.doc.scene.surface_file_problem() {
            Some(_) => FileKind::Scene,
            None => kind,
        };
        let name = match (&self.doc.path, kind == self.doc.kind) {
            (Some(p), true) => crate::files::file_name(p),
            _ => self.suggested_stem() + ".json",
        };
        let folder = self.doc.path.as_ref().and_then(|p| p.parent());
        let folder = folder.map(std::path::Path::to_path_buf);
        self.views
            .files
            .choose(Purpose::SaveAs(kind), folder.as_deref(), &name);
    }

    /// A file stem for a new file: the document's, else the only object's name, else
    /// "scene".
    fn suggested_stem(&self) -> String {
        let stem = match (&self.doc.path, self.doc.scene.objects.as_slice()) {
            (Some(p), _) => p
                .file_stem()
                .map_or("scene".into(), |s| s.to_string_lossy().into_owned()),
            (None, [o]) => o.name.clone(),
            _ => "scene".into(),
        };
        stem.replace(
            |c: char| !(c.is_alphanumeric() || c == '-' || c == '_'),
            "_",
        )
    }

    /// Saves to `path` as a file of `kind` (atomically); the file becomes the document's.
    pub fn save_to(&mut self, path: PathBuf, kind: FileKind) {
        match self.doc.scene.save_as(&path, kind) {
            Ok(()) => {
                self.status = format!("saved {} ({})", path.display(), kind.name());
                crate::files::remember(&mut self.view.recent, &path);
                self.doc.path = Some(path);
                self.doc.kind = kind;
                self.doc.dirty = false;
                self.error = None;
                if let Some(intent) = self.after_save.take() {
                    self.carry_out(intent);
                }
            }
            Err(e) => {
                self.after_save = None;
                self.status = format!("not saved: {e}");
                self.error = Some(format!("Could not save.\n\n{e}"));
            }
        }
    }

    /// Runs files dropped on the window: one file on an empty, unmodified document opens
    /// it; otherwise their objects are added to the scene.
    pub fn dropped(&mut self, paths: Vec<PathBuf>) {
        if let [path] = paths.as_slice()
            && self.doc.scene.objects.is_empty()
            && !self.doc.dirty
        {
            return self.open(path.clone());
        }
        for p in paths {
            self.add_file(&p);
        }
    }

    /// Undoes the last edit.
    pub fn undo(&mut self) {
        if let Some(name) = self.doc.undo_name().map(str::to_owned) {
            self.doc.undo();
            self.status = format!("undid {name}");
        }
    }

    /// Redoes the last undone edit.
    pub fn redo(&mut self) {
        if let Some(name) = self.doc.redo_name().map(str::to_owned) {
            self.doc.redo();
            self.status = format!("redid {name}");
        }
    }

    /// Sets a vertex's control points as one undoable edit; only the vertex's support is
    /// re-sampled.
    pub fn set_vertex(
        &mut self,
        object: usize,
        vertex: usize,
        c: VertexControl,
    ) -> Result<(), String> {
        let old = self.revision(object)?;
        let mut pieces = Vec::new();
        self.doc.edit("edit control points", |scene| {
            let o = &mut scene.objects[object];
            let surface = o.surface_mut().ok_or_else(|| NO_CONTROLS.to_string())?;
            pieces = edit::set_vertex_control(surface, vertex, &c)?;
            Ok::<(), String>(())
        })?;
        self.update_vertex_mesh(object, old, vertex, &pieces);
        Ok(())
    }

    /// Sets a vertex's control points during a drag: no undo step of its own (see
    /// [`Document::checkpoint`]), and only the vertex's support is re-sampled and uploaded.
    pub fn drag_vertex(
        &mut self,
        object: usize,
        vertex: usize,
        c: VertexControl,
    ) -> Result<(), String> {
        let old = self.revision(object)?;
        let mut result = Ok(Vec::new());
        self.doc.edit_continuing(|scene| {
            let o = &mut scene.objects[object];
            result = match o.surface_mut() {
                Some(surface) => edit::set_vertex_control(surface, vertex, &c),
                None => Err(NO_CONTROLS.to_string()),
            };
            if result.is_err() {
                // The library changed nothing: the cached meshes stay valid.
                o.revision = old;
            }
        });
        let pieces = result?;
        self.update_vertex_mesh(object, old, vertex, &pieces);
        Ok(())
    }

    /// Sets several control points of an object: one undo step named `what`, or (None) a step
    /// of a drag. The object's meshes are rebuilt (an edit by curvature moves many control
    /// triangles); traced curves follow.
    pub fn set_controls(
        &mut self,
        object: usize,
        what: Option<&'static str>,
        changes: &[(ControlId, ControlPoint)],
    ) -> Result<(), String> {
        let old = self.revision(object)?;
        let mut pieces = Vec::new();
        let mut apply = |scene: &mut Scene| -> Result<(), String> {
            let o = &mut scene.objects[object];
            pieces = o
                .surface_mut()
                .ok_or_else(|| NO_CONTROLS.to_string())?
                .set_control_points(changes)
                .map_err(|e| e.to_string())?;
            Ok(())
        };
        match what {
            Some(name) => self.doc.edit(name, &mut apply)?,
            None => {
                let mut result = Ok(());
                self.doc.edit_continuing(|scene| {
                    result = apply(scene);
                    if result.is_err() {
                        scene.objects[object].revision = old;
                    }
                });
                result?
            }
        }
        if let Some(o) = self.doc.scene.objects.get(object) {
            self.runtime.curves.edited(o, old, &pieces);
        }
        Ok(())
    }

    fn revision(&self, object: usize) -> Result<u64, String> {
        self.doc
            .scene
            .objects
            .get(object)
            .map(|o| o.revision)
            .ok_or_else(|| format!("there is no object {object}"))
    }

    fn update_vertex_mesh(&mut self, object: usize, old: u64, vertex: usize, pieces: &[usize]) {
        let display = &self.view.display;
        let scene = &self.doc.scene;
        if let Some(o) = scene.objects.get(object) {
            self.runtime.curves.edited(o, old, pieces);
        }
        (self.runtime.cache).update_vertex(scene, object, old, vertex, pieces, display);
    }

    /// Rebuilds the geometry if the scene or the display settings changed (only objects
    /// whose revision is new are sampled).
    pub fn update_geometry(&mut self) {
        self.runtime
            .cache
            .update(&self.doc.scene, &self.view.display);
    }

    /// Like [`App::update_geometry`], but a large rebuild runs on another thread while the
    /// previous geometry stays drawn (see [`crate::cache::GeometryCache::update_in_background`]);
    /// what the view does each frame.
    pub fn update_geometry_in_background(&mut self) {
        (self.runtime.cache).update_in_background(&self.doc.scene, &self.view.display);
    }

    /// The cached mesh of an object (after [`App::update_geometry`]).
    pub fn object_mesh(&self, i: usize) -> Option<&ObjectMesh> {
        self.runtime.cache.object_mesh(&self.doc.scene, i)
    }

    /// The diameter of the drawn scene at the last geometry rebuild (1 before one).
    pub fn scene_size(&self) -> f64 {
        self.runtime.cache.scene_size()
    }

    /// The legend shown beside the view: the shared one, or the selected object's (None
    /// outside curvature plots).
    pub fn legend(&self) -> Option<&crate::display::Legend> {
        let cache = &self.runtime.cache;
        match self.view.display.mode {
            ViewMode::Curvature(_) => cache.legend(&self.doc.scene, self.doc.selection.object),
            _ => None,
        }
    }

    /// The probe, if one is set.
    pub fn probe(&self) -> Option<&Probe> {
        self.runtime.probe.probe.as_ref()
    }

    /// Puts the probe on object `object` at parameters `uv` (removes it outside the domain).
    pub fn set_probe(&mut self, object: usize, uv: Point2<f64>) {
        let size = self.scene_size();
        let scene = &self.doc.scene;
        if (self.runtime.probe).set(scene, object, uv, &self.view.probe, size) {
            self.status = format!("probed {}", scene.objects[object].name);
            if self.doc.selection.object != Some(object) {
                self.doc.select(Selection::object(object));
            }
        }
    }

    /// Traces curves on object `object` (the status line says what came out, or why not).
    pub fn trace_curves(&mut self, object: usize, request: crate::curves::CurveRequest) {
        let what = request.describe();
        self.status = match self.runtime.curves.add(&self.doc.scene, object, request) {
            Ok(summary) => format!("traced {what}: {summary}"),
            Err(e) => format!("could not trace {what}: {e}"),
        };
        self.refresh_probe();
    }

    /// Recomputes the probe after its object changed, and its lines after the probe or its
    /// settings changed.
    pub fn refresh_probe(&mut self) {
        let size = self.scene_size();
        (self.runtime.probe).refresh(&self.doc.scene, &self.view.probe, size);
        self.runtime.curves.refresh(&self.doc.scene);
        self.runtime.join_extra_lines();
    }

    /// Fits the camera to the visible objects in a view of the given aspect ratio.
    pub fn frame_all(&mut self, aspect: f32) {
        self.frame(FrameTarget::All, aspect);
    }

    /// Fits the camera to the selected object (to everything when nothing visible is
    /// selected).
    pub fn frame_selection(&mut self, aspect: f32) {
        self.frame(FrameTarget::Selection, aspect);
    }

    fn frame(&mut self, target: FrameTarget, aspect: f32) {
        self.update_geometry();
        let cache = &self.runtime.cache;
        let selected = match target {
            FrameTarget::All => None,
            FrameTarget::Selection => (self.doc.selection.object)
                .and_then(|i| cache.object_mesh(&self.doc.scene, i))
                .and_then(|m| crate::display::bounds([m])),
        };
        if let Some((lo, hi)) = selected.or_else(|| cache.bounds()) {
            self.view.camera.frame(lo, hi, aspect);
        }
    }

    /// Writes the selected object's mesh with the current colours and fields (see
    /// [`crate::export::export_mesh`]).
    pub fn export_mesh(
        &mut self,
        path: &std::path::Path,
        format: MeshFormat,
    ) -> Result<(), String> {
        self.update_geometry();
        let (doc, display) = (&self.doc, &self.view.display);
        crate::export::export_mesh(doc, display, &self.runtime.cache, path, format)
    }

    /// Renders the 3D view to a PNG file (see [`crate::export::export_picture`]).
    pub fn export_picture(&mut self, path: &std::path::Path, size: [u32; 2]) -> Result<(), String> {
        crate::export::export_picture(&mut self.runtime, &self.doc, &self.view, path, size)
    }

    /// Applies one command (see [`Command`] for what each asks).
    pub fn apply(&mut self, command: Command) {
        match command {
            Command::Select(s) => self.doc.select(s),
            Command::SetProbe { object, uv } => self.set_probe(object, uv),
            Command::RemoveProbe => self.runtime.probe.clear(),
            Command::TraceCurves { object, request } => self.trace_curves(object, request),
            Command::ClearCurves(id) => {
                self.runtime.curves.clear(id);
                self.status = "removed the traced curves".into();
            }
            Command::SetVertex {
                object,
                vertex,
                control,
            } => self.report(|app| app.set_vertex(object, vertex, control)),
            Command::StartDrag => {
                self.doc.checkpoint("drag control point");
                self.runtime.cache.hold_colors = true;
            }
            Command::EndDrag => self.runtime.cache.hold_colors = false,
            Command::DragVertex {
                object,
                vertex,
                control,
            } => self.report(|app| app.drag_vertex(object, vertex, control)),
            Command::SetControls {
                object,
                what,
                changes,
            } => self.report(|app| app.set_controls(object, Some(what), &changes)),
            Command::DragControls { object, changes } => {
                self.report(|app| app.set_controls(object, None, &changes))
            }
            Command::MarkRegion(mark) => self.runtime.region = mark,
            Command::EditObject { object, edit } => self.edit_object(object, edit),
            Command::ToggleVisible(objects) => self.toggle_visible(&objects),
            Command::Delete(object) => self.delete(object),
            Command::Add(object) => self.add(object),
            Command::Insert { objects, what } => self.insert(objects, what),
            Command::ReplaceSurface {
                object,
                what,
                surface,
                status,
            } => self.replace_shape(object, what, Shape::Surface(Arc::new(*surface)), status),
            Command::InBackground { what, work } => self.start_task(what, work),
            Command::ReplaceMesh {
                id,
                what,
                mesh,
                status,
            } => match self.doc.scene.index_of(id) {
                Some(object) => self.replace_shape(object, what, Shape::Mesh(mesh), status),
                None => self.status = "not subdivided: the mesh was deleted meanwhile".into(),
            },
            Command::ReplaceSurfaces {
                surfaces,
                what,
                status,
            } => self.replace_surfaces(surfaces, what, status),
            Command::Frame(target) => self.pending_frame = Some(target),
            Command::Open(path) => self.request(Intent::Open(path)),
            Command::New => self.request(Intent::New),
            Command::Quit => self.request(Intent::Quit),
            Command::AddFile(path) => self.add_file(&path),
            Command::Choose(Purpose::SaveAs(kind)) => self.save_as(kind),
            Command::Choose(purpose) => {
                let folder = self.doc.path.as_ref().and_then(|p| p.parent());
                let folder = folder.map(std::path::Path::to_path_buf);
                let name = self.views.export.file_name();
                self.views.files.choose(purpose, folder.as_deref(), &name);
            }
            Command::RecoverAutosave => self.recover_autosave(),
            Command::Save => self.save(),
            Command::SaveTo { path, kind } => self.save_to(path, kind),
            Command::SaveCancelled => {
                if self.after_save.take().is_some() {
                    self.status = "not saved: nothing else was done".into();
                }
            }
            Command::Answer(a) => self.answer(a),
            Command::SetExportPath(path) => self.views.export.path = path.display().to_string(),
            Command::Undo => self.undo(),
            Command::Redo => self.redo(),
            Command::SetDisplay(d) => self.view.display = d,
            Command::SetLight(l) => self.view.light = l,
            Command::SetProbeSettings(s) => self.view.probe = s,
            Command::SetCamera(c) => self.view.camera = c,
            Command::OpenNewSurface(shape) => self.views.new_surface.open(shape),
            Command::OpenExport(what) => self.views.export.open(what, &self.doc),
            Command::ExportMesh { path, format } => {
                let result = self.export_mesh(&path, format);
                self.exported(&path, result);
            }
            Command::ExportSurface { path } => {
                let result = crate::export::export_surface(&self.doc, &path);
                self.exported(&path, result);
            }
            Command::ExportPicture { path, size } => {
                let result = self.export_picture(&path, size);
                self.exported(&path, result);
            }
            Command::Status(s) => self.status = s,
            Command::Error(e) => self.error = Some(e),
        }
    }

    /// Runs an action, putting its error in the status bar.
    fn report(&mut self, action: impl FnOnce(&mut App) -> Result<(), String>) {
        if let Err(e) = action(self) {
            self.status = e;
        }
    }

    fn edit_object(&mut self, object: usize, edit: ObjectEdit) {
        if object >= self.doc.scene.objects.len() {
            return;
        }
        let what = match &edit {
            ObjectEdit::Rename(_) => "rename",
            ObjectEdit::Group(_) => "group",
            ObjectEdit::Material(_) => "material",
            ObjectEdit::Transform(_) => "transform",
        };
        let _ = self.doc.edit::<()>(what, |s| {
            let o = &mut s.objects[object];
            match edit {
                ObjectEdit::Rename(name) => o.name = name,
                ObjectEdit::Group(group) => o.group = group,
                ObjectEdit::Material(m) => {
                    o.material = m;
                    o.touch();
                }
                ObjectEdit::Transform(t) => {
                    o.transform = t;
                    o.touch();
                }
            }
            Ok(())
        });
    }

    fn toggle_visible(&mut self, objects: &[usize]) {
        let n = self.doc.scene.objects.len();
        let _ = self.doc.edit::<()>("show/hide", |s| {
            for &i in objects.iter().filter(|&&i| i < n) {
                s.objects[i].visible = !s.objects[i].visible;
            }
            Ok(())
        });
    }

    fn delete(&mut self, object: usize) {
        let Some(name) = self.doc.scene.objects.get(object).map(|o| o.name.clone()) else {
            return;
        };
        let _ = self.doc.edit::<()>("delete", |s| {
            s.objects.remove(object);
            Ok(())
        });
        self.doc.selection = Selection::default();
        self.status = format!("deleted {name}");
    }

    fn add(&mut self, objects: Vec<SceneObject>) {
        let name = match objects.as_slice() {
            [one] => one.name.clone(),
            [first, ..] if !first.group.is_empty() => {
                format!("{} ({} patches)", first.group, objects.len())
            }
            _ => format!("{} objects", objects.len()),
        };
        self.add_objects(objects, "new surface");
        self.status = format!("created {name}");
    }

    /// Adds objects where they are as one undo step and selects the first.
    fn insert(&mut self, objects: Vec<SceneObject>, what: &str) {
        if objects.is_empty() {
            return;
        }
        let first = self.doc.scene.objects.len();
        let count = objects.len();
        let _ = self.doc.edit::<()>(what, |scene| {
            scene.objects.extend(objects);
            Ok(())
        });
        self.doc.select(Selection::object(first));
        self.status = format!("{what}: {count} new object(s)");
    }

    /// Adds objects as one undo step, placed together beside the visible objects (to the
    /// right, along x, centred in y), selects the first, and frames the view.
    fn add_objects(&mut self, mut objects: Vec<SceneObject>, what: &str) {
        if objects.is_empty() {
            return;
        }
        self.update_geometry();
        if let Some(existing) = self.runtime.cache.bounds() {
            crate::display::place_beside(&mut objects, existing);
        }
        let first = self.doc.scene.objects.len();
        let _ = self.doc.edit::<()>(what, |scene| {
            scene.objects.extend(objects);
            Ok(())
        });
        self.doc.select(Selection::object(first));
        self.pending_frame = Some(FrameTarget::All);
    }

    /// Starts a computation on another thread (one at a time).
    fn start_task(&mut self, what: String, work: crate::command::BackgroundWork) {
        if let Some(t) = &self.runtime.task {
            self.status = format!("wait: {} is still running", t.what);
            return;
        }
        let Some(work) = work.take() else {
            return;
        };
        let (send, result) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            // The receiver is gone only when the application has closed.
            let _ = send.send(work());
        });
        self.runtime.task = Some(crate::runtime::BackgroundTask {
            what,
            started: std::time::Instant::now(),
            result,
        });
    }

    /// Whether a background rebuild or task is still running (the busy indicator shows).
    pub fn is_busy(&self) -> bool {
        self.runtime.task.is_some() || self.runtime.cache.busy().is_some()
    }

    /// Applies the command of a finished background task; whether one still runs.
    pub fn poll_task(&mut self) -> bool {
        let Some(task) = &self.runtime.task else {
            return false;
        };
        match task.result.try_recv() {
            Ok(command) => {
                self.runtime.task = None;
                self.apply(command);
                false
            }
            Err(std::sync::mpsc::TryRecvError::Empty) => true,
            Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                self.status = format!("{} failed", task.what);
                self.runtime.task = None;
                false
            }
        }
    }

    fn replace_shape(&mut self, object: usize, what: &str, shape: Shape, status: String) {
        if object >= self.doc.scene.objects.len() {
            return;
        }
        let _ = self.doc.edit::<()>(what, |scene| {
            scene.objects[object].set_shape(shape);
            Ok(())
        });
        self.status = status;
    }

    fn replace_surfaces(
        &mut self,
        surfaces: Vec<(usize, Box<pssurf::surface::Surface>)>,
        what: &str,
        status: String,
    ) {
        let count = self.doc.scene.objects.len();
        if surfaces.is_empty() || surfaces.iter().any(|(o, _)| *o >= count) {
            return;
        }
        let _ = self.doc.edit::<()>(what, |scene| {
            for (object, surface) in surfaces {
                scene.objects[object].set_shape(Shape::Surface(Arc::new(*surface)));
            }
            Ok(())
        });
        self.status = status;
    }

    fn recover_autosave(&mut self) {
        if let Some(p) = self.autosave.clone() {
            self.open(p);
            self.doc.path = None;
            self.doc.kind = FileKind::Scene;
            self.doc.dirty = true;
        }
    }

    fn exported(&mut self, path: &std::path::Path, result: Result<(), String>) {
        match result {
            Ok(()) => {
                self.status = format!("wrote {}", path.display());
                self.views.export.open = false;
            }
            Err(e) => {
                self.status = format!("not exported: {e}");
                self.error = Some(format!("Could not export.\n\n{e}"));
            }
        }
    }

    /// Draws the whole application, then applies what the views asked for.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        self.window_events(ui.ctx());
        let mut commands = self.shortcuts(ui.ctx());
        self.autosave_tick(ui.ctx());
        let task_running = self.poll_task();
        self.update_geometry_in_background();
        if task_running || self.runtime.cache.busy().is_some() {
            // Poll the background rebuild; the spinner turns meanwhile.
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(50));
        }
        self.refresh_probe();
        self.draw(ui, &mut commands);
        if !commands.is_empty() {
            for c in commands {
                self.apply(c);
            }
            // Draw the frame again with the commands applied (egui runs a second pass,
            // without the input already handled).
            ui.ctx().request_discard("commands applied");
            ui.ctx().request_repaint();
        }
    }

    /// The window's title, close requests (held back while changes are unsaved) and files
    /// dropped on it.
    fn window_events(&mut self, ctx: &egui::Context) {
        let title = self.title();
        if title != self.title_sent {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title_sent = title;
        }
        if ctx.input(|i| i.viewport().close_requested()) && !self.closing && self.doc.dirty {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.pending.get_or_insert(Intent::Quit);
        }
        if self.closing {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            (i.raw.dropped_files.iter())
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        if !dropped.is_empty() {
            self.dropped(dropped);
        }
    }

    /// Whether the application has agreed to close (nothing unsaved, or the question about
    /// it answered).
    pub fn closing(&self) -> bool {
        self.closing
    }

    /// Draws the panels, the 3D view and the dialogs; their requests go to `commands`.
    fn draw(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        self.side_panels(ui, commands);
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let legend = self.legend().cloned();
            let (view, strip) = match legend {
                Some(_) => rect.split_left_right_at_x(rect.right() - crate::legend::WIDTH),
                None => (rect, Rect::NOTHING),
            };
            // Framing waits for the geometry it frames.
            if self.runtime.cache.busy().is_none()
                && let Some(target) = self.pending_frame.take()
            {
                self.frame(target, view.width() / view.height().max(1.0));
            }
            if let Some(legend) = &legend {
                let display = &self.view.display;
                let note = crate::legend::range_note(display, legend);
                let map = crate::display::color_map(display);
                crate::legend::paint(ui, strip, legend, &map, &note);
            }
            self.layout.view = view;
            self.layout.legend = strip;
            let Parts { views, mut cx, .. } = self.parts(commands);
            let mut child = ui.new_child(egui::UiBuilder::new().max_rect(view));
            views.view3d.ui(&mut child, &mut cx);
        });
        let Parts {
            views,
            mut cx,
            error,
            pending,
            ..
        } = self.parts(commands);
        views.new_surface.window(ui.ctx(), &mut cx);
        views.export.window(ui.ctx(), &mut cx);
        views.files.window(ui.ctx(), &mut cx);
        if let Some(intent) = pending {
            crate::files::unsaved_question(ui.ctx(), &cx.doc.name(), intent, &mut cx);
        }
        error_window(ui.ctx(), error);
    }

    /// The views, and a context over the rest of the application for them to draw from.
    fn parts<'a>(&'a mut self, commands: &'a mut Vec<Command>) -> Parts<'a> {
        let App {
            doc,
            view,
            runtime,
            views,
            autosave,
            status,
            error,
            pending,
            layout,
            ..
        } = self;
        Parts {
            views,
            cx: ViewContext::new(doc, view, runtime, autosave.as_deref(), commands),
            status,
            error,
            pending: pending.as_ref(),
            layout,
        }
    }

    /// The menu bar, the status bar, and the left and right panels.
    fn side_panels(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let Parts {
            views,
            mut cx,
            status,
            layout,
            ..
        } = self.parts(commands);
        egui::Panel::top("menu").show(ui, |ui| views.menu.ui(ui, &mut cx));
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                if let Some(task) = &cx.runtime.task {
                    ui.spinner();
                    ui.label(format!("{}…", task.what));
                    ui.separator();
                }
                if let Some(busy) = cx.runtime.cache.busy() {
                    ui.spinner();
                    ui.label(busy.message());
                    ui.separator();
                }
                ui.label(status);
                if let Some(p) = cx.probe() {
                    ui.separator();
                    ui.monospace(p.summary());
                }
            });
        });
        // The side panels scroll (both ways) rather than grow: numbers changing width never
        // move the panels, and at 1280×800 the content fits their default widths.
        let left = egui::Panel::left("scene")
            .resizable(true)
            .default_size(LEFT_WIDTH)
            .size_range(LEFT_WIDTH * 0.8..=LEFT_WIDTH * 2.0)
            .show(ui, |ui| {
                // Not shrunk to the content: a floating scroll bar at the bottom of short
                // content would cover the lower half of its last row of buttons.
                egui::ScrollArea::both().auto_shrink(false).show(ui, |ui| {
                    views.scene_tree.ui(ui, &mut cx);
                    ui.separator();
                    views.properties.ui(ui, &mut cx);
                });
            });
        let right = egui::Panel::right("tools")
            .resizable(true)
            .default_size(RIGHT_WIDTH)
            .size_range(RIGHT_WIDTH * 0.8..=RIGHT_WIDTH * 2.0)
            .show(ui, |ui| {
                egui::ScrollArea::both()
                    .auto_shrink(false)
                    .show(ui, |ui| tools(ui, views, &mut cx));
            });
        *layout = Layout {
            left: left.response.rect,
            right: right.response.rect,
            ..*layout
        };
    }

    /// Keyboard shortcuts: undo, redo, framing, and the camera from the keyboard (arrows
    /// orbit, Shift+arrows pan, + and - zoom).
    fn shortcuts(&mut self, ctx: &egui::Context) -> Vec<Command> {
        if ctx.egui_wants_keyboard_input() {
            return Vec::new();
        }
        let mut commands = Vec::new();
        let kind = self.doc.kind;
        let files = ctx.input_mut(|i| {
            let command = egui::Modifiers::COMMAND;
            let shift_command = command | egui::Modifiers::SHIFT;
            [
                (i.consume_key(shift_command, egui::Key::S))
                    .then_some(Command::Choose(Purpose::SaveAs(kind))),
                i.consume_key(command, egui::Key::S)
                    .then_some(Command::Save),
                (i.consume_key(command, egui::Key::O)).then_some(Command::Choose(Purpose::Open)),
                i.consume_key(command, egui::Key::N).then_some(Command::New),
                i.consume_key(command, egui::Key::Q)
                    .then_some(Command::Quit),
            ]
        });
        commands.extend(files.into_iter().flatten());
        let (undo, redo, frame, frame_selection) = ctx.input_mut(|i| {
            let frame_selection = i.consume_key(egui::Modifiers::SHIFT, egui::Key::F);
            let redo = i.consume_key(
                egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
                egui::Key::Z,
            ) || i.consume_key(egui::Modifiers::COMMAND, egui::Key::Y);
            let undo = i.consume_key(egui::Modifiers::COMMAND, egui::Key::Z);
            let frame = i.consume_key(egui::Modifiers::NONE, egui::Key::F);
            (undo, redo, frame, frame_selection)
        });
        if frame_selection {
            commands.push(Command::Frame(FrameTarget::Selection));
        }
        if redo {
            commands.push(Command::Redo);
        } else if undo {
            commands.push(Command::Undo);
        }
        if frame {
            commands.push(Command::Frame(FrameTarget::All));
        }
        let camera = keyboard_camera(ctx, self.view.camera);
        if camera != self.view.camera {
            commands.push(Command::SetCamera(camera));
        }
        commands
    }

    fn autosave_tick(&mut self, ctx: &egui::Context) {
        let now = ctx.input(|i| i.time);
        if let Some(path) = &self.autosave
            && self.doc.dirty
            && now - self.last_autosave > 60.0
        {
            self.last_autosave = now;
            if let Some(dir) = path.parent() {
                let _ = std::fs::create_dir_all(dir);
            }
            if let Err(e) = self.doc.scene.save(path) {
                self.status = format!("autosave failed: {e}");
            }
        }
    }
}

/// The application split for drawing: the views (mutable), a read-only context over the
/// document, view state and runtime, and the status and error messages.
struct Parts<'a> {
    views: &'a mut Views,
    cx: ViewContext<'a>,
    status: &'a str,
    error: &'a mut Option<String>,
    pending: Option<&'a Intent>,
    layout: &'a mut Layout,
}

/// Where the parts of the window were drawn in the last frame (for tests of the layout).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// The left panel (scene tree, properties).
    pub left: Rect,
    /// The right panel (domain view, display, probe, algorithm panels).
    pub right: Rect,
    /// The 3D view.
    pub view: Rect,
    /// The legend strip beside the 3D view (`Rect::NOTHING` when there is none).
    pub legend: Rect,
}

impl Default for Layout {
    fn default() -> Self {
        Layout {
            left: Rect::NOTHING,
            right: Rect::NOTHING,
            view: Rect::NOTHING,
            legend: Rect::NOTHING,
        }
    }
}

/// The default width of the left panel, in points.
pub const LEFT_WIDTH: f32 = 310.0;
/// The default width of the right panel, in points.
pub const RIGHT_WIDTH: f32 = 320.0;

/// The right-hand panel: the domain view, the display and probe settings, the algorithm
/// panels.
fn tools(ui: &mut egui::Ui, views: &mut Views, cx: &mut ViewContext<'_>) {
    ui.heading("Domain");
    views.domain.ui(ui, cx);
    ui.separator();
    views.display.ui(ui, cx);
    egui::CollapsingHeader::new("Probe")
        .default_open(false)
        .show(ui, |ui| views.probe.ui(ui, cx));
    for p in &mut views.panels {
        egui::CollapsingHeader::new(p.title())
            .default_open(false)
            .show(ui, |ui| p.ui(ui, cx));
    }
}

/// The camera moved by the arrow and zoom keys pressed this frame.
fn keyboard_camera(
    ctx: &egui::Context,
    mut camera: crate::camera::OrbitCamera,
) -> crate::camera::OrbitCamera {
    let keys = ctx.input_mut(|i| {
        let mut take = |m, k| i.consume_key(m, k);
        use egui::{Key, Modifiers as M};
        [
            take(M::NONE, Key::ArrowLeft),
            take(M::NONE, Key::ArrowRight),
            take(M::NONE, Key::ArrowUp),
            take(M::NONE, Key::ArrowDown),
            take(M::SHIFT, Key::ArrowLeft),
            take(M::SHIFT, Key::ArrowRight),
            take(M::SHIFT, Key::ArrowUp),
            take(M::SHIFT, Key::ArrowDown),
            take(M::NONE, Key::Plus) || take(M::NONE, Key::Equals),
            take(M::NONE, Key::Minus),
        ]
    });
    if !keys.contains(&true) {
        return camera;
    }
    let step = 12.5; // 5° per press
    let [l, r, u, d, pl, pr, pu, pd, zoom_in, zoom_out] = keys.map(f32::from);
    camera.orbit(step * (l - r), step * (u - d));
    camera.pan(40.0 * (pr - pl), 40.0 * (pd - pu), 600.0);
    camera.zoom(1.25f32.powf(zoom_in - zoom_out));
    camera
}

/// The window showing an error until dismissed.
fn error_window(ctx: &egui::Context, error: &mut Option<String>) {
    let Some(msg) = error.clone() else {
        return;
    };
    egui::Window::new("Problem")
        .collapsible(false)
        .resizable(false)
        .show(ctx, |ui| {
            ui.label(msg);
            if ui.button("OK").clicked() {
                *error = None;
            }
        });
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        App::ui(self, ui);
    }

    fn on_exit(&mut self) {
        if let Some(path) = &self.view_file
            && let Err(e) = self.view_state().save(path)
        {
            eprintln!("could not save the view settings: {e}");
        }
    }
}
