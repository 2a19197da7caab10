//! `plot` and `render` on a tiny run: valid SVG with one curve per fitness column, every wall
//! and object of the world and the creature's path; the same for every shipped experiment;
//! bad input refused naming the file.

use berry_evolve::evo::search::ga::first_population;
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
        // The page's key to the arena: the kinds this world has, and no others.
        let mut want = vec!["creature".to_string()];
        for t in 0..4 {
            if world["food"]
                .as_array()
                .unwrap()
                .iter()
                .any(|f| f["food_type"] == t)
            {
                want.push(format!("food-{}", (b'a' + t as u8) as char));
            }
        }
        let walls = world["walls"].as_array().unwrap();
        let areas = world["areas"].as_array().unwrap();
        // The page shows the first trial, every episode of its life (--trial 0 replays one
        // life): its key names the marks of the whole life's events.
        let events: Vec<String> = first
            .lines()
            .skip(1)
            .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
            .filter(|r| r["type"] == "tick")
            .flat_map(|r| r["events"].as_array().cloned().unwrap_or_default())
            .map(|e| e["event"].as_str().unwrap().to_string())
            .collect();
        for (kind, present) in [
            ("aversive", n("aversives") > 0),
            ("wall", walls.iter().any(|w| w["opaque"] == true)),
            ("glass", glass > 0),
            ("door", n("doors") > 0),
            ("trigger", n("doors") > 0),
            ("teleporter", n("teleporters") > 0),
            ("nest", areas.iter().any(|a| a["kind"] == "safe")),
            ("area", areas.iter().any(|a| a["kind"] != "safe")),
            ("landmark", n("landmarks") > 0),
            ("predator", role("predator") > 0),
            ("air-predator", n("air_predators") > 0),
            ("wanderer", role("wanderer") > 0),
            ("mark-eat", events.iter().any(|e| e == "eat")),
            ("mark-shock", events.iter().any(|e| e == "shock")),
            ("mark-death", events.iter().any(|e| e == "death")),
        ] {
            if present {
                want.push(kind.to_string());
            }
        }
        assert_eq!(
            legend_kinds(&page),
            want,
            "{name}: the replay page's arena key"
        );
        // The motor chart names the brain's outputs, and only those.
        let outputs = Experiment::load(&path).unwrap().output_names();
        assert_eq!(
            element_text(&page, "motorlbl"),
            format!("motor outputs ({}) over the trial", outputs.join(", ")),
            "{name}"
        );
        let keys: Vec<String> = outputs.iter().map(|o| format!("output-{o}")).collect();
        assert_eq!(
            kinds_in(&page, "motorkeys"),
            keys,
            "{name}: the motor chart's key"
        );
        assert_eq!(
            kinds_in(&page, "metabkeys"),
            ["m-A", "m-B", "m-C", "m-D"],
            "{name}: the metabolism chart's key"
        );
    }
}

/// The `data-kind` of every entry inside the element `id` of the replay page.
fn kinds_in(page: &str, id: &str) -> Vec<String> {
    let start = page
        .find(&format!("id=\"{id}\""))
        .unwrap_or_else(|| panic!("no element {id}"));
    let end = start + page[start..].find("</div>").unwrap();
    page[start..end]
        .split("data-kind=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect()
}

/// The replay page's key to the arena's symbols, by kind.
fn legend_kinds(page: &str) -> Vec<String> {
    kinds_in(page, "legend")
}

/// The text of the element `id` of the replay page (no markup inside).
fn element_text(page: &str, id: &str) -> String {
    let start = page
        .find(&format!("id=\"{id}\""))
        .unwrap_or_else(|| panic!("no element {id}"));
    let open = start + page[start..].find('>').unwrap() + 1;
    let close = open + page[open..].find('<').unwrap();
    page[open..close].to_string()
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

/// The sum of the `translate(x,y)` of `node` and its ancestors.
fn translation(node: roxmltree::Node) -> (f64, f64) {
    node.ancestors()
        .filter_map(|n| n.attribute("transform"))
        .filter_map(|t| t.strip_prefix("translate(")?.strip_suffix(')'))
        .map(|t| {
            let v: Vec<f64> = t.split(',').map(|x| x.trim().parse().unwrap()).collect();
            (v[0], v.get(1).copied().unwrap_or(0.0))
        })
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// The picture's viewBox width and height.
fn view_box(doc: &roxmltree::Document) -> (f64, f64) {
    let v: Vec<f64> = doc
        .root_element()
        .attribute("viewBox")
        .expect("a viewBox")
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    (v[2], v[3])
}

/// Renders `svg` with rsvg-convert and returns (width, height, RGB bytes), read back through
/// `convert FILE.png ppm:-`; None when either tool is missing.
fn rasterise(svg: &Path) -> Option<(usize, usize, Vec<u8>)> {
    let png = svg.with_extension("png");
    let made = Command::new("rsvg-convert")
        .arg(svg)
        .arg("-o")
        .arg(&png)
        .status()
        .ok()?;
    assert!(made.success(), "rsvg-convert failed on {svg:?}");
    let out = Command::new("convert")
        .arg(&png)
        .arg("ppm:-")
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    // P6 <width> <height> <max> then the bytes.
    let bytes = out.stdout;
    let mut fields = Vec::new();
    let mut at = 0;
    while fields.len() < 4 {
        while bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while !bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..at]).to_string());
    }
    assert_eq!(fields[0], "P6");
    assert_eq!(fields[3], "255");
    let (w, h) = (fields[1].parse().unwrap(), fields[2].parse().unwrap());
    Some((w, h, bytes[at + 1..].to_vec()))
}

/// The README's foraging picture had its legend cut at the right edge: a long genome name and
/// two-digit metabolism no longer pass the picture's viewBox, by the text width estimate and,
/// with rsvg-convert, in the pixels of its right edge.
#[test]
fn render_legend_is_not_cut_at_the_right_edge() {
    let tmp = tempfile::tempdir().unwrap();
    let genome = tmp
        .path()
        .join("a-genome-file-with-a-rather-long-name-as-runs-write.json");
    std::fs::copy(root().join("genomes/braitenberg-forager.json"), &genome).unwrap();
    let picture = tmp.path().join("foraging.svg");
    ok(a![
        "render",
        &genome,
        "--experiment",
        &root().join("experiments/foraging.toml"),
        "-o",
        &picture
    ]);
    let text = svg(&picture);
    let doc = roxmltree::Document::parse(&text).unwrap();
    let (width, height) = view_box(&doc);
    let legend = doc
        .descendants()
        .find(|n| n.attribute("id") == Some("legend"))
        .expect("a legend");
    let mut longest = 0.0_f64;
    for t in legend.descendants().filter(|n| n.has_tag_name("text")) {
        let words = t.text().unwrap_or("");
        let size: f64 = t
            .attribute("font-size")
            .map_or(13.0, |s| s.parse().unwrap());
        let (dx, dy) = translation(t);
        let x = dx + t.attribute("x").map_or(0.0, |x| x.parse().unwrap());
        let y = dy + t.attribute("y").map_or(0.0, |y| y.parse().unwrap());
        let w = berry_evolve::view::render::text_width(words, size);
        let right = if t.attribute("text-anchor") == Some("end") {
            x
        } else {
            x + w
        };
        longest = longest.max(w);
        assert!(
            right <= width - 10.0,
            "legend text {words:?} reaches x = {right:.0} of a picture {width:.0} wide"
        );
        assert!(
            y + 4.0 <= height,
            "legend text {words:?} at y = {y:.0} of {height:.0}"
        );
    }
    assert!(
        text.contains("a-genome-file-with-a-rather-long-name-as-runs-write.json"),
        "the genome's whole name is in the legend"
    );
    assert!(longest > 300.0, "the long line is long: {longest}");
    match rasterise(&picture) {
        None => eprintln!(
            "pixel check skipped: needs rsvg-convert and convert (apt-get install librsvg2-bin imagemagick)"
        ),
        Some((w, h, rgb)) => {
            for y in 0..h {
                for x in w - 8..w {
                    let p = &rgb[3 * (y * w + x)..3 * (y * w + x) + 3];
                    assert_eq!(p, [255, 255, 255], "a drawn pixel at ({x}, {y}) of {w}×{h}");
                }
            }
        }
    }
}

/// Does the segment a–b pass through the rectangle [x0, x1]×[y0, y1]? (Liang–Barsky.)
fn segment_meets_rect(a: (f64, f64), b: (f64, f64), r: [f64; 4]) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - r[0]),
        (dx, r[1] - a.0),
        (-dy, a.1 - r[2]),
        (dy, r[3] - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    t0 <= t1
}

/// `plot`'s legend covers no curve: curves through every corner of the axes, and the legend's
/// box (inside the picture) meets none of their segments.
#[test]
fn plot_legend_covers_no_curve() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    std::fs::create_dir_all(&dir).unwrap();
    // best climbs from the lower left to the upper right, worst falls from the upper left to
    // the lower right, mean and median cross the middle: no corner of the axes is empty.
    let mut csv = String::from("generation,best,mean,median,worst\n");
    for g in 0..=20 {
        let t = f64::from(g) / 20.0;
        csv.push_str(&format!(
            "{g},{},{},{},{}\n",
            100.0 * t,
            50.0 + 40.0 * libm::sin(t * 6.0),
            50.0,
            100.0 * (1.0 - t)
        ));
    }
    std::fs::write(dir.join("fitness.csv"), csv).unwrap();
    for (name, args) in [
        ("run", vec![dir.clone().into_os_string()]),
        ("summary", {
            let summary = tmp.path().join("summary.csv");
            let mut s = String::from(
                "generation,best_q1,best_median,best_q3,mean_median,validation_q1,validation_median,validation_q3\n",
            );
            for g in 0..=20 {
                let t = f64::from(g) / 20.0;
                s.push_str(&format!(
                    "{g},{},{},{},{},{},{},{}\n",
                    90.0 * t,
                    100.0 * t,
                    100.0 * t + 5.0,
                    100.0 * (1.0 - t),
                    40.0,
                    50.0,
                    60.0
                ));
            }
            std::fs::write(&summary, s).unwrap();
            vec![summary.into_os_string()]
        }),
    ] {
        let picture = tmp.path().join(format!("{name}.svg"));
        let mut argv: Vec<&std::ffi::OsStr> = vec![std::ffi::OsStr::new("plot")];
        argv.extend(args.iter().map(|a| a.as_os_str()));
        argv.extend([std::ffi::OsStr::new("-o"), picture.as_os_str()]);
        ok(&argv);
        let text = svg(&picture);
        let doc = roxmltree::Document::parse(&text).unwrap();
        let (width, height) = view_box(&doc);
        let legend = doc
            .descendants()
            .find(|n| n.attribute("id") == Some("legend"))
            .unwrap_or_else(|| panic!("{name}: no legend"));
        let frame = legend
            .children()
            .find(|n| n.has_tag_name("rect"))
            .expect("the legend's box");
        let num = |k: &str| frame.attribute(k).unwrap().parse::<f64>().unwrap();
        let r = [
            num("x"),
            num("x") + num("width"),
            num("y"),
            num("y") + num("height"),
        ];
        assert!(
            r[0] >= 0.0 && r[1] <= width && r[2] >= 0.0 && r[3] <= height,
            "{name}: the legend {r:?} is not inside the picture ({width}×{height})"
        );
        // The entries' text inside the box.
        for t in legend.descendants().filter(|n| n.has_tag_name("text")) {
            let x: f64 = t.attribute("x").unwrap().parse().unwrap();
            let w = berry_evolve::view::render::text_width(t.text().unwrap().trim(), 14.0);
            assert!(x + w <= r[1], "{name}: {:?} passes the box", t.text());
        }
        let mut curves = 0;
        for p in doc.descendants().filter(|n| n.has_tag_name("polyline")) {
            let pts: Vec<(f64, f64)> = p
                .attribute("points")
                .unwrap()
                .split_whitespace()
                .map(|xy| {
                    let (x, y) = xy.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect();
            if pts.len() <= 2 {
                continue;
            }
            curves += 1;
            for s in pts.windows(2) {
                assert!(
                    !segment_meets_rect(s[0], s[1], r),
                    "{name}: the curve {} passes under the legend {r:?} at {:?}–{:?}",
                    p.attribute("stroke").unwrap_or(""),
                    s[0],
                    s[1]
                );
            }
        }
        assert!(curves >= 3, "{name}: {curves} curves");
    }
}
