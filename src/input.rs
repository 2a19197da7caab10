//! Reading input files safely: only regular files (after following symbolic links), and only
//! up to a size cap checked before reading, so that a FIFO cannot hang a command, `/dev/zero`
//! (or a link to it) cannot fill memory, and an oversized file is refused at once.
//! Below every layer that reads a file (`experiment`'s `load`, `record`, `run`), so that none
//! of them imports a layer above it for this.
//!
//! The caps are generous for real files (see the constants); `BERRY_MAX_INPUT_BYTES` (a byte
//! count) replaces every cap for a user whose files are larger still.

use std::fs::{self, File};
use std::io::{self, Read};
use std::path::Path;

/// The largest experiment file read by default (8 MiB). The largest world allowed
/// (100,000 walls) is about 4 MiB of TOML; parsing costs about 75 bytes of memory per byte.
pub const MAX_EXPERIMENT_BYTES: u64 = 8 << 20;

/// The largest genome file read by default (512 MiB): the largest brain allowed
/// (2^22 parameters) is about 100 MiB of pretty JSON.
pub const MAX_GENOME_BYTES: u64 = 512 << 20;

/// The largest checkpoint read by default (8 GiB): a generation holds at most 250 million
/// parameters (about 5 GiB of JSON).
pub const MAX_CHECKPOINT_BYTES: u64 = 8 << 30;

/// The largest `champions.jsonl` read by default (8 GiB: one genome per generation, about
/// 20 bytes per parameter).
pub const MAX_CHAMPIONS_BYTES: u64 = 8 << 30;

/// The largest fitness CSV read by default (1 GiB; a row is about 300 bytes).
pub const MAX_CSV_BYTES: u64 = 1 << 30;

/// The environment variable that replaces every cap (a number of bytes).
pub const MAX_INPUT_ENV: &str = "BERRY_MAX_INPUT_BYTES";

/// The cap in force for a kind of file whose default is `default`.
pub fn cap(default: u64) -> u64 {
    std::env::var(MAX_INPUT_ENV)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .unwrap_or(default)
}

/// Checks that `path` is a regular file (following links) of at most `cap(default)` bytes,
/// without opening it. The error says what the path is and what to do.
pub fn check_regular(path: &Path, default: u64) -> io::Result<u64> {
    let meta = fs::metadata(path)?;
    if !meta.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} (only regular files are read)", describe(&meta)),
        ));
    }
    let limit = cap(default);
    if meta.len() > limit {
        return Err(too_big(meta.len(), limit));
    }
    Ok(meta.len())
}

/// Reads a regular file of at most `cap(default)` bytes (see [`check_regular`]); a file that
/// grows while being read past the cap is refused too.
pub fn read_regular(path: &Path, default: u64) -> io::Result<Vec<u8>> {
    let len = check_regular(path, default)?;
    let limit = cap(default);
    let file = File::open(path)?;
    // The path may have been replaced between the check and the open: check what was opened.
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} (only regular files are read)", describe(&meta)),
        ));
    }
    let mut bytes = Vec::with_capacity(usize::try_from(len.min(limit)).unwrap_or(0));
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_big(bytes.len() as u64, limit));
    }
    Ok(bytes)
}

/// Like [`read_regular`], as UTF-8 text.
pub fn read_regular_text(path: &Path, default: u64) -> io::Result<String> {
    let bytes = read_regular(path, default)?;
    String::from_utf8(bytes).map_err(|e| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

fn too_big(len: u64, limit: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "the file is {len} bytes, more than the limit of {limit} bytes for this kind of \
             file; if it is really meant, set {MAX_INPUT_ENV} to a larger byte count"
        ),
    )
}

fn describe(meta: &fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO (named pipe), not a regular file";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device, not a regular file";
        }
        if t.is_socket() {
            return "a socket, not a regular file";
        }
    }
    if meta.is_dir() {
        "a folder, not a file"
    } else {
        "not a regular file"
    }
}

/// `text` cut to at most `max` characters for a message, saying how much was left out.
pub fn cut(text: &str, max: usize) -> String {
    let count = text.chars().count();
    if count <= max {
        return text.to_string();
    }
    let head: String = text.chars().take(max).collect();
    format!("{head}… ({} more characters)", count - max)
}

/// `message` with every word (a run of non-space characters: a path, a quoted value) longer
/// than `max` characters cut as [`cut`] does, so that a message quoting a huge input stays
/// short while keeping its advice. Spacing is kept.
pub fn cut_long_words(message: &str, max: usize) -> String {
    let mut out = String::with_capacity(message.len().min(4 * max));
    let mut rest = message;
    while !rest.is_empty() {
        let space = rest
            .find(|c: char| !c.is_whitespace())
            .unwrap_or(rest.len());
        out.push_str(&rest[..space]);
        rest = &rest[space..];
        let word = rest.find(char::is_whitespace).unwrap_or(rest.len());
        out.push_str(&cut(&rest[..word], max));
        rest = &rest[word..];
    }
    out
}

/// Levenshtein distance between two short words (insertions, deletions, substitutions).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// The word of `known` nearest to a misspelt `word`, when it is near enough to be meant
/// (at most 2 edits, or a third of its length for long words): keys, enum words,
/// subcommands, `new`'s templates.
pub fn closest<'a>(word: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let (distance, best) = known
        .into_iter()
        .map(|k| (edit_distance(word, k), k))
        .min()?;
    (distance <= 2.max(best.chars().count() / 3)).then_some(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_of_hand_checked_pairs() {
        assert_eq!(edit_distance("inpsect", "inspect"), 2);
        assert_eq!(edit_distance("resme", "resume"), 1);
        assert_eq!(edit_distance("", "plot"), 4);
        assert_eq!(edit_distance("bench", "bench"), 0);
    }

    #[test]
    fn closest_word_only_when_near() {
        let known = ["population".to_string(), "generations".to_string()];
        assert_eq!(
            closest("populaton", known.iter().map(String::as_str)),
            Some("population")
        );
        assert_eq!(closest("zzz", known.iter().map(String::as_str)), None);
        let names = ["foraging", "t-maze", "eye-arena"];
        assert_eq!(closest("foragin", names), Some("foraging"));
        assert_eq!(closest("t-mzae", names), Some("t-maze"));
    }

    #[test]
    fn long_values_are_cut_with_a_count() {
        assert_eq!(cut("abc", 3), "abc");
        assert_eq!(cut("abcdef", 2), "ab… (4 more characters)");
        assert_eq!(
            cut_long_words("see  abcdef and\nab", 3),
            "see  abc… (3 more characters) and\nab"
        );
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_folders_are_refused_without_reading() {
        let e = read_regular(Path::new("/dev/zero"), 10).unwrap_err();
        assert!(e.to_string().contains("a device"), "{e}");
        let e = read_regular(Path::new("/"), 10).unwrap_err();
        assert!(e.to_string().contains("a folder"), "{e}");
    }
}
