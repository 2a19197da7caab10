//! Tests of the record layer: atomic writes, checkpoints and the fitness CSV, including the
//! damage a crash or a careless edit can do to them.

use std::collections::BTreeMap;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use berry_evolve::record::atomic::{remove_stale_temp_files, write_atomic, write_atomic_with};
use berry_evolve::record::checkpoint::{
    self, decode, encode, list_checkpoints, load, load_latest_good, write_checkpoint,
    CheckpointErrorKind, ContentError, CHECKPOINT_FORMAT, PROGRAM,
};
use berry_evolve::record::fitness_csv::{
    self, read_rows, FitnessCsv, FitnessCsvError, FitnessRow, HEADER,
};
use berry_evolve::seed::{
    stream, uniform, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex,
};
use rand::RngCore;
use serde::{Deserialize, Serialize};

/// A fresh, empty folder for one test under cargo's scratch folder for integration tests.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("record-tests")
        .join(name);
    if dir.exists() {
        fs::remove_dir_all(&dir).unwrap();
    }
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn rng(seed: u64) -> Rng {
    stream(
        Seed(seed),
        Purpose::Baseline,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    )
}

// ---------------------------------------------------------------------------------------
// Atomic writes
// ---------------------------------------------------------------------------------------

#[test]
fn write_atomic_replaces_content_and_leaves_no_temp_file() {
    let dir = scratch("atomic_replace");
    let path = dir.join("state.json");
    write_atomic(&path, b"first version, rather long\n").unwrap();
    assert_eq!(fs::read(&path).unwrap(), b"first version, rather long\n");
    write_atomic(&path, b"second\n").unwrap();
    assert_eq!(fs::read(&path).unwrap(), b"second\n");
    write_atomic(&path, b"").unwrap();
    assert_eq!(fs::read(&path).unwrap(), b"");
    assert_eq!(names_in(&dir), ["state.json"]);
}

#[test]
fn failing_writer_leaves_previous_file_byte_identical_and_no_temp_file() {
    let dir = scratch("atomic_failing_writer");
    let path = dir.join("gen-000003.json");
    let before = b"{\"the\":\"old checkpoint\"}\n".to_vec();
    write_atomic(&path, &before).unwrap();

    // A disk that fills up after some bytes were written.
    let err = write_atomic_with(&path, |w: &mut dyn Write| {
        w.write_all(&[b'x'; 100_000])?;
        Err(io::Error::new(
            io::ErrorKind::StorageFull,
            "no space left on device",
        ))
    })
    .unwrap_err();
    assert_eq!(err.kind(), io::ErrorKind::StorageFull);
    assert!(err.to_string().contains("no space left on device"), "{err}");
    assert!(err.to_string().contains("gen-000003.json"), "{err}");
    assert_eq!(fs::read(&path).unwrap(), before);
    assert_eq!(names_in(&dir), ["gen-000003.json"]);

    // The same for a file that did not exist: it still does not.
    let fresh = dir.join("fresh.csv");
    write_atomic_with(&fresh, |_| Err(io::Error::other("simulated failure"))).unwrap_err();
    assert!(!fresh.exists());
    assert_eq!(names_in(&dir), ["gen-000003.json"]);
}

#[test]
fn write_atomic_into_a_missing_folder_names_the_path() {
    let dir = scratch("atomic_missing_folder");
    let path = dir.join("no-such-folder").join("x.json");
    let err = write_atomic(&path, b"x").unwrap_err();
    assert_eq!(err.kind(), io::ErrorKind::NotFound);
    assert!(err.to_string().contains("no-such-folder"), "{err}");
}

#[test]
fn stale_temp_files_are_removed_and_counted_others_untouched() {
    let dir = scratch("atomic_stale");
    let stale = [
        ".gen-000004.json.tmp-4242-0",
        ".fitness.csv.tmp-1-17",
        ".a.tmp-99-3",
    ];
    let kept = [
        "gen-000004.json",
        "fitness.csv",
        ".hidden",
        "notes.tmp",
        "gen-000004.json.tmp-1-2",
        ".x.tmp-abc-1",
        ".x.tmp-1",
        ".tmp-1-2",
    ];
    for name in stale.iter().chain(kept.iter()) {
        fs::write(dir.join(name), name.as_bytes()).unwrap();
    }
    // A folder with a temporary-looking name is not a leftover of ours.
    fs::create_dir(dir.join(".d.tmp-1-2")).unwrap();

    assert_eq!(remove_stale_temp_files(&dir).unwrap(), stale.len());
    let mut expected: Vec<String> = kept.iter().map(|s| s.to_string()).collect();
    expected.push(".d.tmp-1-2".into());
    expected.sort();
    assert_eq!(names_in(&dir), expected);
    for name in kept {
        assert_eq!(fs::read(dir.join(name)).unwrap(), name.as_bytes());
    }
    assert_eq!(remove_stale_temp_files(&dir).unwrap(), 0);
}

// ---------------------------------------------------------------------------------------
// Checkpoints
// ---------------------------------------------------------------------------------------

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Individual {
    parameters: Vec<f64>,
    step_size: Option<f64>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
enum Note {
    Plain,
    Scale(f64),
    Pair(f64, f64),
    Range { lo: f64, hi: f64 },
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct State {
    population: Vec<Individual>,
    best: (f64, u64),
    extra: BTreeMap<String, f64>,
    notes: Vec<Note>,
    narrow: Vec<f32>,
    counters: Vec<u64>,
    signed: i64,
}

fn small_state() -> State {
    State {
        population: vec![
            Individual {
                parameters: vec![0.5, -1.25, 3.0],
                step_size: Some(0.1),
            },
            Individual {
                parameters: vec![2.0],
                step_size: None,
            },
        ],
        best: (7.5, 3),
        extra: BTreeMap::from([("alpha".to_string(), 1e-3)]),
        notes: vec![Note::Plain, Note::Scale(2.5)],
        narrow: vec![0.25],
        counters: vec![1, 2],
        signed: -4,
    }
}

/// Values that a careless float writer or reader gets wrong, then seeded random ones: random
/// bit patterns (every exponent, subnormals included) and ordinary uniform draws.
fn awkward_floats() -> Vec<f64> {
    let mut values = vec![
        0.1 + 0.2,
        0.1,
        1e-308,
        2.2250738585072014e-308, // smallest normal
        2.225073858507201e-308,  // largest subnormal
        5e-324,                  // smallest subnormal
        -5e-324,
        -0.0,
        0.0,
        1e308,
        f64::MAX,
        f64::MIN,
        f64::EPSILON,
        1.0 - f64::EPSILON / 2.0,
        9007199254740993.0,
        1e16,
        1e-7,
        123456789.0,
        std::f64::consts::PI,
    ];
    let mut r = rng(20240601);
    while values.len() < 3000 {
        let bits = f64::from_bits(r.next_u64());
        if bits.is_finite() {
            values.push(bits);
        }
        values.push(uniform(&mut r, -10.0, 10.0));
    }
    values
}

#[test]
fn checkpoint_round_trips_every_f64_bit_exactly() {
    let values = awkward_floats();
    let mut r = rng(7);
    let narrow: Vec<f32> = (0..200)
        .map(|_| f32::from_bits(r.next_u32()))
        .filter(|x| x.is_finite())
        .collect();
    let state = State {
        population: values
            .chunks(97)
            .map(|c| Individual {
                parameters: c.to_vec(),
                step_size: Some(c[0]),
            })
            .collect(),
        best: (values[0], u64::MAX),
        extra: values
            .iter()
            .take(50)
            .enumerate()
            .map(|(i, v)| (format!("k{i}"), *v))
            .collect(),
        notes: vec![
            Note::Plain,
            Note::Scale(values[5]),
            Note::Pair(values[6], values[7]),
            Note::Range {
                lo: values[8],
                hi: values[9],
            },
        ],
        narrow,
        counters: vec![0, 1, u64::MAX, 1 << 53, (1 << 53) + 1],
        signed: i64::MIN,
    };

    let bytes = encode("c0ffee", 42, &state).unwrap();
    let back = decode::<State>(&bytes).unwrap();
    assert_eq!(back.format, CHECKPOINT_FORMAT);
    assert_eq!(back.program, PROGRAM);
    assert_eq!(back.config_hash, "c0ffee");
    assert_eq!(back.generation, 42);

    let bits = |s: &State| -> Vec<u64> {
        let mut out: Vec<u64> = s
            .population
            .iter()
            .flat_map(|i| i.parameters.iter().chain(i.step_size.iter()))
            .map(|v| v.to_bits())
            .collect();
        out.extend(s.extra.values().map(|v| v.to_bits()));
        out.push(s.best.0.to_bits());
        out.extend(s.narrow.iter().map(|v| u64::from(v.to_bits())));
        out
    };
    let (want, got) = (bits(&state), bits(&back.payload));
    assert_eq!(want.len(), got.len());
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        assert_eq!(
            w,
            g,
            "value {i}: wrote {} read {}",
            f64::from_bits(*w),
            f64::from_bits(*g)
        );
    }
    assert_eq!(back.payload.notes, state.notes);
    assert_eq!(back.payload.counters, state.counters);
    assert_eq!(back.payload.signed, i64::MIN);

    // Writing is a pure function of the state, and reading then writing again changes nothing.
    assert_eq!(encode("c0ffee", 42, &state).unwrap(), bytes);
    assert_eq!(encode("c0ffee", 42, &back.payload).unwrap(), bytes);
}

#[test]
fn non_finite_values_are_refused_naming_the_field() {
    type Damage = fn(&mut State);
    let cases: [(Damage, &str, &str); 10] = [
        (
            |s| s.population[1].parameters[0] = f64::NAN,
            "payload.population[1].parameters[0]",
            "NaN",
        ),
        (
            |s| s.population[0].parameters[2] = f64::INFINITY,
            "payload.population[0].parameters[2]",
            "inf",
        ),
        (
            |s| s.population[0].step_size = Some(f64::NEG_INFINITY),
            "payload.population[0].step_size",
            "-inf",
        ),
        (|s| s.best.0 = f64::NAN, "payload.best[0]", "NaN"),
        (
            |s| {
                s.extra.insert("weird key".into(), f64::INFINITY);
            },
            "payload.extra[\"weird key\"]",
            "inf",
        ),
        (
            |s| s.notes[1] = Note::Scale(f64::NAN),
            "payload.notes[1].Scale",
            "NaN",
        ),
        (
            |s| s.notes.push(Note::Pair(1.0, f64::NAN)),
            "payload.notes[2].Pair[1]",
            "NaN",
        ),
        (
            |s| {
                s.notes.push(Note::Range {
                    lo: 0.0,
                    hi: f64::INFINITY,
                })
            },
            "payload.notes[2].Range.hi",
            "inf",
        ),
        (|s| s.narrow[0] = f32::NAN, "payload.narrow[0]", "NaN"),
        (
            |s| s.narrow.push(f32::NEG_INFINITY),
            "payload.narrow[1]",
            "-inf",
        ),
    ];
    let dir = scratch("checkpoint_non_finite");
    for (damage, field, shown) in cases {
        let mut state = small_state();
        damage(&mut state);
        let err = encode("h", 1, &state).unwrap_err();
        match &err {
            ContentError::NonFinite { field: f, .. } => assert_eq!(f, field),
            other => panic!("expected NonFinite at {field}, got {other:?}"),
        }
        let message = err.to_string();
        assert_eq!(
            message,
            format!("the value at `{field}` is {shown}; a checkpoint holds only finite numbers")
        );
        // Nothing is written.
        let err = write_checkpoint(&dir, "h", 1, &state, 3).unwrap_err();
        assert!(err.to_string().contains(field), "{err}");
        assert!(err.to_string().contains("gen-000001.json"), "{err}");
        assert!(names_in(&dir).is_empty(), "{:?}", names_in(&dir));
    }
    // A valid state passes.
    encode("h", 1, &small_state()).unwrap();
}

#[test]
fn every_truncation_of_a_checkpoint_is_a_clear_error() {
    let bytes = encode("abc123", 5, &small_state()).unwrap();
    assert_eq!(bytes.last(), Some(&b'\n'));
    for len in 0..bytes.len() - 1 {
        match decode::<State>(&bytes[..len]) {
            Err(ContentError::NotJson { line, .. }) => assert_eq!(line, 1),
            other => panic!("prefix of {len} bytes: expected NotJson, got {other:?}"),
        }
    }
    // Only the final newline missing: the content is intact.
    assert_eq!(
        decode::<State>(&bytes[..bytes.len() - 1]).unwrap().payload,
        small_state()
    );
    let message = decode::<State>(&bytes[..100]).unwrap_err().to_string();
    assert!(
        message.starts_with("truncated or not JSON (EOF while parsing"),
        "{message}"
    );
    assert!(message.ends_with(" at line 1 column 100)"), "{message}");
}

#[test]
fn every_single_bit_flip_is_detected_or_harmless() {
    let state = small_state();
    let bytes = encode("abc123", 5, &state).unwrap();
    let mut checksum_mismatches = 0;
    let mut not_json = 0;
    for i in 0..bytes.len() {
        for bit in 0..8 {
            let mut damaged = bytes.clone();
            damaged[i] ^= 1 << bit;
            match decode::<State>(&damaged) {
                // E.g. `e` -> `E` in an exponent, or the final newline -> another whitespace.
                Ok(back) => {
                    assert_eq!(back.payload, state, "byte {i} bit {bit}");
                    assert_eq!(back.generation, 5);
                    assert_eq!(back.config_hash, "abc123");
                }
                Err(ContentError::ChecksumMismatch { .. }) => checksum_mismatches += 1,
                Err(ContentError::NotJson { .. }) => not_json += 1,
                Err(_) => {}
            }
        }
    }
    assert!(checksum_mismatches > 100, "{checksum_mismatches}");
    assert!(not_json > 100, "{not_json}");
}

fn replace_once(bytes: &[u8], from: &str, to: &str) -> Vec<u8> {
    let text = std::str::from_utf8(bytes).unwrap();
    assert_eq!(text.matches(from).count(), 1, "`{from}` in {text}");
    text.replacen(from, to, 1).into_bytes()
}

#[test]
fn damaged_and_foreign_checkpoints_give_distinct_clear_errors() {
    let bytes = encode("abc123", 5, &small_state()).unwrap();
    let text = String::from_utf8(bytes.clone()).unwrap();
    let mut messages = Vec::new();
    let mut check = |bytes: Vec<u8>, matches: fn(&ContentError) -> bool, phrase: &str| {
        let err = decode::<State>(&bytes).unwrap_err();
        assert!(matches(&err), "{err:?}");
        let message = err.to_string();
        assert!(message.contains(phrase), "`{message}` lacks `{phrase}`");
        assert!(!messages.contains(&message), "duplicate message {message}");
        messages.push(message);
    };

    // An edited number in the payload.
    check(
        replace_once(&bytes, "-1.25", "-1.26"),
        |e| matches!(e, ContentError::ChecksumMismatch { .. }),
        "checksum mismatch: the file was edited or damaged",
    );
    // Edited envelope fields are damage too.
    check(
        replace_once(&bytes, "\"generation\":5", "\"generation\":6"),
        |e| matches!(e, ContentError::ChecksumMismatch { .. }),
        "checksum mismatch",
    );
    check(
        replace_once(&bytes, "abc123", "abc124"),
        |e| matches!(e, ContentError::ChecksumMismatch { .. }),
        "checksum mismatch",
    );
    check(
        replace_once(&bytes, "\"format\":1", "\"format\":2"),
        |e| matches!(e, ContentError::NewerFormat { found: 2, .. }),
        "written by a newer berry-evolve (format 2, this program reads ≤ 1)",
    );
    check(
        replace_once(&bytes, "\"format\":1", "\"format\":0"),
        |e| matches!(e, ContentError::OlderFormat { found: 0, .. }),
        "format 0, which this program no longer reads",
    );
    check(
        replace_once(&bytes, "\"generation\":5,", ""),
        |e| matches!(e, ContentError::MissingField("generation")),
        "missing field `generation`",
    );
    check(
        replace_once(&bytes, "\"format\":1,", ""),
        |e| matches!(e, ContentError::MissingField("format")),
        "missing field `format`",
    );
    check(
        replace_once(&bytes, "\"format\":1", "\"format\":\"1\""),
        |e| {
            matches!(
                e,
                ContentError::WrongType {
                    field: "format",
                    ..
                }
            )
        },
        "field `format` must be a non-negative integer, found \"1\"",
    );
    check(
        replace_once(
            &bytes,
            "{\"format\":1,",
            "{\"format\":1,\"comment\":\"hi\",",
        ),
        |e| matches!(e, ContentError::UnknownField(f) if f == "comment"),
        "unknown field `comment`",
    );
    let checksum_start = text.find("sha256:").unwrap();
    let stored = &text[checksum_start..checksum_start + 71];
    check(
        replace_once(&bytes, stored, "sha256:1234"),
        |e| matches!(e, ContentError::BadChecksumSyntax(_)),
        "field `checksum` is `sha256:1234`",
    );
    check(
        b"[1, 2, 3]\n".to_vec(),
        |e| matches!(e, ContentError::NotAnObject { found: "an array" }),
        "not a checkpoint",
    );
    check(
        b"\x00\x01binary junk".to_vec(),
        |e| matches!(e, ContentError::NotJson { .. }),
        "truncated or not JSON",
    );
    // A sound checkpoint, read as something else.
    let other = encode("abc123", 5, &vec![1.0, 2.0]).unwrap();
    check(
        other,
        |e| matches!(e, ContentError::PayloadShape(_)),
        "the payload does not have the expected shape: invalid type",
    );
}

/// Writes a checkpoint of `state` with generation-specific content for generation `g`.
fn state_for(g: u64) -> State {
    let mut s = small_state();
    s.best = (g as f64 * 0.5, g);
    s
}

fn corrupt(path: &Path) {
    let bytes = fs::read(path).unwrap();
    fs::write(path, replace_once(&bytes, "-1.25", "-1.35")).unwrap();
}

#[test]
fn load_latest_good_skips_a_damaged_newest_and_names_it() {
    let dir = scratch("checkpoint_latest_good");
    for g in [10, 20, 30] {
        write_checkpoint(&dir, "abc123", g, &state_for(g), 5).unwrap();
    }
    let loaded = load_latest_good::<State>(&dir, Some("abc123")).unwrap();
    assert_eq!(loaded.checkpoint.generation, 30);
    assert!(loaded.skipped.is_empty());

    corrupt(&dir.join("gen-000030.json"));
    // The newest is only half there, as if written without the atomic rename.
    let bytes = fs::read(dir.join("gen-000020.json")).unwrap();
    fs::write(dir.join("gen-000025.json"), &bytes[..bytes.len() / 3]).unwrap();

    let loaded = load_latest_good::<State>(&dir, Some("abc123")).unwrap();
    assert_eq!(loaded.path, dir.join("gen-000020.json"));
    assert_eq!(loaded.checkpoint.generation, 20);
    assert_eq!(loaded.checkpoint.payload, state_for(20));
    let skipped: Vec<&Path> = loaded.skipped.iter().map(|e| e.path.as_path()).collect();
    assert_eq!(
        skipped,
        [dir.join("gen-000030.json"), dir.join("gen-000025.json")]
    );
    assert!(matches!(
        loaded.skipped[0].content(),
        Some(ContentError::ChecksumMismatch { .. })
    ));
    assert!(matches!(
        loaded.skipped[1].content(),
        Some(ContentError::NotJson { .. })
    ));

    let err = loaded.refuse_if_newest_unusable().unwrap_err();
    let message = err.to_string();
    let expected_start = format!(
        "checkpoint {}: checksum mismatch: the file was edited or damaged",
        dir.join("gen-000030.json").display()
    );
    let expected_end = format!(
        "; the previous good checkpoint is {}",
        dir.join("gen-000020.json").display()
    );
    assert!(message.starts_with(&expected_start), "{message}");
    assert!(message.ends_with(&expected_end), "{message}");

    // Nothing usable at all.
    corrupt(&dir.join("gen-000020.json"));
    corrupt(&dir.join("gen-000010.json"));
    let err = load_latest_good::<State>(&dir, None).unwrap_err();
    let CheckpointErrorKind::NoneUsable(all) = &err.kind else {
        panic!("{err:?}")
    };
    assert_eq!(all.len(), 4);
    assert!(err.to_string().starts_with(&format!(
        "checkpoint folder {}: no usable checkpoint: checkpoint {}",
        dir.display(),
        dir.join("gen-000030.json").display()
    )));

    let empty = scratch("checkpoint_latest_good_empty");
    let err = load_latest_good::<State>(&empty, None).unwrap_err();
    assert!(
        matches!(err.kind, CheckpointErrorKind::NoCheckpoint),
        "{err}"
    );
    assert_eq!(
        err.to_string(),
        format!(
            "checkpoint folder {}: no checkpoint (gen-NNNNNN.json) found",
            empty.display()
        )
    );
}

#[test]
fn loading_an_explicit_damaged_file_names_it_and_the_previous_good_one() {
    let dir = scratch("checkpoint_explicit");
    for g in [1, 2, 3] {
        write_checkpoint(&dir, "abc123", g, &state_for(g), 5).unwrap();
    }
    let good = load::<State>(&dir.join("gen-000002.json"), Some("abc123")).unwrap();
    assert_eq!(good.payload, state_for(2));

    corrupt(&dir.join("gen-000002.json"));
    let err = load::<State>(&dir.join("gen-000002.json"), Some("abc123")).unwrap_err();
    assert_eq!(err.path, dir.join("gen-000002.json"));
    // The previous good one is older, not the newer gen 3.
    assert_eq!(err.previous_good, Some(dir.join("gen-000001.json")));
    assert!(err.to_string().contains("checksum mismatch"), "{err}");

    // No older good checkpoint: no suggestion.
    corrupt(&dir.join("gen-000001.json"));
    let err = load::<State>(&dir.join("gen-000001.json"), None).unwrap_err();
    assert_eq!(err.previous_good, None);
    assert!(!err.to_string().contains("previous good"), "{err}");

    // A missing file: the error names it, and the newest good checkpoint of its folder.
    let missing = dir.join("gen-000004.json");
    let err = load::<State>(&missing, None).unwrap_err();
    assert!(matches!(err.kind, CheckpointErrorKind::Read(_)), "{err:?}");
    assert!(err.to_string().contains("gen-000004.json"), "{err}");
    assert_eq!(err.previous_good, Some(dir.join("gen-000003.json")));

    // A renamed checkpoint.
    fs::copy(dir.join("gen-000003.json"), dir.join("gen-000007.json")).unwrap();
    let err = load::<State>(&dir.join("gen-000007.json"), None).unwrap_err();
    assert!(
        matches!(
            err.kind,
            CheckpointErrorKind::GenerationMismatch {
                in_name: 7,
                in_file: 3
            }
        ),
        "{err:?}"
    );
    // Any other name is fine for an explicit file.
    fs::copy(dir.join("gen-000003.json"), dir.join("best-so-far.json")).unwrap();
    assert_eq!(
        load::<State>(&dir.join("best-so-far.json"), None)
            .unwrap()
            .generation,
        3
    );
}

#[test]
fn a_checkpoint_of_another_experiment_is_refused() {
    let dir = scratch("checkpoint_config_mismatch");
    let ours = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08";
    let theirs = "60303ae22b998861bce3b28f33eec1be758a213c86c93c076dbe9f558c11c752";
    write_checkpoint(&dir, theirs, 4, &small_state(), 3).unwrap();
    let path = dir.join("gen-000004.json");
    let err = load::<State>(&path, Some(ours)).unwrap_err();
    assert!(
        matches!(err.kind, CheckpointErrorKind::ConfigMismatch { .. }),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        format!(
            "checkpoint {}: belongs to another experiment (its config hash is 60303ae22b99…, \
             this experiment's is 9f86d081884c…)",
            path.display()
        )
    );
    let err = load_latest_good::<State>(&dir, Some(ours)).unwrap_err();
    assert!(matches!(err.kind, CheckpointErrorKind::NoneUsable(_)));
    assert!(err.to_string().contains("belongs to another experiment"));
    // Without an expected hash it is just a checkpoint.
    assert_eq!(load::<State>(&path, None).unwrap().config_hash, theirs);
}

#[test]
fn retention_keeps_the_newest_checkpoints() {
    let dir = scratch("checkpoint_retention");
    fs::write(dir.join("fitness.csv"), "not a checkpoint").unwrap();
    for g in 0..=10 {
        let path = write_checkpoint(&dir, "h", g, &state_for(g), 3).unwrap();
        assert_eq!(path, dir.join(checkpoint::checkpoint_file_name(g)));
    }
    assert_eq!(
        names_in(&dir),
        [
            "fitness.csv",
            "gen-000008.json",
            "gen-000009.json",
            "gen-000010.json"
        ]
    );
    let listed: Vec<u64> = list_checkpoints(&dir)
        .unwrap()
        .into_iter()
        .map(|(g, _)| g)
        .collect();
    assert_eq!(listed, [8, 9, 10]);

    // Rewriting an existing generation replaces it.
    write_checkpoint(&dir, "h", 10, &state_for(99), 3).unwrap();
    assert_eq!(
        load::<State>(&dir.join("gen-000010.json"), None)
            .unwrap()
            .payload,
        state_for(99)
    );

    // keep = 1 leaves only the one just written.
    write_checkpoint(&dir, "h", 12, &state_for(12), 1).unwrap();
    assert_eq!(names_in(&dir), ["fitness.csv", "gen-000012.json"]);

    // A run resumed from an older checkpoint never deletes what it just wrote, and leaves the
    // later checkpoints of the earlier run alone until it passes them.
    write_checkpoint(&dir, "h", 11, &state_for(11), 1).unwrap();
    assert_eq!(
        names_in(&dir),
        ["fitness.csv", "gen-000011.json", "gen-000012.json"]
    );

    // keep = 0 is refused before anything is written.
    let err = write_checkpoint(&dir, "h", 13, &state_for(13), 0).unwrap_err();
    assert!(matches!(err.kind, CheckpointErrorKind::KeepZero), "{err}");
    assert!(!dir.join("gen-000013.json").exists());
}

#[test]
fn a_checkpoint_file_is_exactly_the_encoded_bytes() {
    let dir = scratch("checkpoint_bytes");
    let path = write_checkpoint(&dir, "abc", 3, &small_state(), 2).unwrap();
    assert_eq!(
        fs::read(&path).unwrap(),
        encode("abc", 3, &small_state()).unwrap()
    );
    let text = fs::read_to_string(&path).unwrap();
    assert!(text.starts_with(&format!(
        "{{\"format\":1,\"program\":\"{PROGRAM}\",\"config_hash\":\"abc\",\"generation\":3,\"checksum\":\"sha256:"
    )));
    assert_eq!(text.lines().count(), 1);
}

// ---------------------------------------------------------------------------------------
// Fitness CSV
// ---------------------------------------------------------------------------------------

fn row(generation: u64, best: f64) -> FitnessRow {
    FitnessRow {
        generation,
        evaluations: 40 * (generation + 1),
        best,
        mean: 0.1 + 0.2,
        median: 0.25,
        worst: -0.0,
        std: 1e-308,
        best_ever: best,
        mean_food_a: 1.0,
        mean_food_b: 2.5,
        mean_food_c: 0.0,
        mean_food_d: 1e16,
        best_food_a: 5e-324,
        best_food_b: 123456789.0,
        best_food_c: 1e-7,
        best_food_d: -3.75,
        non_finite: generation % 2,
    }
}

const HAND_EXAMPLE: &str = "\
generation,evaluations,best,mean,median,worst,std,best_ever,mean_food_a,mean_food_b,mean_food_c,mean_food_d,best_food_a,best_food_b,best_food_c,best_food_d,non_finite
0,40,1.5,0.30000000000000004,0.25,-0.0,1e-308,1.5,1.0,2.5,0.0,1e16,5e-324,123456789.0,1e-7,-3.75,0
1,80,2.0,0.30000000000000004,0.25,-0.0,1e-308,2.0,1.0,2.5,0.0,1e16,5e-324,123456789.0,1e-7,-3.75,1
";

#[test]
fn fitness_csv_header_and_rows_are_byte_exact() {
    let dir = scratch("csv_hand_example");
    let path = dir.join("fitness.csv");
    let mut csv = FitnessCsv::create(&path).unwrap();
    assert_eq!(fs::read_to_string(&path).unwrap(), format!("{HEADER}\n"));
    csv.append(&row(0, 1.5)).unwrap();
    // Each row is on disk as soon as `append` returns.
    assert_eq!(
        fs::read_to_string(&path).unwrap().lines().count(),
        2,
        "row 0 not flushed"
    );
    csv.append(&row(1, 2.0)).unwrap();
    csv.sync().unwrap();
    assert_eq!(fs::read_to_string(&path).unwrap(), HAND_EXAMPLE);

    // The export writer produces the same bytes.
    let exported = dir.join("export.csv");
    fitness_csv::write_all(&exported, &[row(0, 1.5), row(1, 2.0)]).unwrap();
    assert_eq!(fs::read_to_string(&exported).unwrap(), HAND_EXAMPLE);

    // Rows must come in increasing generation order.
    let err = csv.append(&row(1, 3.0)).unwrap_err();
    assert!(
        matches!(
            err,
            FitnessCsvError::OutOfOrder {
                generation: 1,
                previous: 1,
                line: 4,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("fitness.csv"), "{err}");
    assert_eq!(fs::read_to_string(&path).unwrap(), HAND_EXAMPLE);
}

#[test]
fn fitness_rows_round_trip_through_read_rows() {
    let dir = scratch("csv_round_trip");
    let path = dir.join("fitness.csv");
    let values = awkward_floats();
    let mut r = rng(99);
    let mut rows = Vec::new();
    let mut csv = FitnessCsv::create(&path).unwrap();
    for (g, chunk) in values.chunks(14).enumerate() {
        if chunk.len() < 14 {
            break;
        }
        let row = FitnessRow {
            generation: g as u64 * 3,
            evaluations: r.next_u64(),
            best: chunk[0],
            mean: chunk[1],
            median: chunk[2],
            worst: chunk[3],
            std: chunk[4],
            best_ever: chunk[5],
            mean_food_a: chunk[6],
            mean_food_b: chunk[7],
            mean_food_c: chunk[8],
            mean_food_d: chunk[9],
            best_food_a: chunk[10],
            best_food_b: chunk[11],
            best_food_c: chunk[12],
            best_food_d: chunk[13],
            non_finite: r.next_u64() % 5,
        };
        csv.append(&row).unwrap();
        rows.push(row);
    }
    let back = read_rows(&path).unwrap();
    assert_eq!(back.len(), rows.len());
    for (w, g) in rows.iter().zip(&back) {
        // Compare bits, not values: -0.0 == 0.0 would hide a lost sign.
        assert_eq!(format!("{w:?}"), format!("{g:?}"));
        assert_eq!(w.worst.to_bits(), g.worst.to_bits());
        assert_eq!(w.best.to_bits(), g.best.to_bits());
        assert_eq!(w.best_food_d.to_bits(), g.best_food_d.to_bits());
    }
    // Exporting what was read gives the same file.
    let exported = dir.join("export.csv");
    fitness_csv::write_all(&exported, &back).unwrap();
    assert_eq!(fs::read(&exported).unwrap(), fs::read(&path).unwrap());
}

#[test]
fn reopen_for_resume_drops_later_rows_and_a_partial_line() {
    let dir = scratch("csv_resume");
    let uninterrupted = dir.join("uninterrupted.csv");
    let mut csv = FitnessCsv::create(&uninterrupted).unwrap();
    for g in 0..8 {
        csv.append(&row(g, g as f64)).unwrap();
    }

    // A run killed while writing row 6, resumed from the checkpoint after generation 4.
    let path = dir.join("fitness.csv");
    let mut csv = FitnessCsv::create(&path).unwrap();
    for g in 0..6 {
        csv.append(&row(g, g as f64)).unwrap();
    }
    drop(csv);
    let mut killed = fs::read(&path).unwrap();
    killed.extend_from_slice(b"6,280,6.0,0.3000");
    fs::write(&path, &killed).unwrap();
    let err = read_rows(&path).unwrap_err();
    assert!(
        matches!(err, FitnessCsvError::PartialLine { line: 8, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("incomplete last row"), "{err}");

    let reopened = FitnessCsv::reopen_for_resume(&path, 4).unwrap();
    assert_eq!(reopened.dropped_rows, 1);
    assert!(reopened.dropped_partial_line);
    let mut csv = reopened.csv;
    assert_eq!(csv.last_generation(), Some(4));
    let kept: Vec<u64> = read_rows(&path)
        .unwrap()
        .iter()
        .map(|r| r.generation)
        .collect();
    assert_eq!(kept, [0, 1, 2, 3, 4]);
    assert!(
        csv.append(&row(4, 4.0)).is_err(),
        "generation 4 appended twice"
    );
    for g in 5..8 {
        csv.append(&row(g, g as f64)).unwrap();
    }
    assert_eq!(fs::read(&path).unwrap(), fs::read(&uninterrupted).unwrap());
    assert!(
        !names_in(&dir).iter().any(|n| n.contains(".tmp-")),
        "{:?}",
        names_in(&dir)
    );

    // Nothing to drop: the file is left as it is.
    let reopened = FitnessCsv::reopen_for_resume(&path, 7).unwrap();
    assert_eq!(
        (reopened.dropped_rows, reopened.dropped_partial_line),
        (0, false)
    );
    assert_eq!(fs::read(&path).unwrap(), fs::read(&uninterrupted).unwrap());
    drop(reopened);

    // Resuming after a generation the file has no row for is refused: rows would be missing.
    let err = FitnessCsv::reopen_for_resume(&path, 9).unwrap_err();
    assert!(
        matches!(
            err,
            FitnessCsvError::MissingRows {
                last_row: Some(7),
                expected: 9,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        format!(
            "fitness csv {}: the rows end at generation 7, but the run resumes after \
             generation 9; rows are missing",
            path.display()
        )
    );
    assert_eq!(fs::read(&path).unwrap(), fs::read(&uninterrupted).unwrap());
}

#[test]
fn damaged_fitness_csv_errors_name_the_file_and_line() {
    let dir = scratch("csv_damaged");
    let path = dir.join("fitness.csv");

    fs::write(&path, "gen,best\n0,1.0\n").unwrap();
    let err = read_rows(&path).unwrap_err();
    assert!(matches!(err, FitnessCsvError::Header { .. }), "{err:?}");
    assert!(
        err.to_string().starts_with(&format!(
            "fitness csv {}: not a berry-evolve fitness csv",
            path.display()
        )),
        "{err}"
    );
    assert!(FitnessCsv::reopen_for_resume(&path, 0).is_err());

    let good = HAND_EXAMPLE.lines().nth(1).unwrap();
    fs::write(&path, format!("{HEADER}\n{good}\n0,40,1.5\n")).unwrap();
    let err = read_rows(&path).unwrap_err();
    assert!(
        matches!(err, FitnessCsvError::BadRow { line: 3, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("3 fields, expected 17"), "{err}");

    let bad = good.replace("0.25", "zero");
    fs::write(&path, format!("{HEADER}\n{bad}\n")).unwrap();
    let err = read_rows(&path).unwrap_err();
    assert!(
        err.to_string().starts_with(&format!(
            "fitness csv {}, line 2: column 5 (`median`)",
            path.display()
        )),
        "{err}"
    );
    // Damage in the rows to keep blocks a resume; damage after them is dropped with them.
    assert!(FitnessCsv::reopen_for_resume(&path, 0).is_err());
    fs::write(&path, format!("{HEADER}\n{good}\n1,garbage\n")).unwrap();
    let reopened = FitnessCsv::reopen_for_resume(&path, 0).unwrap();
    assert_eq!(reopened.dropped_rows, 1);
    assert_eq!(
        fs::read_to_string(&path).unwrap(),
        format!("{HEADER}\n{good}\n")
    );
    drop(reopened);

    fs::write(&path, format!("{HEADER}\n{good}\n{good}\n")).unwrap();
    let err = read_rows(&path).unwrap_err();
    assert!(
        matches!(err, FitnessCsvError::OutOfOrder { line: 3, .. }),
        "{err:?}"
    );

    let missing = dir.join("missing.csv");
    let err = read_rows(&missing).unwrap_err();
    assert!(
        err.to_string()
            .starts_with(&format!("fitness csv {}: cannot read:", missing.display())),
        "{err}"
    );
}

// ---------------------------------------------------------------------------------------
// Killed writers
// ---------------------------------------------------------------------------------------

const KILL_DIR: &str = "BERRY_RECORD_TEST_KILL_DIR";
const KILL_CONFIG_HASH: &str = "5ca1ab1e";
const KILL_GENERATIONS: u64 = 60;

/// A toy run with the shape of the real one: each generation's state depends on the previous
/// one (read back from a checkpoint after a restart), gets a fitness row, then a checkpoint.
/// It resumes from whatever a killed predecessor left in `dir`.
fn toy_run(dir: &Path) {
    use berry_evolve::record::checkpoint::CheckpointErrorKind as Kind;
    let csv_path = dir.join("fitness.csv");
    remove_stale_temp_files(dir).unwrap();
    let (mut state, mut csv, start) =
        match load_latest_good::<Vec<f64>>(dir, Some(KILL_CONFIG_HASH)) {
            Ok(loaded) => {
                // Atomic writes: a kill never leaves a damaged checkpoint.
                assert!(loaded.skipped.is_empty(), "{:?}", loaded.skipped);
                let g = loaded.checkpoint.generation;
                let reopened = FitnessCsv::reopen_for_resume(&csv_path, g).unwrap();
                (loaded.checkpoint.payload, reopened.csv, g + 1)
            }
            Err(e) if matches!(e.kind, Kind::NoCheckpoint) => {
                (Vec::new(), FitnessCsv::create(&csv_path).unwrap(), 0)
            }
            Err(e) => panic!("{e}"),
        };
    for g in start..KILL_GENERATIONS {
        let mut r = stream(
            Seed(3),
            Purpose::Variation,
            Generation(g),
            IndividualId(0),
            TrialIndex(0),
        );
        if g == 0 {
            state = (0..40_000).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
        } else {
            for p in state.iter_mut() {
                *p = *p * 0.75 + berry_evolve::seed::gaussian(&mut r) * 0.1;
            }
        }
        let best = state.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let worst = state.iter().copied().fold(f64::INFINITY, f64::min);
        let mean = state.iter().sum::<f64>() / state.len() as f64;
        let mut row = row(g, best);
        row.worst = worst;
        row.mean = mean;
        csv.append(&row).unwrap();
        // The row is durable before the checkpoint that covers it.
        csv.sync().unwrap();
        write_checkpoint(dir, KILL_CONFIG_HASH, g, &state, 2).unwrap();
    }
}

/// Runs inside the child processes of `killed_writers_...`; does nothing on its own.
#[test]
#[ignore = "helper process for killed_writers_leave_whole_files_and_resume_identically"]
fn kill_target() {
    if let Some(dir) = std::env::var_os(KILL_DIR) {
        toy_run(Path::new(&dir));
    }
}

#[test]
fn killed_writers_leave_whole_files_and_resume_identically() {
    let reference = scratch("kill_reference");
    toy_run(&reference);

    let dir = scratch("kill_resumed");
    // kill_target's name in this test binary: its module path without the crate's name.
    let target = format!(
        "{}::kill_target",
        module_path!().split_once("::").unwrap().1
    );
    let spawn = || {
        std::process::Command::new(std::env::current_exe().unwrap())
            .args([target.as_str(), "--exact", "--ignored", "--test-threads=1"])
            .env(KILL_DIR, &dir)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap()
    };
    let mut r = rng(31337);
    let mut killed_mid_write = 0;
    let mut reached = Vec::new();
    for round in 0..12 {
        let mut child = spawn();
        let delay = 2 + berry_evolve::seed::below(&mut r, 60);
        std::thread::sleep(std::time::Duration::from_millis(delay));
        child.kill().unwrap(); // SIGKILL on Unix
        child.wait().unwrap();

        // Whatever the moment of the kill: every checkpoint under its final name is whole, and
        // the fitness CSV holds complete rows at least up to the newest checkpoint.
        let checkpoints = list_checkpoints(&dir).unwrap();
        for (_, path) in &checkpoints {
            load::<Vec<f64>>(path, Some(KILL_CONFIG_HASH))
                .unwrap_or_else(|e| panic!("round {round}: {e}"));
        }
        if names_in(&dir).iter().any(|n| n.contains(".tmp-")) {
            killed_mid_write += 1;
        }
        reached.push(checkpoints.last().map(|(g, _)| *g));
        if let Some((g, _)) = checkpoints.last() {
            let csv = fs::read_to_string(dir.join("fitness.csv")).unwrap();
            let complete_rows = csv.matches('\n').count() - 1;
            assert!(complete_rows as u64 > *g, "round {round}: {csv}");
        }
    }
    // The test means something only if some kills landed before the end of the run.
    assert!(
        reached
            .iter()
            .any(|g| g.is_none_or(|g| g < KILL_GENERATIONS - 1)),
        "every kill came after the run had finished: {reached:?}"
    );
    // A last run to the end, undisturbed.
    assert!(spawn().wait().unwrap().success());
    assert!(
        !names_in(&dir).iter().any(|n| n.contains(".tmp-")),
        "{:?}",
        names_in(&dir)
    );
    assert_eq!(
        fs::read(dir.join("fitness.csv")).unwrap(),
        fs::read(reference.join("fitness.csv")).unwrap(),
        "fitness.csv differs from the uninterrupted run's"
    );
    let last = checkpoint::checkpoint_file_name(KILL_GENERATIONS - 1);
    assert_eq!(
        fs::read(dir.join(&last)).unwrap(),
        fs::read(reference.join(&last)).unwrap(),
        "{last} differs from the uninterrupted run's"
    );
    // Informational (with --nocapture): where the kills landed.
    eprintln!(
        "newest checkpoint after each kill: {reached:?}; kills that left a temporary file: \
         {killed_mid_write}"
    );
}
