//! `[evolution] algorithm = "pgpe"`: the update on a hand-computed case, the pinned first
//! samples of a seed, the table's validation, and the run guarantees (any thread count, same
//! bytes; resumed or not, same bytes; GA checkpoints without a PGPE state).

use crate::cli_common::{fixture, read, run_ok};

use berry_evolve::evo::pgpe::{self, PgpeState};
use berry_evolve::experiment::evolution::{Algorithm, PgpeSpec};
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{
    gaussian, stream, Generation, IndividualId, Normals, Purpose, Seed, TrialIndex,
};
use std::path::{Path, PathBuf};

fn spec() -> PgpeSpec {
    PgpeSpec {
        center_learning_rate: 0.1,
        max_speed: 0.15,
        momentum: 0.9,
        stdev_init: 0.1,
        stdev_learning_rate: 0.1,
        stdev_max_change: 0.2,
    }
}

/// f(x) = −(x0 − 1)² − (x1 − 0.5)²: maximal at (1, 0.5).
fn quadratic(x: &[f64]) -> f64 {
    -(x[0] - 1.0) * (x[0] - 1.0) - (x[1] - 0.5) * (x[1] - 0.5)
}

fn close(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-15, "{what}: {a:?} vs {b:?}");
    }
}

/// Two parameters, two pairs, worked by hand:
/// c = (0, 0), σ = (0.1, 0.1), ε0 = (0.1, 0), ε1 = (0, 0.2). Samples (0.1, 0), (−0.1, 0),
/// (0, 0.2), (0, −0.2) score −1.06, −1.46, −1.09, −1.49: ranks 3, 1, 2, 0, centred
/// u = (1/2, −1/6, 1/6, −1/2). Pairs: d = (2/3, 2/3), a = (1/6, −1/6), baseline 0.
/// g_c = ½ (ε0 · 2/3 · ½ + ε1 · 2/3 · ½) = (1/60, 1/30), direction (1, 2)/√5, so
/// v = 0.1 (1, 2)/√5 (speed 0.1 < 0.15) and c' = v.
/// g_σ = ½ ((1/6)(ε0² − σ²)/σ + (−1/6)(ε1² − σ²)/σ) = ½ ((0, −1/60) + (1/60, −1/20))
///     = (1/120, −1/30), so σ' = σ + 0.1 g_σ = (0.1 + 1/1200, 0.1 − 1/300), within ±20 %.
#[test]
fn pgpe_update_matches_the_hand_computed_step() {
    let state = PgpeState::initial(&spec(), 2);
    let noises = vec![vec![0.1, 0.0], vec![0.0, 0.2]];
    let genomes = pgpe::individuals(&state, &noises);
    let samples: Vec<Vec<f64>> = genomes.iter().map(|g| g.parameters.clone()).collect();
    assert_eq!(
        samples,
        [
            vec![0.1, 0.0],
            vec![-0.1, 0.0],
            vec![0.0, 0.2],
            vec![0.0, -0.2],
            vec![0.0, 0.0]
        ],
        "the pairs c ± ε, then the centre"
    );
    let fitness: Vec<f64> = samples[..4].iter().map(|x| quadratic(x)).collect();
    close(
        &pgpe::centred_ranks(&fitness),
        &[0.5, -1.0 / 6.0, 1.0 / 6.0, -0.5],
        "centred ranks",
    );
    let next = pgpe::update(&spec(), &state, &noises, &fitness);
    let s5 = 5f64.sqrt();
    close(&next.velocity, &[0.1 / s5, 0.2 / s5], "velocity");
    close(&next.centre, &[0.1 / s5, 0.2 / s5], "centre");
    close(
        &next.stdev,
        &[0.1 + 1.0 / 1200.0, 0.1 - 1.0 / 300.0],
        "standard deviations",
    );
    // The centre moved towards the optimum (1, 0.5).
    assert!(quadratic(&next.centre) > quadratic(&state.centre));

    // The same gradient again: v = 0.9 · 0.1 ĝ + 0.1 ĝ = 0.19 ĝ is faster than 0.15 and is
    // clipped to 0.15 ĝ, so c'' = 0.25 ĝ.
    let again = pgpe::update(&spec(), &next, &noises, &fitness);
    close(&again.velocity, &[0.15 / s5, 0.3 / s5], "clipped velocity");
    close(
        &again.centre,
        &[0.25 / s5, 0.5 / s5],
        "centre after the clip",
    );
}

#[test]
fn pgpe_standard_deviation_change_is_bounded_and_ties_move_nothing() {
    // A huge stdev learning rate: the change is clipped to ±20 % of σ.
    let wild = PgpeSpec {
        stdev_learning_rate: 1.0e6,
        ..spec()
    };
    let state = PgpeState::initial(&wild, 2);
    let noises = vec![vec![0.1, 0.0], vec![0.0, 0.2]];
    let fitness: Vec<f64> = pgpe::individuals(&state, &noises)[..4]
        .iter()
        .map(|g| quadratic(&g.parameters))
        .collect();
    let next = pgpe::update(&wild, &state, &noises, &fitness);
    close(&next.stdev, &[0.12, 0.08], "clipped standard deviations");
    // Every sample equal: no direction, no change of σ; the velocity only decays.
    let moving = PgpeState {
        velocity: vec![0.1, -0.1],
        ..PgpeState::initial(&spec(), 2)
    };
    let flat = pgpe::update(&spec(), &moving, &noises, &[3.0; 4]);
    close(&flat.velocity, &[0.09, -0.09], "decayed velocity");
    close(&flat.centre, &[0.09, -0.09], "centre");
    assert_eq!(flat.stdev, moving.stdev);
}

/// The first generation of seed 5 with 3 parameters and population 4: the noises are
/// σ · gaussian() from the Search stream of generation 0, pair by pair, parameter by
/// parameter; pinned so that a change of the draw order fails.
#[test]
fn pgpe_first_samples_are_pinned() {
    let pgpe_spec = PgpeSpec {
        stdev_init: 0.5,
        ..PgpeSpec::default()
    };
    let state = PgpeState::initial(&pgpe_spec, 3);
    let genomes = pgpe::sample(Normals::BoxMuller, Seed(5), Generation(0), &state, 4);
    assert_eq!(genomes.len(), 5, "4 samples and the centre");
    let mut rng = stream(
        Seed(5),
        Purpose::Search,
        Generation(0),
        IndividualId(0),
        TrialIndex(0),
    );
    let z: Vec<f64> = (0..6).map(|_| gaussian(&mut rng)).collect();
    for k in 0..2 {
        for j in 0..3 {
            assert_eq!(genomes[2 * k].parameters[j], 0.5 * z[3 * k + j]);
            assert_eq!(genomes[2 * k + 1].parameters[j], -(0.5 * z[3 * k + j]));
        }
    }
    assert_eq!(genomes[4].parameters, [0.0; 3]);
    let bits: Vec<u64> = genomes[0]
        .parameters
        .iter()
        .chain(&genomes[2].parameters)
        .map(|x| x.to_bits())
        .collect();
    assert_eq!(bits, PINNED_SAMPLES, "samples {genomes:?}");
    // The next generation's centre, from a quadratic fitness, is pinned too.
    let fitness: Vec<f64> = genomes[..4]
        .iter()
        .map(|g| {
            -g.parameters
                .iter()
                .map(|x| (x - 1.0) * (x - 1.0))
                .sum::<f64>()
        })
        .collect();
    let next = pgpe::step(
        Normals::BoxMuller,
        Seed(5),
        &pgpe_spec,
        &state,
        Generation(0),
        &fitness,
    );
    // By hand: the scores rank pair members (s0, s1, s2, s3) as 2, 0, 3, 1, so
    // u = (1/6, −1/2, 1/2, −1/6), d = (2/3, 2/3), g_c = (ε0 + ε1)/6 and the first ClipUp step
    // is α (ε0 + ε1)/‖ε0 + ε1‖ with α = 0.15.
    let sum: Vec<f64> = (0..3)
        .map(|j| genomes[0].parameters[j] + genomes[2].parameters[j])
        .collect();
    let length = sum.iter().map(|x| x * x).sum::<f64>().sqrt();
    let expected: Vec<f64> = sum.iter().map(|x| 0.15 * x / length).collect();
    close(&next.centre, &expected, "first centre");
    let centre: Vec<u64> = next.centre.iter().map(|x| x.to_bits()).collect();
    assert_eq!(centre, PINNED_CENTRE, "centre {:?}", next.centre);
    let speed = next.velocity.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((speed - 0.15).abs() < 1e-15, "first step has length α");
}

// 0.05185902423452819, -0.537267136610229, 0.9222603190843298 (pair 0);
// 0.5609383221658242, -0.26751324785039626, 0.09746025728276399 (pair 1).
const PINNED_SAMPLES: [u64; 6] = [
    4587634494066783830,
    13826386528552524705,
    4606482202004009981,
    4603227702782644090,
    13821862747026024591,
    4591687172317278345,
];
// 0.0639964957407762, -0.08404593255654642, 0.1064928624537873.
const PINNED_CENTRE: [u64; 3] = [
    4589275854173103764,
    13814092605206639429,
    4592338040113796831,
];

#[test]
fn pgpe_table_is_validated() {
    let base = std::fs::read_to_string(fixture("tiny-pgpe.toml")).unwrap();
    let parse = |text: &str| Experiment::from_toml(text, Path::new("x.toml"));
    let e = parse(&base).expect("the fixture is valid");
    assert_eq!(e.evolution.algorithm, Algorithm::Pgpe);
    assert_eq!(e.evolution.evaluated_per_generation(), 13);
    let pgpe = e.evolution.pgpe_settings().unwrap();
    assert_eq!(pgpe.stdev_init, 0.5);
    assert_eq!(pgpe.center_learning_rate, 0.15, "default");
    // Written back and read again: the same experiment, the same hash.
    let again = parse(&e.to_toml()).unwrap();
    assert_eq!(again, e);
    assert_eq!(again.config_hash(), e.config_hash());

    let bad = |from: &str, to: &str, expected: &str| {
        assert!(base.contains(from), "{from}");
        let err = parse(&base.replacen(from, to, 1)).unwrap_err().to_string();
        assert!(err.contains(expected), "{to}: {err}");
    };
    bad("population = 12", "population = 13", "must be even");
    bad(
        "algorithm = \"pgpe\"",
        "algorithm = \"pgpe\"\nelitism = 3",
        "evolution.elitism",
    );
    bad(
        "algorithm = \"pgpe\"",
        "algorithm = \"ga\"",
        "evolution.pgpe",
    );
    bad("stdev_init = 0.5", "stdev_init = 0.0", "greater than 0");
    bad(
        "stdev_init = 0.5",
        "stdev_init = 0.5\nmomentum = 1.0",
        "below 1",
    );
    bad(
        "stdev_init = 0.5",
        "stdev_init = 0.5\nlearning_rate = 1.0",
        "unknown key `learning_rate`",
    );
    bad(
        "algorithm = \"pgpe\"",
        "algorithm = \"cma\"",
        "\"cma\" is not one of \"ga\", \"pgpe\"",
    );
    // The GA's tiny experiment writes no `algorithm` key (its bytes and hash are 0.3.5's).
    let ga = Experiment::load(&fixture("tiny.toml")).unwrap();
    assert!(!ga.to_toml().contains("algorithm"));
    assert!(!ga.to_toml().contains("pgpe"));
}

fn checkpoints(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let last = checkpoints(dir).pop().expect("a checkpoint");
    vec![
        ("fitness.csv".into(), read(&dir.join("fitness.csv"))),
        ("best.json".into(), read(&dir.join("best.json"))),
        ("champions.jsonl".into(), read(&dir.join("champions.jsonl"))),
        ("experiment.toml".into(), read(&dir.join("experiment.toml"))),
        (
            format!(
                "checkpoints/{}",
                last.file_name().unwrap().to_string_lossy()
            ),
            read(&last),
        ),
    ]
}

fn assert_same_outputs(a: &Path, b: &Path, what: &str) {
    for ((name_a, bytes_a), (name_b, bytes_b)) in outputs(a).into_iter().zip(outputs(b)) {
        assert_eq!(name_a, name_b, "{what}: different final checkpoint");
        assert!(bytes_a == bytes_b, "{what}: {name_a} differs");
    }
}

fn run_tiny_pgpe(dir: &Path, extra: &[&str]) {
    let exp = fixture("tiny-pgpe.toml");
    let mut args = vec![
        "run",
        exp.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    run_ok(&args);
}

#[test]
fn pgpe_run_gives_same_bytes_with_one_or_two_threads() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    run_tiny_pgpe(&a, &["--jobs", "1"]);
    run_tiny_pgpe(&b, &["--jobs", "2"]);
    assert_same_outputs(&a, &b, "pgpe --jobs 1 vs --jobs 2");
    let csv = String::from_utf8(read(&a.join("fitness.csv"))).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 8);
    // 12 samples and the centre are evaluated per generation.
    assert!(rows[0].starts_with("0,13,"), "{}", rows[0]);
    assert!(rows[7].starts_with("7,104,"), "{}", rows[7]);
    // The checkpoint carries the distribution; best.json is a centre (individual 12).
    let cp = String::from_utf8(read(checkpoints(&a).last().unwrap())).unwrap();
    assert!(
        cp.contains("\"search\":{\"pgpe\":{\"centre\":["),
        "no pgpe state"
    );
    let best = String::from_utf8(read(&a.join("best.json"))).unwrap();
    assert!(best.contains("\"individual\": 12"), "{best}");
}

#[test]
fn pgpe_resumed_run_equals_uninterrupted_run() {
    let tmp = tempfile::tempdir().unwrap();
    let full = tmp.path().join("full");
    run_tiny_pgpe(&full, &["--jobs", "2"]);
    // Stopped after 3 generations, then extended to 8.
    let short = tmp.path().join("short");
    run_tiny_pgpe(&short, &["--generations", "3"]);
    run_ok(&[
        "resume",
        short.to_str().unwrap(),
        "--generations",
        "8",
        "--quiet",
        "--jobs",
        "1",
    ]);
    assert_same_outputs(&full, &short, "pgpe extended run");
    // Killed after the checkpoint of generation 3 (index 3: checkpoint_every = 2 writes
    // generations 1, 3, 5, 7): later checkpoints gone, a half-written row.
    let killed = tmp.path().join("killed");
    run_tiny_pgpe(&killed, &["--jobs", "1"]);
    for late in checkpoints(&killed)
        .iter()
        .filter(|p| !p.ends_with("gen-000003.json"))
    {
        std::fs::remove_file(late).unwrap();
    }
    let mut csv = read(&killed.join("fitness.csv"));
    csv.extend_from_slice(b"8,117,0.5,0.");
    std::fs::write(killed.join("fitness.csv"), csv).unwrap();
    let mut champions = read(&killed.join("champions.jsonl"));
    champions.extend_from_slice(b"{\"format\":1,");
    std::fs::write(killed.join("champions.jsonl"), champions).unwrap();
    run_ok(&["resume", killed.to_str().unwrap(), "--quiet"]);
    assert_same_outputs(&full, &killed, "pgpe resume after a kill");
}

#[test]
fn ga_checkpoint_holds_no_search_state() {
    // GA checkpoints keep 0.3.5's layout: no `search` key at all.
    let tmp = tempfile::tempdir().unwrap();
    let ga = tmp.path().join("ga");
    run_ok(&[
        "run",
        fixture("tiny.toml").to_str().unwrap(),
        "--out",
        ga.to_str().unwrap(),
        "--quiet",
        "--generations",
        "2",
    ]);
    let cp = String::from_utf8(read(checkpoints(&ga).last().unwrap())).unwrap();
    assert!(
        !cp.contains("\"search\""),
        "a GA checkpoint with a search state"
    );
}

/// PGPE's lineage says what a parent is there: a sample has none in the previous generation
/// (it is its own generation's centre plus noise); the centre's parent is the previous
/// centre (individual 12), which the update moved; generation 0's centre has none. A
/// generation's champions.jsonl line is its best scorer, a sample or the centre.
#[test]
fn pgpe_lineage_names_the_previous_centre_as_the_centres_parent() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    run_tiny_pgpe(&dir, &["--generations", "2"]);
    let lineage = |checkpoint: &str| -> Vec<serde_json::Value> {
        let text = read(&dir.join("checkpoints").join(checkpoint));
        let v: serde_json::Value = serde_json::from_slice(&text).unwrap();
        v["payload"]["last"]["individuals"]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| i["lineage"].clone())
            .collect()
    };
    let l = lineage("gen-000001.json");
    assert_eq!(l.len(), 13);
    for sample in &l[..12] {
        assert_eq!(sample, &serde_json::json!({"birth": "pgpe_sample"}));
    }
    assert_eq!(
        l[12],
        serde_json::json!({"birth": "pgpe_centre", "parents": [12]})
    );
    let first = tmp.path().join("first");
    run_tiny_pgpe(&first, &["--generations", "1"]);
    let text = read(&first.join("checkpoints/gen-000000.json"));
    let v: serde_json::Value = serde_json::from_slice(&text).unwrap();
    assert_eq!(
        v["payload"]["last"]["individuals"][12]["lineage"],
        serde_json::json!({"birth": "pgpe_centre"})
    );
    let csv = String::from_utf8(read(&dir.join("fitness.csv"))).unwrap();
    let champions = String::from_utf8(read(&dir.join("champions.jsonl"))).unwrap();
    for (row, line) in csv.lines().skip(1).zip(champions.lines()) {
        let best: f64 = row.split(',').nth(2).unwrap().parse().unwrap();
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["origin"]["fitness"].as_f64(), Some(best), "{line}");
    }
    assert_eq!(champions.lines().count(), 2);
}
