//! The reference against the parser: every key of every raw table described, the parser's
//! ranges and the default scene shown.

use super::*;
use crate::ensemble::{RawEnsemble, RawFamily, RawPlacement, RawRegion};
use crate::raw::{RawGroupSpring, RawHold, RawJack, RawShellMesh, RawTailBeam};
use crate::validate::measurement::{
    RawAcceleration, RawAntiAlias, RawMeasurement, RawSensor, RawStrain, RawSupportForce,
};
use crate::validate::stream::RawStream;
use crate::{
    RawBody, RawCondition, RawCorners, RawEdges, RawGrid, RawPlate, RawPlateDamping, RawPoints, RawScene, RawSignals,
    RawSolver, RawTransient, RawVelocities,
};
use serde::de::{self, Visitor};
use serde::Deserialize;
use std::collections::BTreeSet;

/// A deserializer that only records the field names a derived `Deserialize` asks for.
struct Recorder<'a>(&'a mut &'static [&'static str]);

impl<'de> de::Deserializer<'de> for Recorder<'_> {
    type Error = de::value::Error;
    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(de::Error::custom("not a struct"))
    }
    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        fields: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Self::Error> {
        *self.0 = fields;
        Err(de::Error::custom("recorded"))
    }
    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf option
        unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier ignored_any
    }
}

/// The keys a raw table accepts, from its serde derive.
fn fields<T: for<'de> Deserialize<'de>>() -> BTreeSet<&'static str> {
    let mut names: &'static [&'static str] = &[];
    let _ = T::deserialize(Recorder(&mut names));
    names.iter().copied().collect()
}

#[test]
fn every_key_of_every_table_is_described_and_nothing_else() {
    let tables = [
        ("Top level", fields::<RawScene>()),
        ("[plate]", fields::<RawPlate>()),
        ("[[bodies]]", fields::<RawBody>()),
        ("[[conditions]]", fields::<RawCondition>()),
        ("[conditions.corners]", fields::<RawCorners>()),
        ("[conditions.edges]", fields::<RawEdges>()),
        ("[points]", fields::<RawPoints>()),
        ("[points.grid]", fields::<RawGrid>()),
        ("[velocities]", fields::<RawVelocities>()),
        ("[solver]", fields::<RawSolver>()),
        ("[transient]", fields::<RawTransient>()),
        ("[signals]", fields::<RawSignals>()),
        ("[plate_damping]", fields::<RawPlateDamping>()),
        ("[ensemble]", fields::<RawEnsemble>()),
        ("[ensemble.region]", fields::<RawRegion>()),
        ("[ensemble.placement]", fields::<RawPlacement>()),
        ("[[ensemble.families]]", fields::<RawFamily>()),
        ("[measurement]", fields::<RawMeasurement>()),
        ("[measurement.sensor]", fields::<RawSensor>()),
        ("[measurement.anti_alias]", fields::<RawAntiAlias>()),
        ("[measurement.acceleration]", fields::<RawAcceleration>()),
        ("[measurement.strain]", fields::<RawStrain>()),
        ("[measurement.support_force]", fields::<RawSupportForce>()),
        ("[stream]", fields::<RawStream>()),
        ("[tail_beam]", fields::<RawTailBeam>()),
        ("[[tail_beam.jacks]]", fields::<RawJack>()),
        ("[shell_mesh]", fields::<RawShellMesh>()),
        ("[[shell_mesh.holds]]", fields::<RawHold>()),
        ("[[shell_mesh.springs]]", fields::<RawGroupSpring>()),
    ];
    let sections = sections();
    let titles: Vec<&str> = sections.iter().map(|s| s.title).collect();
    assert_eq!(titles, tables.iter().map(|(t, _)| *t).collect::<Vec<_>>(), "one section per raw table");
    for (s, (title, accepted)) in sections.iter().zip(&tables) {
        assert!(!accepted.is_empty(), "{title}: no fields recorded");
        let described: BTreeSet<&str> = s.keys.iter().map(|k| k.name).collect();
        assert_eq!(&described, accepted, "{title}: the keys described against the keys the parser accepts");
    }
}

#[test]
fn the_reference_shows_the_parsers_ranges_and_the_default_scene() {
    let md = markdown();
    assert!(md.contains(&format!("| `restitution` | number | - | {} |", limits::RESTITUTION)));
    let iterations = format!("| {} | {} |", limits::SOLVER_ITERATIONS, default_max_iterations());
    assert!(md.contains(&format!("| `max_iterations` | whole number | - {iterations}")), "{md}");
    assert!(md.contains(r#"| `supports` | string | - | `"both-fixed"` (Con 1), `"both-springs"` (Con 2), `"fixed-and-springs"` (Con 3) |"#));
    assert!(md.ends_with(&format!("```toml\n{DEFAULT_SCENE}```\n")));
}
