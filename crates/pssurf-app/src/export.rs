//! The Export dialog: the selected object's mesh in any of the library's formats (with the
//! curvature fields and the plot's colours where the format carries them), or a picture of
//! the 3D view at any size, rendered offscreen by the view's own renderer.

use std::path::{Path, PathBuf};

use nalgebra::Point3;
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::io::{Durability, atomic_write, atomic_write_bytes};
use pssurf_viz::{FieldMesh, MeshFormat, write_mesh};

use crate::app::App;
use crate::display::{ViewMode, display_level};

/// What to export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum What {
    /// The selected object's mesh.
    Mesh,
    /// The 3D view as a PNG picture.
    Picture,
}

/// The dialog's state.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportDialog {
    /// Whether the window is open.
    pub open: bool,
    /// Mesh or picture.
    pub what: What,
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
            what: What::Mesh,
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
        What::Picture => "png",
        What::Mesh => FORMATS
            .iter()
            .find(|(f, _)| *f == d.format)
            .map_or("ply", |(_, e)| e),
    }
}

/// A file name next to the scene file, from the object's name.
fn suggested_path(app: &App) -> String {
    let dir = app
        .doc
        .path
        .as_ref()
        .and_then(|p| p.parent())
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let stem = match app.export.what {
        What::Picture => "view".to_string(),
        What::Mesh => app
            .selection
            .object
            .and_then(|i| app.doc.scene.objects.get(i))
            .map_or("surface".into(), |o| {
                o.name.replace(|c: char| !c.is_alphanumeric(), "_")
            }),
    };
    dir.join(format!("{stem}.{}", extension(&app.export)))
        .display()
        .to_string()
}

/// Writes the selected object's mesh in scene placement: points and normals transformed,
/// all five curvature fields (in scene units), and the plot's colours in a curvature plot.
pub fn export_mesh(app: &App, path: &Path, format: MeshFormat) -> Result<(), String> {
    let i = app
        .selection
        .object
        .filter(|&i| i < app.doc.scene.objects.len())
        .ok_or("select an object to export")?;
    let o = &app.doc.scene.objects[i];
    let level = display_level(o, &app.display);
    let mut sampled = sample_patches(&o.surface, level, true);
    let m = o.transform.matrix();
    let rotation = m.fixed_view::<3, 3>(0, 0).into_owned() / o.transform.scale;
    for (p, n) in sampled
        .mesh
        .positions
        .iter_mut()
        .zip(sampled.mesh.normals.iter_mut())
    {
        *p = m.transform_point(&Point3::from(*p)).coords;
        *n = rotation * *n;
    }
    let s = o.transform.scale;
    let fields: Vec<(String, Vec<f64>)> = CurvatureQuantity::ALL
        .iter()
        .map(|q| {
            let power = if *q == CurvatureQuantity::Gaussian {
                2
            } else {
                1
            };
            let values = sampled
                .quantity(*q)
                .iter()
                .map(|x| x / s.powi(power))
                .collect();
            (q.short_name().to_string(), values)
        })
        .collect();
    // The plot's colours, when the view shows one (the cached mesh has the same layout).
    let colors: Option<Vec<[u8; 3]>> = match app.display.mode {
        ViewMode::Curvature(_) => app
            .object_mesh(i)
            .filter(|mesh| mesh.vertices.len() == sampled.mesh.positions.len())
            .map(|mesh| {
                mesh.vertices
                    .iter()
                    .map(|v| [v.color[0], v.color[1], v.color[2]])
                    .collect()
            }),
        _ => None,
    };
    let mesh = FieldMesh {
        mesh: &sampled.mesh,
        fields: if format.carries_fields() {
            &fields
        } else {
            &[]
        },
        colors: colors.as_deref().filter(|_| format.carries_colors()),
    };
    atomic_write(path, Durability::Atomic, |w| {
        write_mesh(w, format, &mesh).map_err(std::io::Error::other)
    })
    .map_err(|e| e.to_string())
}

/// Renders the 3D view (camera direction, light, mode, probe lines; without the egui legend)
/// at `size`, with the visible objects framed to fill the picture, and writes it as PNG.
pub fn export_picture(app: &mut App, path: &Path, size: [u32; 2]) -> Result<(), String> {
    if !(16..=8192).contains(&size[0]) || !(16..=8192).contains(&size[1]) {
        return Err("the picture must be between 16 and 8192 pixels on each side".into());
    }
    let state = app
        .render_state
        .clone()
        .ok_or("pictures need the wgpu renderer")?;
    app.update_geometry();
    app.refresh_probe();
    let on_screen = app.camera;
    if let Some((lo, hi)) = crate::display::bounds(
        app.cache
            .ranges
            .iter()
            .filter_map(|r| app.object_mesh(r.object)),
    ) {
        app.camera.frame(lo, hi, size[0] as f32 / size[1] as f32);
    }
    let uniforms = crate::view3d::uniforms(app, size);
    app.camera = on_screen;
    let picture = crate::gpu::render_picture(
        &state.device,
        &state.queue,
        &app.cache.geometry,
        &app.probe_lines,
        &uniforms,
        size,
    )?;
    let mut png = Vec::new();
    picture
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    atomic_write_bytes(path, Durability::Atomic, &png).map_err(|e| e.to_string())
}

/// Runs the export the dialog describes.
pub fn run(app: &mut App) {
    let path = PathBuf::from(app.export.path.trim());
    if path.as_os_str().is_empty() {
        app.error = Some("Give a file name to export to.".into());
        return;
    }
    let result = match app.export.what {
        What::Mesh => export_mesh(app, &path, app.export.format),
        What::Picture => export_picture(app, &path, app.export.size),
    };
    match result {
        Ok(()) => {
            app.status = format!("wrote {}", path.display());
            app.export.open = false;
        }
        Err(e) => app.error = Some(format!("Could not export.\n\n{e}")),
    }
}

/// Opens the dialog with a suggested file name.
pub fn open(app: &mut App, what: What) {
    app.export.what = what;
    app.export.open = true;
    app.export.path = suggested_path(app);
}

/// Draws the dialog when open.
pub fn window(app: &mut App, ctx: &egui::Context) {
    if !app.export.open {
        return;
    }
    let mut open = true;
    let mut go = false;
    let before = (app.export.what, app.export.format);
    egui::Window::new("Export")
        .open(&mut open)
        .resizable(false)
        .show(ctx, |ui| {
            let d = &mut app.export;
            ui.horizontal(|ui| {
                ui.radio_value(&mut d.what, What::Mesh, "mesh of the selected object");
                ui.radio_value(&mut d.what, What::Picture, "picture of the 3D view");
            });
            match d.what {
                What::Mesh => {
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
                What::Picture => {
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
            ui.horizontal(|ui| {
                let l = ui.label("file");
                ui.text_edit_singleline(&mut d.path).labelled_by(l.id);
            });
            go = ui.button("Export").clicked();
        });
    if (app.export.what, app.export.format) != before {
        // Keep the typed name, change the extension.
        let p = PathBuf::from(app.export.path.trim()).with_extension(extension(&app.export));
        app.export.path = p.display().to_string();
    }
    if go {
        run(app);
    }
    if !open {
        app.export.open = false;
    }
}
