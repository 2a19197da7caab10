//! The values every spec table shares: points, regions, the wall defaults, and the exact
//! reading of fixed-length arrays; a leaf module, so that the gadget specs and the world's
//! specs can both use them without importing each other.

/// Fixed-length arrays read exactly: the `toml` crate silently drops extra elements when it
/// fills a Rust array (`arena = [300, 300, 300]` would read as `[300, 300]`), so every
/// array field goes through a `Vec` and its length is checked.
pub(crate) mod exact {
    use serde::de::Error;
    use serde::{Deserialize, Deserializer};

    pub fn array<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<[f64; N], D::Error> {
        let values = Vec::<f64>::deserialize(d)?;
        let n = values.len();
        values
            .try_into()
            .map_err(|_| D::Error::invalid_length(n, &format!("an array of {N} numbers").as_str()))
    }

    pub fn option_array<'de, D: Deserializer<'de>, const N: usize>(
        d: D,
    ) -> Result<Option<[f64; N]>, D::Error> {
        array(d).map(Some)
    }

    /// A list of arrays of exactly N numbers each.
    pub fn arrays<'de, D: Deserializer<'de>, const N: usize>(
        d: D,
    ) -> Result<Vec<[f64; N]>, D::Error> {
        Vec::<Vec<f64>>::deserialize(d)?
            .into_iter()
            .map(|values| {
                let n = values.len();
                values.try_into().map_err(|_| {
                    D::Error::invalid_length(n, &format!("an array of {N} numbers").as_str())
                })
            })
            .collect()
    }

    /// Serde's `skip_serializing_if` for an odour that is all zeros (the default).
    pub fn is_zero<const N: usize>(values: &[f64; N]) -> bool {
        values.iter().all(|&v| v == 0.0)
    }

    /// Serde's `skip_serializing_if` for an intensity of 0 (the default).
    pub fn is_zero_scalar(value: &f64) -> bool {
        *value == 0.0
    }
}

/// A point `[x, y]` in LU.
pub type Point = [f64; 2];
/// An axis-aligned rectangle `[x0, y0, x1, y1]` in LU with `x0 <= x1` and `y0 <= y1`.
pub type Region = [f64; 4];

/// Grey, the colour of boundary walls and of walls that give none.
pub const DEFAULT_WALL_COLOUR: [f64; 3] = [0.5, 0.5, 0.5];
/// The report's typical wall height (§4.1).
pub const DEFAULT_WALL_HEIGHT: f64 = 10.0;
