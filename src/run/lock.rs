//! One run folder, one writer: an exclusive advisory lock on `<run>/.lock`, taken first by
//! every command that writes a run folder (`run`, `resume`, `run --force`) and held until the
//! process ends. A second writer is refused at once, naming the holder's process id, which the
//! holder writes into the file after taking the lock.
//!
//! The lock is `flock(2)` through the `fs4` crate: the kernel releases it when the holder
//! exits in any way (SIGKILL included), so a lock is never left stale. The file itself is
//! never removed: a writer that removed it could let two later writers lock two different
//! files of the same name. Read-only commands (`export-csv`, `replay`, `compare`, `inspect`)
//! take no lock; they read only files that writers replace atomically.

use fs4::fs_std::FileExt;
use std::fs::{File, OpenOptions};
use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The lock file's name inside a run folder.
pub const LOCK_FILE: &str = ".lock";

/// A held lock on a run folder; released when dropped or when the process ends.
#[derive(Debug)]
pub struct RunLock {
    file: File,
    path: PathBuf,
}

/// Why a run folder's lock could not be taken.
#[derive(Debug)]
pub enum LockError {
    /// Another process holds it (its id when the lock file names one).
    InUse {
        /// The holder's process id, as it wrote it.
        pid: Option<u32>,
    },
    /// The lock file could not be opened or locked.
    Io(io::Error),
}

impl RunLock {
    /// Takes the lock of the existing folder `dir`, or says who holds it. Never waits.
    pub fn acquire(dir: &Path) -> Result<RunLock, LockError> {
        let path = dir.join(LOCK_FILE);
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(LockError::Io)?;
        if !file.try_lock_exclusive().map_err(LockError::Io)? {
            return Err(LockError::InUse {
                pid: holder(&mut file),
            });
        }
        let pid = std::process::id();
        file.set_len(0)
            .and_then(|()| file.seek(SeekFrom::Start(0)))
            .and_then(|_| writeln!(file, "{pid}"))
            .and_then(|()| file.flush())
            .map_err(LockError::Io)?;
        Ok(RunLock { file, path })
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for RunLock {
    fn drop(&mut self) {
        // Closing the file releases the lock too; unlocking first makes it explicit.
        let _ = FileExt::unlock(&self.file);
    }
}

/// The process id the holder wrote. It writes it right after locking, so a reader arriving
/// in between may find the file empty; it looks again a few times.
fn holder(file: &mut File) -> Option<u32> {
    for _ in 0..20 {
        let mut text = String::new();
        if file.seek(SeekFrom::Start(0)).is_ok() && file.read_to_string(&mut text).is_ok() {
            if let Ok(pid) = text.trim().parse() {
                return Some(pid);
            }
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    None
}
