//! `docs/experiment-reference.md`: every key of the experiment file in one page, a table per
//! top-level table, written from [`super::keys`] and [`super::meta`].

use super::meta::{self, KeyMeta, Range};
use super::{toml_literal, KeyDefault, KeyDoc, Shape};

/// The command that writes the page (also in the page's header).
pub const REGENERATE: &str = "berry-evolve config --reference > docs/experiment-reference.md";

/// The whole page, as `berry-evolve config --reference` prints it.
pub fn reference_markdown() -> String {
    let keys = super::keys();
    let metas = meta::keys();
    let mut out = String::new();
    out.push_str("# Experiment file reference\n\n");
    out.push_str(&format!(
        "Every key of an experiment file, generated from the code (the configuration structs' \
         serde attributes and doc comments, plus `src/experiment/reference/meta.rs` for units, \
         ranges and report sections). Do not edit by hand: regenerate with\n`{REGENERATE}`\n\
         (or `BERRY_BLESS=1 cargo test --release --test cli config_reference`); a test fails \
         when this page and the code disagree.\n\n"
    ));
    out.push_str(
        "- **Editors**: `docs/experiment.schema.json` is the file's JSON Schema (`berry-evolve \
         config --schema`); with taplo or Even Better TOML, put `#:schema ../docs/experiment.schema.json` \
         on the first line of a file in experiments/ (the path is relative to the file).\n\
         - **A complete file of defaults**, commented: `berry-evolve config --defaults`.\n\
         - **Units**: lengths in LU, time in ticks, motor speeds in rotations per tick (RPT); \
         angles in the file are in **degrees** (the simulator converts them to radians). \
         x grows to the right, y downwards, a positive angle turns clockwise on screen.\n\
         - **§**: the section of the BERRY III report (Balkenius) the key implements; \
         SPEC-NOTES marks a reading the report leaves open; \"—\" a key of the platform \
         (controller, evolution, output) that the report does not cover (§1).\n\
         - **Paths**: `[]` is an entry of a list of tables (`world.walls[].from` is `from` in a \
         `[[world.walls]]` entry); `<name>` is a table named by the user \
         (`[world.kinds.food]`). A range on a list applies to each number in it. \
         *absent* means the key is left out; its meaning says what that does.\n",
    );
    let mut section: Option<String> = None;
    for key in &keys {
        let top = key.path.split('.').next().unwrap_or("").to_string();
        let heading = if key.depth == 0 && key.shape == Shape::Value {
            "Top level".to_string()
        } else {
            format!("`[{top}]`")
        };
        if section.as_deref() != Some(heading.as_str()) {
            out.push_str(&format!("\n## {heading}\n\n"));
            if key.depth == 0 && key.shape != Shape::Value {
                out.push_str(&format!("{}\n\n", cell(&key.meaning)));
            }
            out.push_str("| key | type | unit | default | range | § | meaning |\n");
            out.push_str("|---|---|---|---|---|---|---|\n");
            section = Some(heading);
        }
        if key.depth == 0 && key.shape != Shape::Value {
            continue;
        }
        let m = metas.iter().find(|m| m.key == key.owner);
        out.push_str(&row(key, m));
    }
    out
}

fn row(key: &KeyDoc, m: Option<&KeyMeta>) -> String {
    let path = match key.shape {
        Shape::Table | Shape::NamedTables => format!("`[{}]`", key.path),
        Shape::TableList => format!("`[[{}]]`", key.path),
        Shape::Value => format!("`{}`", key.path),
    };
    let default = match (&key.default, &key.shape) {
        (_, Shape::TableList | Shape::NamedTables) => "none".to_string(),
        (_, Shape::Table) if key.optional => "absent".to_string(),
        (_, Shape::Table) => "—".to_string(),
        (KeyDefault::Value(v), _) => format!("`{}`", toml_literal(v)),
        (KeyDefault::Absent, _) => "absent".to_string(),
        (KeyDefault::Required, _) => "required".to_string(),
    };
    let mut meaning = key.meaning.clone();
    if let Some(when) = &key.when {
        meaning = format!("(with `{when}`) {meaning}");
    }
    let list = key.type_words.starts_with("list of") && key.shape == Shape::Value;
    format!(
        "| {path} | {} | {} | {default} | {} | {} | {} |\n",
        cell(&key.type_words),
        m.map(|m| m.unit).unwrap_or(""),
        cell(&m.map(|m| range_words(&m.range, list)).unwrap_or_default()),
        m.map(|m| m.section).unwrap_or(""),
        cell(&meaning),
    )
}

/// A range in words: `1 to 10000`, `> 0`, `(0, 360]`, then its note.
pub fn range_words(range: &Range, list: bool) -> String {
    let bounds = match (range.min, range.max) {
        (Some(a), Some(b)) if a.inclusive && b.inclusive => {
            format!("{} to {}", num(a.value), num(b.value))
        }
        (Some(a), Some(b)) => format!(
            "{}{}, {}{}",
            if a.inclusive { "[" } else { "(" },
            num(a.value),
            num(b.value),
            if b.inclusive { "]" } else { ")" }
        ),
        (Some(a), None) => format!("{} {}", if a.inclusive { "≥" } else { ">" }, num(a.value)),
        (None, Some(b)) => format!("{} {}", if b.inclusive { "≤" } else { "<" }, num(b.value)),
        (None, None) => String::new(),
    };
    let bounds = if list && !bounds.is_empty() {
        format!("each {bounds}")
    } else {
        bounds
    };
    match (bounds.is_empty(), range.note.is_empty()) {
        (true, true) => String::new(),
        (true, false) => range.note.clone(),
        (false, true) => bounds,
        (false, false) => format!("{bounds}; {}", range.note),
    }
}

/// A bound as written: whole numbers without a decimal point.
pub fn num(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1.0e16 {
        format!("{}", x as i64)
    } else {
        format!("{x}")
    }
}

/// Text made safe for a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}
