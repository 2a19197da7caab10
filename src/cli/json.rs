//! Machine-readable output (`--json`): the commands whose results scripts read print exactly
//! one pretty-printed JSON document on stdout and nothing else (progress and notes stay on
//! stderr). Each document is a `Serialize` struct of the subcommand's module whose first field
//! is `schema` (`"berry-evolve/<command>/1"`), and the text output is printed from the same
//! struct, so the two cannot disagree. Floats are written at full precision (serde_json's
//! shortest round-trip form); a value that is not finite is `null`.

use crate::cli::console::outln;

use anyhow::Context;
use serde::ser::{Serialize, SerializeMap, Serializer};

/// Prints `document` as the one JSON document of this command on stdout.
pub fn print<T: Serialize>(document: &T) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(document).context("cannot encode the JSON output")?;
    outln!("{text}");
    Ok(())
}

/// `x` when finite, else `None` (written as `null`): JSON has no NaN or infinity.
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Named values written as a JSON object in their own order (the experiment's order of its
/// behaviour measures), which a plain map would sort.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Named<V>(pub Vec<(&'static str, V)>);

impl<V> Named<V> {
    /// True when there are no values.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl<V: Serialize> Serialize for Named<V> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

#[cfg(test)]
mod tests {
    use super::{finite, Named};

    #[test]
    fn named_values_keep_their_order_and_non_finite_values_are_null() {
        let named = Named(vec![("zeta", finite(1.5)), ("alpha", finite(f64::NAN))]);
        assert_eq!(
            serde_json::to_string(&named).unwrap(),
            r#"{"zeta":1.5,"alpha":null}"#
        );
        // Full precision: the shortest text that reads back to the same bits.
        let x: f64 = 0.1 + 0.2;
        let text = serde_json::to_string(&x).unwrap();
        assert_eq!(text.parse::<f64>().unwrap().to_bits(), x.to_bits());
    }
}
