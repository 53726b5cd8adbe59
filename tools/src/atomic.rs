//! Writing a tool's output file atomically.

use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` through a temporary file beside it (`path` + `.partial`) and a
/// rename over `path`: an interrupted or failed write never leaves a half-written file, and
/// what was at `path` stays until the new file is whole. The temporary file is removed on
/// failure.
///
/// # Errors
///
/// The I/O error, with the path, as text.
pub fn write_atomic(path: &Path, bytes: &(impl AsRef<[u8]> + ?Sized)) -> Result<(), String> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = PathBuf::from(tmp);
    let r = std::fs::write(&tmp, bytes.as_ref())
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|e| format!("writing {}: {e}", path.display()));
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::write_atomic;

    #[test]
    fn replaces_the_file_whole_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("scanline3d-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("out.txt");
        std::fs::write(&path, "old").unwrap();
        write_atomic(&path, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert!(!dir.join("out.txt.partial").exists());
        // A path in a missing directory fails with the path named, and creates nothing.
        let bad = dir.join("missing").join("x.bin");
        let e = write_atomic(&bad, &[1u8, 2]).unwrap_err();
        assert!(e.contains("x.bin"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
