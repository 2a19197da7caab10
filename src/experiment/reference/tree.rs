//! Reading the derived schema as a tree: a property seen through its `$ref`s, `allOf`s and
//! `null` alternatives, and the check for a list written where a table belongs. A leaf of
//! `reference`, so that `experiment` can use it while reading a file without an import circle.

use serde_json::{Map, Value};

/// The schema's definitions, by name.
pub(crate) struct Tree {
    defs: Map<String, Value>,
}

/// A property with its `$ref`s, `allOf`s and `null` alternatives seen through.
pub(crate) struct Resolved<'a> {
    /// The schema the value must match.
    pub target: &'a Value,
    /// The definition's name, when it came through a `$ref`.
    pub def: Option<String>,
    /// It may be null (an `Option` in Rust: left out, it is absent).
    pub nullable: bool,
}

impl Tree {
    /// The tree of the root schema `schema`.
    pub(crate) fn new(schema: &Value) -> Tree {
        Tree {
            defs: schema["definitions"]
                .as_object()
                .cloned()
                .unwrap_or_default(),
        }
    }

    pub(crate) fn resolve<'a>(&'a self, v: &'a Value) -> Resolved<'a> {
        let mut nullable = false;
        let mut v = v;
        let mut def = None;
        loop {
            if let Some(r) = v.get("$ref").and_then(Value::as_str) {
                let name = r.trim_start_matches("#/definitions/").to_string();
                v = &self.defs[&name];
                def = Some(name);
                continue;
            }
            if let Some(Value::Array(alts)) = v.get("allOf").or_else(|| v.get("anyOf")) {
                let non_null: Vec<&Value> = alts
                    .iter()
                    .filter(|a| a.get("type") != Some(&Value::from("null")))
                    .collect();
                if non_null.len() < alts.len() {
                    nullable = true;
                }
                if non_null.len() == 1 {
                    v = non_null[0];
                    continue;
                }
            }
            if let Some(Value::Array(types)) = v.get("type") {
                if types.iter().any(|t| t == "null") {
                    nullable = true;
                }
            }
            return Resolved {
                target: v,
                def,
                nullable,
            };
        }
    }
}

/// The first key at which `text` gives a list where the experiment expects a table, with
/// the span of the list. serde reads a struct from a list by position, so
/// `evaluation = [1, 2]` would otherwise silently mean `trials = 1, ticks = 2`.
pub(crate) fn list_for_table(
    text: &str,
    schema: &Value,
) -> Option<(String, std::ops::Range<usize>)> {
    let table = toml::de::DeTable::parse(text).ok()?;
    Tree::new(schema).find_list(schema, table.get_ref(), "")
}

impl Tree {
    fn is_table(&self, schema: &Value) -> bool {
        let t = self.resolve(schema).target;
        t.get("properties").is_some()
            || t.get("oneOf").and_then(Value::as_array).is_some_and(|vs| {
                vs.iter()
                    .all(|v| self.resolve(v).target.get("properties").is_some())
            })
    }

    fn find_list(
        &self,
        schema: &Value,
        table: &toml::de::DeTable<'_>,
        prefix: &str,
    ) -> Option<(String, std::ops::Range<usize>)> {
        use toml::de::DeValue;
        let schema = self.resolve(schema).target;
        for (key, value) in table {
            let name = key.get_ref().as_ref();
            let Some(prop) = schema
                .get("properties")
                .and_then(|p| p.get(name))
                .or_else(|| {
                    // A table chosen by a tag: the key of whichever variant has it.
                    schema
                        .get("oneOf")?
                        .as_array()?
                        .iter()
                        .find_map(|v| self.resolve(v).target.get("properties")?.get(name))
                })
            else {
                continue;
            };
            let path = join(prefix, name);
            let target = self.resolve(prop).target;
            match value.get_ref() {
                DeValue::Array(_) if self.is_table(prop) => return Some((path, value.span())),
                DeValue::Table(inner) if self.is_table(prop) => {
                    if let Some(found) = self.find_list(target, inner, &path) {
                        return Some(found);
                    }
                }
                DeValue::Table(inner) => {
                    // Tables by name: each entry against the named tables' schema.
                    if let Some(entry) = target.get("additionalProperties") {
                        for (k, v) in inner {
                            let p = format!("{path}.{}", k.get_ref());
                            match v.get_ref() {
                                DeValue::Array(_) if self.is_table(entry) => {
                                    return Some((p, v.span()))
                                }
                                DeValue::Table(t) => {
                                    if let Some(found) = self.find_list(entry, t, &p) {
                                        return Some(found);
                                    }
                                }
                                _ => {}
                            }
                        }
                    }
                }
                DeValue::Array(items) if type_is(target, "array") => {
                    // A list of tables: each entry a table, not a list.
                    let item = &target["items"];
                    if self.is_table(item) {
                        for (i, v) in items.iter().enumerate() {
                            let p = format!("{path}[{i}]");
                            match v.get_ref() {
                                DeValue::Array(_) => return Some((p, v.span())),
                                DeValue::Table(t) => {
                                    if let Some(found) = self.find_list(item, t, &p) {
                                        return Some(found);
                                    }
                                }
                                _ => {}
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        None
    }
}

pub(crate) fn type_is(t: &Value, name: &str) -> bool {
    match t.get("type") {
        Some(Value::String(s)) => s == name,
        Some(Value::Array(ts)) => ts.iter().any(|x| x == name),
        _ => false,
    }
}

pub(crate) fn join(prefix: &str, name: &str) -> String {
    if prefix.is_empty() {
        name.to_string()
    } else {
        format!("{prefix}.{name}")
    }
}
