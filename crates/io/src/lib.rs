//! gonio-io: how gonio writes files and reports progress. Every file any gonio crate writes
//! (height maps, BRDF tables and exports, curves, pictures, reports) goes through
//! [`write_atomic`], so that a failure never leaves half a file and outputs get ordinary
//! permissions. Each crate maps the I/O errors into its own error type, naming the file; this
//! crate has no error type of its own. Long computations report how far they have come through
//! one [`Progress`] handle ([`progress`]), and are stopped early through a [`Cancel`] flag
//! ([`cancel`]).

pub mod cancel;
pub mod progress;

pub use cancel::Cancel;
pub use progress::{Progress, Report};

/// The extension of `path` in lower case ("" without one, or when it is not UTF-8): how gonio's
/// readers and writers tell a file's kind (`.exr`, `.gbrdf`, `.toml`, `.csv`…) without regard
/// to case.
pub fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default()
}

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Write the file `path` atomically: `body` writes into a temporary file beside `path`, which is
/// renamed over `path` only when `body` and the flush succeed (the `atomic-write-file` crate).
/// The target is therefore either the old file or the complete new one, never half a file, and
/// on an error the temporary file is removed. A new file gets the ordinary permissions (0666
/// less the umask), a replaced file keeps its own. `io_error` turns the I/O errors of opening,
/// flushing and renaming into the caller's error type; `body`'s errors are returned as they are.
pub fn write_atomic<E>(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<&mut File>) -> Result<(), E>,
    io_error: impl Fn(std::io::Error) -> E,
) -> Result<(), E> {
    let mut file = atomic_write_file::AtomicWriteFile::open(path).map_err(&io_error)?;
    {
        let mut w = BufWriter::new(file.as_file_mut());
        body(&mut w)?;
        w.flush().map_err(&io_error)?;
    }
    file.commit().map_err(io_error)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A body that fails half-way leaves the old file as it was and no temporary file beside it;
    /// one that succeeds replaces it whole.
    #[test]
    fn a_failed_write_keeps_the_old_file_and_leaves_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("peaks.csv");
        std::fs::write(&path, "old,file\n").unwrap();
        let err = write_atomic(
            &path,
            |w| {
                w.write_all(&[b'x'; 200_000])?;
                Err(std::io::Error::other("disk full"))
            },
            |e| e,
        )
        .unwrap_err();
        assert_eq!(err.to_string(), "disk full");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old,file\n");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["peaks.csv"], "a temporary file was left behind");
        write_atomic(&path, |w| w.write_all(b"new,file\n"), |e| e).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new,file\n");
    }

    /// A file that cannot be created (its folder does not exist) is the caller's I/O error.
    #[test]
    fn a_missing_folder_is_an_io_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("no/such/folder/x.csv");
        let err = write_atomic(&path, |w| w.write_all(b"x"), |e| e).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
    }

    /// A file's kind by its extension, whatever its case; none, or a name ending in a dot, is "".
    #[test]
    fn extension_is_lower_case() {
        use std::path::Path;
        assert_eq!(extension(Path::new("dir/Panel.EXR")), "exr");
        assert_eq!(extension(Path::new("a.b.Gbrdf")), "gbrdf");
        assert_eq!(extension(Path::new("noext")), "");
        assert_eq!(extension(Path::new(".hidden")), "");
    }
}
