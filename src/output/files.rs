//! Writing result files: atomically, so that an interrupted run never leaves a half-written
//! result that a later run could read as good.

use std::io::Write;
use std::path::Path;

/// Write `bytes` to `path` atomically: a temporary file beside it, renamed into place.
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |out| out.write_all(bytes))
}

/// Write what `fill` writes to `path` atomically: into a temporary file beside it, renamed
/// into place once `fill` has succeeded (on failure `path` is untouched).
pub(crate) fn write_atomic_with(
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
pub(crate) struct OutputPathError {
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
pub(crate) fn check_output_path(
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
pub(crate) const REPORT_MARKER: &str = ".millimpact-report";

/// Check that a report may be written whole into the folder `path`: it does not exist, or it
/// is an empty folder, or one that holds [`REPORT_MARKER`] (an earlier report). A folder with
/// other files, a symbolic link, something that is not a folder, and the working directory or
/// a folder above it are refused, never replaced.
pub(crate) fn check_report_dir(option: &'static str, path: &Path) -> Result<(), OutputPathError> {
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

/// Why a folder could not be written whole by [`replace_dir`]; each names the folder or file
/// it concerns and keeps the system's error as its source.
#[derive(Debug, thiserror::Error)]
pub enum ReplaceDirError {
    /// The path has no folder name (`/`, or one ending in `..`).
    #[error("{}: a folder's name is needed", path.display())]
    NoName {
        /// The path as resolved.
        path: std::path::PathBuf,
    },
    /// The path could not be made absolute.
    #[error("resolving {}", path.display())]
    Resolve {
        /// The path given.
        path: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The parent folder could not be made.
    #[error("creating {}", path.display())]
    CreateParent {
        /// The parent folder.
        path: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// No temporary folder could be made beside the output.
    #[error("making a folder in {}", parent.display())]
    Temporary {
        /// The parent folder.
        parent: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The new folder could not be opened to those who may read its parent.
    #[error("opening {} to readers", path.display())]
    Permissions {
        /// The new folder.
        path: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The earlier folder could not be moved aside.
    #[error("moving the earlier {} aside", path.display())]
    MoveAside {
        /// The output folder.
        path: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The new folder could not take the output's place.
    #[error("moving the new {} in", path.display())]
    MoveIn {
        /// The output folder.
        path: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The earlier folder, moved aside, could not be removed.
    #[error("removing the earlier output, moved to {}", aside.display())]
    RemoveEarlier {
        /// Where the earlier folder was moved.
        aside: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

/// A folder that could not be written is the system's failure, not the input's.
impl crate::error::Blame for ReplaceDirError {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// Write the folder `path` whole: `fill` writes into a fresh folder beside it, which then
/// takes its place (an earlier folder there is moved aside and removed), so that no file of
/// an earlier output survives and an interrupted write leaves the earlier folder as it was.
/// A report's `path` is checked by `check_report_dir` first. `fill`'s own error type is
/// kept, and a failure of the folder's handling becomes one of it.
pub fn replace_dir<E: From<ReplaceDirError>>(
    path: &Path,
    fill: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    let path = match std::fs::canonicalize(path) {
        Ok(real) => real,
        Err(_) => std::path::absolute(path).map_err(|source| ReplaceDirError::Resolve {
            path: path.to_path_buf(),
            source,
        })?,
    };
    let (Some(parent), Some(name)) = (path.parent(), path.file_name()) else {
        return Err(ReplaceDirError::NoName { path }.into());
    };
    let name = name.to_string_lossy();
    std::fs::create_dir_all(parent).map_err(|source| ReplaceDirError::CreateParent {
        path: parent.to_path_buf(),
        source,
    })?;
    let temporary = |prefix: String| {
        tempfile::Builder::new()
            .prefix(&prefix)
            .tempdir_in(parent)
            .map_err(|source| ReplaceDirError::Temporary {
                parent: parent.to_path_buf(),
                source,
            })
    };
    let fresh = temporary(format!(".{name}.new-"))?;
    fill(fresh.path())?;
    // A temporary folder is private (0700); an output is for everyone who may read its parent.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(fresh.path(), std::fs::Permissions::from_mode(0o755)).map_err(
            |source| ReplaceDirError::Permissions {
                path: fresh.path().to_path_buf(),
                source,
            },
        )?;
    }
    let fresh = fresh.keep();
    let earlier = if path.exists() {
        // Renaming a folder onto an empty one replaces it: the earlier folder goes to a free
        // name beside it.
        let aside = temporary(format!(".{name}.old-"))?.keep();
        std::fs::rename(&path, &aside).map_err(|source| ReplaceDirError::MoveAside {
            path: path.clone(),
            source,
        })?;
        Some(aside)
    } else {
        None
    };
    if let Err(source) = std::fs::rename(&fresh, &path) {
        if let Some(aside) = &earlier {
            let _ = std::fs::rename(aside, &path);
        }
        let _ = std::fs::remove_dir_all(&fresh);
        return Err(ReplaceDirError::MoveIn { path, source }.into());
    }
    if let Some(aside) = earlier {
        std::fs::remove_dir_all(&aside)
            .map_err(|source| ReplaceDirError::RemoveEarlier { aside, source })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::{ReplaceDirError, replace_dir};

    #[test]
    fn replace_dir_keeps_the_fill_error_type_and_names_a_path_without_a_folder_name() {
        #[derive(Debug)]
        enum Mine {
            Folder(ReplaceDirError),
            Fill(&'static str),
        }
        impl From<ReplaceDirError> for Mine {
            fn from(e: ReplaceDirError) -> Self {
                Mine::Folder(e)
            }
        }
        let parent = tempfile::tempdir().unwrap();
        let out = parent.path().join("out");
        let filled = replace_dir(&out, |_| Err::<(), _>(Mine::Fill("no figures")));
        assert!(
            matches!(filled, Err(Mine::Fill("no figures"))),
            "{filled:?}"
        );
        assert!(!out.exists(), "a failed fill leaves no folder");
        let root = replace_dir(Path::new("/"), |_| Ok::<(), Mine>(()));
        match root {
            Err(Mine::Folder(ReplaceDirError::NoName { path })) => assert_eq!(path, Path::new("/")),
            other => panic!("expected NoName, got {other:?}"),
        }
    }
}
