//! The view state that outlives a session: display settings, camera, light, what the probe
//! shows and the panels' settings. It is saved as JSON when the application closes and read
//! when it starts (the document is not part of it: it is saved by the user, and autosaved).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use pssurf::io::{Durability, atomic_write_bytes};
use serde::{Deserialize, Serialize};

use crate::camera::OrbitCamera;
use crate::display::{DisplaySettings, Light};
use crate::probe::ProbeSettings;

/// The saved view settings of the application.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ViewState {
    /// What the 3D view draws and how.
    pub display: DisplaySettings,
    /// The 3D camera.
    pub camera: OrbitCamera,
    /// The light of the shaded view.
    pub light: Light,
    /// What the probe shows.
    pub probe: ProbeSettings,
    /// Each algorithm panel's settings, by panel title (see `Panel::settings`).
    pub panels: BTreeMap<String, serde_json::Value>,
    /// The files opened or saved most recently, newest first (File → Open Recent).
    pub recent: Vec<PathBuf>,
}

/// The largest view-state file read (a real one is a few kilobytes).
const MAX_BYTES: u64 = 1 << 20;

impl ViewState {
    /// Where the view state is kept: `$XDG_CONFIG_HOME/pssurf-app/view.json`, else
    /// `~/.config/pssurf-app/view.json`.
    pub fn default_path() -> Option<PathBuf> {
        let config = std::env::var_os("XDG_CONFIG_HOME")
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
            .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
        Some(config.join("pssurf-app").join("view.json"))
    }

    /// Reads a saved view state; unknown fields are ignored and missing ones take their
    /// defaults, so settings of an older or newer build still load.
    pub fn load(path: &Path) -> Result<ViewState, String> {
        let fail = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
        let len = std::fs::metadata(path).map_err(|e| fail(&e))?.len();
        if len > MAX_BYTES {
            return Err(fail(&format!("{len} bytes is too large for view settings")));
        }
        let text = std::fs::read_to_string(path).map_err(|e| fail(&e))?;
        let state: ViewState = serde_json::from_str(&text).map_err(|e| fail(&e))?;
        state.validated().map_err(|e| fail(&e))
    }

    /// Writes the view state atomically (creating its directory).
    pub fn save(&self, path: &Path) -> Result<(), String> {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        let text = serde_json::to_string_pretty(self).map_err(|e| e.to_string())?;
        atomic_write_bytes(path, Durability::Atomic, text.as_bytes())
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// The state if every number in it is usable (finite camera, level within reach).
    fn validated(self) -> Result<ViewState, String> {
        let c = &self.camera;
        let numbers = [
            c.target.x,
            c.target.y,
            c.target.z,
            c.distance,
            c.azimuth_deg,
            c.elevation_deg,
            c.fov_deg,
            c.half_height,
            self.light.azimuth_deg,
            self.light.elevation_deg,
            self.display.zebra_width_deg,
        ];
        if !numbers.iter().all(|x| x.is_finite()) {
            return Err("the camera and light settings must be finite numbers".into());
        }
        let sizes = [c.distance, c.half_height, c.target.norm()];
        if !(c.distance > 0.0 && c.half_height > 0.0 && (0.0..170.0).contains(&c.fov_deg))
            || sizes.iter().any(|&x| x > 1e12)
        {
            return Err("the camera needs a positive distance and size, at most 1e12".into());
        }
        let zebra = self.display.zebra_width_deg;
        if !(1.0..=20.0).contains(&zebra) {
            return Err(format!("zebra band width {zebra}° is outside 1–20°"));
        }
        match self.display.range {
            pssurf_viz::plot::Range::Fixed(lo, hi)
                if !(lo.is_finite() && hi.is_finite() && lo < hi) =>
            {
                return Err(format!(
                    "the colour range [{lo}, {hi}] must be finite and non-empty"
                ));
            }
            pssurf_viz::plot::Range::Contrast(k) if !(k > 0.0 && k.is_finite()) => {
                return Err(format!("the contrast C = {k} must be positive and finite"));
            }
            _ => {}
        }
        if self.recent.len() > 4 * crate::files::RECENT {
            return Err(format!(
                "{} recent files is more than kept",
                self.recent.len()
            ));
        }
        if self.display.level > 5 {
            return Err(format!(
                "display level {} is beyond the largest (5)",
                self.display.level
            ));
        }
        Ok(self)
    }
}

#[cfg(test)]
mod fuzz {
    //! Issue 13: saved view settings of any content are refused with a message or load valid.

    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        #[test]
        fn mutated_view_settings_load_or_fail_cleanly(
            at in any::<usize>(),
            insert in "[-0-9.e,\\[\\]{}\":a-z ]{0,8}|1e309|-1e300|NaN",
            cut in 0usize..20,
        ) {
            let mut text = serde_json::to_string(&ViewState::default()).unwrap();
            let a = at % (text.len() + 1);
            let b = (a + cut).min(text.len());
            text.replace_range(a..b, &insert);
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("view.json");
            std::fs::write(&path, &text).unwrap();
            if let Ok(state) = ViewState::load(&path) {
                std::fs::write(&path, serde_json::to_string(&state).unwrap()).unwrap();
                prop_assert_eq!(ViewState::load(&path).unwrap(), state);
            }
        }
    }
}
