//! Which keys of an experiment changed between two configurations, for the run folder's
//! `config-changes.log` (a hash says that something changed, not what).

use super::ExperimentConfig;
use serde_json::Value;

/// The keys whose values differ between `old` and `new`, among those the config hash covers,
/// as `key: old -> new` lines in key order (`world.walls[2].to: [10.0,5.0] -> [12.0,5.0]`;
/// a key only one side has shows `(none)` on the other).
pub fn changed_keys(old: &ExperimentConfig, new: &ExperimentConfig) -> Vec<String> {
    let mut lines = Vec::new();
    walk("", &old.identity(), &new.identity(), &mut lines);
    lines
}

fn walk(key: &str, old: &Value, new: &Value, lines: &mut Vec<String>) {
    match (old, new) {
        (Value::Object(a), Value::Object(b)) => {
            let mut names: Vec<&String> = a.keys().chain(b.keys()).collect();
            names.sort();
            names.dedup();
            for name in names {
                let sub = if key.is_empty() {
                    name.clone()
                } else {
                    format!("{key}.{name}")
                };
                match (a.get(name), b.get(name)) {
                    (Some(x), Some(y)) => walk(&sub, x, y, lines),
                    (x, y) => lines.push(format!("{sub}: {} -> {}", shown(x), shown(y))),
                }
            }
        }
        // Arrays of tables ([[world.walls]] and the like) element by element, while the
        // lengths agree; otherwise (and for arrays of numbers) the whole array.
        (Value::Array(a), Value::Array(b))
            if a.len() == b.len() && a.iter().any(Value::is_object) =>
        {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                walk(&format!("{key}[{i}]"), x, y, lines);
            }
        }
        _ if old != new => lines.push(format!(
            "{key}: {} -> {}",
            shown(Some(old)),
            shown(Some(new))
        )),
        _ => {}
    }
}

fn shown(value: Option<&Value>) -> String {
    value.map_or("(none)".to_string(), Value::to_string)
}

#[cfg(test)]
mod tests {
    use super::changed_keys;
    use crate::experiment::Experiment;
    use std::path::Path;

    fn load(text: &str) -> Experiment {
        Experiment::from_toml(text, Path::new("test.toml")).unwrap()
    }

    #[test]
    fn names_each_changed_key_with_both_values() {
        let old = load("name = \"a\"\nseed = 1\n[evolution]\npopulation = 16\n");
        let new = load("name = \"a\"\nseed = 1\n[evolution]\npopulation = 20\n");
        assert_eq!(
            changed_keys(&old, &new),
            vec!["evolution.population: 16 -> 20".to_string()]
        );
        assert!(changed_keys(&old, &old).is_empty());
    }

    #[test]
    fn run_length_and_output_are_not_changes() {
        let old = load("name = \"a\"\nseed = 1\n[evolution]\ngenerations = 5\n");
        let new = load("name = \"a\"\nseed = 1\n[evolution]\ngenerations = 50\n");
        assert!(changed_keys(&old, &new).is_empty());
    }

    #[test]
    fn arrays_of_tables_are_compared_entry_by_entry() {
        let wall = |x: u32| {
            format!("name = \"a\"\nseed = 1\n[[world.walls]]\nfrom = [10, 10]\nto = [{x}, 10]\n")
        };
        let lines = changed_keys(&load(&wall(50)), &load(&wall(60)));
        assert_eq!(
            lines,
            vec!["world.walls[0].to: [50.0,10.0] -> [60.0,10.0]".to_string()]
        );
    }
}
