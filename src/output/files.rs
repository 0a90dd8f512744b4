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
