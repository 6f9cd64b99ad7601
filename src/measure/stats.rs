//! What a solver run cost and did: wall-clock time, rays, and counts of its own.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Run statistics: wall-clock seconds, rays traced, and solver-specific counts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Wall-clock seconds of the solve (without scene loading).
    pub seconds: f64,
    /// Rays traced (closest-hit queries).
    pub rays: u64,
    /// Solver-specific counts, written next to `seconds` and `rays`.
    #[serde(flatten)]
    pub extra: BTreeMap<String, serde_json::Value>,
}

impl Stats {
    /// Adds (or replaces) the solver-specific count `key`.
    pub fn insert(&mut self, key: &str, value: impl Into<serde_json::Value>) {
        self.extra.insert(key.to_string(), value.into());
    }
}
