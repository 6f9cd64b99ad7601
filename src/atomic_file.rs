//! Output files written whole or not at all.
//!
//! Everything strahl writes (images, reports, sensor tables, exports, the validation report)
//! goes through an [`AtomicFile`]: the bytes go to a new temporary file beside the target,
//! every write is checked, and only [`AtomicFile::commit`] — after flushing and syncing the
//! data to disk — renames it over the target. A run that fails or stops half-way (disk
//! full, an error, Ctrl-C) leaves the previous file as it was and no temporary file behind.
//! A target that is not a regular file (`/dev/stdout`, a pipe, `/dev/full`) is written
//! directly, with every write and the final flush checked, so a full device is an error,
//! never a silent success.

use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Bytes gathered before each write to the file: a report of 3,000 objects (3 MB of JSON)
/// went out in 386 writes with the standard 8 KiB.
const BUFFER: usize = 1 << 20;

/// A file being written; the target changes only on [`AtomicFile::commit`].
pub struct AtomicFile {
    /// The file the bytes go to (the temporary file, or the target itself when it is not a
    /// regular file).
    out: BufWriter<File>,
    /// The target path.
    target: PathBuf,
    /// The temporary file beside the target, until it is renamed over it.
    temporary: Option<PathBuf>,
}

impl AtomicFile {
    /// Starts writing `path`: a new temporary file in its folder (with the permissions of the
    /// file it will replace, if any), or `path` itself when that exists and is not a regular
    /// file; a folder is refused. A symbolic link is followed: the file it points to is
    /// replaced, not the link.
    pub fn create(path: &Path) -> io::Result<Self> {
        let linked = std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
        let resolved = if linked {
            std::fs::canonicalize(path)?
        } else {
            path.to_path_buf()
        };
        let path = resolved.as_path();
        let existing = std::fs::metadata(path).ok();
        if existing.as_ref().is_some_and(std::fs::Metadata::is_dir) {
            return Err(io::Error::new(
                io::ErrorKind::IsADirectory,
                "a folder, not a file",
            ));
        }
        if existing.as_ref().is_some_and(|m| !m.is_file()) {
            return Ok(AtomicFile {
                out: BufWriter::with_capacity(BUFFER, File::create(path)?),
                target: path.to_path_buf(),
                temporary: None,
            });
        }
        let temporary = temporary_path(path);
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temporary)?;
        if let Some(metadata) = existing {
            file.set_permissions(metadata.permissions())?;
        }
        Ok(AtomicFile {
            out: BufWriter::with_capacity(BUFFER, file),
            target: path.to_path_buf(),
            temporary: Some(temporary),
        })
    }

    /// Flushes and syncs what was written and puts it in place of the target.
    pub fn commit(mut self) -> io::Result<()> {
        self.out.flush()?;
        let Some(temporary) = self.temporary.take() else {
            return Ok(());
        };
        let renamed = self
            .out
            .get_ref()
            .sync_all()
            .and_then(|()| std::fs::rename(&temporary, &self.target));
        if renamed.is_err() {
            let _ = std::fs::remove_file(&temporary);
        }
        renamed
    }
}

impl Write for AtomicFile {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.out.write(bytes)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

impl Seek for AtomicFile {
    fn seek(&mut self, position: SeekFrom) -> io::Result<u64> {
        self.out.seek(position)
    }
}

impl Drop for AtomicFile {
    /// An uncommitted file leaves the target untouched and removes its temporary file.
    fn drop(&mut self) {
        if let Some(temporary) = &self.temporary {
            let _ = std::fs::remove_file(temporary);
        }
    }
}

/// Writes `bytes` to `path` whole or not at all (see [`AtomicFile`]).
pub fn write(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut file = AtomicFile::create(path)?;
    file.write_all(bytes)?;
    file.commit()
}

/// A name for a new file beside `path`, unique within this process and apart from other
/// processes': `.NAME.PID-N.tmp`.
fn temporary_path(path: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!(".{name}.{}-{n}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder under the system's temporary folder, removed when dropped.
    struct Folder(PathBuf);

    impl Folder {
        fn new(name: &str) -> Self {
            let path =
                std::env::temp_dir().join(format!("strahl-atomic-{name}-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&path);
            std::fs::create_dir_all(&path).unwrap();
            Folder(path)
        }

        /// The names of the files in the folder, sorted.
        fn names(&self) -> Vec<String> {
            let mut names: Vec<String> = std::fs::read_dir(&self.0)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            names.sort();
            names
        }
    }

    impl Drop for Folder {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    #[test]
    fn a_committed_file_replaces_the_target_and_leaves_nothing_else() {
        let folder = Folder::new("commit");
        let target = folder.0.join("report.json");
        std::fs::write(&target, "old").unwrap();
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"new").unwrap();
        // Until the commit the old file is still there, beside the temporary one.
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(folder.names().len(), 2);
        file.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert_eq!(folder.names(), ["report.json"]);
    }

    #[test]
    fn a_file_dropped_before_its_commit_leaves_the_old_one_whole() {
        let folder = Folder::new("drop");
        let target = folder.0.join("image.png");
        std::fs::write(&target, "the last good image").unwrap();
        {
            let mut file = AtomicFile::create(&target).unwrap();
            file.write_all(b"half an ima").unwrap();
            // The run fails here.
        }
        assert_eq!(
            std::fs::read_to_string(&target).unwrap(),
            "the last good image"
        );
        assert_eq!(folder.names(), ["image.png"]);
    }

    #[test]
    fn a_folder_is_no_target() {
        let folder = Folder::new("folder");
        let error = AtomicFile::create(&folder.0).err().unwrap();
        assert_eq!(error.kind(), io::ErrorKind::IsADirectory);
        assert!(folder.names().is_empty());
    }

    #[test]
    fn a_missing_folder_is_an_error_before_anything_is_written() {
        let folder = Folder::new("missing");
        let error = write(&folder.0.join("no/such/folder/out.csv"), b"x").unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::NotFound);
        assert!(folder.names().is_empty());
    }

    #[cfg(unix)]
    #[test]
    fn a_link_is_followed_and_kept() {
        let folder = Folder::new("link");
        let (target, link) = (folder.0.join("real.json"), folder.0.join("link.json"));
        std::fs::write(&target, "old").unwrap();
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write(&link, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_full_device_is_an_error() {
        // /dev/full accepts the open and refuses every write: the buffered bytes fail at
        // the latest on the commit's flush.
        let error = write(Path::new("/dev/full"), &[0; 100]).unwrap_err();
        assert_eq!(error.raw_os_error(), Some(28), "{error}"); // ENOSPC
    }
}
