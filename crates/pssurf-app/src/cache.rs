//! The drawable geometry of the scene: one mesh per visible object, kept while the object and
//! the sampling settings stay the same (keyed by the object's revision), combined into one
//! buffer for the GPU; a control-point edit rewrites only its support in place.

use std::collections::HashMap;
use std::sync::Arc;

use nalgebra::Vector3;
use pssurf_viz::colormap::ColorScale;

use crate::display::{self, DisplaySettings, Legend, ObjectMesh, ToColor};
use crate::gpu::FrameGeometry;
use crate::scene::Scene;

/// The geometry of the visible objects, rebuilt only when an object or a display setting
/// changes.
#[derive(Default)]
pub struct GeometryCache {
    meshes: HashMap<u64, ObjectMesh>,
    key: Option<(Vec<(u64, bool)>, DisplaySettings)>,
    /// The combined geometry for the GPU.
    pub geometry: Arc<FrameGeometry>,
    /// The legends of a curvature plot: one shared scale, or one per visible object.
    pub legends: Vec<Legend>,
    /// Set after an edit that kept the colour scales as they were (a step of a drag): the
    /// next [`GeometryCache::update`] fits the scales to the data again and recolours.
    stale_colors: bool,
    /// While set (during a drag), the colour scales hold still, so colours stay comparable
    /// as the surface moves; they are fitted again when it is cleared.
    pub hold_colors: bool,
    /// The diameter of the drawn meshes' bounding box at the last rebuild (0 before one).
    pub diameter: f64,
    /// Where each visible object lies in `geometry`.
    pub ranges: Vec<ObjectRange>,
    /// How many object meshes were sampled since the start (a mesh is sampled again only
    /// when its object or the sampling settings change).
    pub sampled: usize,
    /// The settings the meshes in `meshes` were sampled with.
    sampled_with: Option<DisplaySettings>,
    /// The meshing running on another thread, if any (see
    /// [`GeometryCache::update_in_background`]).
    job: Option<MeshingJob>,
}

/// Rebuilds estimated to make more triangles than this run on another thread when the view
/// asks (about 0.1 s of sampling on 2 cores); smaller ones are done at once.
pub const BACKGROUND_TRIANGLES: f64 = 250_000.0;

/// Objects being meshed on another thread, for the busy indicator and to take the result.
struct MeshingJob {
    /// The sampling settings.
    settings: DisplaySettings,
    /// The revisions of the objects being meshed.
    revisions: Vec<u64>,
    /// What the job does, for the busy indicator.
    busy: Busy,
    /// The meshes, when done.
    result: std::sync::mpsc::Receiver<Vec<(u64, ObjectMesh)>>,
}

/// What a background rebuild is doing: shown beside a spinner while it runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Busy {
    /// How many objects are being meshed.
    pub objects: usize,
    /// About how many triangles they make.
    pub triangles: f64,
    /// When it started.
    pub started: std::time::Instant,
}

impl Busy {
    /// The status message, e.g. "meshing 2 objects, about 3.1 million triangles…".
    pub fn message(&self) -> String {
        let what = if self.objects == 1 {
            "1 object".to_string()
        } else {
            format!("{} objects", self.objects)
        };
        let t = self.triangles;
        let count = if t >= 1e6 {
            format!(
                "{} million",
                crate::fields::compact((t / 1e5).round() / 10.0)
            )
        } else {
            crate::fields::compact(t.round())
        };
        format!("meshing {what}, about {count} triangles…")
    }
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
    /// object was not drawn with these settings (the next [`GeometryCache::update`] then
    /// rebuilds it; so does an object with curvature combs, which belong to the whole
    /// surface). The colour scale of a curvature plot is kept as it was.
    pub fn update_vertex(
        &mut self,
        scene: &Scene,
        object: usize,
        old: u64,
        vertex: usize,
        pieces: &[usize],
        display: &DisplaySettings,
    ) {
        // Combs belong to the whole surface: the next update rebuilds the object instead.
        if display.overlays.combs {
            return;
        }
        let scale = scene.objects.get(object).and_then(|o| self.scale_of(o.id));
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
        let paint = scale.as_ref().map(|s| (&map, s));
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
        self.stale_colors |= paint.is_some();
    }

    /// The colour scale that colours object `id` (the shared one, or its own).
    pub fn scale_of(&self, id: u64) -> Option<ColorScale> {
        (self.legends.iter())
            .find(|l| l.object.as_ref().is_none_or(|(o, _)| *o == id))
            .map(|l| l.scale)
    }

    /// The legend to show: the shared one, or the selected object's (else the first).
    pub fn legend(&self, scene: &Scene, selected: Option<usize>) -> Option<&Legend> {
        let id = selected.and_then(|i| scene.objects.get(i)).map(|o| o.id);
        (self.legends.iter())
            .find(|l| l.object.as_ref().is_none_or(|(o, _)| Some(*o) == id))
            .or(self.legends.first())
    }

    /// Whether colour scales wait to be fitted again after a drag (see
    /// [`GeometryCache::update`]).
    pub fn colors_stale(&self) -> bool {
        self.stale_colors
    }

    /// Rebuilds the geometry if the scene or the display settings changed, at once (waiting
    /// for nothing: a background rebuild still running is left to finish unused).
    pub fn update(&mut self, scene: &Scene, display: &DisplaySettings) {
        self.update_with(scene, display, false);
    }

    /// Like [`GeometryCache::update`], but a rebuild of more than [`BACKGROUND_TRIANGLES`]
    /// runs on another thread: until it is done the previous geometry stays drawn and
    /// [`GeometryCache::busy`] says what is being meshed. Call it every frame.
    pub fn update_in_background(&mut self, scene: &Scene, display: &DisplaySettings) {
        self.update_with(scene, display, true);
    }

    /// What a background rebuild is doing, while one runs.
    pub fn busy(&self) -> Option<&Busy> {
        self.job.as_ref().map(|j| &j.busy)
    }

    fn update_with(&mut self, scene: &Scene, display: &DisplaySettings, background: bool) {
        let key: Vec<(u64, bool)> = scene
            .objects
            .iter()
            .map(|o| (o.revision, o.visible))
            .collect();
        let current = Some((key.clone(), display.clone()));
        if self.key == current && (!self.stale_colors || self.hold_colors) {
            self.job = None;
            return;
        }
        // Colour map and range changes only recolour; these need new samples.
        if self
            .sampled_with
            .as_ref()
            .is_none_or(|d| !same_sampling(d, display))
        {
            self.meshes.clear();
            self.sampled_with = Some(display.clone());
        }
        self.take_finished_job(display);
        let live: std::collections::HashSet<u64> = key.iter().map(|k| k.0).collect();
        self.meshes.retain(|r, _| live.contains(r));
        let missing: Vec<&crate::scene::SceneObject> = (scene.visible())
            .map(|(_, o)| o)
            .filter(|o| !self.meshes.contains_key(&o.revision))
            .collect();
        let triangles: f64 = missing.iter().map(|o| triangles_of(o, display)).sum();
        if background && triangles > BACKGROUND_TRIANGLES {
            return self.mesh_in_background(&missing, display, triangles);
        }
        self.job = None;
        for o in missing {
            self.meshes
                .insert(o.revision, display::object_mesh(o, display));
            self.sampled += 1;
        }
        self.stale_colors = false;
        let visible: Vec<(usize, u64)> = scene.visible().map(|(i, o)| (i, o.revision)).collect();
        // Sizes and colour scales come from the drawn objects only (not the hidden ones
        // still cached).
        let drawn = visible.iter().filter_map(|(_, r)| self.meshes.get(r));
        let diameter = display::bounds(drawn)
            .map(|(lo, hi)| (hi - lo).norm() as f64)
            .filter(|d| d.is_finite())
            .unwrap_or(1.0)
            .max(1e-12);
        {
            let objects: HashMap<u64, &crate::scene::SceneObject> =
                scene.visible().map(|(_, o)| (o.revision, o)).collect();
            let mut meshes: Vec<ToColor<'_>> = (self.meshes.iter_mut())
                .filter_map(|(r, mesh)| {
                    let o = objects.get(r)?;
                    Some(ToColor {
                        mesh,
                        material: o.material,
                        id: o.id,
                        name: &o.name,
                    })
                })
                .collect();
            // In scene order, so that per-object legends follow the tree.
            meshes.sort_by_key(|m| scene.index_of(m.id));
            self.legends = display::colorize(&mut meshes, display, diameter);
        }
        self.diameter = diameter;
        let mut g = FrameGeometry {
            generation: crate::scene::fresh_revision(),
            ..Default::default()
        };
        self.ranges.clear();
        for (i, r) in visible {
            let m = &self.meshes[&r];
            let base = g.vertices.len() as u32;
            self.ranges.push(ObjectRange {
                object: i,
                vertex: g.vertices.len(),
                index: g.indices.len(),
                line: g.lines.len(),
            });
            g.vertices.extend_from_slice(&m.vertices);
            g.indices.extend(m.indices.iter().map(|k| k + base));
            g.lines.extend_from_slice(&m.lines);
        }
        self.geometry = Arc::new(g);
        self.key = current;
    }

    /// Starts meshing `objects` on another thread, unless a job for the same objects and
    /// sampling runs already; the geometry stays as it is meanwhile.
    fn mesh_in_background(
        &mut self,
        objects: &[&crate::scene::SceneObject],
        display: &DisplaySettings,
        triangles: f64,
    ) {
        let revisions: Vec<u64> = objects.iter().map(|o| o.revision).collect();
        if self
            .job
            .as_ref()
            .is_some_and(|j| j.revisions == revisions && same_sampling(&j.settings, display))
        {
            return;
        }
        let (send, result) = std::sync::mpsc::channel();
        let owned: Vec<crate::scene::SceneObject> = objects.iter().map(|&o| o.clone()).collect();
        let settings = display.clone();
        std::thread::spawn(move || {
            let meshes: Vec<(u64, ObjectMesh)> = (owned.iter())
                .map(|o| (o.revision, display::object_mesh(o, &settings)))
                .collect();
            // The receiver is gone when the job was superseded: nothing to do then.
            let _ = send.send(meshes);
        });
        self.job = Some(MeshingJob {
            settings: display.clone(),
            revisions,
            busy: Busy {
                objects: objects.len(),
                triangles,
                started: std::time::Instant::now(),
            },
            result,
        });
    }

    /// Takes the meshes of a finished background job, when they were sampled as `display`
    /// samples (a job for other settings is dropped).
    fn take_finished_job(&mut self, display: &DisplaySettings) {
        let Some(job) = &self.job else {
            return;
        };
        if !same_sampling(&job.settings, display) {
            self.job = None;
            return;
        }
        match job.result.try_recv() {
            Ok(meshes) => {
                self.sampled += meshes.len();
                self.meshes.extend(meshes);
                self.job = None;
            }
            Err(std::sync::mpsc::TryRecvError::Empty) => {}
            Err(std::sync::mpsc::TryRecvError::Disconnected) => self.job = None,
        }
    }

    /// The cached mesh of object `i` of `scene` (after [`GeometryCache::update`]).
    pub fn object_mesh(&self, scene: &Scene, i: usize) -> Option<&ObjectMesh> {
        scene
            .objects
            .get(i)
            .and_then(|o| self.meshes.get(&o.revision))
    }

    /// The diameter of the drawn scene at the last geometry rebuild (1 before one); cheap,
    /// so the view can use it every frame.
    pub fn scene_size(&self) -> f64 {
        if self.diameter > 0.0 {
            self.diameter
        } else {
            1.0
        }
    }

    /// The bounds of the drawn (visible) meshes at the last rebuild, if any.
    pub fn bounds(&self) -> Option<(Vector3<f32>, Vector3<f32>)> {
        let key = self.key.as_ref().map_or(&[][..], |(k, _)| k.as_slice());
        let drawn = (key.iter())
            .filter(|(_, visible)| *visible)
            .filter_map(|(r, _)| self.meshes.get(r));
        display::bounds(drawn)
    }
}

/// Whether meshes sampled with `a` serve `b` (the colour map and range only recolour).
fn same_sampling(a: &DisplaySettings, b: &DisplaySettings) -> bool {
    a.level == b.level
        && a.overlays == b.overlays
        && a.mesh_edges == b.mesh_edges
        && a.mode == b.mode
}

/// About how many triangles an object's display mesh has.
fn triangles_of(o: &crate::scene::SceneObject, display: &DisplaySettings) -> f64 {
    match &o.shape {
        crate::scene::Shape::Surface(s) => {
            use pssurf::surface::PiecewiseSurface;
            let level = display::display_level(o, display);
            let per = pssurf::interrogate::triangles_per_piece(s.piece_kind(), level);
            s.piece_count() as f64 * per as f64
        }
        crate::scene::Shape::Mesh(m) => m.refined.triangles.len() as f64,
    }
}
