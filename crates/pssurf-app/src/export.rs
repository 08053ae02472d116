//! The Export dialog: the selected object's mesh in any of the library's formats (with the
//! curvature fields and the plot's colours where the format carries them), or a picture of
//! the 3D view at any size, rendered offscreen by the view's own renderer.

use std::path::{Path, PathBuf};

use nalgebra::Point3;
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::io::{Durability, atomic_write, atomic_write_bytes};
use pssurf::mesh::TriMesh;
use pssurf_viz::{FieldMesh, MeshFormat, write_mesh};

use crate::cache::GeometryCache;
use crate::command::{Command, ExportKind, ViewContext};
use crate::display::{DisplaySettings, ViewMode, display_level};
use crate::document::Document;
use crate::runtime::Runtime;
use crate::scene::{MeshShape, Shape};
use crate::state::ViewState;

/// The dialog's state.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportDialog {
    /// Whether the window is open.
    pub open: bool,
    /// Mesh or picture.
    pub what: ExportKind,
    /// The mesh format.
    pub format: MeshFormat,
    /// The picture's size in pixels.
    pub size: [u32; 2],
    /// The file to write.
    pub path: String,
}

impl Default for ExportDialog {
    fn default() -> Self {
        ExportDialog {
            open: false,
            what: ExportKind::Mesh,
            format: MeshFormat::Ply,
            size: [1600, 1000],
            path: String::new(),
        }
    }
}

/// The formats offered, with their names.
const FORMATS: [(MeshFormat, &str); 5] = [
    (MeshFormat::Ply, "ply"),
    (MeshFormat::Obj, "obj"),
    (MeshFormat::Stl, "stl"),
    (MeshFormat::Glb, "glb"),
    (MeshFormat::Vtk, "vtk"),
];

fn extension(d: &ExportDialog) -> &'static str {
    match d.what {
        ExportKind::Picture => "png",
        ExportKind::Surface => "json",
        ExportKind::Mesh => FORMATS
            .iter()
            .find(|(f, _)| *f == d.format)
            .map_or("ply", |(_, e)| e),
    }
}

/// A file name next to the scene file, from the object's name.
fn suggested_path(d: &ExportDialog, doc: &Document) -> String {
    let dir = doc
        .path
        .as_ref()
        .and_then(|p| p.parent())
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let stem = match d.what {
        ExportKind::Picture => "view".to_string(),
        ExportKind::Mesh | ExportKind::Surface => doc
            .selection
            .object
            .and_then(|i| doc.scene.objects.get(i))
            .map_or("surface".into(), |o| {
                o.name.replace(|c: char| !c.is_alphanumeric(), "_")
            }),
    };
    dir.join(format!("{stem}.{}", extension(d)))
        .display()
        .to_string()
}

/// Writes the selected object's mesh in scene placement: points and normals transformed,
/// all five curvature fields (in scene units), and in a curvature plot the colours of the
/// plot (the scale of `cache`, which must be up to date: see `App::export_mesh`).
pub fn export_mesh(
    doc: &Document,
    display: &DisplaySettings,
    cache: &GeometryCache,
    path: &Path,
    format: MeshFormat,
) -> Result<(), String> {
    let i = doc
        .selection
        .object
        .filter(|&i| i < doc.scene.objects.len())
        .ok_or("select an object to export")?;
    let o = &doc.scene.objects[i];
    let (mut mesh, quantities) = match &o.shape {
        Shape::Surface(surface) => {
            let sampled = sample_patches(surface, display_level(o, display), true);
            let quantities = CurvatureQuantity::ALL.map(|q| sampled.quantity(q));
            (sampled.mesh, quantities)
        }
        Shape::Mesh(m) => mesh_with_fields(m),
    };
    let m = o.transform.matrix();
    let rotation = m.fixed_view::<3, 3>(0, 0).into_owned() / o.transform.scale;
    for (p, n) in mesh.positions.iter_mut().zip(mesh.normals.iter_mut()) {
        *p = m.transform_point(&Point3::from(*p)).coords;
        *n = rotation * *n;
    }
    // The plot's colours, when the view shows one: the values computed now, under the scale
    // that colours the object on screen (so never stale after an edit).
    let colors: Option<Vec<[u8; 3]>> = match display.mode {
        ViewMode::Curvature(q) => cache.scale_of(o.id).map(|scale| {
            let map = crate::display::color_map(display);
            let k = CurvatureQuantity::ALL
                .iter()
                .position(|&x| x == q)
                .unwrap_or(0);
            (quantities[k].iter())
                .map(|x| map.at(scale.position(*x)))
                .collect()
        }),
        _ => None,
    };
    // Curvatures scale with the placement: 1/length, the Gaussian 1/length².
    let s = o.transform.scale;
    let fields: Vec<(String, Vec<f64>)> = (CurvatureQuantity::ALL.iter())
        .zip(quantities)
        .map(|(q, values)| {
            let power = if *q == CurvatureQuantity::Gaussian {
                2
            } else {
                1
            };
            let values = values.iter().map(|x| x / s.powi(power)).collect();
            (q.short_name().to_string(), values)
        })
        .collect();
    let mesh = FieldMesh {
        mesh: &mesh,
        fields: if format.carries_fields() {
            &fields
        } else {
            &[]
        },
        colors: colors.as_deref().filter(|_| format.carries_colors()),
        lines: &[],
    };
    atomic_write(path, Durability::Atomic, |w| {
        write_mesh(w, format, &mesh).map_err(std::io::Error::other)
    })
    .map_err(|e| write_error(path, &e))
}

/// A mesh object's refined mesh and its discrete curvatures, in the order of
/// [`CurvatureQuantity::ALL`] (NaN everywhere when the mesh is not manifold).
fn mesh_with_fields(m: &MeshShape) -> (TriMesh, [Vec<f64>; 5]) {
    let n = m.refined.positions.len();
    let quantities = CurvatureQuantity::ALL.map(|q| match &m.curvature {
        Ok(c) => crate::mesh_view::discrete_quantity(c, q),
        Err(_) => vec![f64::NAN; n],
    });
    let mesh = TriMesh {
        positions: m.refined.positions.clone(),
        normals: m.normals.clone(),
        uvs: vec![nalgebra::Point2::origin(); n],
        triangles: m.refined.triangles.clone(),
    };
    (mesh, quantities)
}

/// Writes the selected object's surface as a surface file (its own coordinates: the
/// placement stays in the scene).
pub fn export_surface(doc: &Document, path: &Path) -> Result<(), String> {
    let o = doc
        .selection
        .object
        .and_then(|i| doc.scene.objects.get(i))
        .ok_or("select an object to export")?;
    let surface = o
        .surface()
        .ok_or("the selected object is a mesh: export it as a mesh (PLY, OBJ, STL, glTF, VTK)")?;
    pssurf::io::save(surface, path).map_err(|e| match e {
        pssurf::io::FileError::Io { cause, .. } => write_error(path, &cause),
        other => other.to_string(),
    })
}

/// "cannot write PATH: the cause in a few words".
pub fn write_error(path: &Path, e: &std::io::Error) -> String {
    format!(
        "cannot write {}: {}",
        path.display(),
        pssurf::io::io_cause(e)
    )
}

/// Renders the 3D view (camera direction, light, mode, probe lines) at `size`, with the
/// visible objects framed to fill it, and writes it as PNG. A curvature plot's legend (the
/// one shown beside the view) takes a strip on the right of the picture, so the picture's
/// colours come with what they mean.
pub fn export_picture(
    runtime: &mut Runtime,
    doc: &Document,
    view: &ViewState,
    path: &Path,
    size: [u32; 2],
) -> Result<(), String> {
    if !(16..=8192).contains(&size[0]) || !(16..=8192).contains(&size[1]) {
        return Err("the picture must be between 16 and 8192 pixels on each side".into());
    }
    let state = runtime
        .gpu
        .clone()
        .ok_or("pictures need the wgpu renderer")?;
    let cache = &mut runtime.cache;
    cache.update(&doc.scene, &view.display);
    runtime
        .probe
        .refresh(&doc.scene, &view.probe, cache.scene_size());
    let legend = match view.display.mode {
        ViewMode::Curvature(_) => cache.legend(&doc.scene, doc.selection.object).cloned(),
        _ => None,
    };
    let strip = match &legend {
        Some(_) => legend_width(size).ok_or("the picture is too small for its legend")?,
        None => 0,
    };
    let scene_size = [size[0] - strip, size[1]];
    let mut framed = view.clone();
    let drawn = cache
        .ranges
        .iter()
        .filter_map(|r| cache.object_mesh(&doc.scene, r.object));
    if let Some((lo, hi)) = crate::display::bounds(drawn) {
        framed
            .camera
            .frame(lo, hi, scene_size[0] as f32 / scene_size[1] as f32);
    }
    let uniforms = crate::view3d::uniforms(&framed, scene_size);
    let scene = crate::gpu::render_picture(
        &state.device,
        &state.queue,
        &cache.geometry,
        &runtime.extra,
        &uniforms,
        scene_size,
    )?;
    let mut picture = image::RgbaImage::new(size[0], size[1]);
    image::imageops::replace(&mut picture, &scene, 0, 0);
    if let Some(legend) = &legend {
        let map = crate::display::color_map(&view.display);
        let note = crate::legend::range_note(&view.display, legend);
        let strip_image = crate::legend::picture(legend, &map, &note, strip, size[1]);
        let strip_image = image::DynamicImage::ImageRgb8(strip_image).to_rgba8();
        image::imageops::replace(&mut picture, &strip_image, i64::from(scene_size[0]), 0);
    }
    let mut png = Vec::new();
    picture
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    atomic_write_bytes(path, Durability::Atomic, &png).map_err(|e| write_error(path, &e))
}

/// The width of the legend strip of a picture of `size` (an eighth of the width, 150 to 400
/// pixels), or None when the picture is too small to hold it beside a view.
pub fn legend_width(size: [u32; 2]) -> Option<u32> {
    let w = (size[0] / 8).clamp(150, 400);
    (size[0] >= 2 * w && size[1] >= 120).then_some(w)
}

impl ExportDialog {
    /// The command that runs the export the dialog describes (an error when no file is
    /// given).
    pub fn command(&self) -> Command {
        let path = PathBuf::from(self.path.trim());
        if path.as_os_str().is_empty() {
            return Command::Error("Give a file name to export to.".into());
        }
        match self.what {
            ExportKind::Mesh => Command::ExportMesh {
                path,
                format: self.format,
            },
            ExportKind::Picture => Command::ExportPicture {
                path,
                size: self.size,
            },
            ExportKind::Surface => Command::ExportSurface { path },
        }
    }

    /// The file name in the dialog (for the file chooser to propose).
    pub fn file_name(&self) -> String {
        crate::files::file_name(std::path::Path::new(self.path.trim()))
    }

    /// Opens the dialog with a file name suggested from the document.
    pub fn open(&mut self, what: ExportKind, doc: &Document) {
        self.what = what;
        self.open = true;
        self.path = suggested_path(self, doc);
    }

    /// Draws the dialog when open; Export goes to `cx` as a command.
    pub fn window(&mut self, ctx: &egui::Context, cx: &mut ViewContext<'_>) {
        if !self.open {
            return;
        }
        let mut open = true;
        let (mut go, mut browse) = (false, false);
        let before = (self.what, self.format);
        egui::Window::new("Export")
            .open(&mut open)
            .resizable(false)
            .show(ctx, |ui| (go, browse) = self.fields(ui));
        if browse {
            cx.emit(Command::Choose(crate::files::Purpose::ExportTo));
        }
        if (self.what, self.format) != before {
            // Keep the typed name, change the extension.
            let p = PathBuf::from(self.path.trim()).with_extension(extension(self));
            self.path = p.display().to_string();
        }
        if go {
            cx.emit(self.command());
        }
        if !open {
            self.open = false;
        }
    }

    /// The dialog's fields; returns whether Export and Browse were clicked.
    fn fields(&mut self, ui: &mut egui::Ui) -> (bool, bool) {
        let d = self;
        ui.horizontal_wrapped(|ui| {
            ui.radio_value(&mut d.what, ExportKind::Mesh, "mesh of the selected object");
            ui.radio_value(&mut d.what, ExportKind::Picture, "picture of the 3D view");
            ui.radio_value(
                &mut d.what,
                ExportKind::Surface,
                "surface file of the selected object",
            )
            .on_hover_text("The surface alone, in its own coordinates, as `pssurf` reads it");
        });
        match d.what {
            ExportKind::Mesh => {
                egui::ComboBox::from_label("format")
                    .selected_text(extension(d))
                    .show_ui(ui, |ui| {
                        for (f, name) in FORMATS {
                            ui.selectable_value(&mut d.format, f, name);
                        }
                    });
                ui.weak(if d.format.carries_fields() {
                    "with the curvature fields K, H, k1, k2, kabs"
                } else {
                    "geometry only (the format has no scalar fields)"
                });
            }
            ExportKind::Surface => {
                ui.weak("the placement, material and name stay in the scene");
            }
            ExportKind::Picture => {
                ui.horizontal(|ui| {
                    let l = ui.label("width");
                    ui.add(egui::DragValue::new(&mut d.size[0]).range(16..=8192))
                        .labelled_by(l.id);
                    let l = ui.label("height");
                    ui.add(egui::DragValue::new(&mut d.size[1]).range(16..=8192))
                        .labelled_by(l.id);
                });
            }
        }
        let mut browse = false;
        ui.horizontal(|ui| {
            let l = ui.label("file");
            ui.text_edit_singleline(&mut d.path).labelled_by(l.id);
            browse = ui.button("Browse…").clicked();
        });
        (ui.button("Export").clicked(), browse)
    }
}
