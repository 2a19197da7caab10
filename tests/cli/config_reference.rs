//! `berry-evolve config`: the reference page and the JSON Schema are the code's (committed
//! copies in docs/ are checked byte for byte; `BERRY_BLESS=1` rewrites them), every key has
//! its unit/range/section entry and each range is the one validation enforces, the schema
//! accepts every shipped experiment and refuses a misspelt key, the defaults file parses to
//! the defaults and runs, and reading errors speak plain words with file, line and key.

use crate::cli_common::{bin, run_err, run_ok};
use berry_evolve::experiment::reference::{self, meta, KeyDefault, Shape};
use berry_evolve::experiment::{Experiment, ExperimentConfig};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn stdout_of(args: &[&str]) -> String {
    String::from_utf8(run_ok(args).stdout).expect("UTF-8")
}

/// Compares `docs/<name>` with what the binary prints; `BERRY_BLESS=1` rewrites the file.
fn check_committed(name: &str, args: &[&str]) {
    let printed = stdout_of(args);
    let path = root().join("docs").join(name);
    if std::env::var_os("BERRY_BLESS").is_some() {
        std::fs::write(&path, &printed).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == printed,
        "docs/{name} is not what `berry-evolve {}` prints: the code changed and the page did \
         not. Regenerate: `BERRY_BLESS=1 cargo test --release --test cli config_reference`",
        args.join(" ")
    );
}

#[test]
fn config_reference_page_is_the_codes() {
    check_committed("experiment-reference.md", &["config", "--reference"]);
}

#[test]
fn config_reference_schema_file_is_the_codes() {
    check_committed("experiment.schema.json", &["config", "--schema"]);
}

#[test]
fn config_reference_every_key_has_metadata_and_no_metadata_is_stale() {
    let keys = reference::keys();
    let metas = meta::keys();
    for k in &keys {
        assert!(
            metas.iter().any(|m| m.key == k.owner),
            "{} ({}) has no entry in src/experiment/reference/meta.rs",
            k.path,
            k.owner
        );
    }
    for m in &metas {
        assert!(
            keys.iter().any(|k| k.owner == m.key),
            "meta.rs names {}, which is no key of the experiment file",
            m.key
        );
    }
    // About 200 keys; the eight noise groups share one definition.
    assert!(keys.len() > 190, "{} keys", keys.len());
    let page = reference::reference_markdown();
    for k in &keys {
        let shown = ["`", "]`", "]]`"]
            .iter()
            .any(|end| page.contains(&format!("{}{end}", k.path)));
        assert!(shown, "{} not on the page", k.path);
    }
}

#[test]
fn config_reference_every_value_key_has_a_default_or_says_absent_or_required() {
    for k in reference::keys() {
        if k.shape != Shape::Value || k.optional {
            continue;
        }
        // A key that is neither optional nor required must have a default the page shows.
        assert!(
            !matches!(k.default, KeyDefault::Absent),
            "{} ({}) is not optional, yet neither a default nor `required`: serde leaves it out \
             of files at its default; give meta.rs its default (kd)",
            k.path,
            k.owner
        );
    }
    // Spot checks against the code's defaults.
    let find = |p: &str| reference::keys().into_iter().find(|k| k.path == p).unwrap();
    let value = |p: &str| match find(p).default {
        KeyDefault::Value(v) => v,
        other => panic!("{p}: {other:?}"),
    };
    assert_eq!(value("evaluation.trials"), Value::from(3));
    assert_eq!(value("evolution.selection.tournament_size"), Value::from(3));
    assert_eq!(value("fitness.balance"), Value::from("sum"));
    assert_eq!(value("world.walls[].height"), Value::from(10.0));
    assert_eq!(find("world.walls[].from").default, KeyDefault::Required);
    assert_eq!(find("world.start.heading").default, KeyDefault::Absent);
}

/// The defaults file as a TOML table: a base that validates, to set one key in.
fn base_table(path: &str) -> toml::Table {
    let mut t: toml::Table =
        toml::from_str(&reference::defaults_toml()).expect("the defaults file is TOML");
    // `[evolution.pgpe]` is read only by PGPE.
    if path.starts_with("evolution.pgpe.") {
        set_path(&mut t, "evolution.algorithm", toml::Value::from("pgpe"));
    }
    // `[evolution.cma_es]` only by sep-CMA-ES.
    if path.starts_with("evolution.cma_es.") {
        set_path(
            &mut t,
            "evolution.algorithm",
            toml::Value::from("sep-cma-es"),
        );
    }
    // `[evolution.novelty]` only by novelty search, which needs a descriptor.
    if path.starts_with("evolution.novelty.") {
        set_path(&mut t, "evolution.algorithm", toml::Value::from("novelty"));
        set_path(
            &mut t,
            "behaviour.measures",
            toml::Value::try_from(["ticks_alive"]).unwrap(),
        );
        let descriptor: toml::Value =
            toml::from_str::<toml::Table>("measure = \"ticks_alive\"\nmin = 0.0\nmax = 100.0")
                .unwrap()
                .into();
        set_path(
            &mut t,
            "evolution.novelty.descriptors",
            toml::Value::Array(vec![descriptor]),
        );
    }
    // `[evolution.map_elites]` only by MAP-Elites, which needs a descriptor; `sigma` only by
    // its Gaussian emitter.
    if path.starts_with("evolution.map_elites.") {
        set_path(
            &mut t,
            "evolution.algorithm",
            toml::Value::from("map-elites"),
        );
        set_path(
            &mut t,
            "behaviour.measures",
            toml::Value::try_from(["ticks_alive"]).unwrap(),
        );
        let descriptor: toml::Value = toml::from_str::<toml::Table>(
            "measure = \"ticks_alive\"\nmin = 0.0\nmax = 100.0\nbins = 10",
        )
        .unwrap()
        .into();
        set_path(
            &mut t,
            "evolution.map_elites.descriptors",
            toml::Value::Array(vec![descriptor]),
        );
        if path == "evolution.map_elites.sigma" {
            set_path(
                &mut t,
                "evolution.map_elites.emitter",
                toml::Value::from("gaussian"),
            );
        }
    }
    t
}

fn set_path(table: &mut toml::Table, path: &str, value: toml::Value) {
    let mut parts: Vec<&str> = path.split('.').collect();
    let last = parts.pop().unwrap();
    let mut t = table;
    for p in parts {
        t = t
            .entry(p)
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .unwrap();
    }
    t.insert(last.to_string(), value);
}

/// The error (parse or validation) of the experiment `table`, or None when it is accepted.
fn error_of(table: &toml::Table) -> Option<String> {
    let text = toml::to_string(table).unwrap();
    Experiment::from_toml(&text, Path::new("probe.toml"))
        .err()
        .map(|e| e.to_string())
}

#[test]
fn config_reference_ranges_are_the_ones_validation_enforces() {
    let metas = meta::keys();
    let mut probed = 0;
    for k in reference::keys() {
        // Keys of list entries, named tables and variants need a context of their own.
        if k.shape != Shape::Value || k.path.contains('[') || k.path.contains('<') {
            continue;
        }
        if k.when.is_some() || !matches!(k.default, KeyDefault::Value(_)) {
            continue;
        }
        // `[demo]` is read by `simulate` only, which checks it (not the experiment's
        // validation).
        if k.path.starts_with("demo.") {
            continue;
        }
        let m = metas.iter().find(|m| m.key == k.owner).unwrap();
        let integer = k.type_words.contains("whole number");
        let list = k.type_words.starts_with("list of");
        let KeyDefault::Value(default) = &k.default else {
            unreachable!()
        };
        // An empty list has no first element to change.
        if list && default.as_array().is_some_and(|a| a.is_empty()) {
            continue;
        }
        let toml_value = |x: f64| {
            if integer {
                toml::Value::Integer(x as i64)
            } else {
                toml::Value::Float(x)
            }
        };
        // A list: change its first element only.
        let with = |x: f64| {
            if list {
                let mut items: Vec<toml::Value> = toml::Value::try_from(default.clone())
                    .unwrap()
                    .as_array()
                    .unwrap()
                    .clone();
                items[0] = toml_value(x);
                toml::Value::Array(items)
            } else {
                toml_value(x)
            }
        };
        let step = |x: f64| {
            if integer {
                1.0
            } else {
                x.abs().max(1.0) * 1e-6
            }
        };
        let mut outside = Vec::new();
        let mut inside = Vec::new();
        if let Some(b) = m.range.min {
            outside.push(if b.inclusive {
                b.value - step(b.value)
            } else {
                b.value
            });
            inside.push(if b.inclusive {
                b.value
            } else {
                b.value + step(b.value)
            });
        }
        if let Some(b) = m.range.max {
            outside.push(if b.inclusive {
                b.value + step(b.value)
            } else {
                b.value
            });
            inside.push(if b.inclusive {
                b.value
            } else {
                b.value - step(b.value)
            });
        }
        for x in outside {
            let mut t = base_table(&k.path);
            set_path(&mut t, &k.path, with(x));
            let e = error_of(&t).unwrap_or_else(|| {
                panic!(
                    "{} = {x} is outside the documented range, yet accepted",
                    k.path
                )
            });
            assert!(
                e.contains(&k.path),
                "{} = {x}: the error names another key: {e}",
                k.path
            );
            probed += 1;
        }
        // At the bounds, the key itself must be accepted (a constraint between keys, which
        // the note states, may still refuse it).
        if m.range.note.is_empty() {
            for x in inside {
                let mut t = base_table(&k.path);
                set_path(&mut t, &k.path, with(x));
                if let Some(e) = error_of(&t) {
                    assert!(
                        !e.contains(&format!("`{}`", k.path))
                            && !e.contains(&format!("{}:", k.path)),
                        "{} = {x} is inside the documented range, yet refused: {e}",
                        k.path
                    );
                }
            }
        }
    }
    assert!(probed > 40, "only {probed} bounds probed");
}

/// A JSON Schema checker for the draft-07 keywords the derived schema uses, enough to check
/// the shipped experiments and to refuse a misspelt key.
fn check(schema: &Value, root: &Value, value: &Value, at: &str, errors: &mut Vec<String>) {
    if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
        let name = r.trim_start_matches("#/definitions/");
        return check(&root["definitions"][name], root, value, at, errors);
    }
    if let Some(Value::Array(all)) = schema.get("allOf") {
        for s in all {
            check(s, root, value, at, errors);
        }
    }
    for (word, need) in [("anyOf", 1usize), ("oneOf", 1)] {
        if let Some(Value::Array(alts)) = schema.get(word) {
            let ok = alts
                .iter()
                .filter(|s| {
                    let mut e = Vec::new();
                    check(s, root, value, at, &mut e);
                    e.is_empty()
                })
                .count();
            let good = if word == "oneOf" {
                ok == need
            } else {
                ok >= need
            };
            if !good {
                errors.push(format!("{at}: matches {ok} of the {word} alternatives"));
            }
        }
    }
    if let Some(t) = schema.get("type") {
        let types: Vec<&str> = match t {
            Value::String(s) => vec![s.as_str()],
            Value::Array(ts) => ts.iter().filter_map(Value::as_str).collect(),
            _ => vec![],
        };
        let fits = types.iter().any(|t| match *t {
            "object" => value.is_object(),
            "array" => value.is_array(),
            "string" => value.is_string(),
            "boolean" => value.is_boolean(),
            "integer" => value.is_i64() || value.is_u64(),
            "number" => value.is_number(),
            "null" => value.is_null(),
            _ => false,
        });
        if !fits {
            errors.push(format!("{at}: {value} is not of type {types:?}"));
            return;
        }
    }
    if let Some(c) = schema.get("const") {
        if c != value {
            errors.push(format!("{at}: {value} is not {c}"));
        }
    }
    if let Some(Value::Array(options)) = schema.get("enum") {
        if !options.contains(value) {
            errors.push(format!("{at}: {value} is not one of {options:?}"));
        }
    }
    if let Some(x) = value.as_f64() {
        let bound = |k: &str| schema.get(k).and_then(Value::as_f64);
        let bad = bound("minimum").is_some_and(|b| x < b)
            || bound("maximum").is_some_and(|b| x > b)
            || bound("exclusiveMinimum").is_some_and(|b| x <= b)
            || bound("exclusiveMaximum").is_some_and(|b| x >= b);
        if bad {
            errors.push(format!("{at}: {x} is out of range"));
        }
    }
    if let Value::Array(items) = value {
        let n = items.len() as u64;
        if schema
            .get("minItems")
            .and_then(Value::as_u64)
            .is_some_and(|m| n < m)
            || schema
                .get("maxItems")
                .and_then(Value::as_u64)
                .is_some_and(|m| n > m)
        {
            errors.push(format!("{at}: {n} items"));
        }
        if let Some(item) = schema.get("items") {
            for (i, v) in items.iter().enumerate() {
                check(item, root, v, &format!("{at}[{i}]"), errors);
            }
        }
    }
    if let Value::Object(map) = value {
        let props = schema.get("properties").and_then(Value::as_object);
        for key in schema
            .get("required")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            if !map.contains_key(key.as_str().unwrap_or("")) {
                errors.push(format!("{at}: missing required {key}"));
            }
        }
        for (k, v) in map {
            let here = format!("{at}.{k}");
            match props.and_then(|p| p.get(k)) {
                Some(s) => check(s, root, v, &here, errors),
                None => match schema.get("additionalProperties") {
                    Some(Value::Bool(false)) => errors.push(format!("{here}: unknown key")),
                    Some(s @ Value::Object(_)) => check(s, root, v, &here, errors),
                    _ => {}
                },
            }
        }
    }
}

fn schema_errors(schema: &Value, toml_text: &str) -> Vec<String> {
    let table: toml::Table = toml::from_str(toml_text).expect("TOML");
    let json = serde_json::to_value(table).unwrap();
    let mut errors = Vec::new();
    check(schema, schema, &json, "", &mut errors);
    errors
}

#[test]
fn config_reference_schema_accepts_every_shipped_experiment_and_refuses_mistakes() {
    let schema: Value = serde_json::from_str(&stdout_of(&["config", "--schema"])).unwrap();
    let mut files = Vec::new();
    for dir in [
        "experiments",
        "experiments/ablations",
        "experiments/bench",
        "experiments/learning",
        "experiments/search",
    ] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                files.push(path);
            }
        }
    }
    assert!(files.len() >= 25, "{} files", files.len());
    let defaults = stdout_of(&["config", "--defaults"]);
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let errors = schema_errors(&schema, &text);
        assert!(errors.is_empty(), "{}: {errors:?}", path.display());
    }
    assert_eq!(schema_errors(&schema, &defaults), Vec::<String>::new());
    // The checker can fail: a misspelt key, a text for a number, a value out of range.
    let text = defaults.replace("checkpoint_every = 10", "checkpoint_evry = 10");
    let e = schema_errors(&schema, &text);
    assert!(
        e.iter().any(|e| e.contains("checkpoint_evry: unknown key")),
        "{e:?}"
    );
    let text = defaults.replace("trials = 3", "trials = \"three\"");
    assert!(!schema_errors(&schema, &text).is_empty());
    let text = defaults.replace("trials = 3", "trials = 0");
    assert!(schema_errors(&schema, &text)
        .iter()
        .any(|e| e.contains("trials")));
    let text = defaults.replace("aggregate = \"mean\"", "aggregate = \"median\"");
    assert!(!schema_errors(&schema, &text).is_empty());
}

#[test]
fn config_reference_defaults_file_is_every_default_and_runs() {
    let text = stdout_of(&["config", "--defaults"]);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("defaults.toml");
    std::fs::write(&file, &text).unwrap();
    // Exactly the defaults: the same configuration (and hash) as a file naming only the
    // required keys.
    let parsed = Experiment::load(&file).unwrap();
    let minimal: ExperimentConfig = toml::from_str("name = \"my-experiment\"\nseed = 1\n").unwrap();
    assert_eq!(parsed.config(), &minimal);
    assert_eq!(parsed.config_hash(), minimal.config_hash());
    // Every key of the reference appears in it, set or commented out (tables that share a
    // definition with an earlier one list only their header).
    for k in reference::keys() {
        let shared = reference::keys()
            .iter()
            .any(|t| t.same_as.is_some() && k.path.starts_with(&format!("{}.", t.path)));
        if k.shape == Shape::Value && !shared {
            let set = format!("\n{} = ", k.name);
            let commented = format!("\n# {} = ", k.name);
            assert!(
                text.contains(&set) || text.contains(&commented),
                "{} missing",
                k.path
            );
        }
    }
    let file = file.to_str().unwrap();
    let inspect = stdout_of(&["inspect", file]);
    assert!(inspect.contains("my-experiment"), "{inspect}");
    let out = dir.path().join("run");
    let out = out.to_str().unwrap();
    run_ok(&["run", file, "--generations", "1", "--out", out, "--quiet"]);
    let csv = std::fs::read_to_string(Path::new(out).join("fitness.csv")).unwrap();
    assert_eq!(csv.lines().count(), 2, "{csv}");
}

#[test]
fn config_needs_exactly_one_output() {
    let out = bin().arg("config").output().unwrap();
    assert!(!out.status.success());
    let out = bin()
        .args(["config", "--schema", "--defaults"])
        .output()
        .unwrap();
    assert!(!out.status.success());
}

fn parse_error(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("x.toml");
    std::fs::write(&file, text).unwrap();
    let e = run_err(&["inspect", file.to_str().unwrap()]);
    e.replace(&dir.path().display().to_string(), "DIR")
}

#[test]
fn config_reference_reading_errors_speak_plain_words() {
    let head = "name = \"x\"\nseed = 1\n\n";
    let e = parse_error(&format!("{head}[evolution]\npopulation = \"sixty\"\n"));
    assert!(
        e.starts_with(
            "error: `evolution.population` in DIR/x.toml line 5: expected a whole number ≥ 0, \
             found the text \"sixty\""
        ),
        "{e}"
    );
    assert!(e.contains("5 | population = \"sixty\""), "{e}");
    assert!(!e.contains("usize"), "{e}");
    // A negative number for a count.
    let e = parse_error(&format!("{head}[evaluation]\ntrials = -3\n"));
    assert!(e.contains("`evaluation.trials` in DIR/x.toml line 5: expected a whole number ≥ 0, found the whole number -3"), "{e}");
    // A list where a table belongs, which serde used to read by position.
    let e = parse_error(&format!("{head}evaluation = [1, 2]\n"));
    assert!(
        e.contains("`evaluation` in DIR/x.toml line 4: expected a table, found a list"),
        "{e}"
    );
    // A misspelt key, with the nearest one suggested.
    let e = parse_error(&format!("{head}[output]\ncheckpoint_evry = 3\n"));
    assert!(e.contains("`output.checkpoint_evry` in DIR/x.toml line 5: unknown key `checkpoint_evry`; did you mean `checkpoint_every`?"), "{e}");
    // A misspelt word.
    let e = parse_error(&format!("{head}[evaluation]\naggregate = \"meen\"\n"));
    assert!(
        e.contains("\"meen\" is not one of \"mean\", \"min\"; did you mean \"mean\"?"),
        "{e}"
    );
    // A list of the wrong length, a text for true/false, a missing required key.
    let e = parse_error(&format!("{head}[world]\narena = [300, 300, 300]\n"));
    assert!(e.contains("`world.arena` in DIR/x.toml line 5: expected a list of 2 numbers, found a list of 3 values"), "{e}");
    let e = parse_error(&format!(
        "{head}[creature]\ninhibit_smell_on_whisker = \"yes\"\n"
    ));
    assert!(
        e.contains("expected true or false, found the text \"yes\""),
        "{e}"
    );
    let e = parse_error("seed = 1\n");
    assert!(
        e.contains("`name` in DIR/x.toml line 1: the required key `name` is missing"),
        "{e}"
    );
}
