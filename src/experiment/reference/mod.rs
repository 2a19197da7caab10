//! The experiment file described from the code: its JSON Schema (for editors), every key
//! with type, unit, default, range and report section (`docs/experiment-reference.md`), and a
//! complete commented file of defaults (`berry-evolve config --defaults`).
//!
//! Everything starts from the schema that `schemars` derives from the configuration structs
//! ([`ExperimentConfig`] and the tables it holds): their serde attributes give the keys,
//! types, defaults and which keys are required, their doc comments give the meanings. What a
//! type cannot say (the unit, the range that validation enforces, the report section) is in
//! [`meta`], one line per key; a test checks that the two name the same keys, and that each
//! range is the one validation enforces. The derives add trait impls only: nothing is called
//! on the run path, and serialisation (the run folder's `experiment.toml`, the config hash)
//! is untouched.

mod defaults;
pub mod meta;
mod page;
pub(crate) mod tree;

pub use defaults::defaults_toml;
pub use page::reference_markdown;

use crate::experiment::derived_schema;
use meta::{KeyMeta, Range};
use serde_json::{Map, Value};
use tree::{join, type_is, Resolved, Tree};

/// The JSON Schema of the experiment file, as `berry-evolve config --schema` prints it and
/// `docs/experiment.schema.json` holds: the derived schema without the `null`s that stand for
/// absent optional keys (TOML has no null), without Rust's number formats, and with each
/// key's range from [`meta`] as `minimum`/`maximum`, so that an editor checks them too.
pub fn schema() -> Value {
    let mut schema = derived_schema();
    let metas = meta::keys();
    // Ranges go where the keys are defined: the root's properties, and each definition's.
    if let Some(props) = schema.get_mut("properties").and_then(Value::as_object_mut) {
        add_ranges(props, "ExperimentConfig", &metas);
    }
    if let Some(defs) = schema.get_mut("definitions").and_then(Value::as_object_mut) {
        for (name, def) in defs.iter_mut() {
            for props in object_schemas_mut(def) {
                add_ranges(props, name, &metas);
            }
        }
    }
    tidy(&mut schema);
    schema["$id"] = Value::from("https://berry-evolve/experiment.schema.json");
    schema["title"] = Value::from("berry-evolve experiment file");
    schema
}

/// The `properties` maps of a definition: its own, or each variant's (`oneOf`).
fn object_schemas_mut(def: &mut Value) -> Vec<&mut Map<String, Value>> {
    if def.get("oneOf").is_some() {
        return match def.get_mut("oneOf") {
            Some(Value::Array(variants)) => variants
                .iter_mut()
                .filter_map(|v| v.get_mut("properties").and_then(Value::as_object_mut))
                .collect(),
            _ => Vec::new(),
        };
    }
    def.get_mut("properties")
        .and_then(Value::as_object_mut)
        .into_iter()
        .collect()
}

fn add_ranges(props: &mut Map<String, Value>, owner: &str, metas: &[KeyMeta]) {
    for (field, prop) in props.iter_mut() {
        let key = format!("{owner}.{field}");
        if let Some(m) = metas.iter().find(|m| m.key == key) {
            put_range(prop, &m.range);
        }
    }
}

/// Puts a range on a number, or on the innermost items of a list of numbers.
fn put_range(prop: &mut Value, range: &Range) {
    if is_array(prop) {
        if let Some(items) = prop.get_mut("items") {
            return put_range(items, range);
        }
    }
    let Some(map) = prop.as_object_mut() else {
        return;
    };
    if let Some(b) = range.min {
        let key = if b.inclusive {
            "minimum"
        } else {
            "exclusiveMinimum"
        };
        map.insert(key.into(), number(b.value));
        if !b.inclusive {
            map.remove("minimum");
        }
    }
    if let Some(b) = range.max {
        let key = if b.inclusive {
            "maximum"
        } else {
            "exclusiveMaximum"
        };
        map.insert(key.into(), number(b.value));
    }
}

fn is_array(v: &Value) -> bool {
    match v.get("type") {
        Some(Value::String(t)) => t == "array",
        Some(Value::Array(ts)) => ts.iter().any(|t| t == "array"),
        _ => false,
    }
}

/// A bound as JSON: a whole number when it is one (so `maximum` of a count reads `10000`).
fn number(x: f64) -> Value {
    if x.fract() == 0.0 && x.abs() < 9.0e15 {
        Value::from(x as i64)
    } else {
        Value::from(x)
    }
}

/// Removes `null` alternatives, `default: null` and Rust's `format`s, recursively.
fn tidy(v: &mut Value) {
    match v {
        Value::Object(map) => {
            map.remove("format");
            if map.get("default") == Some(&Value::Null) {
                map.remove("default");
            }
            if let Some(Value::Array(types)) = map.get_mut("type") {
                types.retain(|t| t != "null");
                if types.len() == 1 {
                    let only = types[0].clone();
                    map.insert("type".into(), only);
                }
            }
            if let Some(Value::Array(alts)) = map.get_mut("anyOf") {
                alts.retain(|a| a.get("type") != Some(&Value::from("null")));
                if alts.len() == 1 {
                    let only = alts.pop().expect("one left");
                    map.remove("anyOf");
                    map.insert("allOf".into(), Value::Array(vec![only]));
                }
            }
            for (_, child) in map.iter_mut() {
                tidy(child);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(tidy),
        _ => {}
    }
}

/// What a key holds, as the page and the defaults file show it.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A single value or a list of values: a line `key = value`.
    Value,
    /// A table of keys (`[world.start]`).
    Table,
    /// A list of tables (`[[world.walls]]`), empty by default.
    TableList,
    /// Tables by name (`[world.kinds.<name>]`), none by default.
    NamedTables,
}

/// A key's default, as far as the code says.
#[derive(Debug, Clone, PartialEq)]
pub enum KeyDefault {
    /// The value the key takes when left out.
    Value(Value),
    /// Left out, the key is absent; its meaning says what that means.
    Absent,
    /// The key must be given.
    Required,
}

/// One key of the experiment file.
#[derive(Debug, Clone)]
pub struct KeyDoc {
    /// Its full path, `evaluation.trials`; `[]` marks an entry of a list of tables
    /// (`world.walls[].from`), `<name>` a named table (`world.kinds.<name>.radius`).
    pub path: String,
    /// The struct and field that define it (`EvaluationSpec.trials`), as [`meta`] names it.
    pub owner: String,
    /// Its last path segment, the key as written in its table.
    pub name: String,
    /// Value, table, list of tables or named tables.
    pub shape: Shape,
    /// The type in plain words ("whole number", "list of 4 numbers").
    pub type_words: String,
    /// The default.
    pub default: KeyDefault,
    /// May be left out even without a default (an optional key or table).
    pub optional: bool,
    /// The meaning, from the doc comment, on one line.
    pub meaning: String,
    /// Only read when another key has a value (`kind = "braitenberg"`).
    pub when: Option<String>,
    /// The values it may take, for a key with a fixed set of words.
    pub choices: Vec<String>,
    /// Number of nested levels (0 for the top-level keys).
    pub depth: usize,
    /// For a table whose keys are those of an earlier one: that table's path.
    pub same_as: Option<String>,
}

/// Every key of the experiment file, tables included, in file order: the top level's
/// scalars, then each table with its keys and sub-tables, keys sorted within a table.
pub fn keys() -> Vec<KeyDoc> {
    let schema = derived_schema();
    let mut out = Vec::new();
    let walker = Walker {
        tree: Tree::new(&schema),
        metas: meta::keys(),
        expanded: Default::default(),
    };
    walker.table(&schema, "", "ExperimentConfig", None, None, 0, &mut out);
    out
}

struct Walker {
    tree: Tree,
    metas: Vec<KeyMeta>,
    /// The path where each table definition was first written out: a second table of the
    /// same definition (the eight `[creature.noise.<group>]`) refers to it instead of
    /// repeating its keys.
    expanded: std::cell::RefCell<Vec<(String, String)>>,
}

impl Walker {
    fn resolve<'a>(&'a self, v: &'a Value) -> Resolved<'a> {
        self.tree.resolve(v)
    }

    /// Walks the keys of the table `schema` at `prefix`, defined by the struct `owner`.
    #[allow(clippy::too_many_arguments)]
    fn table(
        &self,
        schema: &Value,
        prefix: &str,
        owner: &str,
        defaults: Option<&Value>,
        when: Option<&str>,
        depth: usize,
        out: &mut Vec<KeyDoc>,
    ) {
        // A table chosen by a tag (`kind = "constant"`): each variant's keys, the tag once.
        if let Some(Value::Array(variants)) = schema.get("oneOf") {
            self.variants(variants, prefix, owner, defaults, depth, out);
            return;
        }
        let Some(props) = schema.get("properties").and_then(Value::as_object) else {
            return;
        };
        let required: Vec<&str> = schema
            .get("required")
            .and_then(Value::as_array)
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        let mut tables = Vec::new();
        for (name, prop) in props {
            let doc = self.key(prop, prefix, owner, name, defaults, when, depth, &required);
            if doc.shape == Shape::Value {
                out.push(doc);
            } else {
                tables.push((doc, prop));
            }
        }
        // TOML puts a table's plain keys before its sub-tables: so does the walk.
        for (doc, prop) in tables {
            let r = self.resolve(prop);
            let own_default = match &doc.default {
                KeyDefault::Value(v) => Some(v.clone()),
                _ => None,
            };
            let path = doc.path.clone();
            let depth = doc.depth + 1;
            let shape = doc.shape.clone();
            let when = doc.when.clone();
            let def = r.def.unwrap_or_default();
            let first = self
                .expanded
                .borrow()
                .iter()
                .find(|(d, _)| *d == def)
                .map(|(_, p)| p.clone());
            if let (Shape::Table, Some(first)) = (&shape, &first) {
                let mut doc = doc;
                doc.meaning = format!("{} Its keys are those of `[{first}]`.", doc.meaning);
                doc.same_as = Some(first.clone());
                out.push(doc);
                continue;
            }
            if shape == Shape::Table {
                self.expanded.borrow_mut().push((def.clone(), path.clone()));
            }
            out.push(doc);
            match shape {
                Shape::Table => self.table(
                    r.target,
                    &path,
                    &def,
                    own_default.as_ref(),
                    when.as_deref(),
                    depth,
                    out,
                ),
                Shape::TableList => {
                    let item = self.resolve(&r.target["items"]);
                    let def = item.def.unwrap_or_default();
                    self.table(
                        item.target,
                        &format!("{path}[]"),
                        &def,
                        None,
                        None,
                        depth,
                        out,
                    )
                }
                Shape::NamedTables => {
                    let item = self.resolve(&r.target["additionalProperties"]);
                    let def = item.def.unwrap_or_default();
                    self.table(
                        item.target,
                        &format!("{path}.<name>"),
                        &def,
                        None,
                        None,
                        depth,
                        out,
                    )
                }
                Shape::Value => {}
            }
        }
    }

    fn variants(
        &self,
        variants: &[Value],
        prefix: &str,
        owner: &str,
        defaults: Option<&Value>,
        depth: usize,
        out: &mut Vec<KeyDoc>,
    ) {
        // The tag is the one key every variant holds with a `const`.
        let tag = variants[0]["properties"]
            .as_object()
            .and_then(|p| p.iter().find(|(_, v)| v.get("const").is_some()))
            .map(|(k, _)| k.clone())
            .unwrap_or_default();
        let choices: Vec<String> = variants
            .iter()
            .filter_map(|v| v["properties"][&tag]["const"].as_str())
            .map(|c| format!("\"{c}\""))
            .collect();
        let meanings: Vec<String> = variants
            .iter()
            .map(|v| {
                format!(
                    "{}: {}",
                    v["properties"][&tag]["const"].as_str().unwrap_or(""),
                    one_line(v["description"].as_str().unwrap_or(""))
                )
            })
            .collect();
        out.push(KeyDoc {
            path: join(prefix, &tag),
            owner: format!("{owner}.{tag}"),
            name: tag.clone(),
            shape: Shape::Value,
            type_words: format!("one of {}", choices.join(", ")),
            default: match defaults.and_then(|d| d.get(&tag)) {
                Some(v) => KeyDefault::Value(v.clone()),
                None => KeyDefault::Required,
            },
            optional: false,
            meaning: format!("Which variant: {}", meanings.join("; ")),
            when: None,
            choices,
            depth,
            same_as: None,
        });
        for v in variants {
            let chosen = v["properties"][&tag]["const"].as_str().unwrap_or("");
            // Defaults apply to the variant the default is.
            let d = defaults.filter(|d| d.get(&tag).and_then(Value::as_str) == Some(chosen));
            let mut v = v.clone();
            if let Some(p) = v.get_mut("properties").and_then(Value::as_object_mut) {
                p.remove(&tag);
            }
            let when = format!("{tag} = \"{chosen}\"");
            self.table(&v, prefix, owner, d, Some(&when), depth, out);
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn key(
        &self,
        prop: &Value,
        prefix: &str,
        owner: &str,
        name: &str,
        defaults: Option<&Value>,
        when: Option<&str>,
        depth: usize,
        required: &[&str],
    ) -> KeyDoc {
        let r = self.resolve(prop);
        let t = r.target;
        let shape = if t.get("properties").is_some()
            || t.get("oneOf").is_some_and(|o| {
                o.as_array()
                    .is_some_and(|vs| vs.iter().all(|v| v.get("properties").is_some()))
            }) {
            Shape::Table
        } else if type_is(t, "array")
            && self.resolve(&t["items"]).target.get("properties").is_some()
        {
            Shape::TableList
        } else if type_is(t, "object")
            && t.get("additionalProperties")
                .is_some_and(|a| self.resolve(a).target.get("properties").is_some())
        {
            Shape::NamedTables
        } else {
            Shape::Value
        };
        let owner_key = format!("{owner}.{name}");
        let meta = self.metas.iter().find(|m| m.key == owner_key);
        // The default: what the enclosing table's default holds (it went through the real
        // type, so it knows defaults that a raw reading table leaves to `try_from`), else the
        // field's own, else the code's value that [`meta`] names for a field that serde
        // leaves out of files when it has its default.
        let found = defaults
            .and_then(|d| d.get(name))
            .cloned()
            .or_else(|| prop.get("default").filter(|d| !d.is_null()).cloned())
            .or_else(|| meta.and_then(|m| m.default.clone()));
        let default = match found {
            Some(v) => KeyDefault::Value(v),
            None if required.contains(&name) => KeyDefault::Required,
            None => KeyDefault::Absent,
        };
        let description = prop
            .get("description")
            .or_else(|| t.get("description"))
            .and_then(Value::as_str)
            .unwrap_or("");
        let choices = self.choices(t);
        KeyDoc {
            path: join(prefix, name),
            owner: owner_key,
            name: name.to_string(),
            type_words: self.type_words(t, &shape, &choices),
            shape,
            default,
            optional: r.nullable,
            meaning: one_line(description),
            when: when.map(str::to_string),
            choices,
            depth,
            same_as: None,
        }
    }

    /// The words an enum accepts (`"mean"`, `"min"`), from `enum` or `oneOf` of `const`s.
    fn choices(&self, t: &Value) -> Vec<String> {
        if let Some(Value::Array(values)) = t.get("enum") {
            return values.iter().map(|v| v.to_string()).collect();
        }
        if let Some(Value::Array(alts)) = t.get("oneOf") {
            let mut out = Vec::new();
            for a in alts {
                let a = self.resolve(a).target;
                if let Some(c) = a.get("const") {
                    out.push(c.to_string());
                } else if let Some(Value::Array(values)) = a.get("enum") {
                    out.extend(values.iter().map(|v| v.to_string()));
                } else {
                    return Vec::new();
                }
            }
            return out;
        }
        Vec::new()
    }

    fn type_words(&self, t: &Value, shape: &Shape, choices: &[String]) -> String {
        match shape {
            Shape::Table => return "table".into(),
            Shape::TableList => return "list of tables".into(),
            Shape::NamedTables => return "tables by name".into(),
            Shape::Value => {}
        }
        if !choices.is_empty() {
            return format!("one of {}", choices.join(", "));
        }
        if type_is(t, "array") {
            let items = self.resolve(&t["items"]).target;
            let count = match (t.get("minItems"), t.get("maxItems")) {
                (Some(a), Some(b)) if a == b => Some(a.as_u64().unwrap_or(0)),
                _ => None,
            };
            let item_choices = self.choices(items);
            let inner = if !item_choices.is_empty() {
                format!("names from {}", item_choices.join(", "))
            } else if type_is(items, "array") {
                let words = self.type_words(items, &Shape::Value, &[]);
                format!("lists of {}", words.trim_start_matches("list of "))
            } else {
                plural(&self.type_words(items, &Shape::Value, &[]))
            };
            return match count {
                Some(n) => format!("list of {n} {inner}"),
                None => format!("list of {inner}"),
            };
        }
        if type_is(t, "integer") {
            "whole number".into()
        } else if type_is(t, "number") {
            "number".into()
        } else if type_is(t, "boolean") {
            "true or false".into()
        } else if type_is(t, "string") {
            "text".into()
        } else {
            "value".into()
        }
    }
}

fn plural(word: &str) -> String {
    match word {
        "whole number" => "whole numbers".into(),
        "number" => "numbers".into(),
        "text" => "texts".into(),
        "true or false" => "true-or-false values".into(),
        other => format!("{other}s"),
    }
}

/// A doc comment on one line: its lines joined, rustdoc links as plain code.
fn one_line(text: &str) -> String {
    let mut joined = text.split_whitespace().collect::<Vec<_>>().join(" ");
    // A rustdoc link with a target, [`TurnAway`](crate::sim::gadgets::TurnAway): the target
    // means nothing on a page.
    while let Some(at) = joined.find("`](") {
        let Some(end) = joined[at..].find(')') else {
            break;
        };
        joined.replace_range(at + 1..at + end + 1, "]");
    }
    // `[`Measure`]` is a rustdoc link; on a page it reads as code.
    joined.replace("[`", "`").replace("`]", "`")
}

/// A JSON value written as TOML (`[1.0, 0.0]`, `"mean"`, `true`).
pub fn toml_literal(v: &Value) -> String {
    match v {
        Value::Null => "absent".into(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.to_string()
            } else if let Some(u) = n.as_u64() {
                u.to_string()
            } else {
                let f = n.as_f64().unwrap_or(0.0);
                if f.fract() == 0.0 && f.abs() < 1.0e15 {
                    format!("{f:.1}")
                } else {
                    f.to_string()
                }
            }
        }
        Value::String(s) => Value::String(s.clone()).to_string(),
        Value::Array(items) => format!(
            "[{}]",
            items
                .iter()
                .map(toml_literal)
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Value::Object(map) => format!(
            "{{ {} }}",
            map.iter()
                .map(|(k, v)| format!("{k} = {}", toml_literal(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use crate::experiment::derived_schema;
    use crate::experiment::terms::TERMS;

    /// The checklist's first step, enforced: every `*_bonus` and `*_penalty` number of
    /// `[fitness]` is a term here (the shock and imbalance penalties belong to the gain), and
    /// every term is a key of `[fitness]` that its formula names.
    #[test]
    fn every_bonus_and_penalty_key_is_a_declared_term() {
        let schema = derived_schema();
        let fitness = &schema["definitions"]["FitnessSpec"];
        let properties = fitness["properties"]
            .as_object()
            .expect("FitnessSpec has keys");
        let formula = fitness["description"].as_str().unwrap_or_default();
        let gain = ["shock_penalty", "imbalance_penalty"];
        for key in properties.keys() {
            if (key.ends_with("_bonus") || key.ends_with("_penalty")) && !gain.contains(&&**key) {
                assert!(
                    TERMS.iter().any(|t| t.key == key),
                    "[fitness] {key} has no entry in experiment::terms::TERMS"
                );
            }
        }
        for term in &TERMS {
            assert!(
                properties.contains_key(term.key),
                "{} is not a [fitness] key",
                term.key
            );
            assert_eq!(term.schema_key, format!("FitnessSpec.{}", term.key));
            assert!(
                formula.contains(term.key),
                "the [fitness] formula leaves out {}",
                term.key
            );
        }
    }
}
