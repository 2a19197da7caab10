//! The replay page in a real browser: `replay --html` writes a page that headless Chromium
//! (Debian's `chromium`) loads at `#tick=N`; the page's own status element says where it drew
//! the creature and a wall and which colours the canvas has there, and those must be where
//! the trace (`--trace`) says, in the creature's and the wall's colours.
//!
//! The status element is for tests only: the page keeps it hidden. The charts' keys name the
//! brain's outputs (the eat output only when the creature eats by action). A plastic brain's
//! life of several episodes is one page: `#tick=P` is a position in the life, and the strip of
//! weights under the arena has its cursor there.
//!
//! Without Chromium the test says so and passes, unless `BERRY_REQUIRE_CHROMIUM=1` (set by
//! `.ci/run`), when it fails.

use berry_evolve::evo::search::ga::first_population;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::{GenomeFile, Origin};
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_berry-evolve"))
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

/// Runs headless Chromium on `url` and returns the DOM it dumps, or why it could not.
fn dump_dom(url: &str) -> Result<String, String> {
    let profile = tempfile::tempdir().map_err(|e| e.to_string())?;
    let out = Command::new("chromium")
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .args(["--virtual-time-budget=10000", "--dump-dom", url])
        .output()
        .map_err(|e| format!("cannot start chromium: {e}"))?;
    if !out.status.success() || out.stdout.is_empty() {
        return Err(format!(
            "chromium exited with {} and printed no page: {}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .rev()
                .take(5)
                .collect::<Vec<_>>()
                .join(" | ")
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).to_string())
}

fn numbers(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter_map(|s| s.parse().ok())
        .collect()
}

#[test]
fn the_page_draws_the_arena_and_the_creature_where_the_trace_says() {
    let tmp = tempfile::tempdir().unwrap();
    let experiment = Experiment::load(&fixture("tiny.toml")).unwrap();
    let genome = first_population(&experiment, &experiment.topology()).swap_remove(3);
    let genome_path = tmp.path().join("genome.json");
    GenomeFile::new(&experiment, &genome, Origin::default())
        .save(&genome_path)
        .unwrap();
    let html = tmp.path().join("page.html");
    let trace = tmp.path().join("trace.csv");
    let out = Command::new(bin())
        .arg("replay")
        .arg(&genome_path)
        .arg("--experiment")
        .arg(fixture("tiny.toml"))
        .args(["--trial", "1", "--html"])
        .arg(&html)
        .arg("--trace")
        .arg(&trace)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    // Self-contained: no external script, style, font or image.
    for needle in ["<script src", "<link", "http://", "https://", "url("] {
        assert!(!page.contains(needle), "the page refers to {needle}");
    }
    let tick = 57;
    let url = format!("file://{}#tick={tick}", html.display());
    let dom = match dump_dom(&url) {
        Ok(dom) => dom,
        Err(why) => {
            assert!(
                std::env::var("BERRY_REQUIRE_CHROMIUM").as_deref() != Ok("1"),
                "BERRY_REQUIRE_CHROMIUM=1 but {why}"
            );
            eprintln!("skipped: headless Chromium could not run ({why}); install Debian's chromium (apt-get install chromium) to run this test");
            return;
        }
    };
    let start = dom
        .find("<pre id=\"status\"")
        .expect("the page has a status element");
    let start = start + dom[start..].find('>').unwrap() + 1;
    let status = &dom[start..dom[start..].find("</pre>").unwrap() + start];
    let lines: Vec<&str> = status.lines().collect();
    assert!(lines[0].ends_with(&format!("tick {tick}")), "{status}");
    let frame = numbers(lines[1]);
    let (scale, offset) = (frame[0], frame[1]);
    // The arena's longer side is 640 pixels.
    assert_eq!(scale, 640.0 / 120.0, "{status}");
    // Where the trace has the creature after tick 57 of trial 1.
    let csv = std::fs::read_to_string(&trace).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let row: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|c| c.parse().unwrap_or(f64::NAN))
                .collect::<Vec<f64>>()
        })
        .find(|r| r[col("trial")] == 1.0 && r[col("tick")] == tick as f64)
        .expect("the trace has the tick");
    let creature = numbers(lines[2]);
    // "creature 0 at X,Y pixel R,G,B alive A"
    let (x, y) = (creature[1], creature[2]);
    assert!(
        (x - (offset + row[col("x")] * scale)).abs() < 0.01
            && (y - (offset + row[col("y")] * scale)).abs() < 0.01,
        "drawn at {x},{y}; the trace says {},{}: {status}",
        row[col("x")],
        row[col("y")]
    );
    assert_eq!(
        &creature[3..6],
        &[31.0, 63.0, 191.0],
        "the creature's colour at its centre: {status}"
    );
    // The interior wall of tiny.toml, (60, 0)–(60, 70), in the default grey.
    let wall = numbers(lines[3]);
    assert_eq!(wall[0], 4.0, "{status}");
    assert!((wall[1] - (offset + 60.0 * scale)).abs() < 0.01, "{status}");
    assert!((wall[2] - (offset + 35.0 * scale)).abs() < 0.01, "{status}");
    assert_eq!(&wall[3..6], &[128.0, 128.0, 128.0], "{status}");
    // Another tick moves the creature: the page did not just draw one frame.
    let dom = dump_dom(&format!("file://{}#tick=0", html.display())).unwrap();
    assert!(dom.contains("tick 0\n"), "tick 0 status");
}

/// Writes the replay page of `experiment` (TOML text) for one of its first genomes.
fn page_for(toml: &str, dir: &Path) -> String {
    let file = dir.join("experiment.toml");
    std::fs::write(&file, toml).unwrap();
    let experiment = Experiment::load(&file).unwrap();
    let genome = first_population(&experiment, &experiment.topology()).swap_remove(0);
    let genome_path = dir.join("genome.json");
    GenomeFile::new(&experiment, &genome, Origin::default())
        .save(&genome_path)
        .unwrap();
    let html = dir.join("page.html");
    let out = Command::new(bin())
        .arg("replay")
        .arg(&genome_path)
        .arg("--experiment")
        .arg(&file)
        .args(["--trial", "0", "--html"])
        .arg(&html)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read_to_string(&html).unwrap()
}

#[test]
fn the_page_hides_its_status_and_its_motor_chart_names_the_brains_outputs() {
    let tmp = tempfile::tempdir().unwrap();
    let tiny = std::fs::read_to_string(fixture("tiny.toml")).unwrap();
    for (toml, outputs) in [
        (tiny.clone(), "motor_left, motor_right"),
        (
            format!("{tiny}\n[creature]\neating = \"action\"\n"),
            "motor_left, motor_right, eat",
        ),
    ] {
        let page = page_for(&toml, tmp.path());
        // The status is for tests: hidden by the attribute and by the style.
        let at = page.find("<pre id=\"status\"").expect("a status element");
        let tag = &page[at..at + page[at..].find('>').unwrap()];
        assert!(
            tag.contains(" hidden") && tag.contains("display:none"),
            "the status element is not hidden: {tag}"
        );
        assert!(page.contains("#status{display:none}"), "the style hides it");
        // The motor chart's title and key: the outputs the brain has.
        let title = format!("motor outputs ({outputs}) over the trial");
        assert!(
            page.contains(&format!("id=\"motorlbl\">{title}<")),
            "{title}"
        );
        let keys: Vec<&str> = page
            .split("data-kind=\"output-")
            .skip(1)
            .map(|s| &s[..s.find('"').unwrap()])
            .collect();
        assert_eq!(keys.join(", "), outputs);
        // The script draws the same outputs' fields.
        let fields = if outputs.ends_with("eat") {
            "const MOTOR=[[\"left\",\"#1f77b4\"],[\"right\",\"#d62728\"],[\"eat\",\"#555555\"]];"
        } else {
            "const MOTOR=[[\"left\",\"#1f77b4\"],[\"right\",\"#d62728\"]];"
        };
        assert!(page.contains(fields), "{fields}");
        // tiny.toml's world: the creature, food A and B, walls; no glass, doors, predators.
        let legend = &page[page.find("id=\"legend\"").unwrap()..];
        let legend = &legend[..legend.find("</div>").unwrap()];
        for kind in ["creature", "food-a", "food-b", "wall"] {
            assert!(legend.contains(&format!("data-kind=\"{kind}\"")), "{kind}");
        }
        for kind in [
            "food-c", "food-d", "glass", "door", "predator", "nest", "landmark",
        ] {
            assert!(!legend.contains(&format!("data-kind=\"{kind}\"")), "{kind}");
        }
    }
}

#[test]
fn a_plastic_lifes_page_follows_the_life_across_episodes_with_its_strip_cursor() {
    let tmp = tempfile::tempdir().unwrap();
    let html = tmp.path().join("page.html");
    let out = Command::new(bin())
        .arg("replay")
        .arg(fixture("plastic-t-maze-best.json"))
        .arg("--experiment")
        .arg(fixture("plastic-t-maze.toml"))
        .args(["--trial", "0", "--html"])
        .arg(&html)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Life position 500: episodes of 180 ticks have 181 positions each, so episode 3, tick 138.
    let dom = match dump_dom(&format!("file://{}#tick=500", html.display())) {
        Ok(dom) => dom,
        Err(why) => {
            assert!(
                std::env::var("BERRY_REQUIRE_CHROMIUM").as_deref() != Ok("1"),
                "BERRY_REQUIRE_CHROMIUM=1 but {why}"
            );
            eprintln!("skipped: headless Chromium could not run ({why})");
            return;
        }
    };
    let start = dom.find("<pre id=\"status\"").unwrap();
    let status = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    assert!(status.contains("tick 138\n"), "{status}");
    assert!(
        status.contains("episode 3 of 10 life position 500"),
        "{status}"
    );
    // The strip's cursor stands at the position's share of the strip, drawn in black.
    let line = status
        .lines()
        .find(|l| l.starts_with("strip cursor"))
        .expect(status);
    let n = numbers(line);
    let (q, w, p, last) = (n[0], n[1], n[2], n[3]);
    assert_eq!(p, 500.0, "{line}");
    let share = (q - 45.5) / (w - 47.0);
    assert!((share - p / last).abs() < 0.01, "{line}");
    assert!(line.ends_with("pixel 0,0,0"), "{line}");
    assert!(dom.contains("episode 3 / 10 · tick 138 / 180"), "the label");
}
