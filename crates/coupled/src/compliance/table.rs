//! Precomputed compliances, looked up by support set and point.
//!
//! A point is keyed by its coordinates rounded to 1e-9 of the plate's sides, so that a point
//! that arrives through another unit conversion (mm in a scene, m in a sweep) finds its value.

use super::Estimate;
use crate::error::ModelError;
use crate::supports::SupportSet;
use std::collections::HashMap;

/// Compliances by (support set, x, z) on a plate of `length` x `width`.
#[derive(Debug, Clone, Default)]
pub struct PointValues {
    values: HashMap<(String, i64, i64), Estimate>,
    length: f64,
    width: f64,
}

impl PointValues {
    /// An empty table for a plate of `length` x `width` (m).
    pub fn new(length: f64, width: f64) -> Self {
        Self { values: HashMap::new(), length, width }
    }

    fn key(&self, set: &str, x: f64, z: f64) -> (String, i64, i64) {
        let round = |v: f64, scale: f64| (v / scale * 1e9).round() as i64;
        (set.to_string(), round(x, self.length), round(z, self.width))
    }

    /// Stores the value of `set` at (x, z).
    pub fn insert(&mut self, set: &str, x: f64, z: f64, value: Estimate) {
        self.values.insert(self.key(set, x, z), value);
    }

    /// The value of `set` at (x, z), if computed.
    pub fn get(&self, set: &str, x: f64, z: f64) -> Option<&Estimate> {
        self.values.get(&self.key(set, x, z))
    }

    /// The value of `set` at (x, z), or the error naming what `model` did not compute.
    pub fn require(&self, model: &str, set: &SupportSet, x: f64, z: f64) -> Result<Estimate, ModelError> {
        self.get(&set.name, x, z).cloned().ok_or_else(|| {
            ModelError::Missing(format!("{model} compliance at ({x}, {z}) m for {} was not computed", set.name))
        })
    }
}
