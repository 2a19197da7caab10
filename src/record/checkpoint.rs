//! Checkpoints: a generic, versioned, checksummed JSON envelope around whatever state a run
//! needs to resume (the payload), written atomically, with the last few kept.
//!
//! # File format (format 1)
//!
//! One compact JSON object on one line, followed by a newline, with the fields in this order:
//!
//! ```text
//! {"format":1,"program":"berry-evolve 0.2.0","config_hash":"<hex>","generation":12,
//!  "checksum":"sha256:<64 hex digits>","payload":{...}}
//! ```
//!
//! - `format`: this layout's version, [`CHECKPOINT_FORMAT`]. Readers refuse newer formats
//!   (written by a newer berry-evolve) and formats older than [`OLDEST_READABLE_FORMAT`].
//! - `program`: the writer's name and version ([`PROGRAM`]); `resume` notes when it differs
//!   from the running program (another version may compute differently).
//! - `config_hash`: the hash of the experiment configuration, so that a run never resumes from
//!   another experiment's checkpoint.
//! - `generation`: the generation the payload belongs to; also in the file name,
//!   `gen-<generation zero-padded to 6 digits>.json`.
//! - `checksum`: SHA-256 of the canonical serialization (below) of every other field.
//! - `payload`: the caller's state, serialized with serde. Its maps are written with sorted
//!   keys (serde_json's default `Value` map), so even a `HashMap` gives the same bytes every
//!   time; a crate enabling serde_json's `preserve_order` would break that, so prefer
//!   `BTreeMap` in payloads.
//!
//! Compact rather than pretty-printed: a payload is mostly long arrays of numbers (genomes),
//! which pretty-printing puts one per line, doubling the size for little gain; `jq .` shows a
//! checkpoint readably when needed.
//!
//! # Canonical serialization and checksum
//!
//! The checksum covers `format`, `program`, `config_hash`, `generation` and `payload`, not
//! only the payload: a hand-edited generation or config hash is damage too. The bytes hashed
//! are `serde_json::to_vec` of a struct with those five fields in that order, the payload
//! being a `serde_json::Value`. Reading parses the payload into a `Value` and serializes it
//! again: with serde_json's `float_roundtrip` feature every number reads back to the same
//! bits, and object keys come back in the same order (sorted, or in file order if some crate
//! turns on `preserve_order`), so the same bytes, and the same hash, come out. The check is
//! semantic: whitespace, or `1e5` rewritten as `1E5`, does not change the checksum; any
//! change of value does.
//!
//! # Numbers
//!
//! JSON has no NaN or infinity, and serde_json silently writes them as `null` (which then
//! fails to read back as a number). [`encode`] therefore walks the payload first and refuses
//! any non-finite `f32`/`f64`, naming the field (`payload.population[3].parameters[17]`).
//!
//! # Errors
//!
//! [`encode`] and [`decode`] work on bytes and return a [`ContentError`]; every function that
//! touches files returns a [`CheckpointError`], which names the file (or folder) and, when one
//! exists, the previous good checkpoint to resume from instead. Nothing here panics on damaged
//! input.

use std::fmt;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::value::RawValue;
use serde_json::Value;
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use thiserror::Error;

use super::atomic::write_atomic;

/// The checkpoint layout this program writes. Bump it whenever the envelope or the meaning of
/// a payload changes, so that an old program refuses a new file instead of misreading it.
pub const CHECKPOINT_FORMAT: u32 = 1;

/// The oldest layout this program can still read.
pub const OLDEST_READABLE_FORMAT: u32 = 1;

/// The `program` field written into every checkpoint.
pub const PROGRAM: &str = concat!("berry-evolve ", env!("CARGO_PKG_VERSION"));

/// The envelope's field names, in file order.
const FIELDS: [&str; 6] = [
    "format",
    "program",
    "config_hash",
    "generation",
    "checksum",
    "payload",
];

const CHECKSUM_PREFIX: &str = "sha256:";

/// How many characters of a hash are shown in messages (enough to tell two apart).
const SHORT_HASH: usize = 12;

/// A decoded checkpoint.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint<T> {
    /// The layout version the file was written with.
    pub format: u32,
    /// The writer, e.g. `berry-evolve 0.2.0`.
    pub program: String,
    /// The hash of the experiment configuration that produced it.
    pub config_hash: String,
    /// The generation the payload belongs to.
    pub generation: u64,
    /// The caller's state.
    pub payload: T,
}

/// The newest usable checkpoint of a folder, found by [`load_latest_good`].
#[derive(Debug)]
pub struct LoadedCheckpoint<T> {
    /// The file it was read from.
    pub path: PathBuf,
    /// Its content.
    pub checkpoint: Checkpoint<T>,
    /// Newer checkpoints that could not be used (damaged, or from another experiment), newest
    /// first, each error naming its file. Empty when the newest checkpoint was used.
    pub skipped: Vec<CheckpointError>,
}

impl<T> LoadedCheckpoint<T> {
    /// Refuses to resume past an unusable newer checkpoint: when `skipped` is not empty,
    /// returns the newest one's error, completed with this (previous good) checkpoint's path,
    /// e.g. "checkpoint run/gen-000012.json: checksum mismatch: the file was edited or
    /// damaged (…); the previous good checkpoint is run/gen-000010.json".
    pub fn refuse_if_newest_unusable(mut self) -> Result<Self, CheckpointError> {
        if self.skipped.is_empty() {
            return Ok(self);
        }
        let mut newest = self.skipped.swap_remove(0);
        newest.previous_good = Some(self.path);
        Err(newest)
    }
}

/// What is wrong with a checkpoint's content, independent of any file.
#[derive(Debug, Error)]
pub enum ContentError {
    /// The payload holds NaN or an infinity, which JSON cannot represent.
    #[error("the value at `{field}` is {value}; a checkpoint holds only finite numbers")]
    NonFinite {
        /// Where, e.g. `payload.population[3].parameters[17]`.
        field: String,
        /// The offending value.
        value: f64,
    },
    /// The payload's `Serialize` implementation failed.
    #[error("the payload cannot be serialized: {0}")]
    Serialize(String),
    /// The bytes are not (complete) JSON.
    #[error("truncated or not JSON ({message})")]
    NotJson {
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem (0 at the very start of an empty file).
        column: usize,
        /// serde_json's description, which ends with the line and column.
        message: String,
    },
    /// Valid JSON, but not an object.
    #[error("not a checkpoint: the file holds {found}, not a JSON object")]
    NotAnObject {
        /// What was found instead, e.g. "an array".
        found: &'static str,
    },
    /// A field of the envelope is missing.
    #[error("not a complete checkpoint: missing field `{0}`")]
    MissingField(&'static str),
    /// A field of the envelope has the wrong JSON type.
    #[error("field `{field}` must be {expected}, found {found}")]
    WrongType {
        /// The field.
        field: &'static str,
        /// What it must be.
        expected: &'static str,
        /// What it is (a short JSON rendering).
        found: String,
    },
    /// A field that the envelope does not have.
    #[error("unknown field `{0}` (a format {CHECKPOINT_FORMAT} checkpoint has only {fields})", fields = FIELDS.join(", "))]
    UnknownField(String),
    /// Written by a newer program with a layout this one does not know.
    #[error("written by a newer berry-evolve (format {found}, this program reads ≤ {supported})")]
    NewerFormat {
        /// The file's format.
        found: u64,
        /// [`CHECKPOINT_FORMAT`].
        supported: u32,
    },
    /// Written by an old program with a layout this one no longer reads.
    #[error(
        "written by an older berry-evolve in format {found}, which this program no longer \
         reads (it reads formats {oldest} to {supported}); resume with the version that wrote it"
    )]
    OlderFormat {
        /// The file's format.
        found: u64,
        /// [`OLDEST_READABLE_FORMAT`].
        oldest: u32,
        /// [`CHECKPOINT_FORMAT`].
        supported: u32,
    },
    /// The checksum field is not `sha256:` and 64 lowercase hex digits.
    #[error("field `checksum` is `{0}`, expected `sha256:` followed by 64 lowercase hex digits")]
    BadChecksumSyntax(String),
    /// The content does not match its checksum.
    #[error(
        "checksum mismatch: the file was edited or damaged (stored sha256:{stored}, \
         content gives sha256:{computed})"
    )]
    ChecksumMismatch {
        /// The stored checksum, shortened.
        stored: String,
        /// The checksum of the content, shortened.
        computed: String,
    },
    /// The checksum holds but the payload is not what the caller expects (a different type).
    #[error("the payload does not have the expected shape: {0}")]
    PayloadShape(String),
}

/// An error about a checkpoint file (or folder): always names the path.
#[derive(Debug)]
pub struct CheckpointError {
    /// The checkpoint file concerned, or the folder for folder-wide problems.
    pub path: PathBuf,
    /// What went wrong.
    pub kind: CheckpointErrorKind,
    /// A good checkpoint in the same folder to resume from instead, when one exists.
    pub previous_good: Option<PathBuf>,
}

/// What went wrong with a checkpoint file; see [`CheckpointError`].
#[derive(Debug, Error)]
pub enum CheckpointErrorKind {
    /// The content is damaged, of another format, or (when writing) not representable.
    #[error(transparent)]
    Content(#[from] ContentError),
    /// The file could not be read.
    #[error("cannot read: {0}")]
    Read(io::Error),
    /// The file could not be written.
    #[error("cannot write: {0}")]
    Write(io::Error),
    /// The folder could not be listed.
    #[error("cannot list: {0}")]
    List(io::Error),
    /// The checkpoint belongs to another experiment.
    #[error(
        "belongs to another experiment (its config hash is {found}, this experiment's is \
         {expected})"
    )]
    ConfigMismatch {
        /// The file's config hash, shortened.
        found: String,
        /// The expected config hash, shortened.
        expected: String,
    },
    /// The file name and the content disagree on the generation (a renamed file).
    #[error("the file name says generation {in_name} but the content says generation {in_file}")]
    GenerationMismatch {
        /// From `gen-NNNNNN.json`.
        in_name: u64,
        /// From the `generation` field.
        in_file: u64,
    },
    /// After a successful write, an old checkpoint (this path) could not be removed, or the
    /// folder (this path) could not be listed to find them.
    #[error("cannot remove old checkpoints after writing {written}: {error}")]
    Prune {
        /// The checkpoint that was written (and is good).
        written: PathBuf,
        /// Why the removal (or the listing before it) failed.
        error: io::Error,
    },
    /// The folder holds no `gen-NNNNNN.json` file.
    #[error("no checkpoint (gen-NNNNNN.json) found")]
    NoCheckpoint,
    /// Every checkpoint of the folder is unusable; each error names its file, newest first.
    #[error("no usable checkpoint: {}", join_errors(.0))]
    NoneUsable(Vec<CheckpointError>),
    /// `keep` was 0; the checkpoint just written is always kept.
    #[error("cannot keep 0 checkpoints (keep must be at least 1)")]
    KeepZero,
}

impl CheckpointError {
    fn new(path: &Path, kind: impl Into<CheckpointErrorKind>) -> Self {
        CheckpointError {
            path: path.to_path_buf(),
            kind: kind.into(),
            previous_good: None,
        }
    }

    /// The content problem, if this is one (damage, wrong format, non-finite value).
    pub fn content(&self) -> Option<&ContentError> {
        match &self.kind {
            CheckpointErrorKind::Content(c) => Some(c),
            _ => None,
        }
    }
}

impl fmt::Display for CheckpointError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.kind {
            CheckpointErrorKind::List(_)
            | CheckpointErrorKind::NoCheckpoint
            | CheckpointErrorKind::NoneUsable(_)
            | CheckpointErrorKind::KeepZero => "checkpoint folder",
            _ => "checkpoint",
        };
        write!(f, "{what} {}: {}", self.path.display(), self.kind)?;
        if let Some(good) = &self.previous_good {
            write!(f, "; the previous good checkpoint is {}", good.display())?;
        }
        Ok(())
    }
}

// The message above already contains the cause, so no `source()`: a cause-chain printer
// would otherwise print it twice.
impl std::error::Error for CheckpointError {}

fn join_errors(errors: &[CheckpointError]) -> String {
    errors
        .iter()
        .map(|e| e.to_string())
        .collect::<Vec<_>>()
        .join("; ")
}

/// The start of a hash, with `…` when something was cut.
fn short(hash: &str) -> String {
    if hash.chars().count() > SHORT_HASH {
        format!("{}…", hash.chars().take(SHORT_HASH).collect::<String>())
    } else {
        hash.to_string()
    }
}

/// The envelope as written, fields in file order.
#[derive(Serialize)]
struct Envelope<'a> {
    format: u32,
    program: &'a str,
    config_hash: &'a str,
    generation: u64,
    checksum: &'a str,
    payload: &'a Value,
}

/// What the checksum covers: every field but the checksum, in a fixed order. The payload is
/// a `Value` when writing, and the file's own bytes (a `RawValue`) when reading.
#[derive(Serialize)]
struct Signed<'a, P: Serialize + ?Sized> {
    format: u32,
    program: &'a str,
    config_hash: &'a str,
    generation: u64,
    payload: &'a P,
}

impl<P: Serialize + ?Sized> Signed<'_, P> {
    /// SHA-256 of the canonical serialization, in lowercase hex.
    fn checksum(&self) -> Result<String, ContentError> {
        let bytes = serde_json::to_vec(self).map_err(|e| ContentError::Serialize(e.to_string()))?;
        let digest = Sha256::digest(&bytes);
        let mut hex = String::with_capacity(64);
        for byte in digest.iter() {
            hex.push(char::from(HEX[usize::from(byte >> 4)]));
            hex.push(char::from(HEX[usize::from(byte & 0xf)]));
        }
        Ok(hex)
    }
}

const HEX: &[u8; 16] = b"0123456789abcdef";

/// Serializes `payload` into a checkpoint for `generation` of the experiment whose
/// configuration hashes to `config_hash` (see the module docs for the format).
///
/// Refuses, before producing anything, a payload holding NaN or an infinity, naming the field.
pub fn encode<T: Serialize + ?Sized>(
    config_hash: &str,
    generation: u64,
    payload: &T,
) -> Result<Vec<u8>, ContentError> {
    finite::check(payload)?;
    let payload =
        serde_json::to_value(payload).map_err(|e| ContentError::Serialize(e.to_string()))?;
    let checksum = Signed {
        format: CHECKPOINT_FORMAT,
        program: PROGRAM,
        config_hash,
        generation,
        payload: &payload,
    }
    .checksum()?;
    let checksum = format!("{CHECKSUM_PREFIX}{checksum}");
    let mut bytes = serde_json::to_vec(&Envelope {
        format: CHECKPOINT_FORMAT,
        program: PROGRAM,
        config_hash,
        generation,
        checksum: &checksum,
        payload: &payload,
    })
    .map_err(|e| ContentError::Serialize(e.to_string()))?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// Payloads up to this size whose bytes are not in canonical form (e.g. reformatted by hand)
/// are still checked semantically (see [`decode`]); larger ones are refused as damaged.
const SEMANTIC_CHECK_MAX_BYTES: usize = 16 << 20;

/// Reads a checkpoint from its bytes, checking the format, the fields and the checksum before
/// the payload is interpreted as a `T`.
///
/// The payload is never turned into a `serde_json::Value` tree when the file is as written
/// (a tree costs about 17 times the bytes of a file of small numbers): its checksum is
/// computed over the file's own bytes, which are the canonical serialization for every file
/// this program writes, and `T` is read straight from them. Only a payload whose bytes are
/// not canonical (whitespace, `1e5` for `100000.0`) and at most `SEMANTIC_CHECK_MAX_BYTES`
/// long is parsed into a tree and checked semantically, as the module docs describe.
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> Result<Checkpoint<T>, ContentError> {
    let not_json = |e: serde_json::Error| ContentError::NotJson {
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    };
    let whole: &RawValue = serde_json::from_slice(bytes).map_err(not_json)?;
    let text = whole.get();
    if !text.starts_with('{') {
        return Err(ContentError::NotAnObject {
            found: raw_kind(text),
        });
    }
    let mut object: BTreeMap<String, &RawValue> = serde_json::from_str(text).map_err(not_json)?;

    // The format first: a newer format may have other fields, and deserves its own message.
    let format = take_u64(&mut object, "format")?;
    if format > u64::from(CHECKPOINT_FORMAT) {
        return Err(ContentError::NewerFormat {
            found: format,
            supported: CHECKPOINT_FORMAT,
        });
    }
    if format < u64::from(OLDEST_READABLE_FORMAT) {
        return Err(ContentError::OlderFormat {
            found: format,
            oldest: OLDEST_READABLE_FORMAT,
            supported: CHECKPOINT_FORMAT,
        });
    }
    let format = u32::try_from(format).unwrap_or(CHECKPOINT_FORMAT);

    if let Some(unknown) = object.keys().find(|k| !FIELDS.contains(&k.as_str())) {
        return Err(ContentError::UnknownField(unknown.clone()));
    }
    let program = take_string(&mut object, "program")?;
    let config_hash = take_string(&mut object, "config_hash")?;
    let generation = take_u64(&mut object, "generation")?;
    let checksum = take_string(&mut object, "checksum")?;
    let payload = object
        .remove("payload")
        .ok_or(ContentError::MissingField("payload"))?;

    let stored = checksum
        .strip_prefix(CHECKSUM_PREFIX)
        .filter(|hex| hex.len() == 64 && hex.bytes().all(|b| HEX.contains(&b)))
        .ok_or_else(|| ContentError::BadChecksumSyntax(checksum.clone()))?;
    let signed =
        |payload: &dyn sign::Sign| payload.sign(format, &program, &config_hash, generation);
    let computed = signed(&payload)?;
    if computed == stored {
        let payload = serde_json::from_str(payload.get())
            .map_err(|e| ContentError::PayloadShape(e.to_string()))?;
        return Ok(Checkpoint {
            format,
            program,
            config_hash,
            generation,
            payload,
        });
    }
    if payload.get().len() > SEMANTIC_CHECK_MAX_BYTES {
        return Err(ContentError::ChecksumMismatch {
            stored: short(stored),
            computed: short(&computed),
        });
    }
    let tree: Value = serde_json::from_str(payload.get()).map_err(not_json)?;
    let computed = signed(&tree)?;
    if computed != stored {
        return Err(ContentError::ChecksumMismatch {
            stored: short(stored),
            computed: short(&computed),
        });
    }
    let payload =
        serde_json::from_value(tree).map_err(|e| ContentError::PayloadShape(e.to_string()))?;
    Ok(Checkpoint {
        format,
        program,
        config_hash,
        generation,
        payload,
    })
}

/// The checksum of a payload given as the file's raw bytes or as a parsed tree.
mod sign {
    use super::{ContentError, Signed};
    use serde_json::value::RawValue;
    use serde_json::Value;

    /// Signs the envelope fields around this payload.
    pub(super) trait Sign {
        fn sign(
            &self,
            format: u32,
            program: &str,
            config_hash: &str,
            generation: u64,
        ) -> Result<String, ContentError>;
    }

    impl Sign for &RawValue {
        fn sign(
            &self,
            format: u32,
            program: &str,
            config_hash: &str,
            generation: u64,
        ) -> Result<String, ContentError> {
            Signed {
                format,
                program,
                config_hash,
                generation,
                payload: *self,
            }
            .checksum()
        }
    }

    impl Sign for Value {
        fn sign(
            &self,
            format: u32,
            program: &str,
            config_hash: &str,
            generation: u64,
        ) -> Result<String, ContentError> {
            Signed {
                format,
                program,
                config_hash,
                generation,
                payload: self,
            }
            .checksum()
        }
    }
}

/// The kind of JSON value that `text` (valid JSON) starts.
fn raw_kind(text: &str) -> &'static str {
    match text.as_bytes().first() {
        Some(b'n') => "null",
        Some(b't' | b'f') => "a boolean",
        Some(b'"') => "a string",
        Some(b'[') => "an array",
        Some(b'{') => "an object",
        _ => "a number",
    }
}

/// The start of a raw JSON value for messages.
fn brief_raw(raw: &RawValue) -> String {
    let text = raw.get();
    if text.chars().count() > 40 {
        format!("{}…", text.chars().take(40).collect::<String>())
    } else {
        text.to_string()
    }
}

fn take_u64(
    object: &mut BTreeMap<String, &RawValue>,
    field: &'static str,
) -> Result<u64, ContentError> {
    let value = object
        .remove(field)
        .ok_or(ContentError::MissingField(field))?;
    serde_json::from_str::<u64>(value.get()).map_err(|_| ContentError::WrongType {
        field,
        expected: "a non-negative integer",
        found: brief_raw(value),
    })
}

fn take_string(
    object: &mut BTreeMap<String, &RawValue>,
    field: &'static str,
) -> Result<String, ContentError> {
    let value = object
        .remove(field)
        .ok_or(ContentError::MissingField(field))?;
    serde_json::from_str::<String>(value.get()).map_err(|_| ContentError::WrongType {
        field,
        expected: "a string",
        found: brief_raw(value),
    })
}

/// The file name of generation `generation`'s checkpoint: `gen-000012.json`.
pub fn checkpoint_file_name(generation: u64) -> String {
    format!("gen-{generation:06}.json")
}

/// The generation of a checkpoint file name, if `name` is exactly what
/// [`checkpoint_file_name`] makes (so `gen-12.json` is not one: two names never share a
/// generation).
pub fn parse_checkpoint_file_name(name: &str) -> Option<u64> {
    let digits = name.strip_prefix("gen-")?.strip_suffix(".json")?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let generation = digits.parse().ok()?;
    (checkpoint_file_name(generation) == name).then_some(generation)
}

/// Writes generation `generation`'s checkpoint to `dir/gen-NNNNNN.json` atomically (see
/// [`super::atomic`]) and returns its path; then removes old checkpoints so that, of those
/// with a lower generation, only the newest `keep - 1` remain beside the new one.
///
/// Checkpoints with a *higher* generation (left by an earlier run that got further) are not
/// touched: they are overwritten or pruned as this run passes them. `dir` must exist. A
/// failure to remove an old checkpoint is an error (kind [`CheckpointErrorKind::Prune`]),
/// although the new checkpoint was written.
pub fn write_checkpoint<T: Serialize + ?Sized>(
    dir: &Path,
    config_hash: &str,
    generation: u64,
    payload: &T,
    keep: usize,
) -> Result<PathBuf, CheckpointError> {
    write_checkpoint_superseding(dir, config_hash, generation, payload, keep, |_| false)
}

/// [`write_checkpoint`], which also removes the older checkpoints for whose generation
/// `superseded` is true (after the new one is written, before the others are pruned; they do
/// not count towards `keep`): checkpoints only needed to continue from until this one existed.
pub fn write_checkpoint_superseding<T: Serialize + ?Sized>(
    dir: &Path,
    config_hash: &str,
    generation: u64,
    payload: &T,
    keep: usize,
    superseded: impl Fn(u64) -> bool,
) -> Result<PathBuf, CheckpointError> {
    if keep == 0 {
        return Err(CheckpointError::new(dir, CheckpointErrorKind::KeepZero));
    }
    let path = dir.join(checkpoint_file_name(generation));
    let bytes =
        encode(config_hash, generation, payload).map_err(|e| CheckpointError::new(&path, e))?;
    write_atomic(&path, &bytes)
        .map_err(|e| CheckpointError::new(&path, CheckpointErrorKind::Write(e)))?;

    let prune = |at: &Path, error: io::Error| {
        CheckpointError::new(
            at,
            CheckpointErrorKind::Prune {
                written: path.clone(),
                error,
            },
        )
    };
    let mut older = Vec::new();
    for (g, old) in list_checkpoints(dir).map_err(|e| prune(dir, e))? {
        if g >= generation {
            continue;
        }
        if superseded(g) {
            fs::remove_file(&old).map_err(|e| prune(&old, e))?;
        } else {
            older.push((g, old));
        }
    }
    let excess = older.len().saturating_sub(keep - 1);
    for (_, old) in &older[..excess] {
        fs::remove_file(old).map_err(|e| prune(old, e))?;
    }
    Ok(path)
}

/// The checkpoints (`gen-NNNNNN.json`) in `dir`, sorted by generation, oldest first.
pub fn list_checkpoints(dir: &Path) -> io::Result<Vec<(u64, PathBuf)>> {
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let with_path =
        |e: io::Error| io::Error::new(e.kind(), format!("cannot list {}: {e}", dir.display()));
    let mut found = Vec::new();
    for entry in fs::read_dir(dir).map_err(with_path)? {
        let entry = entry.map_err(with_path)?;
        let name = entry.file_name();
        let Some(generation) = name.to_str().and_then(parse_checkpoint_file_name) else {
            continue;
        };
        if entry.file_type().map_err(with_path)?.is_dir() {
            continue;
        }
        found.push((generation, entry.path()));
    }
    found.sort();
    Ok(found)
}

/// Reads the checkpoint at `path` (any file name), checking it as [`decode`] does, that a
/// `gen-NNNNNN.json` name agrees with its generation, and that it belongs to the experiment
/// `expected_config_hash` when one is given.
///
/// On error, the error names the file and, when the same folder holds an older good
/// checkpoint, that one (`previous_good`).
pub fn load<T: DeserializeOwned>(
    path: &Path,
    expected_config_hash: Option<&str>,
) -> Result<Checkpoint<T>, CheckpointError> {
    load_one(path, expected_config_hash).map_err(|mut error| {
        error.previous_good = previous_good::<T>(path, expected_config_hash);
        error
    })
}

/// The newest checkpoint in `dir` that reads back intact (and belongs to the experiment
/// `expected_config_hash`, when given), with the newer ones that could not be used.
///
/// Use [`LoadedCheckpoint::refuse_if_newest_unusable`] to refuse to resume past a damaged
/// newest checkpoint with a message that names the previous good one.
pub fn load_latest_good<T: DeserializeOwned>(
    dir: &Path,
    expected_config_hash: Option<&str>,
) -> Result<LoadedCheckpoint<T>, CheckpointError> {
    // A live run may prune a checkpoint between the listing and the read (readers take no
    // lock): a file gone missing is not damage; it is skipped, and if every listed file went,
    // the folder is listed again.
    for _ in 0..10 {
        let all = list_checkpoints(dir)
            .map_err(|e| CheckpointError::new(dir, CheckpointErrorKind::List(e)))?;
        if all.is_empty() {
            return Err(CheckpointError::new(dir, CheckpointErrorKind::NoCheckpoint));
        }
        let mut skipped = Vec::new();
        for (_, path) in all.into_iter().rev() {
            match load_one(&path, expected_config_hash) {
                Ok(checkpoint) => {
                    return Ok(LoadedCheckpoint {
                        path,
                        checkpoint,
                        skipped,
                    })
                }
                Err(CheckpointError {
                    kind: CheckpointErrorKind::Read(e),
                    ..
                }) if e.kind() == io::ErrorKind::NotFound => {}
                Err(e) => skipped.push(e),
            }
        }
        if !skipped.is_empty() {
            return Err(CheckpointError::new(
                dir,
                CheckpointErrorKind::NoneUsable(skipped),
            ));
        }
    }
    Err(CheckpointError::new(dir, CheckpointErrorKind::NoCheckpoint))
}

fn load_one<T: DeserializeOwned>(
    path: &Path,
    expected_config_hash: Option<&str>,
) -> Result<Checkpoint<T>, CheckpointError> {
    let bytes = crate::input::read_regular(path, crate::input::MAX_CHECKPOINT_BYTES)
        .map_err(|e| CheckpointError::new(path, CheckpointErrorKind::Read(e)))?;
    let checkpoint: Checkpoint<T> = decode(&bytes).map_err(|e| CheckpointError::new(path, e))?;
    let named = path
        .file_name()
        .and_then(|n| n.to_str())
        .and_then(parse_checkpoint_file_name);
    if let Some(in_name) = named {
        if in_name != checkpoint.generation {
            return Err(CheckpointError::new(
                path,
                CheckpointErrorKind::GenerationMismatch {
                    in_name,
                    in_file: checkpoint.generation,
                },
            ));
        }
    }
    if let Some(expected) = expected_config_hash {
        if checkpoint.config_hash != expected {
            return Err(CheckpointError::new(
                path,
                CheckpointErrorKind::ConfigMismatch {
                    found: short(&checkpoint.config_hash),
                    expected: short(expected),
                },
            ));
        }
    }
    Ok(checkpoint)
}

/// The newest good checkpoint in `path`'s folder other than `path`, older than it when its
/// name gives its generation. Best effort: any problem just means no suggestion.
fn previous_good<T: DeserializeOwned>(
    path: &Path,
    expected_config_hash: Option<&str>,
) -> Option<PathBuf> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let this_generation = path
        .file_name()
        .and_then(|n| n.to_str())
        .and_then(parse_checkpoint_file_name);
    let this_name = path.file_name();
    list_checkpoints(dir)
        .ok()?
        .into_iter()
        .rev()
        .filter(|(g, p)| p.file_name() != this_name && this_generation.is_none_or(|this| *g < this))
        .find(|(_, p)| load_one::<T>(p, expected_config_hash).is_ok())
        .map(|(_, p)| p)
}

/// A serde `Serializer` that produces nothing and only walks a value, failing on the first
/// non-finite float with the path to it. serde_json cannot be asked to do this: it writes NaN
/// and infinities as `null` without complaint.
mod finite {
    use std::fmt;

    use serde::ser::{self, Serialize};

    use super::ContentError;

    /// Fails with [`ContentError::NonFinite`] if `value` holds a non-finite float.
    pub(super) fn check<T: Serialize + ?Sized>(value: &T) -> Result<(), ContentError> {
        let mut path = Vec::new();
        value
            .serialize(Checker { path: &mut path })
            .map_err(|e| match e {
                Error::NonFinite { field, value } => ContentError::NonFinite { field, value },
                Error::Custom(message) => ContentError::Serialize(message),
            })
    }

    #[derive(Debug)]
    pub(super) enum Error {
        NonFinite { field: String, value: f64 },
        Custom(String),
    }

    impl fmt::Display for Error {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            match self {
                Error::NonFinite { field, value } => write!(f, "`{field}` is {value}"),
                Error::Custom(message) => f.write_str(message),
            }
        }
    }

    impl std::error::Error for Error {}

    impl ser::Error for Error {
        fn custom<M: fmt::Display>(message: M) -> Self {
            Error::Custom(message.to_string())
        }
    }

    /// One step of the path from the payload's root to a value.
    enum Step {
        /// A struct field or an enum variant: `.name`.
        Field(&'static str),
        /// A sequence or tuple element: `[i]`.
        Index(usize),
        /// A map entry, its key already rendered: `["key"]` or `[3]`.
        Key(String),
    }

    fn render(path: &[Step]) -> String {
        let mut out = String::from("payload");
        for step in path {
            match step {
                Step::Field(name) => {
                    out.push('.');
                    out.push_str(name);
                }
                Step::Index(i) => out.push_str(&format!("[{i}]")),
                Step::Key(key) => out.push_str(&format!("[{key}]")),
            }
        }
        out
    }

    fn float(path: &[Step], value: f64) -> Result<(), Error> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(Error::NonFinite {
                field: render(path),
                value,
            })
        }
    }

    struct Checker<'a> {
        path: &'a mut Vec<Step>,
    }

    /// A compound value being walked; `pushed` says whether it added a variant step to the
    /// path that `end` must remove.
    struct Compound<'a> {
        path: &'a mut Vec<Step>,
        index: usize,
        pushed: bool,
    }

    impl<'a> Compound<'a> {
        fn new(path: &'a mut Vec<Step>, variant: Option<&'static str>) -> Self {
            if let Some(name) = variant {
                path.push(Step::Field(name));
            }
            Compound {
                path,
                index: 0,
                pushed: variant.is_some(),
            }
        }

        fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Error> {
            self.path.push(Step::Index(self.index));
            value.serialize(Checker {
                path: &mut *self.path,
            })?;
            self.path.pop();
            self.index += 1;
            Ok(())
        }

        fn field<T: Serialize + ?Sized>(
            &mut self,
            name: &'static str,
            value: &T,
        ) -> Result<(), Error> {
            self.path.push(Step::Field(name));
            value.serialize(Checker {
                path: &mut *self.path,
            })?;
            self.path.pop();
            Ok(())
        }

        fn end(self) -> Result<(), Error> {
            if self.pushed {
                self.path.pop();
            }
            Ok(())
        }
    }

    type Done = Result<(), Error>;

    impl<'a> ser::Serializer for Checker<'a> {
        type Ok = ();
        type Error = Error;
        type SerializeSeq = Compound<'a>;
        type SerializeTuple = Compound<'a>;
        type SerializeTupleStruct = Compound<'a>;
        type SerializeTupleVariant = Compound<'a>;
        type SerializeMap = Compound<'a>;
        type SerializeStruct = Compound<'a>;
        type SerializeStructVariant = Compound<'a>;

        fn serialize_bool(self, _: bool) -> Done {
            Ok(())
        }
        fn serialize_i8(self, _: i8) -> Done {
            Ok(())
        }
        fn serialize_i16(self, _: i16) -> Done {
            Ok(())
        }
        fn serialize_i32(self, _: i32) -> Done {
            Ok(())
        }
        fn serialize_i64(self, _: i64) -> Done {
            Ok(())
        }
        fn serialize_i128(self, _: i128) -> Done {
            Ok(())
        }
        fn serialize_u8(self, _: u8) -> Done {
            Ok(())
        }
        fn serialize_u16(self, _: u16) -> Done {
            Ok(())
        }
        fn serialize_u32(self, _: u32) -> Done {
            Ok(())
        }
        fn serialize_u64(self, _: u64) -> Done {
            Ok(())
        }
        fn serialize_u128(self, _: u128) -> Done {
            Ok(())
        }
        fn serialize_f32(self, v: f32) -> Done {
            float(self.path, f64::from(v))
        }
        fn serialize_f64(self, v: f64) -> Done {
            float(self.path, v)
        }
        fn serialize_char(self, _: char) -> Done {
            Ok(())
        }
        fn serialize_str(self, _: &str) -> Done {
            Ok(())
        }
        fn serialize_bytes(self, _: &[u8]) -> Done {
            Ok(())
        }
        fn serialize_none(self) -> Done {
            Ok(())
        }
        fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Done {
            value.serialize(self)
        }
        fn serialize_unit(self) -> Done {
            Ok(())
        }
        fn serialize_unit_struct(self, _: &'static str) -> Done {
            Ok(())
        }
        fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Done {
            Ok(())
        }
        fn serialize_newtype_struct<T: Serialize + ?Sized>(
            self,
            _: &'static str,
            value: &T,
        ) -> Done {
            value.serialize(self)
        }
        fn serialize_newtype_variant<T: Serialize + ?Sized>(
            self,
            _: &'static str,
            _: u32,
            variant: &'static str,
            value: &T,
        ) -> Done {
            let mut compound = Compound::new(self.path, None);
            compound.field(variant, value)
        }
        fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, None))
        }
        fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, None))
        }
        fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, None))
        }
        fn serialize_tuple_variant(
            self,
            _: &'static str,
            _: u32,
            variant: &'static str,
            _: usize,
        ) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, Some(variant)))
        }
        fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, None))
        }
        fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, None))
        }
        fn serialize_struct_variant(
            self,
            _: &'static str,
            _: u32,
            variant: &'static str,
            _: usize,
        ) -> Result<Compound<'a>, Error> {
            Ok(Compound::new(self.path, Some(variant)))
        }
    }

    impl ser::SerializeSeq for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
            self.element(value)
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }

    impl ser::SerializeTuple for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
            self.element(value)
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }

    impl ser::SerializeTupleStruct for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
            self.element(value)
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }

    impl ser::SerializeTupleVariant for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
            self.element(value)
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }

    impl ser::SerializeMap for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Done {
            // Keys are checked like values (a float key could be NaN), then remembered,
            // rendered as JSON would write them, for the value's path.
            self.path.push(Step::Key("<key>".into()));
            key.serialize(Checker {
                path: &mut *self.path,
            })?;
            self.path.pop();
            let rendered = match serde_json::to_value(key) {
                Ok(serde_json::Value::String(s)) => format!("{s:?}"),
                Ok(other) => other.to_string(),
                Err(_) => "?".into(),
            };
            self.path.push(Step::Key(rendered));
            Ok(())
        }
        fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
            value.serialize(Checker {
                path: &mut *self.path,
            })?;
            self.path.pop();
            Ok(())
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }

    impl ser::SerializeStruct for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_field<T: Serialize + ?Sized>(
            &mut self,
            name: &'static str,
            value: &T,
        ) -> Done {
            self.field(name, value)
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }

    impl ser::SerializeStructVariant for Compound<'_> {
        type Ok = ();
        type Error = Error;
        fn serialize_field<T: Serialize + ?Sized>(
            &mut self,
            name: &'static str,
            value: &T,
        ) -> Done {
            self.field(name, value)
        }
        fn end(self) -> Done {
            Compound::end(self)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_names_are_canonical() {
        assert_eq!(checkpoint_file_name(12), "gen-000012.json");
        assert_eq!(checkpoint_file_name(1_234_567), "gen-1234567.json");
        assert_eq!(parse_checkpoint_file_name("gen-000012.json"), Some(12));
        assert_eq!(
            parse_checkpoint_file_name("gen-1234567.json"),
            Some(1_234_567)
        );
        for other in [
            "gen-12.json",
            "gen-0000012.json",
            "gen-00001a.json",
            "gen-+00012.json",
            "gen-.json",
            "gen-000012.json.tmp",
            ".gen-000012.json.tmp-1-2",
            "gen-99999999999999999999999.json",
        ] {
            assert_eq!(parse_checkpoint_file_name(other), None, "{other}");
        }
    }

    #[test]
    fn envelope_field_order_is_the_documented_one() {
        let bytes = encode("abc", 7, &serde_json::json!({"x": 1.5})).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let prefix = format!(
            "{{\"format\":1,\"program\":\"{PROGRAM}\",\"config_hash\":\"abc\",\"generation\":7,\"checksum\":\"sha256:"
        );
        assert!(text.starts_with(&prefix), "{text}");
        assert!(text.ends_with(",\"payload\":{\"x\":1.5}}\n"), "{text}");
    }
}
