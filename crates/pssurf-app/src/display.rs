//! What the 3D view draws and the meshes it draws: each visible object sampled piece by
//! piece (so curvature jumps across PS split lines stay visible), coloured on the CPU by the
//! library's colour maps, plus overlay lines.

use std::ops::Range as Span;

use nalgebra::{Matrix3, Matrix4, Point3, Vector3};
use pssurf::interrogate::{
    CurvatureQuantity, sample_patches, sample_pieces, triangles_per_piece, vertices_per_piece,
};
use pssurf::surface::{PieceKind, PiecewiseSurface, Surface};
use pssurf_viz::colormap::{ColorMap, ColorScale, DataRange};
use pssurf_viz::plot::{
    Overlays, Polyline, Range, cell_of_piece, cell_overlay, cell_pieces, comb_overlay,
    control_overlay, overlay_cells, range_scale,
};

use crate::edit;
use crate::scene::{Material, SceneObject, Shape};

/// What colours the surface (saved by its [`ViewMode::key`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum ViewMode {
    /// Lit, neutral material.
    Shaded,
    /// A curvature plot.
    Curvature(CurvatureQuantity),
    /// Zebra stripes (reflection lines).
    Zebra,
    /// Hidden-line wireframe: the tessellation's edges, the surface only hiding what lies
    /// behind it.
    Wireframe,
}

impl ViewMode {
    /// The short key used on the command line and in saved settings: shaded, zebra,
    /// wireframe, or a curvature quantity's short name (K, H, k1, k2, kabs).
    pub fn key(self) -> &'static str {
        match self {
            ViewMode::Shaded => "shaded",
            ViewMode::Zebra => "zebra",
            ViewMode::Wireframe => "wireframe",
            ViewMode::Curvature(q) => q.short_name(),
        }
    }

    /// The mode with this [`ViewMode::key`].
    pub fn parse(key: &str) -> Result<ViewMode, String> {
        Ok(match key {
            "shaded" => ViewMode::Shaded,
            "zebra" => ViewMode::Zebra,
            "wireframe" => ViewMode::Wireframe,
            q => ViewMode::Curvature(CurvatureQuantity::parse(q).ok_or_else(|| {
                format!(
                    "unknown view mode `{q}`: use shaded, zebra, wireframe, K, H, k1, k2 or kabs"
                )
            })?),
        })
    }

    /// The unit of the quantity shown, for the legend: curvatures are in 1/length, the
    /// Gaussian curvature in 1/length² (None outside curvature plots).
    pub fn unit(self) -> Option<&'static str> {
        match self {
            ViewMode::Curvature(q) => Some(q.unit()),
            _ => None,
        }
    }

    /// The name shown in the interface and over the legend.
    pub fn name(self) -> &'static str {
        match self {
            ViewMode::Shaded => "shaded",
            ViewMode::Zebra => "zebra stripes",
            ViewMode::Wireframe => "wireframe",
            ViewMode::Curvature(CurvatureQuantity::Gaussian) => "Gaussian curvature K",
            ViewMode::Curvature(CurvatureQuantity::Mean) => "mean curvature H",
            ViewMode::Curvature(CurvatureQuantity::K1) => "κ1",
            ViewMode::Curvature(CurvatureQuantity::K2) => "κ2",
            ViewMode::Curvature(CurvatureQuantity::Absolute) => "absolute curvature",
        }
    }
}

impl From<ViewMode> for String {
    fn from(m: ViewMode) -> String {
        m.key().to_string()
    }
}

impl TryFrom<String> for ViewMode {
    type Error = String;
    fn try_from(key: String) -> Result<ViewMode, String> {
        ViewMode::parse(&key)
    }
}

/// The view's display settings.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct DisplaySettings {
    /// Shaded, curvature or zebra.
    pub mode: ViewMode,
    /// The colour map name (see `pssurf_viz::ColorMap::NAMES`).
    pub colormap: String,
    /// The colour range.
    pub range: Range,
    /// For the automatic range: the share of values (percent, 0 … 25) left out at each end,
    /// so that outliers do not stretch the scale (1: the 1st to 99th percentile; 0: min/max).
    pub tail_percent: f64,
    /// For the automatic range of a signed quantity: symmetric about 0.
    pub symmetric: bool,
    /// One colour scale for all objects (comparable colours), or one per object.
    pub shared_scale: bool,
    /// Sampling level: each PS piece becomes 4^level triangles.
    pub level: u32,
    /// Flat (per-triangle) instead of smooth normals.
    pub flat: bool,
    /// Overlays: triangulation, PS refinement, control triangles, boundary.
    pub overlays: Overlays,
    /// Zebra band width in degrees.
    pub zebra_width_deg: f32,
    /// Draw the tessellation's edges (always in wireframe mode).
    pub mesh_edges: bool,
}

impl DisplaySettings {
    /// Whether the tessellation's edges are drawn.
    pub fn edges_shown(&self) -> bool {
        self.mesh_edges || self.mode == ViewMode::Wireframe
    }
}

impl Default for DisplaySettings {
    fn default() -> Self {
        DisplaySettings {
            mode: ViewMode::Shaded,
            colormap: "coolwarm".into(),
            range: Range::Auto,
            tail_percent: 1.0,
            symmetric: true,
            shared_scale: true,
            level: 2,
            flat: false,
            overlays: Overlays::default(),
            zebra_width_deg: 6.0,
            mesh_edges: false,
        }
    }
}

/// The directional light of the shaded view.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Light {
    /// Fixed to the camera (from above left of the eye) instead of to the scene.
    pub headlight: bool,
    /// For a scene light: the azimuth in the xy-plane, degrees from +x.
    pub azimuth_deg: f32,
    /// For a scene light: the elevation above the xy-plane, degrees.
    pub elevation_deg: f32,
}

impl Default for Light {
    fn default() -> Self {
        Light {
            headlight: true,
            azimuth_deg: 45.0,
            elevation_deg: 50.0,
        }
    }
}

impl Light {
    /// The unit direction towards the light, given the camera's right, up and to-eye axes.
    pub fn direction(
        &self,
        right: nalgebra::Vector3<f32>,
        up: nalgebra::Vector3<f32>,
        to_eye: nalgebra::Vector3<f32>,
    ) -> nalgebra::Vector3<f32> {
        if self.headlight {
            return (0.35 * right + 0.55 * up + 0.75 * to_eye).normalize();
        }
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        nalgebra::Vector3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
    }
}

/// One vertex for the GPU: position, normal, colour (sRGB bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuVertex {
    /// Position in the scene.
    pub position: [f32; 3],
    /// Unit normal (zero where undefined).
    pub normal: [f32; 3],
    /// Colour RGBA.
    pub color: [u8; 4],
}

/// One line vertex for the GPU.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineVertex {
    /// Position in the scene.
    pub position: [f32; 3],
    /// Colour RGBA.
    pub color: [u8; 4],
}

/// The drawable form of one object.
///
/// The surface vertices are laid out piece by piece as `sample_patches` makes them (piece k
/// owns vertices `k·m .. (k+1)·m`), and the overlay lines cell by cell (`layout`; see
/// `pssurf_viz::plot::overlay_cells`), so that a local edit rewrites only the slots of the
/// pieces and cells in the support of what it changed.
#[derive(Clone, Debug, Default)]
pub struct ObjectMesh {
    /// Surface vertices.
    pub vertices: Vec<GpuVertex>,
    /// Triangles (indices into `vertices`).
    pub indices: Vec<u32>,
    /// The parameters (u, v) of each vertex, for picking.
    pub uvs: Vec<[f64; 2]>,
    /// Overlay line segments (pairs of vertices).
    pub lines: Vec<LineVertex>,
    /// The curvature values per vertex, when coloured by curvature.
    pub values: Vec<f64>,
    /// Where each triangle's and vertex's data lies.
    pub layout: MeshLayout,
}

/// Where the parts of an [`ObjectMesh`] lie.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshLayout {
    /// The sampling level (each piece has `vertices_per_piece(kind, level)` vertices).
    pub level: u32,
    /// The shape of the pieces.
    pub kind: Option<PieceKind>,
    /// The overlay line vertices of cell t are `cell_lines[t] .. cell_lines[t+1]`.
    pub cell_lines: Vec<usize>,
    /// The line vertices of control group g are `control_lines[g] .. control_lines[g+1]`,
    /// when the control net is drawn.
    pub control_lines: Option<Vec<usize>>,
}

/// The parts of an [`ObjectMesh`] that a local update rewrote.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Changed {
    /// Ranges of `vertices` (and of `uvs`, `values`).
    pub vertices: Vec<Span<usize>>,
    /// Ranges of `lines`.
    pub lines: Vec<Span<usize>>,
}

/// The colour scale of a curvature plot of `values` in a scene of this diameter: the fixed
/// or contrast range of the settings, or the automatic one (the robust range of
/// [`ColorScale::robust`] with the settings' tail and symmetry; with the seed's map, its
/// contrast curve, see `pssurf_viz::plot::range_scale`).
pub fn scale_for(
    settings: &DisplaySettings,
    q: CurvatureQuantity,
    values: &[f64],
    diameter: f64,
) -> ColorScale {
    let map = color_map(settings);
    if settings.range != Range::Auto || map.name() == "seed" {
        return range_scale(settings.range, &map, q, values, diameter);
    }
    let unit = 1.0 / diameter;
    let negligible = 1e-9
        * if q == CurvatureQuantity::Gaussian {
            unit * unit
        } else {
            unit
        };
    let symmetric = settings.symmetric && q.is_signed();
    ColorScale::robust(values, settings.tail_percent, symmetric, negligible)
}

/// What a legend shows: the quantity, the colour scale, whose values it colours and the
/// data's true range under it.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// The quantity.
    pub mode: ViewMode,
    /// The object whose values the scale was fitted to (its id and name), None when one
    /// scale is shared by all visible objects.
    pub object: Option<(u64, String)>,
    /// The colour scale.
    pub scale: ColorScale,
    /// The values' true extremes and how many the scale clips (None: no finite value).
    pub data: Option<DataRange>,
}

impl Legend {
    /// The title: the quantity's name and unit, e.g. `mean curvature H [1/length]`.
    pub fn title(&self) -> String {
        match self.mode.unit() {
            Some(unit) => format!("{} [{unit}]", self.mode.name()),
            None => self.mode.name().to_string(),
        }
    }
}

/// The sampling level used for an object (the setting, capped by `max_level` so that one object stays under about 4 million triangles).
/// (0 for a mesh, which is drawn as it is).
pub fn display_level(o: &SceneObject, settings: &DisplaySettings) -> u32 {
    o.surface()
        .map_or(0, |s| settings.level.min(max_level(s.piece_count())))
}

/// Samples an object for display, in its material's colour (see [`colorize`]).
pub fn object_mesh(o: &SceneObject, settings: &DisplaySettings) -> ObjectMesh {
    match &o.shape {
        Shape::Surface(surface) => surface_mesh(o, surface, settings),
        Shape::Mesh(mesh) => crate::mesh_view::mesh_object_mesh(o, mesh, settings),
    }
}

/// Samples a surface object piece by piece.
fn surface_mesh(o: &SceneObject, surface: &Surface, settings: &DisplaySettings) -> ObjectMesh {
    let level = display_level(o, settings);
    let curvature = matches!(settings.mode, ViewMode::Curvature(_));
    let sampled = sample_patches(surface, level, curvature);
    let placement = Placement::of(o);
    let values = match settings.mode {
        ViewMode::Curvature(q) => sampled.quantity(q),
        _ => Vec::new(),
    };
    let vertices: Vec<GpuVertex> = sampled
        .mesh
        .positions
        .iter()
        .zip(&sampled.mesh.normals)
        .map(|(p, n)| placement.vertex(p, n, o.material.color()))
        .collect();
    let indices: Vec<u32> = sampled.mesh.triangles.iter().flatten().copied().collect();
    let (lines, layout) = object_lines(o, surface, settings, level, &vertices, &indices);
    ObjectMesh {
        vertices,
        indices,
        uvs: sampled.mesh.uvs.iter().map(|p| [p.x, p.y]).collect(),
        lines,
        values,
        layout,
    }
}

/// The overlay lines of an object, cell by cell (with the tessellation's edges over it when
/// shown), then the control net group by group.
fn object_lines(
    o: &SceneObject,
    surface: &Surface,
    settings: &DisplaySettings,
    level: u32,
    vertices: &[GpuVertex],
    indices: &[u32],
) -> (Vec<LineVertex>, MeshLayout) {
    let placement = Placement::of(o);
    let overlays = &settings.overlays;
    let kind = surface.piece_kind();
    let mut lines = Vec::new();
    let mut cell_lines = vec![0];
    for t in 0..overlay_cells(surface) {
        for pl in cell_overlay(surface, overlays, level.min(3), t) {
            placement.segments(&pl, &mut lines);
        }
        if settings.edges_shown() {
            let grid = PieceGrid { kind, level };
            grid.edges(vertices, indices, cell_pieces(surface, t), &mut lines);
        }
        cell_lines.push(lines.len());
    }
    let control_lines = overlays.control.then(|| {
        let mut offsets = vec![lines.len()];
        for g in 0..edit::vertex_count(surface) {
            placement.segments(
                &control_overlay(surface, edit::group_start(surface, g)),
                &mut lines,
            );
            offsets.push(lines.len());
        }
        offsets
    });
    // Curvature combs of the boundary sides, after everything else: they belong to the
    // whole surface, so a vertex edit rebuilds the object (GeometryCache::update_vertex).
    if overlays.combs {
        for pl in comb_overlay(surface) {
            placement.segments(&pl, &mut lines);
        }
    }
    let layout = MeshLayout {
        level,
        kind: Some(kind),
        cell_lines,
        control_lines,
    };
    (lines, layout)
}

/// Re-samples only `pieces` (the support of control group `group`, which changed: nothing
/// else moved), recolouring with `paint` in a curvature plot, and rewrites the overlay lines
/// of their cells and of the group in place. Returns what changed (nothing for a mesh).
pub fn update_vertex(
    mesh: &mut ObjectMesh,
    o: &SceneObject,
    settings: &DisplaySettings,
    group: usize,
    pieces: &[usize],
    paint: Option<(&ColorMap, &ColorScale)>,
) -> Changed {
    let Some(surface) = o.surface() else {
        return Changed::default();
    };
    let level = mesh.layout.level;
    let kind = surface.piece_kind();
    let per = vertices_per_piece(kind, level);
    let quantity = match settings.mode {
        ViewMode::Curvature(q) => Some(q),
        _ => None,
    };
    let sampled = sample_pieces(surface, level, quantity.is_some(), pieces);
    let placement = Placement::of(o);
    let mut changed = Changed::default();
    for (j, &k) in pieces.iter().enumerate() {
        let (src, dst) = (j * per..(j + 1) * per, k * per..(k + 1) * per);
        for (a, b) in src.clone().zip(dst.clone()) {
            let mut color = mesh.vertices[b].color;
            if let Some(q) = quantity {
                let x = sampled.curvature[a].get(q);
                mesh.values[b] = x;
                if let Some((map, scale)) = paint {
                    let [r, g, b] = map.at(scale.position(x));
                    color = [r, g, b, 255];
                }
            }
            let (p, n) = (&sampled.mesh.positions[a], &sampled.mesh.normals[a]);
            mesh.vertices[b] = placement.vertex(p, n, color);
        }
        push_range(&mut changed.vertices, dst);
    }
    let mut cells: Vec<usize> = pieces.iter().map(|&k| cell_of_piece(surface, k)).collect();
    cells.dedup();
    let overlays = &settings.overlays;
    let mut lines = Vec::new();
    for &t in &cells {
        let slot = mesh.layout.cell_lines[t]..mesh.layout.cell_lines[t + 1];
        lines.clear();
        for pl in cell_overlay(surface, overlays, level.min(3), t) {
            placement.segments(&pl, &mut lines);
        }
        if settings.edges_shown() {
            let grid = PieceGrid { kind, level };
            grid.edges(
                &mesh.vertices,
                &mesh.indices,
                cell_pieces(surface, t),
                &mut lines,
            );
        }
        write_slot(&mut mesh.lines[slot.clone()], &lines);
        push_range(&mut changed.lines, slot);
    }
    if let Some(offsets) = &mesh.layout.control_lines {
        lines.clear();
        placement.segments(
            &control_overlay(surface, edit::group_start(surface, group)),
            &mut lines,
        );
        let slot = offsets[group]..offsets[group + 1];
        write_slot(&mut mesh.lines[slot.clone()], &lines);
        push_range(&mut changed.lines, slot);
    }
    changed
}

/// The colour of the tessellation's edges.
pub const EDGE_COLOR: [u8; 4] = [55, 60, 75, 255];

/// The level of the grid the edges show: each PS piece as at most 4 triangles, so that
/// the wireframe stays readable whatever the display level (the edges follow the finely
/// sampled surface).
pub const EDGE_LEVEL: u32 = 1;

/// The sampling grid of the pieces of one surface: its shape and level.
struct PieceGrid {
    kind: PieceKind,
    level: u32,
}

impl PieceGrid {
    /// Appends the sampled edges of `pieces` that lie on the grid lines of level
    /// [`EDGE_LEVEL`] (an edge inside a piece may be drawn twice, which looks the same).
    fn edges(
        &self,
        vertices: &[GpuVertex],
        indices: &[u32],
        pieces: Span<usize>,
        out: &mut Vec<LineVertex>,
    ) {
        let n = 1usize << self.level;
        let stride = 1usize << self.level.saturating_sub(EDGE_LEVEL);
        let per_vertex = vertices_per_piece(self.kind, self.level);
        let per_piece = 3 * triangles_per_piece(self.kind, self.level);
        // (i, j) of each local vertex index, rows of constant j.
        let ij: Vec<(usize, usize)> = match self.kind {
            PieceKind::Triangle => (0..=n)
                .flat_map(|j| (0..=n - j).map(move |i| (i, j)))
                .collect(),
            PieceKind::Rectangle => (0..=n).flat_map(|j| (0..=n).map(move |i| (i, j))).collect(),
        };
        let diagonals = self.kind == PieceKind::Triangle;
        for k in pieces {
            let base = k * per_vertex;
            for tri in indices[k * per_piece..(k + 1) * per_piece].chunks_exact(3) {
                for e in 0..3 {
                    let (a, b) = (tri[e] as usize, tri[(e + 1) % 3] as usize);
                    let ((ia, ja), (ib, jb)) = (ij[a - base], ij[b - base]);
                    let on_line = (ja == jb && ja % stride == 0)
                        || (ia == ib && ia % stride == 0)
                        || (diagonals && ia + ja == ib + jb && (ia + ja) % stride == 0);
                    if on_line {
                        for v in [a, b] {
                            out.push(LineVertex {
                                position: vertices[v].position,
                                color: EDGE_COLOR,
                            });
                        }
                    }
                }
            }
        }
    }
}

/// Appends a range, merging it with the last one when they touch.
fn push_range(ranges: &mut Vec<Span<usize>>, r: Span<usize>) {
    if r.is_empty() {
        return;
    }
    match ranges.last_mut() {
        Some(last) if last.end == r.start => last.end = r.end,
        _ => ranges.push(r),
    }
}

/// Writes `lines` into a fixed slot; the rest of the slot becomes invisible (alpha 0; the
/// line shader discards it). A line whose point could not be evaluated may make the new
/// lines shorter than the slot, never longer in practice; extra segments are dropped.
fn write_slot(slot: &mut [LineVertex], lines: &[LineVertex]) {
    let n = lines.len().min(slot.len()) & !1;
    slot[..n].copy_from_slice(&lines[..n]);
    for v in &mut slot[n..] {
        v.color = [0; 4];
    }
}

/// An object's placement applied to points, normals and lines.
pub(crate) struct Placement {
    matrix: Matrix4<f64>,
    rotation: Matrix3<f64>,
}

impl Placement {
    pub(crate) fn of(o: &SceneObject) -> Self {
        let matrix = o.transform.matrix();
        Placement {
            rotation: matrix.fixed_view::<3, 3>(0, 0).into_owned(),
            matrix,
        }
    }

    pub(crate) fn point(&self, p: &Vector3<f64>) -> [f32; 3] {
        self.matrix
            .transform_point(&Point3::from(*p))
            .coords
            .map(|x| x as f32)
            .into()
    }

    pub(crate) fn vertex(&self, p: &Vector3<f64>, n: &Vector3<f64>, color: [u8; 4]) -> GpuVertex {
        let n = (self.rotation * n)
            .try_normalize(1e-300)
            .unwrap_or_else(Vector3::zeros);
        GpuVertex {
            position: self.point(p),
            normal: n.map(|x| x as f32).into(),
            color,
        }
    }

    /// Appends a polyline as line-list segments.
    fn segments(&self, pl: &Polyline, out: &mut Vec<LineVertex>) {
        let color = [pl.color[0], pl.color[1], pl.color[2], 255];
        for w in pl.points.windows(2) {
            for p in w {
                out.push(LineVertex {
                    position: self.point(p),
                    color,
                });
            }
        }
    }
}

/// An object's mesh to colour, with what the legend needs of the object.
pub struct ToColor<'a> {
    /// The mesh.
    pub mesh: &'a mut ObjectMesh,
    /// The object's material (the colour outside curvature plots).
    pub material: Material,
    /// The object's id.
    pub id: u64,
    /// The object's name.
    pub name: &'a str,
}

/// Colours the meshes of a curvature plot, with one scale fitted to all their values or
/// one per mesh (`settings.shared_scale`), and returns the legends; in other modes each
/// mesh gets its material's colour and there is no legend.
pub fn colorize(
    meshes: &mut [ToColor<'_>],
    settings: &DisplaySettings,
    diameter: f64,
) -> Vec<Legend> {
    let ViewMode::Curvature(q) = settings.mode else {
        for m in meshes.iter_mut() {
            let c = m.material.color();
            m.mesh.vertices.iter_mut().for_each(|v| v.color = c);
        }
        return Vec::new();
    };
    let map = color_map(settings);
    let legend = |values: &[f64], object: Option<(u64, String)>| {
        let scale = scale_for(settings, q, values, diameter);
        Legend {
            mode: settings.mode,
            object,
            data: DataRange::of(values, &scale),
            scale,
        }
    };
    let legends: Vec<Legend> = if settings.shared_scale {
        let all: Vec<f64> = (meshes.iter())
            .flat_map(|m| m.mesh.values.iter().copied())
            .collect();
        vec![legend(&all, None)]
    } else {
        (meshes.iter())
            .map(|m| legend(&m.mesh.values, Some((m.id, m.name.to_string()))))
            .collect()
    };
    for (k, m) in meshes.iter_mut().enumerate() {
        let scale = legends[if settings.shared_scale { 0 } else { k }].scale;
        paint(m.mesh, &map, &scale);
    }
    legends
}

/// Colours a mesh's vertices by their values under a scale.
pub fn paint(mesh: &mut ObjectMesh, map: &ColorMap, scale: &ColorScale) {
    for (v, x) in mesh.vertices.iter_mut().zip(&mesh.values) {
        let [r, g, b] = map.at(scale.position(*x));
        v.color = [r, g, b, 255];
    }
}

/// The colour map of the settings (coolwarm if the name is unknown).
pub fn color_map(settings: &DisplaySettings) -> ColorMap {
    ColorMap::named(&settings.colormap)
        .unwrap_or_else(|_| ColorMap::named("coolwarm").expect("built in"))
}

/// The highest level that keeps one object under about 4 million triangles.
fn max_level(pieces: usize) -> u32 {
    let mut level = 0;
    while level < 6 && pieces << (2 * (level + 1)) <= 4_000_000 {
        level += 1;
    }
    level
}

/// Moves `objects` together so that they sit beside the `existing` bounds: to the right
/// along x with a gap of a tenth of the larger size, centred on them in y, at their height.
/// Their shapes are found from a coarse sampling (level 0).
pub fn place_beside(objects: &mut [SceneObject], existing: (Vector3<f32>, Vector3<f32>)) {
    let coarse = DisplaySettings {
        level: 0,
        overlays: Overlays {
            wire: false,
            refinement: false,
            control: false,
            boundary: false,
            combs: false,
        },
        ..DisplaySettings::default()
    };
    let meshes: Vec<ObjectMesh> = objects.iter().map(|o| object_mesh(o, &coarse)).collect();
    let Some((lo, hi)) = bounds(&meshes) else {
        return;
    };
    let (elo, ehi) = existing;
    let size = (hi - lo).norm().max((ehi - elo).norm());
    let shift = Vector3::new(
        ehi.x + 0.1 * size - lo.x,
        0.5 * (elo.y + ehi.y) - 0.5 * (lo.y + hi.y),
        0.0,
    )
    .cast::<f64>();
    if !shift.iter().all(|x| x.is_finite()) {
        return;
    }
    for o in objects {
        for (t, d) in o.transform.translate.iter_mut().zip(shift.iter()) {
            *t += d;
        }
        o.touch();
    }
}

/// The axis-aligned bounds of meshes, or None when empty.
pub fn bounds<'a>(
    meshes: impl IntoIterator<Item = &'a ObjectMesh>,
) -> Option<(Vector3<f32>, Vector3<f32>)> {
    let mut lo = Vector3::repeat(f32::INFINITY);
    let mut hi = Vector3::repeat(f32::NEG_INFINITY);
    for m in meshes {
        for v in &m.vertices {
            let p = Vector3::from(v.position);
            if p.iter().all(|x| x.is_finite()) {
                lo = lo.inf(&p);
                hi = hi.sup(&p);
            }
        }
    }
    (lo.x <= hi.x).then_some((lo, hi))
}
