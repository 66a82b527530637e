//! `--presort-cache FILE`: a `Presorted` certificate built once and loaded on later runs.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use face_sort::{Geometry, PresortError, PresortOptions, Presorted};

/// How the certificate was had.
#[derive(Debug)]
pub enum Source {
    /// Built (no cache asked for).
    Built,
    /// Built and written to the cache (the file was missing, or refused on load: why).
    Saved(Option<String>),
    /// Loaded from the cache.
    Loaded,
}

impl Source {
    /// Words for a summary line, naming the file.
    pub fn words(&self, cache: Option<&Path>) -> String {
        let file = cache.map_or_else(String::new, |p| p.display().to_string());
        match self {
            Source::Built => "built".to_owned(),
            Source::Saved(None) => format!("built and saved to {file}"),
            Source::Saved(Some(why)) => {
                format!("built again and saved to {file} (the saved one was refused: {why})")
            }
            Source::Loaded => format!("loaded from {file}"),
        }
    }
}

/// The certificate of `geometry`: loaded from `cache` when it holds one for this geometry,
/// else built (and written there when `cache` is given), with the milliseconds either took.
///
/// # Errors
/// The build's own refusal (a budget), or the cache file failing to be written.
pub fn load_or_build(
    geometry: &Geometry,
    cache: Option<&Path>,
) -> Result<Result<(Presorted, Source, f64), PresortError>> {
    let start = Instant::now();
    let mut refused = None;
    if let Some(path) = cache
        && let Ok(bytes) = std::fs::read(path)
    {
        match Presorted::from_bytes(&bytes, geometry) {
            Ok(sorter) => {
                let ms = start.elapsed().as_secs_f64() * 1e3;
                return Ok(Ok((sorter, Source::Loaded, ms)));
            }
            Err(error) => refused = Some(error.to_string()),
        }
    }
    // A bar on builds that take over a second (on a terminal).
    let bar = std::sync::OnceLock::new();
    let progress = |p: face_sort::PresortProgress| {
        if start.elapsed().as_secs_f64() > 1.0 {
            let bar = bar.get_or_init(|| crate::progress::bar(p.total as u64, "presort"));
            bar.set_length(p.total as u64);
            bar.set_position(p.done as u64);
        }
    };
    let built = Presorted::try_new_with_progress(geometry, &PresortOptions::default(), &progress);
    if let Some(bar) = bar.get() {
        bar.finish_and_clear();
    }
    let sorter = match built {
        Ok(sorter) => sorter,
        Err(error) => return Ok(Err(error)),
    };
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let source = match cache {
        Some(path) => {
            std::fs::write(path, sorter.to_bytes())
                .with_context(|| format!("writing the presort cache {}", path.display()))?;
            Source::Saved(refused)
        }
        None => Source::Built,
    };
    Ok(Ok((sorter, source, ms)))
}
