//! Validation of configuration values: the typed error every config table returns when a
//! value is out of range, and the small checks that build it. Values are rejected with the
//! key and the reason, never silently corrected.

use thiserror::Error;

/// A configuration value that is present and well-typed but not acceptable.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("`{key}`: {reason}")]
pub struct InvalidValue {
    /// The full key path, e.g. `world.walls[2].to` or `evolution.elitism`.
    pub key: String,
    /// What is wrong, lowercase, no trailing period.
    pub reason: String,
}

impl InvalidValue {
    /// An error for `key` with `reason`.
    pub fn new(key: impl Into<String>, reason: impl Into<String>) -> Self {
        InvalidValue {
            key: key.into(),
            reason: reason.into(),
        }
    }
}

/// Shorthand for validation results.
pub type Valid = Result<(), InvalidValue>;

/// `value` must be finite (not NaN, not infinite).
pub fn finite(key: &str, value: f64) -> Valid {
    if value.is_finite() {
        Ok(())
    } else {
        Err(InvalidValue::new(
            key,
            format!("must be a finite number, got {value}"),
        ))
    }
}

/// Every component of `values` must be finite; the error names the index.
pub fn all_finite(key: &str, values: &[f64]) -> Valid {
    for (i, v) in values.iter().enumerate() {
        finite(&format!("{key}[{i}]"), *v)?;
    }
    Ok(())
}

/// `value` must be finite and >= 0.
pub fn non_negative(key: &str, value: f64) -> Valid {
    finite(key, value)?;
    if value < 0.0 {
        return Err(InvalidValue::new(key, format!("must be >= 0, got {value}")));
    }
    Ok(())
}

/// Every component must be finite and >= 0.
pub fn all_non_negative(key: &str, values: &[f64]) -> Valid {
    for (i, v) in values.iter().enumerate() {
        non_negative(&format!("{key}[{i}]"), *v)?;
    }
    Ok(())
}

/// `value` must be finite and > 0.
pub fn positive(key: &str, value: f64) -> Valid {
    finite(key, value)?;
    if value <= 0.0 {
        return Err(InvalidValue::new(key, format!("must be > 0, got {value}")));
    }
    Ok(())
}

/// `value` must be finite and within [lo, hi].
pub fn within(key: &str, value: f64, lo: f64, hi: f64) -> Valid {
    finite(key, value)?;
    if value < lo || value > hi {
        return Err(InvalidValue::new(
            key,
            format!("must be between {lo} and {hi}, got {value}"),
        ));
    }
    Ok(())
}

/// An integer count must be within [lo, hi]; `what` explains the upper limit when exceeded.
pub fn count_within(key: &str, value: u64, lo: u64, hi: u64, what: &str) -> Valid {
    if value < lo {
        return Err(InvalidValue::new(
            key,
            format!("must be at least {lo}, got {value}"),
        ));
    }
    if value > hi {
        return Err(InvalidValue::new(
            key,
            format!("must be at most {hi} ({what}), got {value}"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_key_and_reason() {
        let e = positive("creature.diameter", -1.0).unwrap_err();
        assert_eq!(e.to_string(), "`creature.diameter`: must be > 0, got -1");
        let e = all_finite("world.food[0].odour", &[0.0, f64::NAN]).unwrap_err();
        assert_eq!(e.key, "world.food[0].odour[1]");
        assert!(within("x", 0.5, 0.0, 1.0).is_ok());
        assert!(within("x", 1.5, 0.0, 1.0).is_err());
        let e = count_within(
            "evolution.population",
            10u64.pow(12),
            2,
            1_000_000,
            "memory",
        )
        .unwrap_err();
        assert!(e.reason.contains("at most 1000000 (memory)"), "{e}");
    }
}
