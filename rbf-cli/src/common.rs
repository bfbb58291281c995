//! What every command shares: reading inputs (files or stdin), writing outputs without leaving
//! half-written files, the built-in mesh, and the spinner shown while a long step runs.

use std::io::{Read, Write};
use std::path::Path;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget};

use crate::failure::{BAD_INPUT, Failure};

/// The text of a file, or of stdin for `-`.
pub(crate) fn read_text(path: &Path) -> Result<String, Failure> {
    let mut text = String::new();
    let result = if path == Path::new("-") {
        std::io::stdin().read_to_string(&mut text).map(|_| ())
    } else {
        std::fs::File::open(path).and_then(|mut f| f.read_to_string(&mut text).map(|_| ()))
    };
    result.map_err(|e| Failure::new(BAD_INPUT, format!("{}: {e}", path.display())))?;
    Ok(text)
}

/// A model file, either dimension.
pub(crate) fn read_model(path: &Path) -> Result<rbf_core::AnyModel, Failure> {
    rbf_core::AnyModel::from_json(&read_text(path)?)
        .map_err(|e| Failure::file(&path.display().to_string(), &e))
}

/// A 3D model file; a 2D one is a usage error saying that `command` works on surfaces.
pub(crate) fn read_model_3d(path: &Path, command: &str) -> Result<rbf_core::Model<3>, Failure> {
    match read_model(path)? {
        rbf_core::AnyModel::Three(model) => Ok(model),
        rbf_core::AnyModel::Two(_) => Err(Failure::new(
            crate::failure::USAGE,
            format!(
                "{} is a 2D model: {command} works on surfaces in 3D (curves are plotted with `rbf plot`)",
                path.display()
            ),
        )),
    }
}

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename, so
/// that an interrupted run never leaves a truncated file behind.
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    let fail = |e: std::io::Error| Failure::new(BAD_INPUT, format!("{}: {e}", path.display()));
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = std::fs::File::create(&tmp)
        .and_then(|mut f| f.write_all(bytes).and_then(|_| f.sync_all()))
        .and_then(|_| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(fail(e));
    }
    Ok(())
}

/// Spot the cow (Keenan Crane, public domain; see NOTICE.md), inside the binary for `rbf demo`
/// and `rbf gallery`.
pub(crate) const SPOT: &[u8] = include_bytes!("../assets/spot.obj");

/// A mesh file (OBJ, PLY, STL); a failure names the file and, for a parse error, the line.
pub(crate) fn read_mesh(path: &Path) -> Result<rbf_mesh::TriMesh, Failure> {
    rbf_mesh::read_mesh(path).map_err(|e| Failure::mesh(&e))
}

/// A spinner on stderr while a long step runs, if stderr is a terminal and not `--quiet`.
pub(crate) fn spinner(quiet: bool, message: String) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    if quiet {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    bar.set_message(message);
    bar.enable_steady_tick(Duration::from_millis(120));
    bar
}

/// "watertight, genus 0, 1 component(s)" for a polygonized surface; `open` says what an open
/// mesh means for the command.
pub(crate) fn surface_topology(r: &rbf_mesh::MeshReport, open: &str) -> String {
    format!(
        "{}, genus {}, {} component(s)",
        if r.is_watertight() {
            "watertight"
        } else {
            open
        },
        r.genus.map_or("-".into(), |g| g.to_string()),
        r.components
    )
}
