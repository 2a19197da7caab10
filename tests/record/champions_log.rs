//! `champions.jsonl` (`record::champions`): lines appended in order, and on resume the lines
//! after the checkpoint and a half-written last line cut back, a damaged kept line refused
//! with its line number, a missing file started anew.

use berry_evolve::brain::genome::Genome;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::champions::{read_champions, ChampionsError, ChampionsLog};
use berry_evolve::record::genome_file::{GenomeFile, Origin};
use std::path::Path;

fn champion(generation: u64) -> GenomeFile {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml");
    let experiment = Experiment::load(&path).unwrap();
    let n = experiment.topology().parameter_count();
    let genome = Genome::new((0..n).map(|i| i as f64 * 0.1 + generation as f64).collect());
    GenomeFile::new(
        &experiment,
        &genome,
        Origin::evolved(
            &experiment,
            generation,
            Some(generation % 3),
            Some(0.1 * generation as f64),
            Some([1.0, 2.0, 3.0, 4.0]),
        ),
    )
}

fn generations(path: &Path) -> Vec<u64> {
    read_champions(path)
        .unwrap()
        .iter()
        .map(|c| c.origin.generation.unwrap())
        .collect()
}

#[test]
fn resume_cuts_later_lines_and_a_half_line_and_continues_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("champions.jsonl");
    let mut log = ChampionsLog::create(&path).unwrap();
    for g in 0..4 {
        log.append(&champion(g)).unwrap();
    }
    drop(log);
    let whole = std::fs::read(&path).unwrap();
    assert_eq!(generations(&path), [0, 1, 2, 3]);
    // Every line reads back as the genome file written.
    assert_eq!(read_champions(&path).unwrap()[2], champion(2));

    let mut killed = whole.clone();
    killed.extend_from_slice(b"{\"format\":1,\"brain\"");
    std::fs::write(&path, &killed).unwrap();
    assert!(matches!(
        read_champions(&path),
        Err(ChampionsError::PartialLine { line: 5, .. })
    ));
    let reopened = ChampionsLog::reopen_for_resume(&path, 1).unwrap();
    assert_eq!(reopened.dropped_lines, 2);
    assert!(reopened.dropped_partial_line && !reopened.created);
    assert_eq!(generations(&path), [0, 1]);
    let mut log = reopened.log;
    let err = log.append(&champion(1)).unwrap_err();
    assert!(
        err.to_string()
            .contains("generation 1 follows generation 1"),
        "{err}"
    );
    log.append(&champion(2)).unwrap();
    log.append(&champion(3)).unwrap();
    log.sync().unwrap();
    assert!(
        std::fs::read(&path).unwrap() == whole,
        "resumed bytes differ"
    );
}

#[test]
fn a_damaged_kept_line_is_refused_and_a_missing_file_started_anew() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("champions.jsonl");
    let mut log = ChampionsLog::create(&path).unwrap();
    for g in 0..3 {
        log.append(&champion(g)).unwrap();
    }
    drop(log);
    let text = String::from_utf8(std::fs::read(&path).unwrap()).unwrap();
    let damaged = text.replacen("\"parameters\":[", "\"parameters\":[\"x\",", 2);
    std::fs::write(&path, &damaged).unwrap();
    let err = ChampionsLog::reopen_for_resume(&path, 2).unwrap_err();
    let message = err.to_string();
    assert!(
        message.contains("champions.jsonl, line 1") && message.contains("move the file out"),
        "{message}"
    );
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        damaged,
        "a refused file is kept as it was"
    );
    std::fs::remove_file(&path).unwrap();
    let reopened = ChampionsLog::reopen_for_resume(&path, 2).unwrap();
    assert!(reopened.created);
    let mut log = reopened.log;
    log.append(&champion(3)).unwrap();
    assert_eq!(generations(&path), [3]);
}

#[test]
fn a_champion_json_cannot_hold_is_refused_before_writing() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("champions.jsonl");
    let mut log = ChampionsLog::create(&path).unwrap();
    let mut bad = champion(0);
    bad.parameters[3] = f64::INFINITY;
    let err = log.append(&bad).unwrap_err().to_string();
    assert!(err.contains("parameters[3] is not finite"), "{err}");
    let mut bad = champion(0);
    bad.origin.generation = None;
    assert!(log.append(&bad).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"");
}
