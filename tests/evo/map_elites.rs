//! `[evolution] algorithm = "map-elites"`: grid archive insertion and replacement on hand-made
//! cases (empty cell, better, worse, equal), iso-line variation on a hand-computed case, the
//! refusals of `[evolution.map_elites]` naming their key, the run guarantees (any thread
//! count, same bytes; resumed or not, same bytes, archive included), fitness.csv's QD columns
//! (only for map-elites), and `extract --cell` giving an elite that replays to its fitness.

use crate::cli_common::{fixture, read, run_err, run_ok};
use crate::run_guarantees::{last_checkpoint, run, same_bytes_on_any_thread_count_and_resumed};

use berry_evolve::brain::genome::Genome;
use berry_evolve::evo::evaluate::Evaluation;
use berry_evolve::evo::lineage::GenomeId;
use berry_evolve::evo::search::grid::{cell_of, enters, flat_index, Elite, GridArchive};
use berry_evolve::evo::search::map_elites::{
    gaussian_offspring, iso_line, iso_line_with, MapElitesState,
};
use berry_evolve::evo::search::{self, Search};
use berry_evolve::evo::state::{EvaluatedGeneration, Individual};
use berry_evolve::experiment::Experiment;
use berry_evolve::record::fitness_csv::extra_columns;
use berry_evolve::seed::{gaussian, stream, Generation, IndividualId, Purpose, Seed, TrialIndex};

fn elite(cell: Vec<usize>, fitness: f64, individual: u64) -> Elite {
    Elite {
        cell,
        id: GenomeId {
            generation: 0,
            individual,
        },
        fitness,
        measures: vec![0.0, 0.0],
        genome: Genome::new(vec![individual as f64]),
        lineage: None,
    }
}

/// A 3 × 2 grid: an empty cell takes any finite fitness; a better one replaces the elite; a
/// worse or an equal one does not (ties keep the older elite); a non-finite fitness or a cell
/// outside the grid never enters. Cells are ⌊s · bins⌋, the top edge in the last bin.
#[test]
fn insertion_and_replacement_on_hand_made_cases() {
    assert_eq!(cell_of(&[0.0, 0.0], &[3, 2]), vec![0, 0]);
    assert_eq!(cell_of(&[0.34, 0.5], &[3, 2]), vec![1, 1]);
    assert_eq!(
        cell_of(&[1.0, 0.49], &[3, 2]),
        vec![2, 0],
        "top edge: last bin"
    );
    assert_eq!(flat_index(&[2, 1], &[3, 2]), 5);
    assert!(enters(None, -7.0));
    assert!(enters(Some(1.0), 1.5));
    assert!(!enters(Some(1.0), 1.0));
    assert!(!enters(Some(1.0), 0.5));

    let mut a = GridArchive::new(vec![3, 2]);
    assert!(a.insert(elite(vec![1, 0], 2.0, 0)), "empty cell");
    assert!(a.insert(elite(vec![1, 0], 3.0, 1)), "better");
    assert!(!a.insert(elite(vec![1, 0], 1.0, 2)), "worse");
    assert!(
        !a.insert(elite(vec![1, 0], 3.0, 3)),
        "equal: the old elite stays"
    );
    assert_eq!(a.get(&[1, 0]).unwrap().id.individual, 1);
    assert!(!a.insert(elite(vec![1, 0], f64::NAN, 4)), "non-finite");
    assert!(!a.insert(elite(vec![3, 0], 9.0, 5)), "outside the grid");
    assert!(!a.insert(elite(vec![1], 9.0, 6)), "too few dimensions");
    assert!(a.insert(elite(vec![0, 1], -1.0, 7)));
    assert_eq!(a.len(), 2);
    let cells: Vec<Vec<usize>> = a.elites().map(|e| e.cell.clone()).collect();
    assert_eq!(cells, vec![vec![0, 1], vec![1, 0]], "cell order");
    assert!(a.get(&[2, 1]).is_none() && a.get(&[7, 7]).is_none());
}

/// tiny-map-elites.toml with the `[evolution.map_elites]` table replaced by `table` and the
/// population by `population`.
fn with_table(population: usize, table: &str) -> String {
    let text = std::fs::read_to_string(fixture("tiny-map-elites.toml")).unwrap();
    let start = text.find("[evolution.map_elites]").unwrap();
    let end = text.find("[behaviour]").unwrap();
    format!(
        "{}[evolution.map_elites]\n{table}\n\n{}",
        &text[..start],
        &text[end..]
    )
    .replace("population = 12", &format!("population = {population}"))
}

fn load(text: &str) -> Experiment {
    Experiment::from_toml(text, &fixture("tiny-map-elites.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// An individual with `[behaviour] measures = ["food_types", "distinct_food"]` values.
fn individual(
    fitness: Option<f64>,
    food_types: f64,
    distinct_food: f64,
    parameters: usize,
) -> Individual {
    Individual {
        genome: Genome::new(vec![fitness.unwrap_or(-1.0); parameters]),
        evaluation: Evaluation {
            fitness,
            metabolism: [0.0; 4],
            measures: vec![food_types, distinct_food],
            area_ticks: Vec::new(),
        },
        lineage: None,
    }
}

/// The same rules through the search, on a 4 × 2 grid of distinct_food in [0, 4] and
/// food_types in [0, 2]: generation 0 fills cells (1, 0) with fitness 2 (individual 0, tied
/// later by individual 2, which stays out) and (3, 1) with fitness 1 (individual 1, then
/// replaced by individual 3's 5 in the same generation); a broken brain (individual 4) never
/// enters; a value above the range is clamped into the last bin. Generation 1: a worse
/// genome leaves (1, 0) alone, an equal one too, a better one replaces it. The archive view
/// before telling shows the same as the archive after.
#[test]
fn the_search_places_a_generation_by_its_descriptors() {
    let e = load(&with_table(
        5,
        "descriptors = [{ measure = \"distinct_food\", min = 0, max = 4, bins = 4 }, \
         { measure = \"food_types\", min = 0, max = 2, bins = 2 }]\nqd_offset = -1",
    ));
    let topology = e.topology();
    let n = topology.parameter_count();
    let mut search = search::factory::of(&e, &topology);
    let zero = EvaluatedGeneration {
        generation: 0,
        individuals: vec![
            individual(Some(2.0), 0.5, 1.5, n),
            individual(Some(1.0), 1.5, 3.9, n),
            individual(Some(2.0), 0.9, 1.0, n),
            individual(Some(5.0), 2.0, 9.0, n),
            individual(None, 0.0, 0.0, n),
        ],
    };
    let view: Vec<(Vec<usize>, f64, u64)> = search
        .archive(&zero)
        .unwrap()
        .elites
        .iter()
        .map(|v| (v.cell.clone(), v.fitness, v.id.individual))
        .collect();
    assert_eq!(view, vec![(vec![1, 0], 2.0, 0), (vec![3, 1], 5.0, 3)]);
    search.tell(&zero);
    let state = |s: &dyn Search| {
        s.state()
            .and_then(|s| s.read::<MapElitesState>("map_elites"))
            .unwrap()
            .unwrap()
    };
    let told: Vec<(Vec<usize>, f64, u64)> = state(search.as_ref())
        .elites
        .iter()
        .map(|e| (e.cell.clone(), e.fitness, e.id.individual))
        .collect();
    assert_eq!(told, view, "the view before telling is the archive after");
    assert_eq!(
        state(search.as_ref()).elites[1].measures,
        vec![9.0, 2.0],
        "measures unscaled, in descriptor order"
    );
    let one = EvaluatedGeneration {
        generation: 1,
        individuals: vec![
            individual(Some(1.0), 0.0, 1.0, n),
            individual(Some(2.0), 0.0, 1.0, n),
            individual(Some(2.5), 0.0, 1.0, n),
            individual(Some(0.0), 0.0, 0.0, n),
            individual(Some(0.0), 1.0, 0.0, n),
        ],
    };
    search.tell(&one);
    let elites = state(search.as_ref()).elites;
    let got: Vec<(Vec<usize>, f64, (u64, u64))> = elites
        .iter()
        .map(|e| {
            (
                e.cell.clone(),
                e.fitness,
                (e.id.generation, e.id.individual),
            )
        })
        .collect();
    assert_eq!(
        got,
        vec![
            (vec![0, 0], 0.0, (1, 3)),
            (vec![0, 1], 0.0, (1, 4)),
            (vec![1, 0], 2.5, (1, 2)),
            (vec![3, 1], 5.0, (0, 3)),
        ]
    );
    let metrics = search
        .archive(&EvaluatedGeneration {
            generation: 2,
            individuals: Vec::new(),
        })
        .unwrap()
        .metrics();
    // qd_offset = −1 in the fixture: (0 + 1) + (0 + 1) + (2.5 + 1) + (5 + 1).
    assert_eq!(metrics.qd_score, 11.5);
    assert_eq!(metrics.coverage, 0.5);
    assert_eq!(metrics.archive_size, 4);
    assert_eq!(metrics.max_fitness, Some(5.0));
    // Generation 2 varies elites: its lineage names them by genome id.
    let asked = search.ask();
    assert_eq!(asked.genomes.len(), 5);
    for l in &asked.lineage {
        assert_eq!(l.birth.name(), "iso_line");
        assert_eq!(l.elites.len(), 2);
        assert!(elites.iter().any(|e| e.id == l.elites[0]));
    }
}

/// x' = x_i + σ_iso · n + σ_line · line · (x_j − x_i) with σ_iso = 0.1, σ_line = 0.5,
/// x_i = (0, 1), x_j = (2, −1), line = 2, n = (1, −1): (0 + 0.1 + 2, 1 − 0.1 − 2) =
/// (2.1, −1.1). With the stream, the draws are the line's first, then one per gene.
#[test]
fn iso_line_variation_on_a_hand_computed_case() {
    let x = iso_line_with(&[0.0, 1.0], &[2.0, -1.0], 0.1, 0.5, 2.0, &[1.0, -1.0]);
    assert!(
        (x[0] - 2.1).abs() < 1e-15 && (x[1] + 1.1).abs() < 1e-15,
        "{x:?}"
    );
    let rng = stream(
        Seed(3),
        Purpose::Variation,
        Generation(4),
        IndividualId(0),
        TrialIndex(0),
    );
    let mut draws = rng.clone();
    let line = gaussian(&mut draws);
    let n = [gaussian(&mut draws), gaussian(&mut draws)];
    let mut r = rng.clone();
    assert_eq!(
        iso_line(&[0.0, 1.0], &[2.0, -1.0], 0.1, 0.5, &mut r),
        vec![
            0.1 * n[0] + 0.5 * line * 2.0,
            1.0 + 0.1 * n[1] + 0.5 * line * -2.0
        ]
    );
    // The same elite twice: only the isotropic noise moves it.
    let mut r = rng.clone();
    let same = iso_line(&[0.5, 0.5], &[0.5, 0.5], 0.0, 0.5, &mut r);
    assert_eq!(same, vec![0.5, 0.5]);
    let mut r = rng;
    assert_eq!(gaussian_offspring(&[1.0, 2.0], 0.0, &mut r), vec![1.0, 2.0]);
}

#[test]
fn the_map_elites_table_is_checked_and_names_its_key() {
    let error = |text: &str| {
        Experiment::from_toml(text, &fixture("tiny-map-elites.toml"))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let key = "evolution.map_elites.descriptors";
    let d = |m: &str, min: f64, max: f64, bins: usize| {
        format!("{{ measure = \"{m}\", min = {min}, max = {max}, bins = {bins} }}")
    };
    let grid = |ds: &[String]| format!("descriptors = [{}]", ds.join(", "));
    let one = grid(&[d("distinct_food", 0.0, 4.0, 4)]);
    assert_eq!(error(&with_table(12, &one)), "");
    let missing = error(&with_table(12, &grid(&[d("ticks_alive", 0.0, 9.0, 3)])));
    assert!(
        missing.contains(key)
            && missing.contains("ticks_alive")
            && missing.contains("food_types, distinct_food"),
        "{missing}"
    );
    let range = error(&with_table(12, &grid(&[d("distinct_food", 4.0, 4.0, 3)])));
    assert!(
        range.contains(key) && range.contains("min < max"),
        "{range}"
    );
    let bins = error(&with_table(12, &grid(&[d("distinct_food", 0.0, 4.0, 0)])));
    assert!(bins.contains(key) && bins.contains("bins = 0"), "{bins}");
    let big = error(&with_table(
        12,
        &grid(&[
            d("distinct_food", 0.0, 4.0, 1000),
            d("food_types", 0.0, 2.0, 101),
        ]),
    ));
    assert!(
        big.contains(key)
            && big.contains("101000 cells")
            && big.contains("100000")
            && big.contains("1000 × 101"),
        "{big}"
    );
    let four = error(&with_table(
        12,
        &grid(&[
            d("distinct_food", 0.0, 4.0, 2),
            d("food_types", 0.0, 2.0, 2),
            d("distinct_food", 0.0, 4.0, 2),
            d("food_types", 0.0, 2.0, 2),
        ]),
    ));
    assert!(
        four.contains(key) && four.contains("1 to 3 dimensions"),
        "{four}"
    );
    let twice = error(&with_table(
        12,
        &grid(&[
            d("distinct_food", 0.0, 4.0, 2),
            d("distinct_food", 0.0, 4.0, 2),
        ]),
    ));
    assert!(twice.contains(key) && twice.contains("twice"), "{twice}");
    let none = error(&with_table(12, ""));
    assert!(
        none.contains(key) && none.contains("at least one"),
        "{none}"
    );
    let seeded = error(&with_table(12, &format!("{one}\ninitial_random = 5")));
    assert!(
        seeded.contains("evolution.map_elites.initial_random") && seeded.contains("4 cells"),
        "{seeded}"
    );
    let sigma = error(&with_table(12, &format!("{one}\nsigma = 0.1")));
    assert!(
        sigma.contains("evolution.map_elites.sigma") && sigma.contains("iso-line"),
        "{sigma}"
    );
    let iso = error(&with_table(
        12,
        &format!("{one}\nemitter = \"gaussian\"\niso_sigma = 0.1"),
    ));
    assert!(iso.contains("evolution.map_elites.iso_sigma"), "{iso}");
    assert_eq!(
        error(&with_table(
            12,
            &format!("{one}\nemitter = \"gaussian\"\nsigma = 0.3")
        )),
        ""
    );
    let negative = error(&with_table(12, &format!("{one}\nline_sigma = -1")));
    assert!(
        negative.contains("evolution.map_elites.line_sigma"),
        "{negative}"
    );
    let ga =
        error(&with_table(12, &one).replace("algorithm = \"map-elites\"", "algorithm = \"ga\""));
    assert!(
        ga.contains("evolution.map_elites") && ga.contains("only used with"),
        "{ga}"
    );
    let mutation = error(&format!(
        "{}\n[evolution.mutation]\nsigma = 0.3\n",
        with_table(12, &one)
    ));
    assert!(
        mutation.contains("evolution.mutation") && mutation.contains("map-elites"),
        "{mutation}"
    );
    assert_eq!(
        error(
            &with_table(12, &one).replace("population = 12", "population = 12\ninit_range = 0.5")
        ),
        "",
        "init_range draws the random genomes"
    );
}

/// 1 and 2 threads give the same bytes; a run stopped after 3 generations and resumed to 6
/// gives the bytes of one never stopped, archive.csv and the checkpoint's archive included;
/// the checkpoint holds the elites with their genomes; fitness.csv ends with the QD columns,
/// whose last row agrees with archive.csv; other algorithms' files have no QD columns.
#[test]
fn map_elites_runs_are_the_same_bytes_on_any_thread_count_and_resumed() {
    let (_dir, one) =
        same_bytes_on_any_thread_count_and_resumed("tiny-map-elites.toml", &["archive.csv"]);
    let checkpoint = last_checkpoint(&one);
    let file = fixture("tiny-map-elites.toml");
    let elites = checkpoint["payload"]["search"]["map_elites"]["elites"]
        .as_array()
        .unwrap()
        .clone();
    assert!(!elites.is_empty());
    assert!(elites.iter().all(|e| e["genome"]["parameters"]
        .as_array()
        .is_some_and(|p| !p.is_empty())));
    assert!(
        elites
            .iter()
            .all(|e| e["id"]["generation"].as_u64().unwrap() < 5),
        "before generation 5 was told"
    );

    let fitness = String::from_utf8(read(&one.join("fitness.csv"))).unwrap();
    let header: Vec<&str> = fitness.lines().next().unwrap().split(',').collect();
    assert_eq!(
        header[header.len() - 4..],
        ["qd_score", "coverage", "archive_size", "max_fitness"]
    );
    let last: Vec<f64> = fitness
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let archive = String::from_utf8(read(&one.join("archive.csv"))).unwrap();
    let mut lines = archive.lines();
    assert_eq!(
        lines.next().unwrap(),
        "cell_distinct_food,cell_food_types,distinct_food,food_types,fitness,generation,individual"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let qd: f64 = rows.iter().map(|r| r[4] + 1.0).sum();
    let n = last.len();
    assert!(
        (last[n - 4] - qd).abs() < 1e-9,
        "qd_score {} vs {qd}",
        last[n - 4]
    );
    assert_eq!(
        last[n - 3],
        rows.len() as f64 / 32.0,
        "coverage of the 8 × 4 grid"
    );
    assert_eq!(last[n - 2], rows.len() as f64);
    assert_eq!(
        last[n - 1],
        rows.iter().map(|r| r[4]).fold(f64::MIN, f64::max)
    );

    for other in ["tiny.toml", "tiny-novelty.toml", "tiny-pgpe.toml"] {
        let e = Experiment::load(&fixture(other)).unwrap();
        assert!(
            !extra_columns(&e).iter().any(|c| c == "qd_score"),
            "{other}"
        );
    }
    let e = Experiment::load(&file).unwrap();
    assert!(extra_columns(&e)
        .ends_with(&["qd_score", "coverage", "archive_size", "max_fitness"].map(String::from)));
}

/// `extract RUN --cell i,j` writes the elite of that cell; replayed on its own generation's
/// worlds it scores the fitness archive.csv gives it. An empty or an out-of-range cell, and a
/// run without an archive, are refused with what to do.
#[test]
fn extract_cell_round_trips_an_elite() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    run(&fixture("tiny-map-elites.toml"), &out, "4", "2");
    let archive = String::from_utf8(read(&out.join("archive.csv"))).unwrap();
    let row: Vec<&str> = archive.lines().nth(1).unwrap().split(',').collect();
    let cell = format!("{},{}", row[0], row[1]);
    let genome = dir.path().join("elite.json");
    run_ok(&[
        "extract",
        out.to_str().unwrap(),
        "--cell",
        &cell,
        "-o",
        genome.to_str().unwrap(),
    ]);
    let file: serde_json::Value = serde_json::from_slice(&read(&genome)).unwrap();
    assert_eq!(
        file["origin"]["generation"].as_u64().unwrap().to_string(),
        row[5]
    );
    assert_eq!(
        file["origin"]["individual"].as_u64().unwrap().to_string(),
        row[6]
    );
    let replay = run_ok(&[
        "replay",
        genome.to_str().unwrap(),
        "--experiment",
        out.join("experiment.toml").to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&replay.stdout).to_string()
        + &String::from_utf8_lossy(&replay.stderr);
    let fitness: f64 = row[4].parse().unwrap();
    assert!(text.contains(&format!("fitness {fitness:.6}")), "{text}");

    let filled: Vec<String> = archive
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(2).collect::<Vec<_>>().join(","))
        .collect();
    let empty = (0..8)
        .flat_map(|i| (0..4).map(move |j| format!("{i},{j}")))
        .find(|c| !filled.contains(c))
        .unwrap();
    let o = genome.to_str().unwrap();
    let run_dir = out.to_str().unwrap();
    let e = run_err(&["extract", run_dir, "--cell", &empty, "-o", o]);
    assert!(e.contains("is empty") && e.contains("archive.csv"), "{e}");
    let e = run_err(&["extract", run_dir, "--cell", "8,0", "-o", o]);
    assert!(
        e.contains("outside") && e.contains("8 bins of distinct_food"),
        "{e}"
    );
    let e = run_err(&["extract", run_dir, "--cell", "1", "-o", o]);
    assert!(e.contains("2 dimensions"), "{e}");
    let ga = dir.path().join("ga");
    run(&fixture("tiny.toml"), &ga, "1", "1");
    let e = run_err(&["extract", ga.to_str().unwrap(), "--cell", "0,0", "-o", o]);
    assert!(
        e.contains("keeps no archive") && e.contains("--individual"),
        "{e}"
    );
}

/// A finished run with `[validation]` extended by `resume --generations` sets aside its
/// end-of-run validation (the row's validation columns rewound) and keeps its QD columns
/// after them: the bytes of a run planned that long from the start.
#[test]
fn an_extended_run_keeps_its_qd_columns() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("tiny-map-elites.toml"))
        .unwrap()
        .replace(
            "[output]",
            "[validation]\nevery = 2\ntop = 2\ntrials = 2\n\n[output]",
        );
    let file = dir.path().join("validated.toml");
    std::fs::write(&file, text).unwrap();
    let (whole, extended) = (dir.path().join("whole"), dir.path().join("extended"));
    run(&file, &whole, "7", "2");
    run(&file, &extended, "4", "2");
    let header = String::from_utf8(read(&extended.join("fitness.csv"))).unwrap();
    assert!(header
        .lines()
        .next()
        .unwrap()
        .ends_with("validation_distinct_food,qd_score,coverage,archive_size,max_fitness"));
    run_ok(&[
        "resume",
        extended.to_str().unwrap(),
        "--generations",
        "7",
        "--quiet",
    ]);
    for f in [
        "fitness.csv",
        "archive.csv",
        "best.json",
        "checkpoints/gen-000006.json",
    ] {
        assert!(
            read(&whole.join(f)) == read(&extended.join(f)),
            "{f} differs"
        );
    }
}
