//! The application state and its top-level layout: menu bar, scene tree and properties on
//! the left, the 3D view in the centre, the domain view and algorithm panels on the right,
//! a status bar below.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use pssurf::interrogate::CurvatureQuantity;
use pssurf_viz::colormap::ColorScale;

use crate::camera::OrbitCamera;
use crate::display::{self, DisplaySettings, ObjectMesh, ViewMode};
use crate::document::Document;
use crate::edit::{self, VertexControl};
use crate::gpu::{FrameGeometry, LineSet};
use crate::panels::{Panel, PanelContext, default_panels};
use crate::probe::{Probe, ProbeSettings, probe_at, probe_lines};
use crate::scene::{Material, Scene};

/// What is selected.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Selection {
    /// The selected object.
    pub object: Option<usize>,
    /// The selected vertex (control triangle) of that object.
    pub vertex: Option<usize>,
}

/// The geometry of the visible objects, rebuilt only when an object or a display setting
/// changes.
#[derive(Default)]
pub struct GeometryCache {
    meshes: HashMap<u64, ObjectMesh>,
    key: Option<(Vec<(u64, bool)>, DisplaySettings)>,
    /// The combined geometry for the GPU.
    pub geometry: Arc<FrameGeometry>,
    /// The colour scale of a curvature plot (for the legend).
    pub scale: Option<ColorScale>,
    /// The diameter of the drawn meshes' bounding box at the last rebuild (0 before one).
    pub diameter: f64,
    /// Where each visible object lies in `geometry`.
    pub ranges: Vec<ObjectRange>,
}

/// Where one object's data starts in the combined [`FrameGeometry`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ObjectRange {
    /// The object's index in the scene.
    pub object: usize,
    /// Its first surface vertex.
    pub vertex: usize,
    /// Its first index.
    pub index: usize,
    /// Its first line vertex.
    pub line: usize,
}

impl GeometryCache {
    /// After control group `vertex` of object `object` changed (its revision was `old`),
    /// updates only `pieces` (the group's support) in the object's mesh and in the combined
    /// geometry, and records the rewritten ranges for the GPU upload. Does nothing when the
    /// object was not drawn with these settings (the next [`App::update_geometry`] then
    /// rebuilds it). The colour scale of a curvature plot is kept as it was.
    pub fn update_vertex(
        &mut self,
        scene: &Scene,
        object: usize,
        old: u64,
        vertex: usize,
        pieces: &[usize],
        display: &DisplaySettings,
    ) {
        let Some((key, settings)) = &mut self.key else {
            return;
        };
        let o = &scene.objects[object];
        let Some(range) = self.ranges.iter().find(|r| r.object == object).copied() else {
            return;
        };
        if settings != display || key.get(object).is_none_or(|k| k.0 != old) {
            return;
        }
        let Some(mut mesh) = self.meshes.remove(&old) else {
            return;
        };
        let map = display::color_map(display);
        let paint = self.scale.as_ref().map(|s| (&map, s));
        let changed = display::update_vertex(&mut mesh, o, display, vertex, pieces, paint);
        let g = Arc::make_mut(&mut self.geometry);
        let shift = |rs: &[std::ops::Range<usize>], by: usize| -> Vec<std::ops::Range<usize>> {
            rs.iter().map(|r| r.start + by..r.end + by).collect()
        };
        for r in &changed.vertices {
            g.vertices[r.start + range.vertex..r.end + range.vertex]
                .copy_from_slice(&mesh.vertices[r.clone()]);
        }
        for r in &changed.lines {
            g.lines[r.start + range.line..r.end + range.line]
                .copy_from_slice(&mesh.lines[r.clone()]);
        }
        g.record(
            shift(&changed.vertices, range.vertex),
            shift(&changed.lines, range.line),
        );
        key[object].0 = o.revision;
        self.meshes.insert(o.revision, mesh);
    }
}

/// The application.
pub struct App {
    /// The open document.
    pub doc: Document,
    /// The selection.
    pub selection: Selection,
    /// Display settings of the 3D view.
    pub display: DisplaySettings,
    /// The 3D camera.
    pub camera: OrbitCamera,
    /// The light of the shaded view.
    pub light: display::Light,
    /// The status bar's message.
    pub status: String,
    /// An error shown in a window until dismissed.
    pub error: Option<String>,
    /// The algorithm panels.
    pub panels: Vec<Box<dyn Panel>>,
    /// The drawable geometry.
    pub cache: GeometryCache,
    /// Whether the GPU view resources are installed.
    pub gpu: bool,
    /// The path typed in the File menu.
    pub path_text: String,
    /// The numeric editor's copy of the selected vertex's control triangle.
    pub vertex_edit: Option<(usize, usize, VertexControl)>,
    /// The probed surface point.
    pub probe: Option<Probe>,
    /// What the probe shows.
    pub probe_settings: ProbeSettings,
    /// The probe's lines for the GPU.
    pub probe_lines: Arc<LineSet>,
    probe_key: Option<(u64, ProbeSettings)>,
    /// A control point being dragged: (object, vertex, point index).
    pub drag: Option<(usize, usize, usize)>,
    /// Frame the scene at the next draw.
    pub frame_pending: bool,
    /// Frame the selected object at the next draw.
    pub frame_selection_pending: bool,
    /// The Export dialog.
    pub export: crate::export::ExportDialog,
    /// The wgpu device and queue (for offscreen pictures), when running on wgpu.
    pub render_state: Option<eframe::egui_wgpu::RenderState>,
    /// The "New surface" dialog.
    pub new_surface: crate::create::NewSurface,
    /// Where autosaves go (None: no autosave).
    pub autosave: Option<PathBuf>,
    last_autosave: f64,
}

impl App {
    /// An application showing `scene`.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        let selection = Selection {
            object: (!scene.objects.is_empty()).then_some(0),
            vertex: None,
        };
        App {
            path_text: path
                .as_ref()
                .map(|p| p.display().to_string())
                .unwrap_or_default(),
            doc: Document::new(scene, path),
            selection,
            display: DisplaySettings::default(),
            camera: OrbitCamera::default(),
            light: Default::default(),
            status: String::new(),
            error: None,
            panels: default_panels(),
            cache: GeometryCache::default(),
            gpu: false,
            vertex_edit: None,
            probe: None,
            probe_settings: ProbeSettings::default(),
            probe_lines: Arc::default(),
            probe_key: None,
            drag: None,
            frame_pending: true,
            frame_selection_pending: false,
            new_surface: Default::default(),
            export: Default::default(),
            render_state: None,
            autosave: None,
            last_autosave: 0.0,
        }
    }

    /// The built-in demo: a curvature-coloured UPS patch and a NURPS paraboloid.
    pub fn demo() -> Self {
        let mut app = App::new(crate::demo::scene(), None);
        app.display.mode = ViewMode::Curvature(CurvatureQuantity::Mean);
        app.status =
            "demo scene: a UPS wave patch coloured by mean curvature, and a NURPS paraboloid"
                .into();
        app
    }

    /// Opens a scene or surface file, replacing the document; a bad file leaves the scene
    /// unchanged and shows the message.
    pub fn open(&mut self, path: PathBuf) {
        match Scene::load(&path) {
            Ok(scene) => {
                self.selection = Selection {
                    object: (!scene.objects.is_empty()).then_some(0),
                    vertex: None,
                };
                self.doc = Document::new(scene, Some(path.clone()));
                self.path_text = path.display().to_string();
                self.status = format!("opened {}", path.display());
                self.frame_pending = true;
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
            self.after_history();
        }
    }

    /// Redoes the last undone edit.
    pub fn redo(&mut self) {
        if let Some(name) = self.doc.redo_name().map(str::to_owned) {
            self.doc.redo();
            self.status = format!("redid {name}");
            self.after_history();
        }
    }

    fn after_history(&mut self) {
        self.vertex_edit = None;
        let n = self.doc.scene.objects.len();
        if self.selection.object.is_some_and(|i| i >= n) {
            self.selection = Selection::default();
        }
        if let Some(i) = self.selection.object
            && self
                .selection
                .vertex
                .is_some_and(|v| v >= edit::vertex_count(&self.doc.scene.objects[i].surface))
        {
            self.selection.vertex = None;
        }
    }

    /// Sets the selected vertex's control triangle as one undoable edit.
    pub fn set_vertex(
        &mut self,
        object: usize,
        vertex: usize,
        c: VertexControl,
    ) -> Result<(), String> {
        let old = self.doc.scene.objects[object].revision;
        let mut pieces = Vec::new();
        self.doc.edit("edit control points", |scene| {
            let o = &mut scene.objects[object];
            pieces = edit::set_vertex_control(&mut o.surface, vertex, &c)?;
            o.touch();
            Ok::<(), String>(())
        })?;
        self.cache
            .update_vertex(&self.doc.scene, object, old, vertex, &pieces, &self.display);
        Ok(())
    }

    /// Sets a vertex's control triangle during a drag: no undo step of its own (see
    /// [`Document::checkpoint`]), and only the vertex's molecule is re-tessellated and
    /// uploaded.
    pub fn drag_vertex(
        &mut self,
        object: usize,
        vertex: usize,
        c: VertexControl,
    ) -> Result<(), String> {
        let old = self.doc.scene.objects[object].revision;
        let mut result = Ok(Vec::new());
        self.doc.edit_continuing(|scene| {
            let o = &mut scene.objects[object];
            result = edit::set_vertex_control(&mut o.surface, vertex, &c);
            if result.is_ok() {
                o.touch();
            }
        });
        let pieces = result?;
        self.cache
            .update_vertex(&self.doc.scene, object, old, vertex, &pieces, &self.display);
        Ok(())
    }

    /// Rebuilds the geometry if the scene or the display settings changed.
    pub fn update_geometry(&mut self) {
        let key: Vec<(u64, bool)> = self
            .doc
            .scene
            .objects
            .iter()
            .map(|o| (o.revision, o.visible))
            .collect();
        let current = Some((key.clone(), self.display.clone()));
        if self.cache.key == current {
            return;
        }
        // Colour map and range changes only recolour; these need new samples.
        let sampling_changed = self.cache.key.as_ref().is_none_or(|(_, d)| {
            d.level != self.display.level
                || d.overlays != self.display.overlays
                || d.mesh_edges != self.display.mesh_edges
                || d.mode != self.display.mode
        });
        if sampling_changed {
            self.cache.meshes.clear();
        }
        let live: std::collections::HashSet<u64> = key.iter().map(|k| k.0).collect();
        self.cache.meshes.retain(|r, _| live.contains(r));
        for (_, o) in self.doc.scene.visible() {
            if !self.cache.meshes.contains_key(&o.revision) {
                self.cache
                    .meshes
                    .insert(o.revision, display::object_mesh(o, &self.display));
            }
        }
        let visible: Vec<(usize, u64)> = self
            .doc
            .scene
            .visible()
            .map(|(i, o)| (i, o.revision))
            .collect();
        let diameter = display::bounds(self.cache.meshes.values())
            .map(|(lo, hi)| (hi - lo).norm() as f64)
            .unwrap_or(1.0)
            .max(1e-12);
        {
            let materials: HashMap<u64, Material> = self
                .doc
                .scene
                .objects
                .iter()
                .map(|o| (o.revision, o.material))
                .collect();
            let mut meshes: Vec<(&mut ObjectMesh, Material)> = self
                .cache
                .meshes
                .iter_mut()
                .map(|(r, m)| (m, materials.get(r).copied().unwrap_or_default()))
                .collect();
            self.cache.scale = display::colorize(&mut meshes, &self.display, diameter);
        }
        self.cache.diameter = diameter;
        let mut g = FrameGeometry {
            generation: crate::scene::fresh_revision(),
            ..Default::default()
        };
        self.cache.ranges.clear();
        for (i, r) in visible {
            let m = &self.cache.meshes[&r];
            let base = g.vertices.len() as u32;
            self.cache.ranges.push(ObjectRange {
                object: i,
                vertex: g.vertices.len(),
                index: g.indices.len(),
                line: g.lines.len(),
            });
            g.vertices.extend_from_slice(&m.vertices);
            g.indices.extend(m.indices.iter().map(|k| k + base));
            g.lines.extend_from_slice(&m.lines);
        }
        self.cache.geometry = Arc::new(g);
        self.cache.key = current;
    }

    /// The cached mesh of an object (after [`App::update_geometry`]).
    pub fn object_mesh(&self, i: usize) -> Option<&ObjectMesh> {
        self.doc
            .scene
            .objects
            .get(i)
            .and_then(|o| self.cache.meshes.get(&o.revision))
    }

    /// The diameter of the drawn scene at the last geometry rebuild (1 before one); cheap,
    /// so the view can use it every frame.
    pub fn scene_size(&self) -> f64 {
        if self.cache.diameter > 0.0 {
            self.cache.diameter
        } else {
            1.0
        }
    }

    /// Puts the probe on object `object` at parameters `uv` (removes it outside the domain).
    pub fn set_probe(&mut self, object: usize, uv: nalgebra::Point2<f64>) {
        let size = self.scene_size();
        let alignment = self.probe_settings.alignment;
        self.probe = probe_at(&self.doc.scene, object, uv, alignment, size);
        self.probe_key = None;
        if self.probe.is_some() {
            self.selection.object = Some(object);
            self.status = format!("probed {}", self.doc.scene.objects[object].name);
        }
        self.refresh_probe();
    }

    /// Recomputes the probe after its object changed, and its lines after the probe or its
    /// settings changed.
    pub fn refresh_probe(&mut self) {
        if let Some(p) = &self.probe {
            // Follow the object by identity: deleting another object moves it in the list.
            let found = self.doc.scene.index_of(p.id);
            let stale = found
                .is_none_or(|i| i != p.object || self.doc.scene.objects[i].revision != p.revision);
            let realigned = self
                .probe_key
                .is_some_and(|(_, s)| s.alignment != self.probe_settings.alignment);
            if stale || realigned {
                let uv = p.uv;
                let size = self.scene_size();
                let alignment = self.probe_settings.alignment;
                self.probe = found.and_then(|i| probe_at(&self.doc.scene, i, uv, alignment, size));
            }
        }
        let key = self
            .probe
            .as_ref()
            .map(|p| (p.revision, self.probe_settings));
        if key == self.probe_key && self.probe_key.is_some() {
            return;
        }
        let lines = self
            .probe
            .as_ref()
            .map(|p| probe_lines(p, &self.probe_settings, self.scene_size()))
            .unwrap_or_default();
        self.probe_lines = Arc::new(LineSet {
            generation: crate::scene::fresh_revision(),
            lines,
        });
        self.probe_key = key;
    }

    /// Fits the camera to the visible objects in a view of the given aspect ratio.
    pub fn frame_all(&mut self, aspect: f32) {
        self.update_geometry();
        if let Some((lo, hi)) = display::bounds(self.cache.meshes.values()) {
            self.camera.frame(lo, hi, aspect);
        }
        self.frame_pending = false;
    }

    /// Fits the camera to the selected object (to everything when nothing visible is
    /// selected).
    pub fn frame_selection(&mut self, aspect: f32) {
        self.update_geometry();
        let mesh = self.selection.object.and_then(|i| self.object_mesh(i));
        match mesh.and_then(|m| display::bounds([m])) {
            Some((lo, hi)) => self.camera.frame(lo, hi, aspect),
            None => self.frame_all(aspect),
        }
        self.frame_selection_pending = false;
    }

    /// Draws the whole application.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        self.shortcuts(ui.ctx());
        self.autosave_tick(ui.ctx());
        egui::Panel::top("menu").show(ui, |ui| self.menu_bar(ui));
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.label(&self.status);
                if let Some(p) = &self.probe {
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
                    crate::scene_tree::ui(self, ui);
                    ui.separator();
                    crate::properties::ui(self, ui);
                });
            });
        egui::Panel::right("tools")
            .resizable(true)
            .default_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    ui.heading("Domain");
                    crate::domain_view::ui(self, ui);
                    ui.separator();
                    crate::properties::display_ui(self, ui);
                    egui::CollapsingHeader::new("Probe")
                        .default_open(false)
                        .show(ui, |ui| crate::properties::probe_ui(self, ui));
                    let mut panels = std::mem::take(&mut self.panels);
                    for p in &mut panels {
                        egui::CollapsingHeader::new(p.title())
                            .default_open(false)
                            .show(ui, |ui| {
                                let mut cx = PanelContext {
                                    doc: &mut self.doc,
                                    selected: self.selection.object,
                                    status: &mut self.status,
                                };
                                p.ui(ui, &mut cx);
                            });
                    }
                    self.panels = panels;
                });
            });
        egui::CentralPanel::no_frame().show(ui, |ui| crate::view3d::ui(self, ui));
        crate::create::window(self, ui.ctx());
        crate::export::window(self, ui.ctx());
        self.error_window(ui.ctx());
    }

    fn menu_bar(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                let label = ui.label("File (scene or surface .json):");
                ui.text_edit_singleline(&mut self.path_text)
                    .labelled_by(label.id)
                    .on_hover_text("Type a path, then Open or Save");
                ui.horizontal(|ui| {
                    if ui.button("Open").clicked() {
                        self.open(PathBuf::from(self.path_text.trim()));
                    }
                    if ui.button("Save").clicked() {
                        self.save(PathBuf::from(self.path_text.trim()));
                    }
                });
                if let Some(p) = self.autosave.clone().filter(|p| p.exists())
                    && ui
                        .button("Recover autosave")
                        .on_hover_text(p.display().to_string())
                        .clicked()
                {
                    self.open(p);
                    self.doc.path = None;
                }
                ui.separator();
                if ui
                    .button("Export mesh…")
                    .on_hover_text("PLY, OBJ, STL, glTF or VTK, with curvature fields")
                    .clicked()
                {
                    crate::export::open(self, crate::export::What::Mesh);
                }
                if ui
                    .add_enabled(
                        self.render_state.is_some(),
                        egui::Button::new("Export picture…"),
                    )
                    .on_hover_text("The 3D view as a PNG picture of any size")
                    .clicked()
                {
                    crate::export::open(self, crate::export::What::Picture);
                }
            });
            ui.menu_button("New", |ui| {
                use crate::create::Shape;
                for (label, tip, shape) in [
                    (
                        "UPS patch…",
                        "A 3–6-sided UPS patch interpolating a height formula",
                        Shape::Formula,
                    ),
                    (
                        "Quadric…",
                        "z = a x² + b xy + c y², reproduced exactly",
                        Shape::Quadric,
                    ),
                ] {
                    if ui.button(label).on_hover_text(tip).clicked() {
                        self.new_surface.shape = shape;
                        self.new_surface.open = true;
                    }
                }
            });
            ui.menu_button("Edit", |ui| {
                let undo = self.doc.undo_name().map(|n| format!("Undo {n}"));
                if ui
                    .add_enabled(
                        undo.is_some(),
                        egui::Button::new(undo.unwrap_or("Undo".into())).shortcut_text("Ctrl+Z"),
                    )
                    .clicked()
                {
                    self.undo();
                }
                let redo = self.doc.redo_name().map(|n| format!("Redo {n}"));
                if ui
                    .add_enabled(
                        redo.is_some(),
                        egui::Button::new(redo.unwrap_or("Redo".into()))
                            .shortcut_text("Ctrl+Shift+Z"),
                    )
                    .clicked()
                {
                    self.redo();
                }
            });
            ui.menu_button("View", |ui| {
                if ui.button("Frame all (F)").clicked() {
                    self.frame_pending = true;
                }
                if ui.button("Frame selection (Shift+F)").clicked() {
                    self.frame_selection_pending = true;
                }
                ui.checkbox(&mut self.display.flat, "Flat shading");
            });
        });
    }

    fn shortcuts(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        if ctx.input_mut(|i| i.consume_key(egui::Modifiers::SHIFT, egui::Key::F)) {
            self.frame_selection_pending = true;
        }
        let (undo, redo, frame) = ctx.input_mut(|i| {
            let redo = i.consume_key(
                egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
                egui::Key::Z,
            ) || i.consume_key(egui::Modifiers::COMMAND, egui::Key::Y);
            let undo = i.consume_key(egui::Modifiers::COMMAND, egui::Key::Z);
            let frame = i.consume_key(egui::Modifiers::NONE, egui::Key::F);
            (undo, redo, frame)
        });
        if redo {
            self.redo();
        } else if undo {
            self.undo();
        }
        if frame {
            self.frame_pending = true;
        }
        // The camera from the keyboard: arrows orbit (Shift+arrows pan), + and - zoom.
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
        let step = 12.5; // 5° per press
        let [l, r, u, d, pl, pr, pu, pd, zoom_in, zoom_out] = keys.map(f32::from);
        self.camera.orbit(step * (l - r), step * (u - d));
        self.camera.pan(40.0 * (pr - pl), 40.0 * (pd - pu), 600.0);
        self.camera.zoom(1.25f32.powf(zoom_in - zoom_out));
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

    fn error_window(&mut self, ctx: &egui::Context) {
        let Some(msg) = self.error.clone() else {
            return;
        };
        egui::Window::new("Problem")
            .collapsible(false)
            .resizable(false)
            .show(ctx, |ui| {
                ui.label(msg);
                if ui.button("OK").clicked() {
                    self.error = None;
                }
            });
    }
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        App::ui(self, ui);
    }
}
