//! The application: the document, the saved view state, the runtime resources and the views,
//! and the one place where commands change them.
//!
//! Each frame the views draw from a read-only [`ViewContext`] and emit [`Command`]s; after
//! the frame [`App::apply`] applies them in order. The layout: menu bar; scene tree and
//! properties on the left; the 3D view in the centre; the domain view, display and probe
//! settings and the algorithm panels on the right; a status bar below.

use std::path::PathBuf;

use nalgebra::Point2;
use pssurf::interrogate::CurvatureQuantity;
use pssurf_viz::MeshFormat;

use crate::command::{Command, FrameTarget, ObjectEdit, ViewContext};
use crate::create::NewSurface;
use crate::display::{ObjectMesh, ViewMode};
use crate::document::{Document, Selection};
use crate::domain_view::DomainView;
use crate::edit::{self, VertexControl};
use crate::export::ExportDialog;
use crate::menu::MenuBar;
use crate::panels::{Panel, default_panels};
use crate::probe::Probe;
use crate::properties::Properties;
use crate::runtime::Runtime;
use crate::scene::{Scene, SceneObject};
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
}

impl Default for Views {
    fn default() -> Self {
        Views {
            menu: MenuBar::default(),
            scene_tree: SceneTree,
            properties: Properties::default(),
            domain: DomainView,
            view3d: View3d::default(),
            display: DisplayPanel,
            probe: ProbePanel,
            new_surface: NewSurface::default(),
            export: ExportDialog::default(),
            panels: default_panels(),
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
    pending_frame: Option<FrameTarget>,
    last_autosave: f64,
}

impl App {
    /// An application showing `scene`, with default view settings.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        let mut views = Views::default();
        views.menu.path_text = path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        App {
            doc: Document::new(scene, path),
            view: ViewState::default(),
            runtime: Runtime::default(),
            views,
            status: String::new(),
            error: None,
            autosave: None,
            view_file: None,
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

    /// Opens a scene or surface file, replacing the document; a bad file leaves the scene
    /// unchanged and shows the message.
    pub fn open(&mut self, path: PathBuf) {
        match Scene::load(&path) {
            Ok(scene) => {
                self.doc = Document::new(scene, Some(path.clone()));
                self.views.menu.path_text = path.display().to_string();
                self.status = format!("opened {}", path.display());
                self.pending_frame = Some(FrameTarget::All);
            }
            Err(e) => self.error = Some(format!("Could not open the file.\n\n{e}")),
        }
    }

    /// Saves to `path` (atomically).
    pub fn save(&mut self, path: PathBuf) {
        match self.doc.scene.save(&path) {
            Ok(()) => {
                self.status = format!("saved {}", path.display());
                self.doc.path = Some(path);
                self.doc.dirty = false;
            }
            Err(e) => self.error = Some(format!("Could not save.\n\n{e}")),
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
            pieces = edit::set_vertex_control(o.surface_mut(), vertex, &c)?;
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
            result = edit::set_vertex_control(o.surface_mut(), vertex, &c);
            if result.is_err() {
                // The library changed nothing: the cached meshes stay valid.
                o.revision = old;
            }
        });
        let pieces = result?;
        self.update_vertex_mesh(object, old, vertex, &pieces);
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
        (self.runtime.cache).update_vertex(scene, object, old, vertex, pieces, display);
    }

    /// Rebuilds the geometry if the scene or the display settings changed (only objects
    /// whose revision is new are sampled).
    pub fn update_geometry(&mut self) {
        self.runtime
            .cache
            .update(&self.doc.scene, &self.view.display);
    }

    /// The cached mesh of an object (after [`App::update_geometry`]).
    pub fn object_mesh(&self, i: usize) -> Option<&ObjectMesh> {
        self.runtime.cache.object_mesh(&self.doc.scene, i)
    }

    /// The diameter of the drawn scene at the last geometry rebuild (1 before one).
    pub fn scene_size(&self) -> f64 {
        self.runtime.cache.scene_size()
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
            self.doc.selection.object = Some(object);
            self.status = format!("probed {}", scene.objects[object].name);
        }
    }

    /// Recomputes the probe after its object changed, and its lines after the probe or its
    /// settings changed.
    pub fn refresh_probe(&mut self) {
        let size = self.scene_size();
        (self.runtime.probe).refresh(&self.doc.scene, &self.view.probe, size);
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

    /// Writes the selected object's mesh (see [`crate::export::export_mesh`]).
    pub fn export_mesh(&self, path: &std::path::Path, format: MeshFormat) -> Result<(), String> {
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
            Command::Select(s) => self.doc.selection = s,
            Command::SetProbe { object, uv } => self.set_probe(object, uv),
            Command::RemoveProbe => self.runtime.probe.clear(),
            Command::SetVertex {
                object,
                vertex,
                control,
            } => self.report(|app| app.set_vertex(object, vertex, control)),
            Command::StartDrag => self.doc.checkpoint("drag control point"),
            Command::DragVertex {
                object,
                vertex,
                control,
            } => self.report(|app| app.drag_vertex(object, vertex, control)),
            Command::EditObject { object, edit } => self.edit_object(object, edit),
            Command::ToggleVisible(objects) => self.toggle_visible(&objects),
            Command::Delete(object) => self.delete(object),
            Command::Add(object) => self.add(object),
            Command::ReplaceSurface {
                object,
                what,
                surface,
                status,
            } => self.replace_surface(object, what, *surface, status),
            Command::Frame(target) => self.pending_frame = Some(target),
            Command::Open(path) => self.open(path),
            Command::RecoverAutosave => self.recover_autosave(),
            Command::Save(path) => self.save(path),
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

    fn add(&mut self, object: SceneObject) {
        let name = object.name.clone();
        let _ = self.doc.edit::<()>("new surface", |scene| {
            scene.objects.push(object);
            Ok(())
        });
        self.doc.selection = Selection::object(self.doc.scene.objects.len() - 1);
        self.status = format!("created {name}");
    }

    fn replace_surface(
        &mut self,
        object: usize,
        what: &str,
        surface: pssurf::surface::Surface,
        status: String,
    ) {
        if object >= self.doc.scene.objects.len() {
            return;
        }
        let _ = self.doc.edit::<()>(what, |scene| {
            *scene.objects[object].surface_mut() = surface;
            Ok(())
        });
        self.status = status;
    }

    fn recover_autosave(&mut self) {
        if let Some(p) = self.autosave.clone() {
            self.open(p);
            self.doc.path = None;
        }
    }

    fn exported(&mut self, path: &std::path::Path, result: Result<(), String>) {
        match result {
            Ok(()) => {
                self.status = format!("wrote {}", path.display());
                self.views.export.open = false;
            }
            Err(e) => self.error = Some(format!("Could not export.\n\n{e}")),
        }
    }

    /// Draws the whole application, then applies what the views asked for.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let mut commands = self.shortcuts(ui.ctx());
        self.autosave_tick(ui.ctx());
        self.update_geometry();
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

    /// Draws the panels, the 3D view and the dialogs; their requests go to `commands`.
    fn draw(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        self.side_panels(ui, commands);
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            if let Some(target) = self.pending_frame.take() {
                self.frame(target, rect.width() / rect.height().max(1.0));
            }
            let Parts { views, mut cx, .. } = self.parts(commands);
            views.view3d.ui(ui, &mut cx);
        });
        let Parts {
            views,
            mut cx,
            error,
            ..
        } = self.parts(commands);
        views.new_surface.window(ui.ctx(), &mut cx);
        views.export.window(ui.ctx(), &mut cx);
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
            ..
        } = self;
        Parts {
            views,
            cx: ViewContext::new(doc, view, runtime, autosave.as_deref(), commands),
            status,
            error,
        }
    }

    /// The menu bar, the status bar, and the left and right panels.
    fn side_panels(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let Parts {
            views,
            mut cx,
            status,
            ..
        } = self.parts(commands);
        egui::Panel::top("menu").show(ui, |ui| views.menu.ui(ui, &mut cx));
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.label(status);
                if let Some(p) = cx.probe() {
                    ui.separator();
                    ui.monospace(p.summary());
                }
            });
        });
        egui::Panel::left("scene")
            .resizable(true)
            .default_size(250.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    views.scene_tree.ui(ui, &mut cx);
                    ui.separator();
                    views.properties.ui(ui, &mut cx);
                });
            });
        egui::Panel::right("tools")
            .resizable(true)
            .default_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| tools(ui, views, &mut cx));
            });
    }

    /// Keyboard shortcuts: undo, redo, framing, and the camera from the keyboard (arrows
    /// orbit, Shift+arrows pan, + and - zoom).
    fn shortcuts(&mut self, ctx: &egui::Context) -> Vec<Command> {
        if ctx.egui_wants_keyboard_input() {
            return Vec::new();
        }
        let mut commands = Vec::new();
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
}

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
