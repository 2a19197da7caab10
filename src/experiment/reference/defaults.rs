//! `berry-evolve config --defaults`: a complete experiment file with every key at its
//! default, each with its meaning, unit and range as a comment. Keys without a default
//! (optional keys, lists of tables, the other variants of a table chosen by `kind`) are
//! written commented out, so that the file parses and runs as it stands.

use super::meta::{self, KeyMeta};
use super::page::range_words;
use super::{toml_literal, KeyDefault, KeyDoc, Shape};

/// The name the defaults file gives its experiment.
pub const DEFAULTS_NAME: &str = "my-experiment";

/// The file, as `berry-evolve config --defaults` prints it.
pub fn defaults_toml() -> String {
    let keys = super::keys();
    let metas = meta::keys();
    let mut out = String::new();
    out.push_str(
        "# An experiment file with every key at its default (berry-evolve config --defaults).\n\
         # Each key's meaning, unit and range is in the comment above it; keys that have no\n\
         # default (optional keys, lists of tables, other variants) are commented out.\n\
         # Every key: docs/experiment-reference.md. Check a file: berry-evolve inspect FILE.\n\
         # Units: lengths in LU, time in ticks, motor speeds in RPT, angles in degrees.\n\
         # As it stands the world is empty: nothing to eat, so every creature scores 0 and\n\
         # evolution has nothing to select (`inspect` and `run` say so). Add food, as\n\
         # experiments/foraging.toml does with [world.kinds.<name>] and [[world.place]], or\n\
         # start from a built-in experiment instead: berry-evolve new NAME --from foraging\n",
    );
    // Paths under which everything is written commented out.
    let mut commented: Vec<String> = Vec::new();
    for key in &keys {
        let m = metas.iter().find(|m| m.key == key.owner);
        let inside = commented.iter().any(|p| {
            key.path.starts_with(&format!("{p}.")) || key.path.starts_with(&format!("{p}[]"))
        });
        match key.shape {
            Shape::Value => value(&mut out, key, m, inside),
            Shape::Table => {
                let off = inside || (key.optional && !matches!(key.default, KeyDefault::Value(_)));
                if off {
                    commented.push(key.path.clone());
                }
                out.push('\n');
                comment(&mut out, &key.meaning, m, false);
                let hash = if off { "# " } else { "" };
                out.push_str(&format!("{hash}[{}]\n", key.path));
            }
            Shape::TableList => {
                commented.push(key.path.clone());
                out.push('\n');
                comment(&mut out, &key.meaning, m, false);
                out.push_str("# None by default; each entry is a table like this one:\n");
                out.push_str(&format!("# [[{}]]\n", key.path));
            }
            Shape::NamedTables => {
                commented.push(key.path.clone());
                out.push('\n');
                comment(&mut out, &key.meaning, m, false);
                out.push_str("# None by default; each is a table named by you, like this one:\n");
                out.push_str(&format!("# [{}]\n", key.path.replace("<name>", "NAME")));
                commented.push(format!("{}.<name>", key.path));
            }
        }
    }
    out
}

fn value(out: &mut String, key: &KeyDoc, m: Option<&KeyMeta>, inside: bool) {
    comment(out, &key.meaning, m, true);
    let line = match &key.default {
        KeyDefault::Value(v) if !inside => format!("{} = {}", key.name, toml_literal(v)),
        KeyDefault::Value(v) => format!("# {} = {}", key.name, toml_literal(v)),
        KeyDefault::Required if key.depth == 0 && key.name == "name" => {
            format!("{} = \"{DEFAULTS_NAME}\"    # required", key.name)
        }
        KeyDefault::Required if key.depth == 0 && key.name == "seed" => {
            format!("{} = 1    # required", key.name)
        }
        KeyDefault::Required => match &key.when {
            Some(when) => format!(
                "# {} = <{}>    # required with {when}",
                key.name, key.type_words
            ),
            None => format!("# {} = <{}>    # required", key.name, key.type_words),
        },
        KeyDefault::Absent => format!(
            "# {} = <{}>    # absent by default",
            key.name, key.type_words
        ),
    };
    out.push_str(&line);
    out.push('\n');
}

/// The comment above a key: its meaning, then unit, range and report section.
fn comment(out: &mut String, meaning: &str, m: Option<&KeyMeta>, value: bool) {
    let mut text = meaning.to_string();
    if let Some(m) = m {
        let mut facts = Vec::new();
        if !m.unit.is_empty() {
            facts.push(format!("unit: {}", m.unit));
        }
        let range = range_words(&m.range, false);
        if value && !range.is_empty() {
            facts.push(format!("range: {range}"));
        }
        facts.push(format!("report: {}", m.section));
        text = format!("{text} [{}]", facts.join("; "));
    }
    for line in wrap(&text, 94) {
        out.push_str("# ");
        out.push_str(&line);
        out.push('\n');
    }
}

/// Words of `text` in lines of at most `width` characters (a longer word gets its own line).
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}
