//! How to call this program again, for the commands that messages print (`Continue with:
//! berry-evolve resume DIR`): `berry-evolve` when that is how the program was started or when
//! that name on the PATH is this very program; otherwise the path it was started by. So a
//! hint printed after `cargo run --release -- x.toml` (cargo starts
//! `/…/target/release/berry-evolve`) or `./target/release/berry-evolve x.toml` names that
//! binary and works when pasted into the same shell, in the same folder as the relative
//! paths the message prints.
//!
//! The binary's path rather than `cargo run --release --`: cargo would first rebuild from the
//! sources as they are now, and results reproduce per version, so the hint names the program
//! that wrote the run. The README gives the cargo form too.
//!
//! The library only reads what `main` stored with [`init`]; any other program using it (the
//! tests) prints the documented name.

use std::ffi::OsStr;
use std::path::Path;
use std::sync::OnceLock;

/// The program's name as installed (`cargo install --path .` puts it in `~/.cargo/bin`).
pub const NAME: &str = "berry-evolve";

static PROGRAM: OnceLock<String> = OnceLock::new();

/// Works out how this process was started and stores it for [`program`]; `main` calls it once.
pub fn init() {
    let argv0 = std::env::args_os().next();
    let exe = std::env::current_exe().ok();
    let path = std::env::var_os("PATH");
    let _ = PROGRAM.set(choose(argv0.as_deref(), exe.as_deref(), path.as_deref()));
}

/// The command that starts this program, ready to paste into a shell (quoted if need be):
/// what [`init`] found, or [`NAME`] when it was not called.
pub fn program() -> &'static str {
    PROGRAM.get().map_or(NAME, String::as_str)
}

/// The command for a program started as `argv0` whose executable is `exe`, with `path` as the
/// PATH variable: `argv0` itself when it is a bare name (the shell found it on the PATH);
/// [`NAME`] when the PATH's `berry-evolve` is `exe`; else the path `argv0` gives (or `exe`).
pub fn choose(argv0: Option<&OsStr>, exe: Option<&Path>, path: Option<&OsStr>) -> String {
    let argv0 = argv0.map(|a| a.to_string_lossy().into_owned());
    match (&argv0, exe) {
        (Some(a), _) if !a.is_empty() && !a.contains('/') => shell_word(a),
        (_, Some(exe)) if path.is_some_and(|p| on_path(exe, p)) => NAME.to_string(),
        (Some(a), _) if !a.is_empty() => shell_word(a),
        (_, Some(exe)) => shell_word(&exe.to_string_lossy()),
        _ => NAME.to_string(),
    }
}

/// Whether `berry-evolve` in one of `path`'s folders is the file `exe` (links followed).
fn on_path(exe: &Path, path: &OsStr) -> bool {
    let Ok(exe) = exe.canonicalize() else {
        return false;
    };
    std::env::split_paths(path)
        .filter_map(|dir| dir.join(NAME).canonicalize().ok())
        .any(|found| found == exe)
}

/// `word` as one shell word: unchanged when it holds only characters no shell treats
/// specially, else in single quotes.
pub fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_-./+:@%,=".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_program_found_on_the_path_is_named_as_typed() {
        let exe = Path::new("/home/u/.cargo/bin/berry-evolve");
        assert_eq!(
            choose(Some(OsStr::new("berry-evolve")), Some(exe), None),
            "berry-evolve"
        );
    }

    #[test]
    fn a_program_started_by_its_path_is_named_by_that_path() {
        let exe = Path::new("/work/repo/target/release/berry-evolve");
        let argv0 = OsStr::new("./target/release/berry-evolve");
        let path = OsStr::new("/usr/bin:/bin");
        assert_eq!(
            choose(Some(argv0), Some(exe), Some(path)),
            "./target/release/berry-evolve"
        );
        // As cargo run starts it.
        let argv0 = OsStr::new("/work/my repo/target/release/berry-evolve");
        assert_eq!(
            choose(Some(argv0), Some(exe), Some(path)),
            "'/work/my repo/target/release/berry-evolve'"
        );
        assert_eq!(choose(None, Some(exe), None), exe.to_str().unwrap());
        assert_eq!(choose(None, None, None), NAME);
    }

    #[cfg(unix)]
    #[test]
    fn a_path_whose_berry_evolve_is_this_program_gives_the_bare_name() {
        let dir = tempfile::tempdir().unwrap();
        let bin = dir.path().join("bin");
        std::fs::create_dir(&bin).unwrap();
        let exe = dir.path().join("berry-evolve");
        std::fs::write(&exe, b"").unwrap();
        let argv0 = exe.as_os_str();
        // Another berry-evolve on the PATH (an older install) is not this program.
        std::fs::write(bin.join(NAME), b"").unwrap();
        let path = std::env::join_paths([Path::new("/nonexistent"), &bin]).unwrap();
        assert_eq!(
            choose(Some(argv0), Some(&exe), Some(&path)),
            exe.to_str().unwrap()
        );
        // A link to this program is.
        std::fs::remove_file(bin.join(NAME)).unwrap();
        std::os::unix::fs::symlink(&exe, bin.join(NAME)).unwrap();
        assert_eq!(choose(Some(argv0), Some(&exe), Some(&path)), NAME);
    }

    #[test]
    fn odd_characters_are_quoted_for_the_shell() {
        assert_eq!(shell_word("a/b-c_1.2"), "a/b-c_1.2");
        assert_eq!(shell_word("it's here"), r"'it'\''s here'");
        assert_eq!(shell_word("$HOME/x"), "'$HOME/x'");
    }
}
