//! Writing result files: atomically, so that an interrupted run never leaves a half-written
//! result that a later run could read as good.

use std::io::Write;
use std::path::Path;

/// Write `bytes` to `path` atomically: a temporary file beside it, renamed into place.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |out| out.write_all(bytes))
}

/// Write what `fill` writes to `path` atomically: into a temporary file beside it, renamed
/// into place once `fill` has succeeded (on failure `path` is untouched).
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir)?;
    // A hidden name, so that a write killed half way leaves nothing a reader of `*.json` or
    // `*.csv` takes for a result.
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut tmp = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(".tmp")
        .tempfile_in(dir)?;
    {
        let mut out = std::io::BufWriter::new(tmp.as_file_mut());
        fill(&mut out)?;
        out.flush()?;
    }
    tmp.as_file().sync_all()?;
    // A temporary file is private (0600); a result is for everyone who may read the folder.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// Why an output path cannot be written.
#[derive(Debug, thiserror::Error)]
#[error("{option} = {}: {reason}", path.display())]
pub struct OutputPathError {
    /// The option that named it.
    pub option: &'static str,
    /// The path.
    pub path: std::path::PathBuf,
    /// Why not.
    pub reason: &'static str,
}

/// Check that `path` may be written as a command's output: it does not exist, or it is a
/// regular file with one name that is not one of the command's `inputs`. A device, a folder,
/// a symbolic link, a hard-linked file or the command's own input is refused, never replaced.
pub fn check_output_path(
    option: &'static str,
    path: &Path,
    inputs: &[&Path],
) -> Result<(), OutputPathError> {
    let refuse = |reason| OutputPathError {
        option,
        path: path.to_path_buf(),
        reason,
    };
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        // A mistyped directory is refused rather than made: the file would land where nobody
        // looks for it.
        let parent = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        if !parent.is_dir() {
            return Err(refuse(
                "its directory does not exist (millimpact does not create it)",
            ));
        }
        return Ok(());
    };
    if meta.file_type().is_symlink() {
        return Err(refuse("a symbolic link; name the file itself"));
    }
    if !meta.file_type().is_file() {
        return Err(refuse("exists and is not a regular file"));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if meta.nlink() > 1 {
            return Err(refuse(
                "a file with other names (hard links); it would be replaced for all of them",
            ));
        }
        for input in inputs {
            if let Ok(other) = std::fs::metadata(input)
                && other.dev() == meta.dev()
                && other.ino() == meta.ino()
            {
                return Err(refuse("is an input of this command"));
            }
        }
    }
    Ok(())
}

/// The file a report writes into its folder: a later report recognises the folder as one it
/// may replace.
pub const REPORT_MARKER: &str = ".millimpact-report";

/// Check that a report may be written whole into the folder `path`: it does not exist, or it
/// is an empty folder, or one that holds [`REPORT_MARKER`] (an earlier report). A folder with
/// other files, a symbolic link, something that is not a folder, and the working directory or
/// a folder above it are refused, never replaced.
pub fn check_report_dir(option: &'static str, path: &Path) -> Result<(), OutputPathError> {
    let refuse = |reason| OutputPathError {
        option,
        path: path.to_path_buf(),
        reason,
    };
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return Ok(());
    };
    if meta.file_type().is_symlink() {
        return Err(refuse("a symbolic link; name the folder itself"));
    }
    if !meta.is_dir() {
        return Err(refuse("exists and is not a folder"));
    }
    let here = std::env::current_dir().and_then(std::fs::canonicalize);
    if let (Ok(dir), Ok(here)) = (std::fs::canonicalize(path), here)
        && here.starts_with(&dir)
    {
        return Err(refuse(
            "the working directory or a folder above it, which the output would replace; name a new folder, or an empty one, or one an earlier report wrote",
        ));
    }
    let mut entries = std::fs::read_dir(path).map_err(|_| refuse("cannot be read"))?;
    if entries.next().is_none() || path.join(REPORT_MARKER).is_file() {
        return Ok(());
    }
    Err(refuse(
        "a folder that is not empty and holds no earlier report (no .millimpact-report in it); name a new folder, or an empty one, or one an earlier report wrote",
    ))
}

/// Write the folder `path` whole: `fill` writes into a fresh folder beside it, which then
/// takes its place (an earlier folder there is moved aside and removed), so that no file of
/// an earlier output survives and an interrupted write leaves the earlier folder as it was.
/// A report's `path` is checked by [`check_report_dir`] first.
pub fn replace_dir(
    path: &Path,
    fill: impl FnOnce(&Path) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    use anyhow::Context;
    let path = match std::fs::canonicalize(path) {
        Ok(real) => real,
        Err(_) => std::path::absolute(path)?,
    };
    let (Some(parent), Some(name)) = (path.parent(), path.file_name()) else {
        anyhow::bail!("{}: a folder's name is needed", path.display());
    };
    let name = name.to_string_lossy();
    std::fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
    let fresh = tempfile::Builder::new()
        .prefix(&format!(".{name}.new-"))
        .tempdir_in(parent)
        .with_context(|| format!("making a folder in {}", parent.display()))?;
    fill(fresh.path())?;
    // A temporary folder is private (0700); an output is for everyone who may read its parent.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(fresh.path(), std::fs::Permissions::from_mode(0o755))?;
    }
    let fresh = fresh.keep();
    let earlier = if path.exists() {
        // Renaming a folder onto an empty one replaces it: the earlier folder goes to a free
        // name beside it.
        let aside = tempfile::Builder::new()
            .prefix(&format!(".{name}.old-"))
            .tempdir_in(parent)?
            .keep();
        std::fs::rename(&path, &aside)
            .with_context(|| format!("moving the earlier {} aside", path.display()))?;
        Some(aside)
    } else {
        None
    };
    if let Err(e) = std::fs::rename(&fresh, &path) {
        if let Some(aside) = &earlier {
            let _ = std::fs::rename(aside, &path);
        }
        let _ = std::fs::remove_dir_all(&fresh);
        return Err(anyhow::Error::from(e).context(format!("moving the new {} in", path.display())));
    }
    if let Some(aside) = earlier {
        std::fs::remove_dir_all(&aside).with_context(|| {
            format!("removing the earlier output, moved to {}", aside.display())
        })?;
    }
    Ok(())
}
