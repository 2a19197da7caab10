//! TOML reading errors in plain words. The `toml` crate reports serde's messages, which speak
//! Rust ("invalid type: string \"sixty\", expected usize"); this rewrites them for a person
//! writing an experiment file ("expected a whole number ≥ 0, found the text \"sixty\""),
//! keeping the line, the key's full path and toml's picture of the offending text, and
//! suggesting the nearest key or word for a misspelt one. A message it does not know is kept
//! as it is, so nothing is lost.

use crate::input::{closest, cut};

/// A reading error of an experiment file, ready to show.
#[derive(Debug, Clone, PartialEq)]
pub struct PlainError {
    /// The full path of the key (`evolution.population`), when toml knows it.
    pub key: Option<String>,
    /// The 1-based line of the offending text.
    pub line: Option<usize>,
    /// What is wrong, in plain words.
    pub message: String,
    /// toml's picture of the line with the offending text marked (may be empty).
    pub excerpt: String,
}

/// Rewrites toml's error `error` about `text`.
pub fn plain_error(error: &toml::de::Error, text: &str) -> PlainError {
    let span = error.span();
    let line = span
        .as_ref()
        .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
    // toml names the key only when it has no input to quote: ask it that way.
    let mut bare = error.clone();
    bare.set_input(None);
    let table = bare
        .to_string()
        .lines()
        .find_map(|l| l.strip_prefix("in `").and_then(|l| l.strip_suffix('`')))
        .map(str::to_string);
    let raw = error.message().trim();
    let (key, message) = rewrite(raw, table);
    // toml's own rendering: the header line, then the quoted line with carets, then the
    // message; keep the picture, cut so that a huge value is not echoed back whole.
    let full = error.to_string();
    let picture: Vec<String> = full
        .lines()
        .skip(1)
        .take_while(|l| l.trim() != raw.lines().next().unwrap_or("").trim())
        .map(|l| cut(l, 300))
        .collect();
    PlainError {
        key,
        line,
        message,
        excerpt: picture.join("\n"),
    }
}

/// The error for a list written where a table belongs (`evaluation = [1, 2]`), at `span`.
pub fn list_for_table_error(key: String, span: std::ops::Range<usize>, text: &str) -> PlainError {
    let start = span.start.min(text.len());
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line = text[..start].matches('\n').count() + 1;
    let gutter = " ".repeat(line.to_string().len());
    let column = text[line_start..start].chars().count();
    let width = text[start..span.end.min(line_end).max(start)]
        .chars()
        .count()
        .max(1);
    let excerpt = format!(
        "{gutter} |\n{line} | {}\n{gutter} | {}{}",
        cut(&text[line_start..line_end], 300),
        " ".repeat(column),
        "^".repeat(width.min(300))
    );
    let hint = match key.rsplit_once('[') {
        Some((list, _)) => format!(
            "each entry of `{list}` is a table: a `[[{list}]]` header with its keys below it, \
             or `{{ key = value, ... }}`"
        ),
        None => {
            format!("write a `[{key}]` header with its keys below it, or `{{ key = value, ... }}`")
        }
    };
    PlainError {
        key: Some(key),
        line: Some(line),
        message: format!("expected a table, found a list; {hint}"),
        excerpt,
    }
}

/// The key path and the plain message for serde's `message` at the table or key `at`.
fn rewrite(message: &str, at: Option<String>) -> (Option<String>, String) {
    let join = |name: &str| match &at {
        Some(t) => format!("{t}.{name}"),
        None => name.to_string(),
    };
    if let Some(rest) = message.strip_prefix("unknown field `") {
        let (field, expected) = split_tick(rest);
        let known = ticked_words(expected);
        let mut text = format!("unknown key `{field}`");
        if let Some(best) = closest(field, known.iter().map(String::as_str)) {
            text.push_str(&format!("; did you mean `{best}`?"));
        }
        if known.is_empty() {
            text.push_str(" (this table takes no keys)");
        } else {
            text.push_str(&format!(" (this table's keys: {})", known.join(", ")));
        }
        return (Some(join(field)), text);
    }
    if let Some(rest) = message.strip_prefix("unknown variant `") {
        let (word, expected) = split_tick(rest);
        let known = ticked_words(expected);
        let quoted: Vec<String> = known.iter().map(|k| format!("\"{k}\"")).collect();
        let mut text = format!("\"{word}\" is not one of {}", quoted.join(", "));
        if let Some(best) = closest(word, known.iter().map(String::as_str)) {
            text.push_str(&format!("; did you mean \"{best}\"?"));
        }
        return (at, text);
    }
    if let Some(rest) = message.strip_prefix("missing field `") {
        let (field, _) = split_tick(rest);
        return (
            Some(join(field)),
            format!("the required key `{field}` is missing; add it"),
        );
    }
    if let Some(rest) = message.strip_prefix("duplicate field `") {
        let (field, _) = split_tick(rest);
        return (
            Some(join(field)),
            format!("the key `{field}` is given twice"),
        );
    }
    for prefix in ["invalid type: ", "invalid value: "] {
        if let Some(rest) = message.strip_prefix(prefix) {
            if let Some((found, expected)) = rest.rsplit_once(", expected ") {
                return (
                    at,
                    format!(
                        "expected {}, found {}",
                        expected_words(expected),
                        found_words(found)
                    ),
                );
            }
        }
    }
    if let Some(rest) = message.strip_prefix("invalid length ") {
        if let Some((n, expected)) = rest.split_once(", expected ") {
            let n: usize = n.trim().parse().unwrap_or(0);
            let values = if n == 1 { "value" } else { "values" };
            return (
                at,
                format!(
                    "expected {}, found a list of {n} {values}",
                    expected_words(expected)
                ),
            );
        }
    }
    if message == "wanted string or table" {
        return (at, "expected a table, found some other value".into());
    }
    (at, message.to_string())
}

/// `name\`, rest` -> (`name`, `rest`).
fn split_tick(rest: &str) -> (&str, &str) {
    match rest.split_once('`') {
        Some((word, tail)) => (word, tail),
        None => (rest, ""),
    }
}

/// The words in backticks of serde's "expected one of `a`, `b`" or "expected `a` or `b`".
fn ticked_words(text: &str) -> Vec<String> {
    text.split('`')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, w)| w.to_string())
        .collect()
}

/// What serde expected, in plain words.
fn expected_words(expected: &str) -> String {
    let e = expected.trim();
    match e {
        "u8" | "u16" | "u32" | "u64" | "u128" | "usize" => "a whole number ≥ 0".into(),
        "i8" | "i16" | "i32" | "i64" | "i128" | "isize" => "a whole number".into(),
        "f32" | "f64" => "a number".into(),
        "a boolean" => "true or false".into(),
        "a string" => "text in quotes".into(),
        "a sequence" => "a list [ … ]".into(),
        "a map" => "a table".into(),
        "[min, max]" => "a list [min, max] of 2 whole numbers".into(),
        _ if e.starts_with("struct ") || e.starts_with("a table") => "a table".into(),
        _ if e.starts_with("an array of ") => format!("a list of {}", &e["an array of ".len()..]),
        _ => e.to_string(),
    }
}

/// What serde found, in plain words.
fn found_words(found: &str) -> String {
    let f = found.trim();
    let ticked = |prefix: &str| {
        f.strip_prefix(prefix)
            .map(|v| v.trim_matches('`').to_string())
    };
    if let Some(s) = f.strip_prefix("string ") {
        return format!("the text {s}");
    }
    if let Some(v) = ticked("integer ") {
        return format!("the whole number {v}");
    }
    if let Some(v) = ticked("floating point ") {
        return format!("the number {v}");
    }
    if let Some(v) = ticked("boolean ") {
        return v;
    }
    match f {
        "sequence" => "a list".into(),
        "map" => "a table".into(),
        _ => f.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::rewrite;

    fn at(t: &str) -> Option<String> {
        Some(t.to_string())
    }

    #[test]
    fn serde_messages_read_as_plain_words() {
        let (k, m) = rewrite(
            "invalid type: string \"sixty\", expected usize",
            at("evolution.population"),
        );
        assert_eq!(k.as_deref(), Some("evolution.population"));
        assert_eq!(m, "expected a whole number ≥ 0, found the text \"sixty\"");
        let (_, m) = rewrite("invalid value: integer `-3`, expected u64", at("seed"));
        assert_eq!(m, "expected a whole number ≥ 0, found the whole number -3");
        let (_, m) = rewrite(
            "invalid type: sequence, expected struct EvaluationSpec",
            at("evaluation"),
        );
        assert_eq!(m, "expected a table, found a list");
        let (_, m) = rewrite(
            "invalid length 3, expected an array of 2 numbers",
            at("world.arena"),
        );
        assert_eq!(m, "expected a list of 2 numbers, found a list of 3 values");
        let (k, m) = rewrite(
            "unknown field `populaton`, expected one of `population`, `generations`",
            at("evolution"),
        );
        assert_eq!(k.as_deref(), Some("evolution.populaton"));
        assert!(
            m.starts_with("unknown key `populaton`; did you mean `population`?"),
            "{m}"
        );
        let (_, m) = rewrite("unknown variant `meen`, expected `mean` or `min`", at("x"));
        assert_eq!(
            m,
            "\"meen\" is not one of \"mean\", \"min\"; did you mean \"mean\"?"
        );
        let (k, m) = rewrite("missing field `name`", None);
        assert_eq!(k.as_deref(), Some("name"));
        assert_eq!(m, "the required key `name` is missing; add it");
        // A message of the project's own (a `try_from`) is kept as it is.
        let own = "`bite` applies only to food kinds, and this kind has class = \"aversive\"";
        assert_eq!(rewrite(own, at("world.kinds.x")).1, own);
    }

    #[test]
    fn a_far_misspelling_gets_no_suggestion() {
        let (_, m) = rewrite(
            "unknown field `zzzzzz`, expected one of `kind`, `probability`",
            at("t"),
        );
        assert!(!m.contains("did you mean"), "{m}");
        assert!(m.contains("kind, probability"), "{m}");
    }
}
