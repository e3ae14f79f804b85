//! Atomic file writes.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// `dir/.name.tmp<pid>-<n>.<ext>` beside `path`: hidden, unique within the process (two threads
/// may write the same file), and keeping the extension, from which image encoders pick the
/// format.
fn temporary_sibling(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let extension = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp{}-{n}{extension}", std::process::id()))
}

/// Write `bytes` to `path` atomically: the file is either the old one or the whole new one.
/// Missing parent directories are created.
///
/// # Errors
/// Any I/O error of creating the directory, writing, syncing or renaming; the temporary file is
/// removed then.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |temporary| {
        let mut file = File::create(temporary)?;
        file.write_all(bytes)?;
        file.flush()
    })
}

/// Write `path` atomically through `write`, which creates and fills the file at the path it is
/// given (a temporary beside `path`, with the same extension): for writers that want a path
/// rather than bytes, such as image encoders. The temporary is then synced to disk and renamed
/// over `path`, and the directory synced where the platform allows. Missing parent directories
/// are created.
///
/// # Errors
/// The error of `write`, or any I/O error of creating the directory, syncing or renaming; the
/// temporary file is removed then.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&Path) -> io::Result<()>,
) -> io::Result<()> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
    if let Some(dir) = dir {
        std::fs::create_dir_all(dir)?;
    }
    let temporary = temporary_sibling(path);
    let result = write(&temporary)
        .and_then(|()| File::open(&temporary)?.sync_all())
        .and_then(|()| std::fs::rename(&temporary, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
        return result;
    }
    sync_directory(dir.unwrap_or(Path::new(".")))
}

/// Make the rename durable: on Unix a directory's entries reach the disk with an `fsync` of the
/// directory itself. Filesystems that cannot sync a directory say so (`EINVAL`), which is not
/// an error of the write.
#[cfg(unix)]
fn sync_directory(dir: &Path) -> io::Result<()> {
    match File::open(dir).and_then(|d| d.sync_all()) {
        Err(e)
            if matches!(
                e.kind(),
                io::ErrorKind::InvalidInput | io::ErrorKind::Unsupported
            ) =>
        {
            Ok(())
        }
        other => other,
    }
}

/// Windows has no directory `fsync`; its rename is durable once the file's data is.
#[cfg(not(unix))]
fn sync_directory(_dir: &Path) -> io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("mdr-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".tmp"))
            .collect()
    }

    #[test]
    fn replaces_the_whole_file_and_leaves_no_temporary() {
        let dir = scratch("replace");
        let path = dir.join("nested").join("a.txt");
        write_atomic(&path, b"a longer first content").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        assert!(leftovers(path.parent().unwrap()).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_write_keeps_the_old_file_and_removes_the_temporary() {
        let dir = scratch("failed");
        let path = dir.join("plot.png");
        write_atomic(&path, b"old").unwrap();
        let error = write_atomic_with(&path, |temporary| {
            assert_eq!(temporary.extension().unwrap(), "png");
            std::fs::write(temporary, b"half")?;
            Err(io::Error::other("encoder failed"))
        })
        .unwrap_err();
        assert_eq!(error.to_string(), "encoder failed");
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_write_that_creates_no_file_is_an_error() {
        let dir = scratch("nofile");
        let path = dir.join("x.csv");
        assert!(write_atomic_with(&path, |_| Ok(())).is_err());
        assert!(!path.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn concurrent_writers_of_one_path_do_not_collide() {
        let dir = scratch("concurrent");
        let path = dir.join("shared.txt");
        std::fs::create_dir_all(&dir).unwrap();
        std::thread::scope(|s| {
            for k in 0..8u8 {
                let path = &path;
                s.spawn(move || write_atomic(path, &[k; 4096]).unwrap());
            }
        });
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes.len(), 4096);
        assert!(bytes.iter().all(|&b| b == bytes[0]), "a torn file");
        assert!(leftovers(&dir).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
