//! The selected object's properties (name, group, material, placement), the numeric editor of the selected
//! vertex's control triangle (like the thesis' Figure 6.12), the display settings and the
//! probe panel.

use pssurf::interrogate::CurvatureQuantity;
use pssurf::surface::PiecewiseSurface;
use pssurf_viz::colormap::ColorMap;
use pssurf_viz::plot::Range;

use crate::app::App;
use crate::display::ViewMode;
use crate::edit;
use crate::probe::Alignment;
use crate::scene::Material;

/// Draws the properties of the selection.
pub fn ui(app: &mut App, ui: &mut egui::Ui) {
    let Some(i) = app
        .selection
        .object
        .filter(|&i| i < app.doc.scene.objects.len())
    else {
        ui.weak("Select an object.");
        return;
    };
    ui.heading("Object");
    let o = &app.doc.scene.objects[i];
    let (old_name, old_t) = (o.name.clone(), o.transform);
    let (old_group, old_material) = (o.group.clone(), o.material);
    let (mut name, mut group, mut material) = (o.name.clone(), o.group.clone(), o.material);
    let mut t = o.transform;
    ui.horizontal(|ui| {
        let label = ui.label("name");
        ui.text_edit_singleline(&mut name).labelled_by(label.id);
    });
    ui.horizontal(|ui| {
        let label = ui.label("group");
        ui.text_edit_singleline(&mut group)
            .labelled_by(label.id)
            .on_hover_text("Objects with the same group name are listed together");
    });
    egui::ComboBox::from_label("material")
        .selected_text(material.name())
        .show_ui(ui, |ui| {
            for m in Material::ALL {
                ui.selectable_value(&mut material, m, m.name());
            }
        });
    let n = edit::vertex_count(&o.surface);
    ui.label(format!(
        "{} surface, {n} vertices, {} triangles",
        o.surface.kind().name(),
        o.surface.ps_basis().map_or(o.surface.piece_count(), |b| b
            .triangulation()
            .triangle_count())
    ));
    egui::Grid::new("transform").num_columns(4).show(ui, |ui| {
        for (row, values, speed) in [
            ("move", &mut t.translate, 0.01),
            ("turn", &mut t.rotate_deg, 0.5),
        ] {
            ui.label(row);
            for (x, axis) in values.iter_mut().zip(["x", "y", "z"]) {
                let value = *x;
                let name = format!("{row} {axis}");
                ui.add(egui::DragValue::new(x).speed(speed))
                    .widget_info(|| labeled_value(true, value, &name));
            }
            ui.end_row();
        }
        let label = ui.label("scale");
        ui.add(
            egui::DragValue::new(&mut t.scale)
                .speed(0.01)
                .range(1e-6..=1e6),
        )
        .labelled_by(label.id);
        ui.end_row();
    });
    if name != old_name {
        let _ = app.doc.edit::<()>("rename", |s| {
            s.objects[i].name = name;
            Ok(())
        });
    }
    if group != old_group {
        let _ = app.doc.edit::<()>("group", |s| {
            s.objects[i].group = group.trim().to_string();
            Ok(())
        });
    }
    if material != old_material {
        let _ = app.doc.edit::<()>("material", |s| {
            s.objects[i].material = material;
            s.objects[i].touch();
            Ok(())
        });
    }
    if t != old_t {
        let _ = app.doc.edit::<()>("transform", |s| {
            s.objects[i].transform = t;
            s.objects[i].touch();
            Ok(())
        });
    }
    ui.separator();
    vertex_ui(app, ui, i);
}

fn vertex_ui(app: &mut App, ui: &mut egui::Ui, i: usize) {
    ui.heading("Control triangle");
    let Some(v) = app.selection.vertex else {
        ui.weak("Click a PS-triangle in the domain view to select its vertex.");
        return;
    };
    let surface = &app.doc.scene.objects[i].surface;
    if v >= edit::vertex_count(surface) {
        app.selection.vertex = None;
        return;
    }
    let current = edit::vertex_control(surface, v);
    // Keep the user's half-typed values while the same vertex stays selected.
    let mut c = match &app.vertex_edit {
        Some((oi, vi, c)) if *oi == i && *vi == v => c.clone(),
        _ => current.clone(),
    };
    ui.label(format!("vertex {v}"));
    let mut changed = false;
    egui::Grid::new("control")
        .num_columns(5)
        .striped(true)
        .show(ui, |ui| {
            ui.strong("");
            for h in [
                "x",
                "y",
                "z",
                if c.weights.is_some() { "weight" } else { "" },
            ] {
                ui.strong(h);
            }
            ui.end_row();
            for j in 0..c.points.len() {
                ui.label(format!("Q{}", j + 1));
                for k in 0..3 {
                    let enabled = !c.functional || k == 2;
                    let r = ui.add_enabled(
                        enabled,
                        egui::DragValue::new(&mut c.points[j][k])
                            .speed(0.005)
                            .max_decimals(6),
                    );
                    let (name, value) =
                        (format!("Q{} {}", j + 1, ["x", "y", "z"][k]), c.points[j][k]);
                    r.widget_info(|| labeled_value(enabled, value, &name));
                    changed |= r.changed();
                }
                if let Some(w) = &mut c.weights {
                    let r = ui.add(
                        egui::DragValue::new(&mut w[j])
                            .speed(0.01)
                            .range(1e-6..=1e6),
                    );
                    let (name, value) = (format!("Q{} weight", j + 1), w[j]);
                    r.widget_info(|| labeled_value(true, value, &name));
                    changed |= r.changed();
                }
                ui.end_row();
            }
        });
    if c.functional {
        ui.weak("A functional surface: only the heights of its control points can change.");
    }
    if changed && c != current {
        match app.set_vertex(i, v, c.clone()) {
            Ok(()) => app.vertex_edit = None,
            Err(e) => {
                app.status = e;
                app.vertex_edit = Some((i, v, c));
            }
        }
    }
}

/// Accessibility info of a number field with a name (so tests and screen readers find it).
fn labeled_value(enabled: bool, value: f64, name: &str) -> egui::WidgetInfo {
    let mut info = egui::WidgetInfo::drag_value(enabled, value);
    info.label = Some(name.to_string());
    info
}

/// Draws the display settings of the 3D view.
pub fn display_ui(app: &mut App, ui: &mut egui::Ui) {
    ui.heading("Display");
    let d = &mut app.display;
    egui::ComboBox::from_label("show")
        .selected_text(mode_name(d.mode))
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut d.mode, ViewMode::Shaded, "shaded");
            for q in CurvatureQuantity::ALL {
                ui.selectable_value(
                    &mut d.mode,
                    ViewMode::Curvature(q),
                    mode_name(ViewMode::Curvature(q)),
                );
            }
            ui.selectable_value(&mut d.mode, ViewMode::Zebra, "zebra stripes");
            ui.selectable_value(&mut d.mode, ViewMode::Wireframe, "wireframe");
        });
    if matches!(d.mode, ViewMode::Curvature(_)) {
        egui::ComboBox::from_label("colour map")
            .selected_text(d.colormap.clone())
            .show_ui(ui, |ui| {
                for name in ColorMap::NAMES {
                    ui.selectable_value(&mut d.colormap, name.to_string(), name);
                }
            });
        range_ui(ui, &mut d.range);
    }
    if d.mode == ViewMode::Zebra {
        ui.add(egui::Slider::new(&mut d.zebra_width_deg, 1.0..=20.0).text("band width °"));
    }
    ui.add(egui::Slider::new(&mut d.level, 0..=5).text("display level"))
        .on_hover_text("Each PS piece is drawn as 4^level triangles");
    if d.mode == ViewMode::Shaded {
        let l = &mut app.light;
        ui.checkbox(&mut l.headlight, "headlight")
            .on_hover_text("The light moves with the camera; off: fixed in the scene");
        if !l.headlight {
            ui.add(egui::Slider::new(&mut l.azimuth_deg, -180.0..=180.0).text("light azimuth °"));
            ui.add(egui::Slider::new(&mut l.elevation_deg, -90.0..=90.0).text("light elevation °"));
        }
    }
    let d = &mut app.display;
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut d.flat, "flat");
        ui.checkbox(&mut d.mesh_edges, "mesh edges")
            .on_hover_text("The edges of the drawn triangles (display level)");
        ui.checkbox(&mut d.overlays.wire, "triangulation");
        ui.checkbox(&mut d.overlays.refinement, "PS refinement");
        ui.checkbox(&mut d.overlays.control, "control triangles");
        ui.checkbox(&mut d.overlays.boundary, "boundary");
    });
}

/// The colour range: automatic, the seed's contrast curve with C, or a fixed interval.
fn range_ui(ui: &mut egui::Ui, range: &mut Range) {
    #[derive(PartialEq)]
    enum Kind {
        Auto,
        Contrast,
        Fixed,
    }
    let mut kind = match range {
        Range::Auto => Kind::Auto,
        Range::Contrast(_) => Kind::Contrast,
        Range::Fixed(..) => Kind::Fixed,
    };
    ui.horizontal(|ui| {
        ui.radio_value(&mut kind, Kind::Auto, "auto range")
            .on_hover_text("Symmetric about 0 at the 98th percentile of |q| for signed quantities");
        ui.radio_value(&mut kind, Kind::Contrast, "contrast C")
            .on_hover_text("The seed's contrast curve");
        ui.radio_value(&mut kind, Kind::Fixed, "fixed");
    });
    *range = match kind {
        Kind::Auto => Range::Auto,
        Kind::Contrast => {
            let mut c = match *range {
                Range::Contrast(c) => c,
                _ => 1.0,
            };
            ui.horizontal(|ui| {
                let l = ui.label("C");
                ui.add(egui::DragValue::new(&mut c).speed(0.05).range(1e-6..=1e6))
                    .labelled_by(l.id);
            });
            Range::Contrast(c)
        }
        Kind::Fixed => {
            let (mut lo, mut hi) = match *range {
                Range::Fixed(a, b) => (a, b),
                _ => (-1.0, 1.0),
            };
            ui.horizontal(|ui| {
                let l = ui.label("from");
                ui.add(egui::DragValue::new(&mut lo).speed(0.01))
                    .labelled_by(l.id);
                let l = ui.label("to");
                ui.add(egui::DragValue::new(&mut hi).speed(0.01))
                    .labelled_by(l.id);
            });
            // Keep the interval non-empty.
            if hi <= lo {
                hi = lo + 1e-9_f64.max(lo.abs() * 1e-9);
            }
            Range::Fixed(lo, hi)
        }
    };
}

/// The probe's settings and values.
pub fn probe_ui(app: &mut App, ui: &mut egui::Ui) {
    ui.label("Click the surface (Shift+drag to move), or Shift+click the domain view.");
    let s = &mut app.probe_settings;
    ui.horizontal(|ui| {
        ui.label("cross-planes:");
        ui.radio_value(&mut s.alignment, Alignment::Principal, "principal")
            .on_hover_text("Along the principal directions: the sections have curvatures κ1, κ2");
        ui.radio_value(&mut s.alignment, Alignment::Parametric, "parametric")
            .on_hover_text("Along the parameter directions s_u and s_v");
    });
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut s.planes, "planes");
        ui.checkbox(&mut s.sections, "sections");
        ui.checkbox(&mut s.circles, "osculating circles");
        ui.checkbox(&mut s.glyphs, "normal, directions");
    });
    let Some(p) = &app.probe else {
        ui.weak("no probe");
        return;
    };
    egui::Grid::new("probe values")
        .num_columns(2)
        .show(ui, |ui| {
            let mut row = |name: &str, value: String| {
                ui.label(name);
                ui.monospace(value);
                ui.end_row();
            };
            row("u, v", format!("{:.6}, {:.6}", p.uv.x, p.uv.y));
            let q = p.point;
            row("point", format!("{:.5}, {:.5}, {:.5}", q.x, q.y, q.z));
            match (&p.curvature, &p.cross) {
                (Some(c), Some(x)) => {
                    row("K", format!("{:.6e}", c.gaussian));
                    row("H", format!("{:.6e}", c.mean));
                    row("κ1", format!("{:.6e}", c.k1));
                    row("κ2", format!("{:.6e}", c.k2));
                    let n = c.normal;
                    row("normal", format!("{:.4}, {:.4}, {:.4}", n.x, n.y, n.z));
                    row("κn plane 1", format!("{:.6e}", x.curvatures[0]));
                    row("κn plane 2", format!("{:.6e}", x.curvatures[1]));
                }
                _ => row("curvature", "undefined (singular point)".into()),
            }
        });
    if ui.button("Remove probe").clicked() {
        app.probe = None;
    }
}

/// The UI name of a view mode.
pub fn mode_name(m: ViewMode) -> &'static str {
    match m {
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
