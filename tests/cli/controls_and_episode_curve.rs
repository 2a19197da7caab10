//! `compare --ablate` (a plastic genome's controls as rows of their own: frozen, ungated) and
//! `compare --episode-curve` (the share of correct first choices per episode, SVG and CSV),
//! on the tiny T-maze with a switch made plastic.

use crate::cli_common::{fixture, run_err, run_ok};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The `[brain]` lines that make the tiny T-maze's MLP neuromodulated.
const PLASTIC: &str = "hidden = [8]\nplasticity = \"neuromodulated\"\ngranularity = \"network\"\n\
                       modulators = [\"food_a\", \"food_b\", \"food_c\", \"neurons\"]";

/// Weights and biases of the tiny T-maze's fixed 24 → 8 → 2 MLP; the rule's five genes follow.
const FIXED: usize = 25 * 8 + 9 * 2;

/// In `dir`: the plastic experiment, a plastic genome whose learning matters, and the fixed
/// MLP genome of its weights. The rule is η = 0.5, D = 1 (every weight drifts by g/2 per tick)
/// and the modulatory neuron is held at tanh(−3) (no weights from the hidden layer, bias −3),
/// so that g ≈ −0.46 until a food detector says otherwise: the weights head for −4 when the
/// rule is gated, for +4 when it is not (ungated) and stay when frozen.
fn genomes(dir: &Path) -> (PathBuf, PathBuf, PathBuf) {
    let text = std::fs::read_to_string(fixture("t-maze-switch-tiny.toml")).unwrap();
    assert!(text.contains("hidden = [8]\n"));
    let experiment = dir.join("plastic.toml");
    std::fs::write(&experiment, text.replace("hidden = [8]", PLASTIC)).unwrap();
    let run = dir.join("run");
    run_ok(&[
        "run",
        experiment.to_str().unwrap(),
        "--generations",
        "1",
        "--out",
        run.to_str().unwrap(),
        "--quiet",
    ]);
    let mut genome: Value = serde_json::from_slice(&std::fs::read(run.join("best.json")).unwrap())
        .expect("best.json is JSON");
    let parameters = genome["parameters"].as_array_mut().unwrap();
    assert_eq!(parameters.len(), FIXED + 5 + 3 + 9, "{parameters:?}");
    parameters[FIXED] = 0.5.into();
    parameters[FIXED + 4] = 1.0.into();
    for w in &mut parameters[FIXED + 8..FIXED + 16] {
        *w = 0.0.into();
    }
    parameters[FIXED + 16] = (-3.0).into();
    let plastic = dir.join("plastic.json");
    std::fs::write(&plastic, serde_json::to_vec_pretty(&genome).unwrap()).unwrap();
    genome["parameters"].as_array_mut().unwrap().truncate(FIXED);
    genome["brain"] = serde_json::json!({"kind": "mlp", "hidden": [8]});
    let fixed = dir.join("fixed.json");
    std::fs::write(&fixed, serde_json::to_vec_pretty(&genome).unwrap()).unwrap();
    (experiment, plastic, fixed)
}

/// A row's trial scores and final metabolisms, as bits.
fn trials(row: &Value) -> Vec<(u64, Vec<u64>)> {
    row["trials"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            let metabolism = t["metabolism"].as_array().unwrap();
            (
                t["score"].as_f64().unwrap().to_bits(),
                metabolism
                    .iter()
                    .map(|m| m.as_f64().unwrap().to_bits())
                    .collect(),
            )
        })
        .collect()
}

/// The frozen row is the fixed MLP of the genome's weights, bit for bit; the ungated row (the
/// modulators cut) differs from both the genome as it is and the frozen one; the rows follow
/// their genome, labelled, in the text and the JSON.
#[test]
fn frozen_is_the_fixed_mlp_bit_for_bit_and_ungated_differs_from_both() {
    let tmp = tempfile::tempdir().unwrap();
    let (experiment, plastic, fixed) = genomes(tmp.path());
    let args = [
        "compare",
        plastic.to_str().unwrap(),
        fixed.to_str().unwrap(),
        "--experiment",
        experiment.to_str().unwrap(),
        "--trials",
        "4",
        "--random",
        "0",
        "--ablate",
    ];
    let json: Value = serde_json::from_slice(&run_ok(&[&args[..], &["--json"]].concat()).stdout)
        .expect("compare --json prints JSON");
    let rows = json["genomes"].as_array().unwrap();
    let labels: Vec<(String, Option<&str>)> = rows
        .iter()
        .map(|r| {
            let path = r["path"].as_str().unwrap();
            let name = Path::new(path).file_name().unwrap().to_str().unwrap();
            (name.to_string(), r["ablation"].as_str())
        })
        .collect();
    assert_eq!(
        labels,
        [
            ("plastic.json".to_string(), None),
            ("plastic.json".to_string(), Some("frozen")),
            ("plastic.json".to_string(), Some("ungated")),
            ("fixed.json".to_string(), None),
        ]
    );
    let (intact, frozen, ungated, fixed_mlp) = (
        trials(&rows[0]),
        trials(&rows[1]),
        trials(&rows[2]),
        trials(&rows[3]),
    );
    assert_eq!(frozen, fixed_mlp, "frozen = the fixed MLP, every trial");
    assert_eq!(
        rows[1]["fitness"].as_f64().map(f64::to_bits),
        rows[3]["fitness"].as_f64().map(f64::to_bits)
    );
    assert_ne!(intact, frozen, "the genome's learning changes its lives");
    assert_ne!(ungated, intact, "ungated differs from the genome as it is");
    assert_ne!(ungated, frozen, "ungated differs from frozen");
    // Per-episode choices for the ablated rows too.
    let episodes = &rows[2]["trials"][0]["episodes"]["correct_first_choice"];
    assert_eq!(episodes.as_array().map(Vec::len), Some(6), "{episodes}");

    let text = String::from_utf8(run_ok(&args).stdout).unwrap();
    let frozen_line = text
        .lines()
        .find(|l| l.contains("plastic.json (frozen): fitness"))
        .unwrap_or_else(|| panic!("no frozen row:\n{text}"));
    assert!(text.contains("plastic.json (ungated): fitness"), "{text}");
    let fixed_line = text
        .lines()
        .find(|l| l.contains("fixed.json: fitness"))
        .unwrap();
    assert_eq!(
        frozen_line.split_once(": fitness").unwrap().1,
        fixed_line.split_once(": fitness").unwrap().1
    );
    // `--ablate=frozen` gives that row only.
    let one = [&args[..9], &["--ablate=frozen", "--json"]].concat();
    let json: Value = serde_json::from_slice(&run_ok(&one).stdout).unwrap();
    let ablations: Vec<Option<&str>> = json["genomes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["ablation"].as_str())
        .collect();
    assert_eq!(ablations, [None, Some("frozen"), None]);
}

/// `--ablate` with no plastic genome, and `--episode-curve` where no curve can be drawn (lives
/// of one episode, no switch, a name not ending in .svg) are refused naming the option.
#[test]
fn ablate_without_learning_and_curves_without_episodes_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (experiment, plastic, fixed) = genomes(tmp.path());
    let e = experiment.to_str().unwrap();
    let message = run_err(&[
        "compare",
        fixed.to_str().unwrap(),
        "--experiment",
        e,
        "--ablate",
    ]);
    assert!(
        message.contains("--ablate") && message.contains("plastic") && message.contains("none"),
        "{message}"
    );

    let svg = tmp.path().join("curve.svg");
    let svg = svg.to_str().unwrap();
    let tiny = fixture("tiny.toml");
    let message = run_err(&[
        "compare",
        "--experiment",
        tiny.to_str().unwrap(),
        "--random",
        "2",
        "--episode-curve",
        svg,
    ]);
    assert!(
        message.contains("--episode-curve") && message.contains("episodes_per_life"),
        "{message}"
    );
    let text = std::fs::read_to_string(&experiment).unwrap();
    let start = text.find("[evaluation.switch]").unwrap();
    let end = start + text[start..].find("\n\n").unwrap();
    let unswitched = tmp.path().join("unswitched.toml");
    let text = format!("{}{}", &text[..start], &text[end..]);
    let measures = "measures = [\"adapted_choice\", \"good_bite_share\", \"richest_side_first\", \"food_types\"]";
    assert!(text.contains(measures));
    let text = text.replace(measures, "measures = [\"food_types\"]");
    std::fs::write(&unswitched, text).unwrap();
    let message = run_err(&[
        "compare",
        "--experiment",
        unswitched.to_str().unwrap(),
        "--random",
        "2",
        "--episode-curve",
        svg,
    ]);
    assert!(
        message.contains("--episode-curve") && message.contains("[evaluation.switch]"),
        "{message}"
    );
    let png = tmp.path().join("curve.png");
    let message = run_err(&[
        "compare",
        plastic.to_str().unwrap(),
        "--experiment",
        e,
        "--episode-curve",
        png.to_str().unwrap(),
    ]);
    assert!(message.contains(".svg"), "{message}");
    assert!(!Path::new(svg).exists() && !png.exists());
}

/// The curve holds one line per row in each of its two panels (the genome, its two
/// ablations, the random genomes), a legend entry per row, and its numbers beside it as CSV.
#[test]
fn the_episode_curve_draws_one_line_per_row_and_writes_its_numbers() {
    let tmp = tempfile::tempdir().unwrap();
    let (experiment, plastic, _) = genomes(tmp.path());
    let svg = tmp.path().join("curve.svg");
    run_ok(&[
        "compare",
        plastic.to_str().unwrap(),
        "--experiment",
        experiment.to_str().unwrap(),
        "--trials",
        "4",
        "--random",
        "3",
        "--ablate",
        "--episode-curve",
        svg.to_str().unwrap(),
    ]);
    let picture = std::fs::read_to_string(&svg).unwrap();
    let lines = picture
        .lines()
        .filter(|l| l.contains("<polyline") && l.contains("stroke-width=\"2\""))
        .count();
    assert_eq!(lines, 4 * 2, "4 rows x 2 panels:\n{picture}");
    for label in [
        "plastic.json (4 lives)",
        "plastic.json (frozen) (4 lives)",
        "plastic.json (ungated) (4 lives)",
        "3 random genomes (12 lives)",
        "chance (0.5)",
    ] {
        assert!(picture.contains(label), "no legend entry {label}");
    }
    let csv = std::fs::read_to_string(svg.with_extension("csv")).unwrap();
    let mut rows = csv.lines();
    assert_eq!(
        rows.next(),
        Some("panel,row,x,share_correct,lives,switched_share")
    );
    let by_episode: Vec<&str> = csv.lines().filter(|l| l.starts_with("episode,")).collect();
    assert_eq!(by_episode.len(), 4 * 6, "{csv}");
    assert!(csv.lines().any(|l| l.starts_with("since_switch,")), "{csv}");
    // Every share is a share, and the switch strip reaches 1 by the last episode (the
    // switch comes before episode 3 or 4 of 6).
    for l in &by_episode {
        let cells: Vec<&str> = l.rsplitn(4, ',').collect();
        let share: f64 = cells[2].parse().unwrap();
        assert!((0.0..=1.0).contains(&share), "{l}");
        if l.contains(",6,") {
            assert_eq!(cells[0], "1.000000", "{l}");
        }
    }
}

/// The curve's numbers on two lives worked by hand: per episode, per episode since the last
/// switch (0 = the first after it, counted only after a switch), and the switch strip; a life
/// with too few choices is refused naming the row.
#[test]
fn the_episode_curve_numbers_are_those_worked_by_hand() {
    use berry_evolve::view::episode_curve::{CurveRow, EpisodeCurve, LifeEpisodes};
    let lives = [
        LifeEpisodes {
            switches: &[3],
            correct: &[true, false, false, true],
        },
        LifeEpisodes {
            switches: &[2],
            correct: &[true, true, false, false],
        },
    ];
    let row = CurveRow::new("g".into(), &lives, 4, false).unwrap();
    assert_eq!(row.by_episode, [1.0, 0.5, 0.0, 0.5]);
    assert_eq!(row.since_switch, [(0.5, 2), (0.5, 2), (0.0, 1)]);
    let curve = EpisodeCurve::new("t".into(), 4, &lives, vec![row]).unwrap();
    assert_eq!(curve.switched, [0.0, 0.5, 1.0, 1.0]);
    assert!(curve.csv().contains("since_switch,g,2,0.000000,1,\n"));
    let short = [LifeEpisodes {
        switches: &[2],
        correct: &[true],
    }];
    let message = CurveRow::new("g".into(), &short, 4, false)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("row `g`") && message.contains("4 episodes"),
        "{message}"
    );
}
