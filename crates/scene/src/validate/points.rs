//! `[points]` and `[transient]`: where the bodies strike, in the plate, at most
//! [`MAX_POINTS`](crate::MAX_POINTS).

use super::{count, other, Invalid, MM};
use crate::raw::*;
use crate::{limits, MAX_POINTS};
use analytic::params::{check, Range};
use analytic::Plate;
use coupled::scene::{even_points, Points};

fn positions(field: &str, list: &[f64], range_mm: Range) -> Result<Vec<f64>, Invalid> {
    if list.is_empty() {
        return Err(other(field, "the list is empty; give at least one position"));
    }
    if list.len() > MAX_POINTS {
        return Err(other(field, format!("{} positions; at most {MAX_POINTS} are allowed", list.len())));
    }
    list.iter().enumerate().map(|(j, &v)| Ok(check(&format!("{field}[{j}]"), v, range_mm, "mm")? * MM)).collect()
}

pub(super) fn validate_points(raw: &RawPoints, plate: &Plate, l_mm: f64, b_mm: f64) -> Result<Points, Invalid> {
    let (l, b) = (plate.length(), plate.width());
    let along = Range::closed(0.0, l_mm);
    let across = Range::closed(0.0, b_mm);
    if raw.z_mm.is_some() {
        return Err(other(
            "points.z_mm",
            "z_mm beside x_mm would silently form a grid; write pairs_mm = [[x, z], ...] for explicit points, or a [points.grid] table with x_mm and z_mm for every combination",
        ));
    }
    let given = [raw.x_mm.is_some(), raw.count.is_some(), raw.pairs_mm.is_some(), raw.grid.is_some()];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(other(
            "points",
            "give exactly one of x_mm (positions on the centreline z = B/2), count (evenly spaced on the centreline), pairs_mm (explicit [x, z] pairs) or [points.grid]",
        ));
    }
    if let Some(xs) = &raw.x_mm {
        let xs = positions("points.x_mm", xs, along)?;
        return Ok(Points::Pairs { pairs: xs.into_iter().map(|x| (x, b / 2.0)).collect() });
    }
    if let Some(n) = raw.count {
        return Ok(Points::centreline(l, b, count("points.count", n, limits::POINT_COUNT)?));
    }
    if let Some(pairs) = &raw.pairs_mm {
        if pairs.is_empty() {
            return Err(other("points.pairs_mm", "the list is empty; give at least one [x, z] pair"));
        }
        if pairs.len() > MAX_POINTS {
            return Err(other("points.pairs_mm", format!("{} pairs; at most {MAX_POINTS} are allowed", pairs.len())));
        }
        let mut out = Vec::with_capacity(pairs.len());
        for (j, pair) in pairs.iter().enumerate() {
            let (x, z) = super::pair(&format!("points.pairs_mm[{j}]"), pair, "[x, z]")?;
            let x = check(&format!("points.pairs_mm[{j}][0] (x)"), x, along, "mm")? * MM;
            let z = check(&format!("points.pairs_mm[{j}][1] (z)"), z, across, "mm")? * MM;
            out.push((x, z));
        }
        return Ok(Points::Pairs { pairs: out });
    }
    let g = raw.grid.as_ref().ok_or_else(|| other("points", "no points given"))?;
    let axis = |list: &Option<Vec<f64>>, n: Option<f64>, name: &str, range: Range, extent: f64| match (list, n) {
        (Some(v), None) => positions(&format!("points.grid.{name}_mm"), v, range),
        (None, Some(n)) => {
            Ok(even_points(extent, count(&format!("points.grid.{name}_count"), n, limits::POINT_COUNT)?))
        }
        _ => Err(other(format!("points.grid.{name}"), format!("give exactly one of {name}_mm or {name}_count"))),
    };
    let x = axis(&g.x_mm, g.x_count, "x", along, l)?;
    let z = axis(&g.z_mm, g.z_count, "z", across, b)?;
    if x.len().saturating_mul(z.len()) > MAX_POINTS {
        return Err(other(
            "points.grid",
            format!("{} x {} = {} points; at most {MAX_POINTS} are allowed", x.len(), z.len(), x.len() * z.len()),
        ));
    }
    Ok(Points::Grid { x, z })
}

/// `[transient]`: the transient model's own points, as `pairs_mm`; an error names the
/// `transient.` key, not the `points.` key it is checked as.
pub(super) fn transient_points(
    t: &RawTransient,
    plate: &Plate,
    l_mm: f64,
    b_mm: f64,
) -> Result<Vec<(f64, f64)>, Invalid> {
    let as_points = RawPoints { x_mm: None, count: None, pairs_mm: Some(t.pairs_mm.clone()), grid: None, z_mm: None };
    match validate_points(&as_points, plate, l_mm, b_mm) {
        Ok(p) => Ok(p.pairs()),
        Err(Invalid::Range(mut e)) => {
            e.name = e.name.replacen("points.", "transient.", 1);
            Err(Invalid::Range(e))
        }
        Err(Invalid::Other { field, message }) => {
            Err(Invalid::Other { field: field.replacen("points.", "transient.", 1), message })
        }
    }
}
