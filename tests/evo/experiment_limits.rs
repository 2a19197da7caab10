//! Absurd sizes and non-finite numbers in an experiment file are refused when it is loaded,
//! naming the key and the limit (never a panic, a hang or a huge allocation later).

use berry_evolve::experiment::Experiment;
use std::path::Path;

fn tiny() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tiny.toml"))
        .unwrap()
}

/// Loads tiny.toml with `from` replaced by `to` (once) and returns the error message.
fn refused(from: &str, to: &str) -> String {
    let original = tiny();
    let text = original.replacen(from, to, 1);
    assert_ne!(text, original, "fixture has no `{from}`");
    match Experiment::from_toml(&text, Path::new("absurd.toml")) {
        Ok(_) => panic!("`{to}` was accepted"),
        Err(e) => {
            let message = e.to_string();
            assert!(message.contains("absurd.toml"), "{message}");
            message
        }
    }
}

fn assert_names(message: &str, key: &str, words: &[&str]) {
    assert!(message.contains(key), "does not name `{key}`: {message}");
    assert!(
        words.iter().any(|w| message.contains(w)),
        "says none of {words:?}: {message}"
    );
}

#[test]
fn a_population_of_a_trillion_is_refused() {
    let m = refused("population = 12", "population = 1000000000000");
    assert_names(&m, "evolution.population", &["at most", "limit"]);
}

#[test]
fn a_trial_of_10_to_the_15_ticks_is_refused() {
    let m = refused("ticks = 120", "ticks = 1000000000000000");
    assert_names(&m, "evaluation.ticks", &["at most", "limit"]);
}

#[test]
fn a_world_of_ten_million_objects_is_refused() {
    let m = refused("count = 6", "count = 10000000");
    assert_names(&m, "world.place[0].count", &["at most", "limit"]);
}

#[test]
fn a_hidden_layer_of_100000_units_is_refused() {
    let m = refused("hidden = [4]", "hidden = [100000]");
    assert_names(&m, "brain.hidden[0]", &["at most", "limit"]);
}

#[test]
fn too_many_hidden_layers_are_refused() {
    let layers = vec!["8"; 17].join(", ");
    let m = refused("hidden = [4]", &format!("hidden = [{layers}]"));
    assert_names(&m, "brain.hidden", &["at most", "limit"]);
}

/// Every size within its own limit, but a generation of petabytes together.
#[test]
fn a_population_of_huge_brains_is_refused() {
    let layers = vec!["4096"; 16].join(", ");
    let text = tiny()
        .replacen("hidden = [4]", &format!("hidden = [{layers}]"), 1)
        .replacen("population = 12", "population = 1000000", 1);
    let m = Experiment::from_toml(&text, Path::new("absurd.toml"))
        .expect_err("accepted")
        .to_string();
    assert_names(&m, "brain.hidden", &["at most", "limit"]);
    assert!(m.contains("population"), "{m}");
    // One such brain alone is still too big (2 GB of parameters).
    let text = tiny().replacen("hidden = [4]", &format!("hidden = [{layers}]"), 1);
    let m = Experiment::from_toml(&text, Path::new("absurd.toml"))
        .expect_err("accepted")
        .to_string();
    assert_names(&m, "brain.hidden", &["at most", "limit"]);
}

#[test]
fn other_absurd_counts_are_refused() {
    for (from, to, key) in [
        ("trials = 2", "trials = 100000000", "evaluation.trials"),
        (
            "generations = 8",
            "generations = 1000000000000",
            "evolution.generations",
        ),
        (
            "keep_checkpoints = 3",
            "keep_checkpoints = 100000000000",
            "output.keep_checkpoints",
        ),
        (
            "arena = [120.0, 120.0]",
            "arena = [1e300, 1e300]",
            "world.arena[0]",
        ),
    ] {
        let m = refused(from, to);
        assert_names(&m, key, &["at most", "limit"]);
    }
}

#[test]
fn nan_and_infinite_values_are_refused_naming_the_key() {
    for (from, to, key) in [
        ("radius = 2.0", "radius = nan", "world.kinds.food_a.radius"),
        (
            "intensity = 1.0",
            "intensity = inf",
            "world.kinds.food_a.intensity",
        ),
        ("range = 50.0", "range = -inf", "world.kinds.food_a.range"),
        (
            "arena = [120.0, 120.0]",
            "arena = [inf, 120.0]",
            "world.arena[0]",
        ),
        (
            "arena = [120.0, 120.0]",
            "arena = [120.0, nan]",
            "world.arena[1]",
        ),
        (
            "min_spacing = 10.0",
            "min_spacing = +inf",
            "world.place[0].min_spacing",
        ),
        (
            "bite = [0.5, 0.0, 0.0, 0.0]",
            "bite = [0.5, -nan, 0.0, 0.0]",
            "world.kinds.food_a.bite",
        ),
        ("from = [60.0, 0.0]", "from = [nan, 0.0]", "world.walls[0]"),
    ] {
        let m = refused(from, to);
        assert_names(&m, key, &["finite"]);
    }
}

#[test]
fn an_absurd_retina_is_refused_naming_the_limit() {
    let text = "name = \"x\"\nseed = 1\n[creature.eye]\nwidth = 1000000\nheight = 1\n[creature.inputs]\neye = true\n";
    let err =
        berry_evolve::experiment::Experiment::from_toml(text, std::path::Path::new("eye.toml"))
            .unwrap_err()
            .to_string();
    assert!(
        err.contains("eye.toml") && err.contains("creature.eye.width") && err.contains("at most"),
        "{err}"
    );
}

#[test]
fn an_unknown_draw_order_is_refused() {
    for order in ["0", "3"] {
        let m = refused(
            "population = 12",
            &format!("population = 12\ndraw_order = {order}"),
        );
        assert_names(&m, "evolution.draw_order", &["must be 1", "or 2"]);
    }
}
