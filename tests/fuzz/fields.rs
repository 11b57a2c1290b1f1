//! The scene's numeric fields, each with its range and the hostile values tried on it.

#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![allow(dead_code)]

use super::*;

// ---------------------------------------------------------------- the numeric fields

/// A number in the scene, its allowed range and any constraint it meets in the default
/// scene beside the range (the points lie inside the plate, the thickness under the sides).
#[derive(Clone)]
pub struct Field {
    pub path: &'static str,
    pub range: Range,
    pub also: fn(f64) -> bool,
}

pub fn unconstrained(_: f64) -> bool {
    true
}

pub const POS_MM: Range = Range::closed(0.0, 458.4);

pub fn fields() -> Vec<Field> {
    let mut f = vec![
        Field { path: "restitution", range: limits::RESTITUTION, also: unconstrained },
        // The default points reach x = 458.4 mm; the thickness is 8 mm.
        // Beside the other side (360 mm and 458.4 mm) within limits::MAX_ASPECT_RATIO.
        Field {
            path: "plate.length_mm",
            range: limits::PLATE_SIZE_MM,
            also: |v| (458.4..=360.0 * limits::MAX_ASPECT_RATIO).contains(&v),
        },
        Field {
            path: "plate.width_mm",
            range: limits::PLATE_SIZE_MM,
            also: |v| (8.0..=458.4 * limits::MAX_ASPECT_RATIO).contains(&v),
        },
        Field { path: "plate.thickness_mm", range: limits::THICKNESS_MM, also: |v| v <= 360.0 },
        Field { path: "plate.youngs_modulus_gpa", range: limits::MODULUS_GPA, also: unconstrained },
        Field { path: "plate.poisson_ratio", range: POISSON_RATIO, also: unconstrained },
        Field { path: "plate.density_kg_m3", range: limits::DENSITY_KG_M3, also: unconstrained },
        Field { path: "conditions[1].spring_stiffness_n_per_m", range: limits::SPRING_N_PER_M, also: unconstrained },
        Field { path: "conditions[2].spring_stiffness_n_per_m", range: limits::SPRING_N_PER_M, also: unconstrained },
        Field { path: "velocities.m_per_s[0]", range: limits::VELOCITY_M_PER_S, also: unconstrained },
        Field { path: "velocities.m_per_s[1]", range: limits::VELOCITY_M_PER_S, also: unconstrained },
        Field { path: "points.x_mm[0]", range: POS_MM, also: unconstrained },
        Field { path: "points.x_mm[4]", range: POS_MM, also: unconstrained },
        Field { path: "points.x_mm[8]", range: POS_MM, also: unconstrained },
        Field { path: "solver.tolerance", range: limits::SOLVER_TOLERANCE, also: unconstrained },
    ];
    const BODY: [&str; 3] = ["bodies[0]", "bodies[1]", "bodies[2]"];
    for b in BODY {
        let p = |k: &str| -> &'static str { Box::leak(format!("{b}.{k}").into_boxed_str()) };
        f.extend([
            Field { path: p("density_kg_m3"), range: limits::DENSITY_KG_M3, also: unconstrained },
            Field { path: p("youngs_modulus_gpa"), range: limits::MODULUS_GPA, also: unconstrained },
            Field { path: p("poisson_ratio"), range: POISSON_RATIO, also: unconstrained },
            Field { path: p("cohesion_mpa"), range: limits::COHESION_MPA, also: unconstrained },
            Field { path: p("friction_angle_deg"), range: FRICTION_ANGLE_DEG, also: unconstrained },
            Field { path: p("radius_mm"), range: limits::RADIUS_MM, also: unconstrained },
        ]);
    }
    f
}

/// Hostile values for a field whose value in the default scene is `o`: the number line's
/// traps, the ends of the range and the numbers just past them, integers and wrong types.
pub fn hostile_values(o: f64, r: Range) -> Vec<Value> {
    let mut fl = vec![
        0.0,
        -0.0,
        -1.0,
        -o,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        5e-324,
        -5e-324,
        // The largest subnormal.
        f64::from_bits(0x000F_FFFF_FFFF_FFFF),
        f64::MIN_POSITIVE,
        1e-300,
        1e300,
        -1e300,
        f64::MAX,
        o,
        o * 1e6,
        o * 1e-6,
    ];
    for end in [r.lo, r.hi] {
        if end.is_finite() {
            fl.extend([end, next_up(end), next_down(end), end * (1.0 + 1e-9), end * (1.0 - 1e-9)]);
        }
    }
    let mut out: Vec<Value> = fl.into_iter().map(Value::Float).collect();
    out.extend([
        Value::Integer(o.round() as i64),
        Value::Integer(0),
        Value::Integer(-1),
        Value::Integer(i64::MAX),
        Value::String(format!("{o}")),
        Value::Boolean(true),
        Value::Array(vec![Value::Float(o)]),
        Value::Table(toml::Table::new()),
    ]);
    if r.hi.is_finite() && r.hi < 1e15 {
        out.push(Value::Integer(r.hi as i64 + 1));
        out.push(Value::Integer(r.hi as i64));
    }
    out
}
