//! Crash-safe file replacement: a file is either its old content or its new content, never a
//! mixture, even if the process is killed or the machine loses power mid-write.
//!
//! The sequence is PostgreSQL's durable rename:
//!
//! 1. write the new content to a temporary file in the *same folder* (a rename is only atomic
//!    within one file system),
//! 2. `fsync` the temporary file, so its data is on disk before its name can point to it,
//! 3. rename it over the destination (atomic on POSIX),
//! 4. `fsync` the folder, so the rename itself survives a power loss.
//!
//! A failed `fsync` is returned as an error and never retried: after a failed `fsync` Linux may
//! have dropped the dirty pages and marked them clean, so a second `fsync` can "succeed"
//! without the data being on disk (the 2018 "fsyncgate" finding that made PostgreSQL panic
//! instead of retrying).
//!
//! Temporary files are named `.<file name>.tmp-<pid>-<n>` (hidden, next to their destination;
//! `<n>` counts writes within one process). A process killed between steps 1 and 3 leaves such
//! a file behind; [`remove_stale_temp_files`] deletes them, but only a process that holds the
//! run folder's lock (`run::lock`) may call it: it cannot tell a dead writer's file from a
//! live one's.
//!
//! [`AtomicFile`] is the same sequence for output streamed over a long time (traces): the
//! destination keeps its previous content until [`AtomicFile::commit`], and a dropped (failed,
//! killed) one leaves no temporary file, or one that the next lock holder removes.
//! [`refuse_output_over_input`] keeps a command from writing over one of its own inputs.
//!
//! Folder `fsync` is done on Unix (Linux is the target). Other platforms have no portable way
//! to sync a folder (on Windows, opening a folder as a file fails with "access denied"), so
//! step 4 is skipped there and a rename may be lost on power loss, though never half-done.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The marker between the destination's name and the writer's process id in a temporary name.
const TEMP_MARKER: &str = ".tmp-";

/// Counts temporary files created by this process, so that two threads writing the same
/// destination never share a temporary file.
static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Replaces the file at `path` with `bytes`, atomically and durably (see the module docs).
///
/// Errors name the path and the step that failed. On error the previous file, if any, is left
/// untouched and the temporary file is removed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Like [`write_atomic`], but the content is produced by `write`, which streams it into the
/// temporary file (through a buffer).
///
/// This is also the seam that lets tests simulate a full disk: a closure that returns an error
/// aborts the write, the destination keeps its previous content and no temporary file remains.
pub fn write_atomic_with<F>(path: &Path, write: F) -> io::Result<()>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let file_name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("cannot write {}: the path has no file name", path.display()),
        )
    })?;
    let dir = parent_dir(path);
    remove_dead_writers_temp_files(dir, &file_name.to_string_lossy());
    let (temp_path, file) = create_temp(dir, &file_name.to_string_lossy())?;

    let result = fill_and_sync(file, write)
        .map_err(|e| context(e, "cannot write temporary file", &temp_path))
        .and_then(|()| {
            fs::rename(&temp_path, path).map_err(|e| {
                context(
                    e,
                    &format!("cannot rename {} over", temp_path.display()),
                    path,
                )
            })
        });
    if let Err(error) = result {
        // The temporary file must not outlive a failed write; if even removing it fails, say
        // so, and let `remove_stale_temp_files` clean it up at the next start.
        return match fs::remove_file(&temp_path) {
            Ok(()) => Err(error),
            Err(e) if e.kind() == io::ErrorKind::NotFound => Err(error),
            Err(e) => Err(io::Error::new(
                error.kind(),
                format!(
                    "{error} (and the temporary file {} could not be removed: {e})",
                    temp_path.display()
                ),
            )),
        };
    }
    sync_dir(dir)
}

/// A file being written that replaces `path` only when [`AtomicFile::commit`] succeeds; until
/// then `path` keeps its previous content (or stays absent). Dropped without a commit (an
/// error, a panic), the temporary file is removed.
pub struct AtomicFile {
    dest: PathBuf,
    temp: PathBuf,
    writer: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Starts replacing `path`: creates the temporary file beside it.
    pub fn create(path: &Path) -> io::Result<AtomicFile> {
        let file_name = path.file_name().ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("cannot write {}: the path has no file name", path.display()),
            )
        })?;
        let dir = parent_dir(path);
        let name = file_name.to_string_lossy();
        remove_dead_writers_temp_files(dir, &name);
        let (temp, file) = create_temp(dir, &name)?;
        Ok(AtomicFile {
            dest: path.to_path_buf(),
            temp,
            writer: Some(BufWriter::with_capacity(1 << 16, file)),
        })
    }

    /// Syncs the content and renames it over the destination (see the module docs).
    pub fn commit(mut self) -> io::Result<()> {
        let Some(writer) = self.writer.take() else {
            return Err(io::Error::other("atomic file already finished"));
        };
        let result = writer
            .into_inner()
            .map_err(|e| e.into_error())
            .and_then(|f| f.sync_all())
            .map_err(|e| context(e, "cannot write temporary file", &self.temp))
            .and_then(|()| {
                fs::rename(&self.temp, &self.dest).map_err(|e| {
                    context(
                        e,
                        &format!("cannot rename {} over", self.temp.display()),
                        &self.dest,
                    )
                })
            });
        if let Err(error) = result {
            let _ = fs::remove_file(&self.temp);
            return Err(error);
        }
        sync_dir(parent_dir(&self.dest))
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.writer {
            Some(w) => w.write(buf),
            None => Err(io::Error::other("atomic file already finished")),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match &mut self.writer {
            Some(w) => w.flush(),
            None => Ok(()),
        }
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.writer.take().is_some() {
            let _ = fs::remove_file(&self.temp);
        }
    }
}

/// Removes the temporary files for `file_name` in `dir` left by processes that no longer
/// exist (a killed trace writer): outside a locked run folder nobody else would. A file whose
/// writer's process id is alive (or may be: no `/proc`) is left alone. Best effort.
fn remove_dead_writers_temp_files(dir: &Path, file_name: &str) {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return;
    }
    let prefix = format!(".{file_name}{TEMP_MARKER}");
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let Some(rest) = name.strip_prefix(&prefix) else {
            continue;
        };
        let Some((pid, _)) = rest.split_once('-') else {
            continue;
        };
        if !is_temp_name(name) || proc.join(pid).exists() {
            continue;
        }
        if entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// Refuses to write `output` when it is (or, through a link, names) one of `inputs`: the
/// command would destroy what it reads. Files are compared by device and inode when both
/// exist, and by canonical path otherwise (a not-yet-existing output cannot be an input).
/// `flag` names the option in the message (e.g. `--trace`).
pub fn refuse_output_over_input(flag: &str, output: &Path, inputs: &[&Path]) -> io::Result<()> {
    for input in inputs {
        if same_file(output, input) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "{flag} {} is the same file as {}, an input of this command: writing it \
                     would destroy it; choose another output file",
                    output.display(),
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Whether `a` and `b` name the same existing file (after following links).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (fs::metadata(a), fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    match (fs::canonicalize(a), fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// Removes the temporary files that killed writes left in `dir` (names of the form
/// `.<name>.tmp-<pid>-<n>`), and returns how many were removed. Other files are not touched.
///
/// Call it only while holding the run folder's lock (`run::lock::RunLock`), so that no other
/// writer is active in `dir`: it cannot tell a dead writer's file from a live one's (process
/// ids are reused, e.g. in containers). Read-only commands never call it.
pub fn remove_stale_temp_files(dir: &Path) -> io::Result<usize> {
    let entries = fs::read_dir(dir).map_err(|e| context(e, "cannot list folder", dir))?;
    let mut removed = 0;
    for entry in entries {
        let entry = entry.map_err(|e| context(e, "cannot list folder", dir))?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if !is_temp_name(name) {
            continue;
        }
        let file_type = entry
            .file_type()
            .map_err(|e| context(e, "cannot inspect", &entry.path()))?;
        if !file_type.is_file() {
            continue;
        }
        let path = entry.path();
        fs::remove_file(&path)
            .map_err(|e| context(e, "cannot remove stale temporary file", &path))?;
        removed += 1;
    }
    Ok(removed)
}

/// Whether `name` is a temporary file name made by this module: `.<name>.tmp-<pid>-<n>` with a
/// non-empty `<name>` and decimal `<pid>` and `<n>`.
pub fn is_temp_name(name: &str) -> bool {
    let Some(rest) = name.strip_prefix('.') else {
        return false;
    };
    let Some(marker) = rest.rfind(TEMP_MARKER) else {
        return false;
    };
    if marker == 0 {
        return false;
    }
    let suffix = &rest[marker + TEMP_MARKER.len()..];
    let Some((pid, n)) = suffix.split_once('-') else {
        return false;
    };
    let decimal = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    decimal(pid) && decimal(n)
}

/// The folder holding `path` (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Creates a fresh temporary file for `file_name` in `dir`. `create_new` refuses to reuse a
/// name, so a leftover from a dead process with the same pid is skipped, not overwritten.
fn create_temp(dir: &Path, file_name: &str) -> io::Result<(PathBuf, File)> {
    let pid = std::process::id();
    let mut attempts = 0;
    loop {
        let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp_path = dir.join(format!(".{file_name}{TEMP_MARKER}{pid}-{n}"));
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp_path)
        {
            Ok(file) => return Ok((temp_path, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempts < 100 => {
                attempts += 1;
            }
            Err(e) => return Err(context(e, "cannot create temporary file", &temp_path)),
        }
    }
}

/// Streams the content into `file`, flushes the buffer and syncs data and metadata to disk.
fn fill_and_sync<F>(file: File, write: F) -> io::Result<()>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let mut buffered = BufWriter::new(file);
    write(&mut buffered)?;
    let file = buffered.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()
}

/// Makes a rename in `dir` durable.
#[cfg(unix)]
fn sync_dir(dir: &Path) -> io::Result<()> {
    File::open(dir)
        .and_then(|d| d.sync_all())
        .map_err(|e| context(e, "cannot sync folder", dir))
}

/// No portable folder sync outside Unix (see the module docs).
#[cfg(not(unix))]
fn sync_dir(_dir: &Path) -> io::Result<()> {
    Ok(())
}

/// Prefixes an I/O error with what was being done and to which path, keeping its kind.
fn context(error: io::Error, what: &str, path: &Path) -> io::Error {
    io::Error::new(error.kind(), format!("{what} {}: {error}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temp_names_are_recognised_exactly() {
        assert!(is_temp_name(".gen-000001.json.tmp-123-0"));
        assert!(is_temp_name(".a.tmp-1-22"));
        assert!(is_temp_name(".x.tmp-5.tmp-1-2"));
        for other in [
            "gen-000001.json",
            "gen-000001.json.tmp-1-2",
            ".tmp-1-2",
            "..tmp-1-2",
            ".a.tmp-1",
            ".a.tmp-1-",
            ".a.tmp--2",
            ".a.tmp-x-2",
            ".a.tmp-1-2x",
            ".bashrc",
            "x.tmp",
        ] {
            assert!(!is_temp_name(other), "{other} taken for a temporary file");
        }
    }

    #[test]
    fn bare_file_names_live_in_the_current_folder() {
        assert_eq!(parent_dir(Path::new("a.json")), Path::new("."));
        assert_eq!(parent_dir(Path::new("d/a.json")), Path::new("d"));
    }
}
