//! `pssurf view FILE...`: opens the files in the interactive application (the `pssurf-app`
//! binary, looked up next to this one, then on the PATH).

use std::path::PathBuf;
use std::process::Command;

use anyhow::{Context, Result, bail};

/// Arguments of `pssurf view`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Surface or scene files (none: the application's demo scene).
    #[arg(value_name = "FILE")]
    pub files: Vec<PathBuf>,
}

/// The application binary: beside the running `pssurf`, else `pssurf-app` on the PATH.
fn app_binary() -> PathBuf {
    let name = format!("pssurf-app{}", std::env::consts::EXE_SUFFIX);
    std::env::current_exe()
        .ok()
        .and_then(|exe| exe.parent().map(|d| d.join(&name)))
        .filter(|p| p.exists())
        .unwrap_or_else(|| PathBuf::from(name))
}

/// Runs `pssurf view`.
pub fn run(args: &ViewArgs) -> Result<()> {
    for f in &args.files {
        if !f.exists() {
            bail!("{}: no such file", f.display());
        }
    }
    let app = app_binary();
    let status = Command::new(&app)
        .args(&args.files)
        .status()
        .with_context(|| {
            format!(
                "could not start {} (build it with `cargo build --release -p pssurf-app`)",
                app.display()
            )
        })?;
    if !status.success() {
        // The application has said why in its own line: end with its status, adding none.
        std::process::exit(status.code().unwrap_or(1));
    }
    Ok(())
}
