//! A file's kind by its extension, as the renderer's readers and writers tell them apart
//! (`.exr`/`.hdr`/`.png`, `.gbrdf`/`.astm`/`.binary`, `.toml`): compared without regard to case.

use std::path::Path;

/// The extension of `path` in lower case ("" without one, or when it is not UTF-8).
pub(crate) fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default()
}
