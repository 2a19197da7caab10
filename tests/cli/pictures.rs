//! `plot` and `render` on a tiny run: valid SVG with one curve per fitness column, every wall
//! and object of the world and the creature's path; the same for every shipped experiment;
//! bad input refused naming the file.

use berry_evolve::evo::state::first_population;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::{GenomeFile, Origin};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(bin()).args(args).output().unwrap()
}

fn ok(args: &[&std::ffi::OsStr]) -> Output {
    let out = run(args);
    assert!(
        out.status.success(),
        "{:?}: {}",
        args,
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn fails(args: &[&std::ffi::OsStr]) -> String {
    let out = run(args);
    assert!(!out.status.success(), "{args:?} should fail");
    String::from_utf8_lossy(&out.stderr).to_string()
}

macro_rules! a {
    ($($x:expr),* $(,)?) => { &[$(std::ffi::OsStr::new($x)),*] };
}

fn svg(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{path:?} is not XML: {e}"));
    text
}

/// Polylines of more than two points (curves; legend samples have two) with each stroke.
fn curves(text: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(text).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .filter(|n| {
            n.attribute("points")
                .unwrap_or("")
                .split_whitespace()
                .count()
                > 2
        })
        .map(|n| n.attribute("stroke").unwrap_or("").to_string())
        .collect()
}

fn with_class<'a>(doc: &'a roxmltree::Document<'a>, class: &str) -> Vec<roxmltree::Node<'a, 'a>> {
    doc.descendants()
        .filter(|n| {
            n.attribute("class")
                .is_some_and(|c| c.split_whitespace().next() == Some(class))
        })
        .collect()
}

fn genome_for(experiment: &Path, at: &Path) {
    let e = Experiment::load(experiment).unwrap();
    let genome = first_population(&e, &e.topology()).swap_remove(1);
    GenomeFile::new(&e, &genome, Origin::default())
        .save(at)
        .unwrap();
}

#[test]
fn plot_and_render_a_tiny_run() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let tiny = root().join("tests/fixtures/tiny.toml");
    ok(a![
        "run",
        &tiny,
        "--out",
        &dir,
        "--quiet",
        "--generations",
        "4"
    ]);
    // The run's curves: best, mean, median, worst, one polyline each, 4 colours.
    let plot = tmp.path().join("fitness.svg");
    ok(a!["plot", &dir, "-o", &plot]);
    let text = svg(&plot);
    let c = curves(&text);
    assert_eq!(c.len(), 4, "{c:?}");
    c.iter()
        .for_each(|s| assert_eq!(c.iter().filter(|t| *t == s).count(), 1));
    let doc = roxmltree::Document::parse(&text).unwrap();
    let texts: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    for label in [
        "tiny (seed 5): fitness",
        "best",
        "mean",
        "median",
        "worst",
        "generation",
        "fitness",
    ] {
        assert!(texts.contains(&label), "no text {label}: {texts:?}");
    }
    // A validation_best column (read by name, wherever it is) is a fifth curve.
    let csv = std::fs::read_to_string(dir.join("fitness.csv")).unwrap();
    let mut with_validation = String::new();
    for (k, line) in csv.lines().enumerate() {
        let extra = if k == 0 {
            "validation_best".to_string()
        } else {
            format!("{}", k as f64 * 0.5)
        };
        with_validation.push_str(&format!("{extra},{line}\n"));
    }
    let v = tmp.path().join("v").join("fitness.csv");
    std::fs::create_dir_all(v.parent().unwrap()).unwrap();
    std::fs::write(&v, with_validation).unwrap();
    let vplot = tmp.path().join("v.svg");
    ok(a!["plot", &v, "-o", &vplot]);
    assert_eq!(curves(&svg(&vplot)).len(), 5);
    // A summary across seeds: median lines, quartile bands.
    let summary = tmp.path().join("summary.csv");
    std::fs::write(
        &summary,
        "generation,best_q1,best_median,best_q3,mean_median,seeds\n0,1,2,3,1.5,5\n1,2,3,4,2,5\n2,2.5,3.5,5,2.2,5\n",
    )
    .unwrap();
    let splot = tmp.path().join("summary.svg");
    ok(a!["plot", &summary, "-o", &splot]);
    let text = svg(&splot);
    assert_eq!(curves(&text).len(), 2, "best and mean medians");
    let doc = roxmltree::Document::parse(&text).unwrap();
    let bands = doc
        .descendants()
        .filter(|n| n.has_tag_name("polygon"))
        .count();
    assert_eq!(bands, 1, "one quartile band (best)");

    // The champion's trial 1, drawn.
    let picture = tmp.path().join("best.svg");
    ok(a![
        "render",
        &dir.join("best.json"),
        "--experiment",
        &dir.join("experiment.toml"),
        "--trial",
        "1",
        "-o",
        &picture
    ]);
    let text = svg(&picture);
    let doc = roxmltree::Document::parse(&text).unwrap();
    // 4 boundary walls and the interior one; 12 food objects of types A and B.
    let walls = with_class(&doc, "wall");
    assert_eq!(walls.len(), 5);
    let ids: Vec<&str> = walls.iter().map(|n| n.attribute("id").unwrap()).collect();
    assert_eq!(ids, ["wall-0", "wall-1", "wall-2", "wall-3", "wall-4"]);
    let interior = walls[4];
    assert_eq!(
        interior.attribute("x1"),
        interior.attribute("x2"),
        "vertical"
    );
    let food = with_class(&doc, "food");
    assert_eq!(food.len(), 12);
    let types = |t: &str| {
        food.iter()
            .filter(|n| n.attribute("class").unwrap().contains(t))
            .count()
    };
    assert_eq!((types("type-a"), types("type-b")), (6, 6));
    let path = with_class(&doc, "creature-path");
    assert_eq!(path.len(), 1);
    assert!(
        path[0]
            .children()
            .filter(|n| n.has_tag_name("polyline"))
            .count()
            > 3
    );
    assert_eq!(with_class(&doc, "creature").len(), 1);
    assert!(text.contains("score "), "the outcome is in the legend");
}

#[test]
fn bad_input_is_refused_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let tiny = root().join("tests/fixtures/tiny.toml");
    let genome = tmp.path().join("g.json");
    genome_for(&tiny, &genome);
    // A genome of another experiment (other inputs) does not fit.
    let eye = tmp.path().join("eye.json");
    genome_for(&root().join("experiments/eye-arena.toml"), &eye);
    let err = fails(a![
        "render",
        &eye,
        "--experiment",
        &tiny,
        "-o",
        &tmp.path().join("x.svg")
    ]);
    assert!(
        err.contains(&*eye.to_string_lossy()) && err.contains("inputs"),
        "{err}"
    );
    // A trial index out of range.
    let err = fails(a![
        "render",
        &genome,
        "--experiment",
        &tiny,
        "--trial",
        "2",
        "-o",
        &tmp.path().join("x.svg")
    ]);
    assert!(
        err.contains("--trial 2") && err.contains("tiny.toml") && err.contains("0..2"),
        "{err}"
    );
    let err = fails(a!["replay", &genome, "--experiment", &tiny, "--trial", "9"]);
    assert!(err.contains("--trial 9"), "{err}");
    // An output that is an input, also through another spelling of its path.
    let before = std::fs::read(&genome).unwrap();
    let other = tmp.path().join(".").join("g.json");
    for output in [&genome, &other] {
        let err = fails(a!["render", &genome, "--experiment", &tiny, "-o", output]);
        assert!(
            err.contains("is an input") || err.contains("that is an input"),
            "{err}"
        );
    }
    let err = fails(a![
        "replay",
        &genome,
        "--experiment",
        &tiny,
        "--html",
        &genome
    ]);
    assert!(err.contains("that is an input"), "{err}");
    let err = fails(a![
        "replay",
        &genome,
        "--experiment",
        &tiny,
        "--trace",
        &tiny
    ]);
    assert!(err.contains("that is an input"), "{err}");
    assert_eq!(
        std::fs::read(&genome).unwrap(),
        before,
        "the genome is untouched"
    );
    let csv = tmp.path().join("fitness.csv");
    std::fs::write(&csv, "generation,best\n0,1\n").unwrap();
    let err = fails(a!["plot", &csv, "-o", &csv]);
    assert!(err.contains("that is an input"), "{err}");
    // A table without the columns plot needs.
    let bad = tmp.path().join("bad.csv");
    std::fs::write(&bad, "a,b\n1,2\n").unwrap();
    let err = fails(a!["plot", &bad]);
    assert!(
        err.contains("bad.csv") && err.contains("generation"),
        "{err}"
    );
    let err = fails(a!["plot", &tmp.path().join("missing")]);
    assert!(err.contains("missing"), "{err}");
}

/// For every shipped experiment, `render` draws one element per wall, door, trigger,
/// teleporter, area, landmark, food, aversive object, predator, air predator and wanderer of
/// the world the trace describes, and `replay --html` writes its page.
#[test]
fn render_and_replay_work_on_every_shipped_experiment() {
    let tmp = tempfile::tempdir().unwrap();
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("experiments"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    for path in files {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let genome = tmp.path().join(format!("{name}.json"));
        genome_for(&path, &genome);
        let picture = tmp.path().join(format!("{name}.svg"));
        let jsonl = tmp.path().join(format!("{name}.jsonl"));
        let html = tmp.path().join(format!("{name}.html"));
        ok(a!["render", &genome, "--experiment", &path, "-o", &picture]);
        ok(a![
            "replay",
            &genome,
            "--experiment",
            &path,
            "--trial",
            "0",
            "--trace-jsonl",
            &jsonl,
            "--html",
            &html
        ]);
        let first = std::fs::read_to_string(&jsonl).unwrap();
        let world: serde_json::Value = serde_json::from_str(first.lines().next().unwrap()).unwrap();
        let n = |key: &str| world[key].as_array().unwrap().len();
        let role = |r: &str| {
            world["actors"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|a| a["role"] == r)
                .count()
        };
        let text = svg(&picture);
        let doc = roxmltree::Document::parse(&text).unwrap();
        let count = |class: &str| with_class(&doc, class).len();
        for (class, want) in [
            ("wall", n("walls")),
            ("door", n("doors")),
            ("trigger", n("doors")),
            ("teleporter", n("teleporters")),
            ("area", n("areas")),
            ("landmark", n("landmarks")),
            ("food", n("food")),
            ("aversive", n("aversives")),
            ("predator", role("predator")),
            ("wanderer", role("wanderer")),
            ("air-predator", n("air_predators")),
            ("creature-path", 1),
        ] {
            assert_eq!(count(class), want, "{name}: elements of class {class}");
        }
        let glass = world["walls"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|w| w["opaque"] == false)
            .count();
        let drawn_glass = with_class(&doc, "wall")
            .iter()
            .filter(|n| n.attribute("class").unwrap().contains("glass"))
            .count();
        assert_eq!(drawn_glass, glass, "{name}: glass walls");
        let page = std::fs::read_to_string(&html).unwrap();
        assert!(page.contains("id=\"status\"") && page.contains("\"type\":\"world\""));
    }
}

/// A raider away between flights (`pause`) waits outside the arena: `render` draws no strike
/// disc for it there, while one in flight gets one.
#[test]
fn render_draws_no_strike_disc_for_a_raider_away_between_flights() {
    let tmp = tempfile::tempdir().unwrap();
    let tiny = std::fs::read_to_string(root().join("tests/fixtures/tiny.toml")).unwrap();
    let discs = |pause: &str| {
        let file = tmp.path().join(format!("raid{}.toml", pause.len()));
        std::fs::write(
            &file,
            format!("{tiny}\n[[world.air_predators]]\nspeed = 1\n{pause}\n"),
        )
        .unwrap();
        let genome = tmp.path().join("g.json");
        genome_for(&file, &genome);
        let picture = tmp.path().join("raid.svg");
        ok(a!["render", &genome, "--experiment", &file, "-o", &picture]);
        let text = svg(&picture);
        let doc = roxmltree::Document::parse(&text).unwrap();
        let group = with_class(&doc, "air-predator");
        assert_eq!(group.len(), 1);
        group[0]
            .descendants()
            .filter(|n| n.has_tag_name("circle"))
            .count()
    };
    assert_eq!(discs(""), 1);
    assert_eq!(discs("pause = [1000000, 1000000]"), 0);
}
