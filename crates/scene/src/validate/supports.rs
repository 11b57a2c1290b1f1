//! `[[conditions]]`: a support set (the paper's shorthand or edges and corners one by one),
//! each spring in its range.

use super::{other, Invalid};
use crate::limits;
use crate::raw::*;
use analytic::params::check;
use analytic::Plate;
use coupled::SupportSet;
use plate_fem::{CornerSupport, EdgeSupport, Supports};

pub(super) fn validate_condition(i: usize, c: &RawCondition, plate: &Plate) -> Result<SupportSet, Invalid> {
    let key = format!("conditions[{i}].spring_stiffness_n_per_m");
    let spring = |c: &RawCondition| match c.spring_stiffness_n_per_m {
        Some(k) => Ok(check(&key, k, limits::SPRING_N_PER_M, "N/m")?),
        None => Err(other(
            &key,
            format!("is required for supports with springs; the allowed range is {} N/m", limits::SPRING_N_PER_M),
        )),
    };
    let supports = match (c.supports, c.corners.is_some() || c.edges.is_some()) {
        (Some(_), true) => {
            return Err(other(
                format!("conditions[{i}]"),
                "give either supports = \"both-fixed\" | \"both-springs\" | \"fixed-and-springs\" (the paper's Con 1-3) or [conditions.corners] / [conditions.edges], not both",
            ))
        }
        (None, false) => {
            return Err(other(
                format!("conditions[{i}]"),
                "give supports = \"both-fixed\" | \"both-springs\" | \"fixed-and-springs\", or [conditions.corners] and [conditions.edges]",
            ))
        }
        (Some(Preset::BothFixed), false) => {
            if c.spring_stiffness_n_per_m.is_some() {
                return Err(other(&key, "does not apply to supports = \"both-fixed\" (Con 1 has no springs)"));
            }
            Supports::con1()
        }
        (Some(Preset::BothSprings), false) => Supports::con2(spring(c)?),
        (Some(Preset::FixedAndSprings), false) => Supports::con3(spring(c)?),
        (None, true) => {
            if c.spring_stiffness_n_per_m.is_some() {
                return Err(other(&key, "applies only to the presets; give each spring its own spring_n_per_m in [conditions.corners]"));
            }
            let corners = c.corners.as_ref();
            let key = |name: &str| format!("conditions[{i}].corners.{name}");
            let edges = c.edges.as_ref();
            let edge = |v: Option<RawEdge>| match v {
                None | Some(RawEdge::Free) => EdgeSupport::Free,
                Some(RawEdge::SimplySupported) => EdgeSupport::Simple,
                Some(RawEdge::Clamped) => EdgeSupport::Clamped,
            };
            let s = Supports {
                corners: [
                    corner(&key("left_near"), corners.and_then(|c| c.left_near.as_ref()))?,
                    corner(&key("right_near"), corners.and_then(|c| c.right_near.as_ref()))?,
                    corner(&key("left_far"), corners.and_then(|c| c.left_far.as_ref()))?,
                    corner(&key("right_far"), corners.and_then(|c| c.right_far.as_ref()))?,
                ],
                edges: [
                    edge(edges.and_then(|e| e.left)),
                    edge(edges.and_then(|e| e.right)),
                    edge(edges.and_then(|e| e.near)),
                    edge(edges.and_then(|e| e.far)),
                ],
            };
            // A rigid-body motion left free makes every plate model singular: refuse it
            // here, before anything is assembled.
            s.validate(plate.length(), plate.width())
                .map_err(|e| other(format!("conditions[{i}]"), format!("{e}")))?;
            s
        }
    };
    let default_name = match c.supports {
        Some(p) => p.default_name().to_string(),
        None => default_set_name(i + 1),
    };
    Ok(SupportSet::new(c.name.clone().unwrap_or(default_name), supports))
}

/// One corner of `[conditions.corners]` at `field`: "fixed", "free" (also when absent) or a
/// table with exactly the key `spring_n_per_m`, in its range.
fn corner(field: &str, v: Option<&toml::Value>) -> Result<CornerSupport, Invalid> {
    const FORMS: &str = "allowed: \"fixed\", \"free\" or { spring_n_per_m = k }";
    match v {
        None => Ok(CornerSupport::Free),
        Some(toml::Value::String(s)) => match s.as_str() {
            "free" => Ok(CornerSupport::Free),
            "fixed" => Ok(CornerSupport::Fixed),
            _ => Err(other(field, format!("'{s}' is not a corner support; {FORMS}"))),
        },
        Some(toml::Value::Table(t)) => {
            if let Some(k) = t.keys().find(|k| *k != "spring_n_per_m") {
                return Err(other(
                    format!("{field}.{k}"),
                    "is not a key of a corner spring; it takes spring_n_per_m only",
                ));
            }
            let key = format!("{field}.spring_n_per_m");
            let k = match t.get("spring_n_per_m") {
                Some(toml::Value::Float(f)) => *f,
                Some(toml::Value::Integer(n)) => *n as f64,
                Some(v) => return Err(other(&key, format!("{v} is not a number"))),
                None => return Err(other(&key, format!("is required in a corner spring table; {FORMS}"))),
            };
            Ok(CornerSupport::Spring(check(&key, k, limits::SPRING_N_PER_M, "N/m")?))
        }
        Some(v) => Err(other(field, format!("{v} is not a corner support; {FORMS}"))),
    }
}
