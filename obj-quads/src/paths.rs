//! Confinement of the files a model names (glTF buffers and images, OBJ
//! `mtllib`, MTL `map_Kd`) to the model's folder.
//!
//! A named file is resolved against the folder it is relative to, then
//! canonicalised (which follows `..`, symbolic links and absolute paths), and
//! accepted only when the result lies inside the canonical model folder,
//! unless the caller allows paths outside
//! ([`LoadOptions::allow_outside_paths`](crate::LoadOptions::allow_outside_paths)).
//! The canonical path is the one read, so the check and the read name the
//! same file.

use std::path::{Path, PathBuf};

/// The folder a model's named files must stay in.
#[derive(Debug, Clone)]
pub(crate) struct Folder {
    /// The model's folder as given (for display and for resolving when allowed).
    given: PathBuf,
    /// Its canonical form, `None` when it cannot be canonicalised.
    canonical: Option<PathBuf>,
    /// Paths outside are allowed.
    allow_outside: bool,
}

/// Why a named file is not read.
#[derive(Debug)]
pub(crate) enum Refusal {
    /// It resolves outside the model's folder.
    Outside {
        /// Where it resolves to.
        resolved: PathBuf,
    },
    /// It does not exist or cannot be resolved.
    Unresolvable {
        /// The joined (non-canonical) path.
        joined: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

impl Folder {
    /// The folder of a model file `dir` (its parent directory; empty means the
    /// current directory).
    pub(crate) fn new(dir: &Path, allow_outside: bool) -> Folder {
        let given = if dir.as_os_str().is_empty() {
            PathBuf::from(".")
        } else {
            dir.to_path_buf()
        };
        let canonical = given.canonicalize().ok();
        Folder {
            given,
            canonical,
            allow_outside,
        }
    }

    /// The folder as given.
    pub(crate) fn path(&self) -> &Path {
        &self.given
    }

    /// Resolves `name` relative to `dir` (the model's folder or a folder
    /// inside it, e.g. an MTL library's) and checks that it stays inside the
    /// model's folder. Returns the path to read.
    pub(crate) fn resolve(&self, dir: &Path, name: &Path) -> Result<PathBuf, Refusal> {
        let joined = dir.join(name);
        if self.allow_outside {
            return Ok(joined);
        }
        let resolved = joined
            .canonicalize()
            .map_err(|source| Refusal::Unresolvable {
                joined: joined.clone(),
                source,
            })?;
        match &self.canonical {
            Some(root) if resolved.starts_with(root) => Ok(resolved),
            _ => Err(Refusal::Outside { resolved }),
        }
    }
}

impl Refusal {
    /// One-line description for warnings.
    pub(crate) fn describe(&self, folder: &Folder, name: &str) -> String {
        match self {
            Refusal::Outside { resolved } => format!(
                "`{name}` resolves to {} outside the model's folder {} \
                 (LoadOptions::allow_outside_paths allows it)",
                resolved.display(),
                folder.path().display()
            ),
            Refusal::Unresolvable { joined, source } => {
                format!("`{name}` ({}): {source}", joined.display())
            }
        }
    }
}
