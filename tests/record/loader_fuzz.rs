//! Random and mutated inputs to every loader a user can feed a file to: the experiment TOML,
//! a checkpoint and a genome file. Each must answer Ok or an error with a message; never
//! panic. Thousands of cases from a fixed seed (the crate's own ChaCha8 streams, so a failure
//! reproduces exactly; `BERRY_FUZZ_CASES` and `BERRY_FUZZ_SEED` change the amount and cases).

use berry_evolve::experiment::Experiment;
use berry_evolve::record::checkpoint;
use berry_evolve::record::genome_file::{GenomeFile, GenomeFileError};
use berry_evolve::run::{self, CheckpointPayload, RunOptions, Silent};
use berry_evolve::seed::{below, chance, Rng};
use rand::{RngCore, SeedableRng};
use serde_json::Value;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn cases(default: u64) -> u64 {
    env_number("BERRY_FUZZ_CASES", default)
}

fn rng(salt: u64) -> Rng {
    Rng::seed_from_u64(env_number("BERRY_FUZZ_SEED", 1) ^ salt)
}

fn tiny() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml"))
        .unwrap()
}

/// Runs `f` on `input`; a panic fails the test showing the input, an error must have a message.
fn never_panics<E: std::fmt::Display>(
    what: &str,
    input: &[u8],
    f: impl FnOnce() -> Result<(), E>,
) -> bool {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => true,
        Ok(Err(e)) => {
            assert!(
                !e.to_string().trim().is_empty(),
                "{what}: empty error message for {:?}",
                String::from_utf8_lossy(input)
            );
            false
        }
        Err(_) => panic!("{what}: panicked on {:?}", String::from_utf8_lossy(input)),
    }
}

fn random_bytes(rng: &mut Rng, max: u64) -> Vec<u8> {
    let n = below(rng, max + 1) as usize;
    let mut v = vec![0u8; n];
    rng.fill_bytes(&mut v);
    v
}

/// A TOML value that is well-formed but likely wrong somewhere.
fn odd_value(rng: &mut Rng) -> String {
    const VALUES: &[&str] = &[
        "nan",
        "+nan",
        "-nan",
        "inf",
        "-inf",
        "0",
        "-1",
        "-0.0",
        "1e308",
        "-1e308",
        "5e-324",
        "18446744073709551615",
        "9223372036854775807",
        "-9223372036854775808",
        "4294967296",
        "1000000000000",
        "0.5",
        "2",
        "\"x\"",
        "\"\"",
        "true",
        "[]",
        "[1.0]",
        "[nan, inf]",
        "[1e308, 1e308]",
        "{}",
        "[[1.0]]",
        "\"mlp\"",
        "\"ctrnn\"",
        "\"relu\"",
        "100000",
        "[100000]",
        "[0]",
        "[4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4]",
    ];
    if chance(rng, 0.3) {
        format!("{}", (rng.next_u64() as i64) >> below(rng, 64))
    } else {
        VALUES[below(rng, VALUES.len() as u64) as usize].to_string()
    }
}

/// One to four line-level mutations of `text`.
fn mutate_toml(rng: &mut Rng, text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + below(rng, 4) {
        let n = lines.len() as u64;
        if n == 0 {
            break;
        }
        let i = below(rng, n) as usize;
        let j = below(rng, n) as usize;
        match below(rng, 8) {
            0 => {
                lines.remove(i);
            }
            1 => {
                let line = lines[i].clone();
                lines.insert(j, line);
            }
            2 | 3 => {
                // A new value for a key.
                if let Some((key, _)) = lines[i].split_once('=') {
                    lines[i] = format!("{}= {}", key, odd_value(rng));
                }
            }
            4 => {
                // Two keys swap values.
                if let (Some((ka, va)), Some((kb, vb))) =
                    (lines[i].split_once('='), lines[j].split_once('='))
                {
                    let (a, b) = (format!("{ka}={vb}"), format!("{kb}={va}"));
                    lines[i] = a;
                    lines[j] = b;
                }
            }
            5 => {
                let key = format!("key{}", below(rng, 1000));
                lines.insert(i, format!("{key} = {}", odd_value(rng)));
            }
            6 => {
                // A table header moves or repeats.
                let headers: Vec<String> = lines
                    .iter()
                    .filter(|l| l.starts_with('['))
                    .cloned()
                    .collect();
                if !headers.is_empty() {
                    let h = headers[below(rng, headers.len() as u64) as usize].clone();
                    lines.insert(i, h);
                }
            }
            _ => {
                let line = &mut lines[i];
                let cut = below(rng, line.len() as u64 + 1) as usize;
                if line.is_char_boundary(cut) {
                    line.truncate(cut);
                }
            }
        }
    }
    lines.join("\n")
}

#[test]
fn experiment_loader_never_panics_on_random_or_mutated_toml() {
    let mut rng = rng(0x70);
    let origin = Path::new("fuzz.toml");
    let base = tiny();
    let mut accepted = 0;
    for _ in 0..cases(1000) {
        let bytes = random_bytes(&mut rng, 200);
        let text = String::from_utf8_lossy(&bytes).to_string();
        never_panics("random TOML", text.as_bytes(), || {
            Experiment::from_toml(&text, origin).map(|_| ())
        });
    }
    for _ in 0..cases(4000) {
        let text = mutate_toml(&mut rng, &base);
        let ok = never_panics("mutated TOML", text.as_bytes(), || {
            Experiment::from_toml(&text, origin).map(|e| {
                // What loads must also describe itself and hash without panicking.
                let _ = (e.to_toml(), e.config_hash(), e.topology().parameter_count());
            })
        });
        accepted += ok as u32;
    }
    // Some mutations are harmless (a deleted default, a duplicated comment); most are not.
    assert!(accepted > 0, "no mutated file loaded: mutations too coarse");
}

/// A real checkpoint of tiny.toml after 2 generations.
fn real_checkpoint() -> Vec<u8> {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let experiment = Experiment::from_toml(&tiny(), Path::new("tiny.toml"))
        .unwrap()
        .with_overrides()
        .generations(2)
        .build()
        .unwrap();
    let summary = run::start(
        experiment,
        &dir,
        false,
        RunOptions {
            jobs: 1,
            stop: None,
            evaluator: None,
        },
        &mut Silent,
    )
    .unwrap();
    std::fs::read(summary.checkpoint.unwrap()).unwrap()
}

fn mutate_bytes(rng: &mut Rng, bytes: &[u8]) -> Vec<u8> {
    let mut v = bytes.to_vec();
    for _ in 0..1 + below(rng, 3) {
        let i = below(rng, v.len() as u64 + 1) as usize;
        match below(rng, 4) {
            0 => v.truncate(i),
            1 if i < v.len() => v[i] = rng.next_u32() as u8,
            2 if i < v.len() && v[i].is_ascii_digit() => v[i] = b'0' + below(rng, 10) as u8,
            _ => v.insert(i, b"{}[],:\"0e-9"[below(rng, 11) as usize]),
        }
    }
    v
}

/// A JSON value that is well-formed but likely wrong where it is put.
fn odd_json(rng: &mut Rng) -> Value {
    match below(rng, 9) {
        0 => Value::Null,
        1 => Value::from(-1),
        2 => Value::from(u64::MAX),
        3 => Value::from(1e308),
        4 => Value::from(-5e-324),
        5 => Value::from("x"),
        6 => Value::Array(vec![]),
        7 => serde_json::json!({}),
        _ => Value::from(rng.next_u64() >> below(rng, 64)),
    }
}

/// Changes, removes or replaces one random leaf or member of `value`.
fn mutate_json(rng: &mut Rng, value: &mut Value) {
    match value {
        Value::Object(map) if !map.is_empty() => {
            let keys: Vec<String> = map.keys().cloned().collect();
            let key = &keys[below(rng, keys.len() as u64) as usize];
            if chance(rng, 0.15) {
                map.remove(key);
            } else if chance(rng, 0.1) {
                map.insert(key.clone(), odd_json(rng));
            } else {
                mutate_json(rng, map.get_mut(key).unwrap());
            }
        }
        Value::Array(items) if !items.is_empty() => {
            let i = below(rng, items.len() as u64) as usize;
            if chance(rng, 0.1) {
                items.remove(i);
            } else if chance(rng, 0.1) {
                let copy = items[i].clone();
                items.push(copy);
            } else {
                mutate_json(rng, &mut items[i]);
            }
        }
        leaf => *leaf = odd_json(rng),
    }
}

#[test]
fn checkpoint_decoder_never_panics_on_random_or_mutated_bytes() {
    let mut rng = rng(0xc4);
    let good = real_checkpoint();
    let decode = |bytes: &[u8]| checkpoint::decode::<CheckpointPayload>(bytes).map(|_| ());
    assert!(decode(&good).is_ok());
    for _ in 0..cases(1000) {
        let bytes = random_bytes(&mut rng, 300);
        never_panics("random checkpoint", &bytes, || decode(&bytes));
    }
    for _ in 0..cases(1000) {
        let bytes = mutate_bytes(&mut rng, &good);
        never_panics("mutated checkpoint", &bytes, || decode(&bytes));
    }
    // Structural changes re-signed with a correct checksum, so they reach the payload checks.
    let envelope: Value = serde_json::from_slice(&good).unwrap();
    let hash = envelope["config_hash"].as_str().unwrap().to_string();
    let generation = envelope["generation"].as_u64().unwrap();
    for _ in 0..cases(1000) {
        let mut payload = envelope["payload"].clone();
        for _ in 0..1 + below(&mut rng, 2) {
            mutate_json(&mut rng, &mut payload);
        }
        let Ok(bytes) = checkpoint::encode(&hash, generation, &payload) else {
            continue;
        };
        never_panics("re-signed checkpoint", &bytes, || decode(&bytes));
    }
}

#[test]
fn genome_loader_never_panics_on_random_or_mutated_json() {
    let mut rng = rng(0x9e);
    let experiment = Experiment::from_toml(&tiny(), Path::new("tiny.toml")).unwrap();
    let topology = experiment.topology();
    let genome = berry_evolve::evo::search::ga::first_population(&experiment, &topology).remove(0);
    let good = GenomeFile::new(&experiment, &genome, Default::default()).to_json();
    let origin = Path::new("fuzz.json");
    let load = |bytes: &[u8]| {
        let file = GenomeFile::from_slice(bytes, origin)?;
        // A genome that loads must fit the experiment and become a brain, or say why not
        // (as `replay` does).
        let topology = file.topology_for(&experiment, origin)?;
        file.genome()
            .decode(&topology)
            .map(|_| ())
            .map_err(|e| GenomeFileError::Mismatch {
                path: origin.to_path_buf(),
                reason: e.to_string(),
            })
    };
    assert!(load(&good).is_ok());
    for _ in 0..cases(1000) {
        let bytes = random_bytes(&mut rng, 300);
        never_panics("random genome", &bytes, || load(&bytes));
    }
    for _ in 0..cases(1000) {
        let bytes = mutate_bytes(&mut rng, &good);
        never_panics("mutated genome", &bytes, || load(&bytes));
    }
    let value: Value = serde_json::from_slice(&good).unwrap();
    for _ in 0..cases(2000) {
        let mut v = value.clone();
        for _ in 0..1 + below(&mut rng, 2) {
            mutate_json(&mut rng, &mut v);
        }
        let bytes = serde_json::to_vec(&v).unwrap();
        never_panics("mutated genome JSON", &bytes, || load(&bytes));
    }
}

/// A finished 2-generation run of tiny.toml: (its final checkpoint, its fitness.csv).
fn real_run(tmp: &Path) -> (Vec<u8>, Vec<u8>) {
    let base = tmp.join("base");
    let experiment = Experiment::from_toml(&tiny(), Path::new("tiny.toml"))
        .unwrap()
        .with_overrides()
        .generations(2)
        .build()
        .unwrap();
    let summary = run::start(
        experiment,
        &base,
        false,
        RunOptions {
            jobs: 1,
            stop: None,
            evaluator: None,
        },
        &mut Silent,
    )
    .unwrap();
    let checkpoint = std::fs::read(summary.checkpoint.unwrap()).unwrap();
    (checkpoint, std::fs::read(base.join("fitness.csv")).unwrap())
}

/// Checkpoints edited and re-signed with a correct checksum reach `resume`, which must refuse
/// what does not fit (wrong genome sizes, an empty generation, ...) instead of panicking in
/// variation or selection.
#[test]
fn resume_never_panics_on_re_signed_edited_checkpoints() {
    let mut rng = rng(0x5e);
    let tmp = tempfile::tempdir().unwrap();
    let (good, csv) = real_run(tmp.path());
    let envelope: Value = serde_json::from_slice(&good).unwrap();
    let hash = envelope["config_hash"].as_str().unwrap().to_string();
    let generation = envelope["generation"].as_u64().unwrap();
    let (mut resumed, mut refused) = (0, 0);
    for case in 0..cases(300) {
        let mut payload = envelope["payload"].clone();
        for _ in 0..1 + below(&mut rng, 3) {
            mutate_json(&mut rng, &mut payload);
        }
        let Ok(bytes) = checkpoint::encode(&hash, generation, &payload) else {
            continue;
        };
        let dir = tmp.path().join(format!("case-{case}"));
        let checkpoints = dir.join(run::CHECKPOINT_DIR);
        std::fs::create_dir_all(&checkpoints).unwrap();
        std::fs::write(
            checkpoints.join(checkpoint::checkpoint_file_name(generation)),
            &bytes,
        )
        .unwrap();
        std::fs::write(dir.join(run::FITNESS_FILE), &csv).unwrap();
        let ok = never_panics("resume of a re-signed checkpoint", &bytes, || {
            let options = RunOptions {
                jobs: 1,
                stop: None,
                evaluator: None,
            };
            run::resume(&dir, Some(3), false, options, &mut Silent).map(|_| ())
        });
        if ok {
            resumed += 1;
        } else {
            refused += 1;
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(
        resumed > 0 && refused > 0,
        "{resumed} resumed, {refused} refused"
    );
}

/// A change to a checkpoint payload.
type Edit = fn(&mut Value);

/// The two shapes the fuzzer found panicking before `resume` checked the payload.
#[test]
fn resume_refuses_a_checkpoint_whose_genomes_do_not_fit_its_experiment() {
    let tmp = tempfile::tempdir().unwrap();
    let (good, csv) = real_run(tmp.path());
    let envelope: Value = serde_json::from_slice(&good).unwrap();
    let hash = envelope["config_hash"].as_str().unwrap().to_string();
    let generation = envelope["generation"].as_u64().unwrap();
    let edits: [(&str, Edit); 2] = [
        ("individual 3 has 109 parameters", |p| {
            p["last"]["individuals"][3]["genome"]["parameters"]
                .as_array_mut()
                .unwrap()
                .pop();
        }),
        ("holds 0 individuals", |p| {
            p["last"]["individuals"].as_array_mut().unwrap().clear();
        }),
    ];
    for (needle, edit) in edits {
        let mut payload = envelope["payload"].clone();
        edit(&mut payload);
        let dir = tmp.path().join("edited");
        let checkpoints = dir.join(run::CHECKPOINT_DIR);
        std::fs::create_dir_all(&checkpoints).unwrap();
        let path = checkpoints.join(checkpoint::checkpoint_file_name(generation));
        std::fs::write(
            &path,
            checkpoint::encode(&hash, generation, &payload).unwrap(),
        )
        .unwrap();
        std::fs::write(dir.join(run::FITNESS_FILE), &csv).unwrap();
        let options = RunOptions {
            jobs: 1,
            stop: None,
            evaluator: None,
        };
        let message = run::resume(&dir, Some(3), false, options, &mut Silent)
            .expect_err("edited checkpoint accepted")
            .to_string();
        assert!(message.contains(needle), "{message}");
        assert!(message.contains(path.to_str().unwrap()), "{message}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
