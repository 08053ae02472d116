//! `pssurf-app [FILE...]`: the interactive application; `--screenshot OUT.png` renders one
//! picture without a window and exits.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Parser;
use pssurf_app::App;
use pssurf_app::display::ViewMode;
use pssurf_app::scene::Scene;
use pssurf_app::state::ViewState;

/// The pssurf modeller: open PS, UPS and NURPS surfaces (or scenes) and interrogate them.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Scene or surface files to open (none: the built-in demo scene).
    files: Vec<PathBuf>,
    /// Render the scene once to this PNG file and exit (needs no display; uses wgpu, e.g.
    /// Mesa's software Vulkan).
    #[arg(long, value_name = "OUT.png")]
    screenshot: Option<PathBuf>,
    /// Start in this view: shaded, zebra, wireframe, or a curvature quantity (K, H, k1, k2,
    /// kabs).
    #[arg(long, value_name = "MODE")]
    mode: Option<String>,
    /// Start with the probe on object OBJECT (0 is the first) at parameters (U, V).
    #[arg(long, value_name = "OBJECT,U,V", allow_hyphen_values = true)]
    probe: Option<String>,
    /// Window or screenshot size.
    #[arg(long, value_name = "WxH", default_value = "1400x900")]
    size: String,
}

fn parse_size(s: &str) -> Result<(f32, f32)> {
    let (w, h) = s
        .split_once('x')
        .context("--size must look like 1400x900")?;
    let (w, h): (f32, f32) = (w.trim().parse()?, h.trim().parse()?);
    if !(w >= 200.0 && h >= 150.0 && w <= 8192.0 && h <= 8192.0) {
        bail!("--size must be between 200x150 and 8192x8192");
    }
    Ok((w, h))
}

fn parse_mode(s: &str) -> Result<ViewMode> {
    ViewMode::parse(s).map_err(|e| anyhow::anyhow!("--mode: {e}"))
}

fn parse_probe(s: &str) -> Result<(usize, f64, f64)> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [object, u, v] = parts[..] else {
        bail!("--probe must look like 1,0.2,-0.1 (object, u, v)");
    };
    let (u, v): (f64, f64) = (u.parse()?, v.parse()?);
    if !(u.is_finite() && v.is_finite()) {
        bail!("--probe: u and v must be finite numbers");
    }
    Ok((object.parse()?, u, v))
}

fn load(files: &[PathBuf]) -> Result<App> {
    if files.is_empty() {
        return Ok(App::demo());
    }
    if let [file] = files {
        let (scene, kind) = Scene::load_file(file)?;
        return Ok(App::from_file(scene, file.clone(), kind));
    }
    // Several files make one new, unnamed scene.
    let mut scene = Scene::default();
    for f in files {
        scene.objects.extend(Scene::load(f)?.objects);
    }
    Ok(App::new(scene, None))
}

/// The saved view settings of earlier sessions, unless rendering a screenshot (which must
/// not depend on them). A damaged settings file is reported and replaced on exit.
fn restore_view(app: &mut App, interactive: bool) {
    if !interactive {
        return;
    }
    app.view_file = ViewState::default_path();
    let Some(path) = app.view_file.clone().filter(|p| p.exists()) else {
        return;
    };
    match ViewState::load(&path) {
        Ok(view) => app.restore_view(view),
        Err(e) => app.status = format!("view settings not restored: {e}"),
    }
}

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            // One line, whatever the causes hold (issue 13).
            let message = format!("{e:#}").replace(['\n', '\r'], " ");
            eprintln!("error: {}", pssurf::text::cut_line(&message));
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let args = Args::parse();
    let (w, h) = parse_size(&args.size)?;
    let mut app = load(&args.files)?;
    restore_view(&mut app, args.screenshot.is_none());
    if let Some(m) = &args.mode {
        app.view.display.mode = parse_mode(m)?;
    }
    if let Some(text) = &args.probe {
        let (object, u, v) = parse_probe(text)?;
        if object >= app.doc.scene.objects.len() {
            bail!("--probe: there is no object {object}");
        }
        app.update_geometry();
        app.set_probe(object, nalgebra::Point2::new(u, v));
        if app.probe().is_none() {
            bail!("--probe: ({u}, {v}) lies outside the domain of object {object}");
        }
    }
    if let Some(out) = args.screenshot {
        let picture = pssurf_app::headless::screenshot(app, w, h).map_err(anyhow::Error::msg)?;
        let mut png = Vec::new();
        picture.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)?;
        pssurf::io::atomic_write_bytes(&out, pssurf::io::Durability::Atomic, &png)?;
        eprintln!("wrote {}", out.display());
        return Ok(());
    }
    app.autosave =
        std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache/pssurf-app/autosave.json"));
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([w, h])
            .with_drag_and_drop(true)
            .with_title(app.title()),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    eframe::run_native(
        "pssurf",
        options,
        Box::new(move |cc| {
            if let Some(state) = &cc.wgpu_render_state {
                app.attach_gpu(state.clone());
            }
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("could not start the window: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use pssurf::interrogate::CurvatureQuantity;

    #[test]
    fn bad_options_are_clear_errors() {
        assert_eq!(parse_probe("1, 0.2,-0.1").unwrap(), (1, 0.2, -0.1));
        for bad in ["1,0.2", "x,0,0", "1,nan,0", "1,0,inf", "1,0,0,0"] {
            assert!(parse_probe(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_mode("wireframe").unwrap(), ViewMode::Wireframe);
        assert_eq!(
            parse_mode("H").unwrap(),
            ViewMode::Curvature(CurvatureQuantity::Mean)
        );
        let e = parse_mode("glossy").unwrap_err().to_string();
        assert!(e.contains("shaded, zebra, wireframe"), "{e}");
        assert_eq!(parse_size("800x600").unwrap(), (800.0, 600.0));
        for bad in ["800", "10x10", "axb", "99999x600"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }
}
