//! The compliance of a supported plate at the impact point: the one input through which
//! any plate model (the paper's beams, or plate finite elements) feeds the energy balance.
//!
//! Under a static point load P the supported plate stores Σ_s ½ C_s P² in its energy
//! stores s (bending, cantilever, springs). The total compliance C = Σ_s C_s is the
//! deflection of the loaded point per unit force, springs included, and it is all the
//! energy balance (eqs. 14, 25, 46) needs. The split tells where the energy went.

use serde::Serialize;

/// What an energy store belongs to, for the energy ratios of Figs. 10 and 13.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StoreKind {
    /// Strain energy of the plate (beam bending, cantilever bending, plate bending).
    Plate,
    /// Energy of the support springs (props, jacks).
    Spring,
}

/// One energy store: it holds ½ `compliance` P² under the contact force P.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Store {
    /// What stores the energy ("bending", "springs", ...), for reports.
    pub name: String,
    /// Plate or spring, for the energy ratios.
    pub kind: StoreKind,
    /// m/N, finite and non-negative.
    pub compliance: f64,
}

/// A support spring and its force per unit contact force.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpringReaction {
    /// Which spring ("left spring", ...).
    pub name: String,
    /// N/N: the spring force is `per_unit_load` · P.
    pub per_unit_load: f64,
}

/// Error for a compliance that cannot be physical.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("compliance of store '{name}' is {value}: it must be finite and non-negative")]
pub struct InvalidCompliance {
    /// The store, spring or "deflection" that holds the value.
    pub name: String,
    /// The offending value (m/N, or N/N for a spring reaction).
    pub value: f64,
}

/// Compliance of the supported plate at one impact point, split into its stores.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointCompliance {
    stores: Vec<Store>,
    springs: Vec<SpringReaction>,
    deflection_per_unit_load: f64,
}

impl PointCompliance {
    /// `deflection_per_unit_load` is what the model reports as "plate deflection at the
    /// impact point" per unit force; the paper's beams exclude the rigid motion on the
    /// springs in Con 2 but include the cantilever part in Con 3 (eqs. 11 and 41), so it
    /// is not in general the total compliance.
    pub fn new(
        stores: Vec<Store>,
        springs: Vec<SpringReaction>,
        deflection_per_unit_load: f64,
    ) -> Result<Self, InvalidCompliance> {
        for s in &stores {
            if !(s.compliance.is_finite() && s.compliance >= 0.0) {
                return Err(InvalidCompliance { name: s.name.clone(), value: s.compliance });
            }
        }
        for s in &springs {
            if !s.per_unit_load.is_finite() {
                return Err(InvalidCompliance { name: s.name.clone(), value: s.per_unit_load });
            }
        }
        if !deflection_per_unit_load.is_finite() {
            return Err(InvalidCompliance { name: "deflection".into(), value: deflection_per_unit_load });
        }
        Ok(Self { stores, springs, deflection_per_unit_load })
    }

    /// C = Σ_s C_s (m/N).
    pub fn total(&self) -> f64 {
        // A fold from +0: an empty sum is 0, not the -0 that `Iterator::sum` gives for f64.
        self.stores.iter().map(|s| s.compliance).fold(0.0, |a, c| a + c)
    }

    /// Σ of the compliances of one kind of store.
    pub fn of_kind(&self, kind: StoreKind) -> f64 {
        self.stores.iter().filter(|s| s.kind == kind).map(|s| s.compliance).fold(0.0, |a, c| a + c)
    }

    /// The energy stores, each holding ½ C_s P².
    pub fn stores(&self) -> &[Store] {
        &self.stores
    }

    /// The support springs and their forces per unit contact force.
    pub fn springs(&self) -> &[SpringReaction] {
        &self.springs
    }

    /// The model's plate deflection at the impact point per unit force (m/N), see
    /// [`new`](Self::new).
    pub fn deflection_per_unit_load(&self) -> f64 {
        self.deflection_per_unit_load
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_or_nan_store_is_rejected() {
        let bad = |c| vec![Store { name: "b".into(), kind: StoreKind::Plate, compliance: c }];
        assert!(PointCompliance::new(bad(-1e-9), vec![], 0.0).is_err());
        assert!(PointCompliance::new(bad(f64::NAN), vec![], 0.0).is_err());
        assert!(PointCompliance::new(bad(f64::INFINITY), vec![], 0.0).is_err());
        assert!(PointCompliance::new(bad(0.0), vec![], 0.0).is_ok());
    }

    #[test]
    fn totals_sum_the_stores() {
        let c = PointCompliance::new(
            vec![
                Store { name: "a".into(), kind: StoreKind::Plate, compliance: 1.0 },
                Store { name: "b".into(), kind: StoreKind::Spring, compliance: 2.0 },
                Store { name: "c".into(), kind: StoreKind::Plate, compliance: 4.0 },
            ],
            vec![],
            0.0,
        )
        .unwrap();
        assert_eq!(c.total(), 7.0);
        assert_eq!(c.of_kind(StoreKind::Plate), 5.0);
        assert_eq!(c.of_kind(StoreKind::Spring), 2.0);
    }
}
