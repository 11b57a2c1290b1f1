//! Mutations of the default scene: numbers, names, missing and unknown keys, velocities,
//! analyses, the solver and the extremes.

#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![allow(dead_code)]

use super::*;

// ---------------------------------------------------------------- mutations

/// What a mutation says about the scene, when it is the only one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Expect {
    Accept,
    Reject,
    Unknown,
}

#[derive(Debug, Clone)]
pub enum Edit {
    Set(String, Value),
    Remove(String),
    /// In-range extremes, then the points moved to the plate's corners and centre and the
    /// thickness capped by the smaller side (so the scene stays valid).
    Extremes(Vec<(String, f64)>),
}

#[derive(Debug, Clone)]
pub struct Op {
    pub label: String,
    /// Any of these in a refusal shows the field.
    pub hints: Vec<String>,
    pub expect: Expect,
    pub edit: Edit,
}

pub fn apply(root: &mut Value, edit: &Edit) {
    match edit {
        Edit::Set(p, v) => set(root, p, v.clone()),
        Edit::Remove(p) => remove(root, p),
        Edit::Extremes(list) => {
            for (p, v) in list {
                set(root, p, Value::Float(*v));
            }
            let side = |k| get(root, k).as_ref().and_then(num).unwrap_or(1.0);
            let (l, b) = (side("plate.length_mm"), side("plate.width_mm"));
            if side("plate.thickness_mm") > l.min(b) {
                set(root, "plate.thickness_mm", Value::Float(l.min(b)));
            }
            let pair = |x: f64, z: f64| Value::Array(vec![Value::Float(x), Value::Float(z)]);
            let pairs = vec![pair(0.0, 0.0), pair(l, b), pair(l / 2.0, b / 2.0), pair(l, 0.0)];
            let mut pts = toml::Table::new();
            pts.insert("pairs_mm".into(), Value::Array(pairs));
            set(root, "points", Value::Table(pts));
        }
    }
}

/// The last key of a path ("bodies[1].radius_mm" -> "radius_mm").
pub fn leaf(path: &str) -> String {
    let last = path.rsplit('.').next().unwrap_or(path);
    last.split('[').next().unwrap_or(last).to_string()
}

pub fn number_op(fields: &'static [Field], base: &'static Value) -> impl Strategy<Value = Op> {
    (0..fields.len(), any::<prop::sample::Index>()).prop_map(move |(fi, pick)| {
        let f = &fields[fi];
        let o = get(base, f.path).as_ref().and_then(num).unwrap_or(1e-13);
        let values = hostile_values(o, f.range);
        let v = pick.get(&values).clone();
        let expect = match num(&v) {
            Some(x) if matches!(v, Value::Float(_) | Value::Integer(_)) => {
                if f.range.contains(x) && (f.also)(x) {
                    Expect::Accept
                } else {
                    Expect::Reject
                }
            }
            _ => Expect::Reject,
        };
        let mut hints = vec![f.path.to_string(), leaf(f.path)];
        // A smaller plate moves the points off it or under the thickness.
        hints.extend(["points.x_mm".into(), "plate.thickness_mm".into()]);
        Op { label: format!("{} = {v:?}", f.path), hints, expect, edit: Edit::Set(f.path.into(), v) }
    })
}

pub fn name_values() -> Vec<(Value, &'static str)> {
    vec![
        (Value::String(String::new()), "empty"),
        (Value::String("   ".into()), "blank"),
        (Value::String("\t\n".into()), "whitespace"),
        (Value::String("x".repeat(10_000)), "long"),
        (Value::String("é".repeat(5_000)), "long multibyte"),
        (Value::String("coal".into()), "coal"),
        (Value::String("COAL".into()), "case of coal"),
        (Value::String("Coal".into()), "case of coal"),
        (Value::String("coal.".into()), "punctuated coal"),
        (Value::String("coal ".into()), "coal with a space"),
        (Value::String("gangue 1".into()), "gangue 1"),
        (Value::String("gangue-1".into()), "gangue-1"),
        (Value::String("gangue_1".into()), "gangue_1"),
        (Value::String("Con 1".into()), "Con 1"),
        (Value::String("Con 2".into()), "Con 2"),
        (Value::String("con 1".into()), "con 1"),
        (Value::String("a|b".into()), "pipe"),
        (Value::String("a,b\"c".into()), "comma and quote"),
        (Value::String("line\nbreak".into()), "newline"),
        (Value::String("\u{0}\u{7}".into()), "control characters"),
        (Value::String("😀 rock".into()), "emoji"),
        (Value::Integer(1), "integer"),
        (Value::Float(1.5), "float"),
        (Value::Boolean(false), "bool"),
    ]
}

pub fn name_op() -> impl Strategy<Value = Op> {
    let targets = [
        "name",
        "bodies[0].name",
        "bodies[1].name",
        "bodies[2].name",
        "conditions[0].name",
        "conditions[1].name",
        "conditions[2].name",
        "description",
    ];
    (0..targets.len(), 0..name_values().len()).prop_map(move |(ti, vi)| {
        let path = targets[ti];
        let (v, what) = name_values().swap_remove(vi);
        let expect = match &v {
            Value::String(_) if path == "description" => Expect::Accept,
            Value::String(s) if s.trim().is_empty() => Expect::Reject,
            Value::String(s) => {
                let others: &[&str] = match path {
                    "bodies[0].name" => &["gangue 1", "gangue 2"],
                    "bodies[1].name" => &["coal", "gangue 2"],
                    "bodies[2].name" => &["coal", "gangue 1"],
                    "conditions[0].name" => &["Con 2", "Con 3"],
                    "conditions[1].name" => &["Con 1", "Con 3"],
                    "conditions[2].name" => &["Con 1", "Con 2"],
                    _ => &[],
                };
                // Names title tables and files: at most MAX_NAME_CHARS characters, with a
                // letter or digit, and distinct from the others after reduction to a file stem.
                let stem = slug(s);
                if s.chars().count() > MAX_NAME_CHARS || stem.is_empty() || others.iter().any(|o| slug(o) == stem) {
                    Expect::Reject
                } else {
                    Expect::Accept
                }
            }
            _ => Expect::Reject,
        };
        Op {
            label: format!("{path} = {what}"),
            hints: vec![path.into(), leaf(path)],
            expect,
            edit: Edit::Set(path.into(), v),
        }
    })
}

pub fn missing_op() -> impl Strategy<Value = Op> {
    let keys: Vec<(&str, Expect)> = vec![
        ("name", Expect::Reject),
        ("description", Expect::Accept),
        ("restitution", Expect::Reject),
        ("analyses", Expect::Accept),
        ("plate", Expect::Reject),
        ("plate.length_mm", Expect::Reject),
        ("plate.width_mm", Expect::Reject),
        ("plate.thickness_mm", Expect::Reject),
        ("plate.youngs_modulus_gpa", Expect::Reject),
        ("plate.poisson_ratio", Expect::Reject),
        ("plate.density_kg_m3", Expect::Reject),
        ("bodies", Expect::Reject),
        ("bodies[1].name", Expect::Reject),
        ("bodies[1].radius_mm", Expect::Reject),
        ("bodies[2].cohesion_mpa", Expect::Reject),
        ("bodies[0].friction_angle_deg", Expect::Reject),
        ("conditions", Expect::Reject),
        ("conditions[0].name", Expect::Accept),
        ("conditions[1].name", Expect::Accept),
        ("conditions[0].supports", Expect::Reject),
        ("conditions[1].spring_stiffness_n_per_m", Expect::Reject),
        ("points", Expect::Reject),
        ("points.x_mm", Expect::Reject),
        ("velocities", Expect::Reject),
        ("velocities.m_per_s", Expect::Reject),
    ];
    (0..keys.len()).prop_map(move |i| {
        let (path, expect) = keys[i];
        let parent = path.rsplit_once('.').map_or("", |(p, _)| p);
        let parent = parent.split('[').next().unwrap_or("").to_string();
        let mut hints = vec![path.to_string(), leaf(path)];
        if !parent.is_empty() {
            hints.push(parent);
        }
        Op { label: format!("remove {path}"), hints, expect, edit: Edit::Remove(path.into()) }
    })
}

pub fn unknown_key_op() -> impl Strategy<Value = Op> {
    let places = ["", "plate.", "bodies[1].", "conditions[0].", "points.", "velocities.", "solver."];
    let keys = ["widht_mm", "colour", "Length_mm", "length-mm", "x", "spring"];
    (0..places.len(), 0..keys.len()).prop_map(move |(p, k)| {
        let path = format!("{}{}", places[p], keys[k]);
        Op {
            label: format!("unknown key {path}"),
            hints: vec![keys[k].into()],
            expect: Expect::Reject,
            edit: Edit::Set(path, Value::Float(1.0)),
        }
    })
}

pub fn keys(k: &[&str]) -> Vec<String> {
    k.iter().map(|s| s.to_string()).collect()
}

pub fn f(v: f64) -> Value {
    Value::Float(v)
}

pub fn arr(v: Vec<Value>) -> Value {
    Value::Array(v)
}

/// Positions along a default-plate axis of length `extent` mm, on, near and past its ends.
pub fn position_values(extent: f64) -> Vec<Value> {
    vec![
        f(0.0),
        f(-0.0),
        f(extent),
        f(extent / 2.0),
        f(next_up(extent)),
        f(-1e-12),
        f(5e-324),
        f(f64::NAN),
        f(1e300),
        Value::Integer(extent as i64),
        Value::Integer(0),
        Value::String("0".into()),
    ]
}

pub fn velocities_op() -> impl Strategy<Value = Op> {
    let vel = prop::sample::select(vec![
        f(1e-9),
        f(1e3),
        f(next_down(1e-9)),
        f(next_up(1e3)),
        f(0.008),
        f(0.0),
        f(-0.008),
        f(f64::NAN),
        f(f64::INFINITY),
        f(5e-324),
        f(1e300),
        Value::Integer(1),
        Value::String("fast".into()),
    ]);
    (prop::collection::vec(vel, 0..4), any::<bool>()).prop_map(|(list, drop)| {
        if drop {
            Op {
                label: "remove velocities".into(),
                hints: vec!["velocities".into()],
                expect: Expect::Reject,
                edit: Edit::Remove("velocities".into()),
            }
        } else {
            let v = arr(list);
            Op {
                label: format!("velocities.m_per_s = {v}"),
                hints: keys(&["velocities", "m_per_s"]),
                expect: Expect::Unknown,
                edit: Edit::Set("velocities.m_per_s".into(), v),
            }
        }
    })
}

pub fn analyses_op() -> impl Strategy<Value = Op> {
    let entry = prop::sample::select(vec!["responses", "yield-velocity", "width-maps", "bogus", "Responses"]);
    prop::collection::vec(entry, 0..4).prop_map(|list| {
        let v = arr(list.iter().map(|s| Value::String((*s).into())).collect());
        Op {
            label: format!("analyses = {v}"),
            hints: vec!["analyses".into()],
            expect: Expect::Unknown,
            edit: Edit::Set("analyses".into(), v),
        }
    })
}

pub fn solver_op() -> impl Strategy<Value = Op> {
    let method = prop::sample::select(vec!["recursion", "bracketed", "newton"]);
    let iters = prop::sample::select(vec![
        Value::Integer(0),
        Value::Integer(1),
        Value::Integer(2),
        Value::Integer(10_000),
        Value::Integer(10_001),
        Value::Integer(-1),
        Value::Integer(4_294_967_296),
        f(200.0),
        Value::String("200".into()),
    ]);
    (method, prop::option::of(iters)).prop_map(|(m, it)| {
        let mut t = toml::Table::new();
        t.insert("method".into(), Value::String(m.into()));
        if let Some(it) = it {
            t.insert("max_iterations".into(), it);
        }
        let v = Value::Table(t);
        Op {
            label: format!("solver = {v}"),
            hints: vec!["solver".into(), "method".into(), "max_iterations".into()],
            expect: Expect::Unknown,
            edit: Edit::Set("solver".into(), v),
        }
    })
}

/// Realistic extremes, all inside their ranges: a thin film or a slab, a huge sphere on a
/// small plate, springs of 1e-3 and 1e18 N/m, velocities at their ends.
pub fn extremes_op() -> impl Strategy<Value = Op> {
    let choices: Vec<(&'static str, Vec<f64>)> = vec![
        // Sides whose ratio stays within limits::MAX_ASPECT_RATIO whatever the pairing.
        ("plate.length_mm", vec![50.0, 1e3, 458.4]),
        ("plate.width_mm", vec![10.0, 1e3, 360.0]),
        ("plate.thickness_mm", vec![1e-3, 10.0, 8.0]),
        ("plate.youngs_modulus_gpa", vec![1e-6, 1e4]),
        ("plate.poisson_ratio", vec![1e-9, 0.499_999_9]),
        ("plate.density_kg_m3", vec![1.0, 1e5]),
        ("bodies[0].radius_mm", vec![1e-3, 1e4]),
        ("bodies[0].youngs_modulus_gpa", vec![1e-6, 1e4]),
        ("bodies[0].density_kg_m3", vec![1.0, 1e5]),
        ("bodies[0].cohesion_mpa", vec![1e-6, 1e5]),
        ("bodies[0].friction_angle_deg", vec![1e-9, 89.999_999]),
        ("bodies[0].poisson_ratio", vec![1e-9, 0.499_999_9]),
        ("bodies[1].radius_mm", vec![1e4]),
        ("restitution", vec![0.010_000_001, 1.0]),
        ("conditions[1].spring_stiffness_n_per_m", vec![1e-3, 1e18]),
        ("conditions[2].spring_stiffness_n_per_m", vec![1e-3, 1e18]),
        ("velocities.m_per_s[0]", vec![1e-9, 1e3]),
        ("velocities.m_per_s[1]", vec![1e-9, 1e3]),
        ("solver.tolerance", vec![1e-14, 1e-3]),
    ];
    let n = choices.len();
    prop::collection::vec((0..n, any::<prop::sample::Index>()), 1..7).prop_map(move |picks| {
        let list: Vec<(String, f64)> = picks
            .into_iter()
            .map(|(i, k)| {
                let (p, vs) = &choices[i];
                (p.to_string(), *k.get(vs))
            })
            .collect();
        let label = list.iter().map(|(p, v)| format!("{p} = {v:e}")).collect::<Vec<_>>().join(", ");
        Op {
            label: format!("extremes: {label}; points at corners and centre"),
            hints: vec!["plate".into(), "points".into()],
            expect: Expect::Accept,
            edit: Edit::Extremes(list),
        }
    })
}

pub fn op_strategy() -> impl Strategy<Value = Op> {
    let fields: &'static [Field] = Box::leak(fields().into_boxed_slice());
    let base: &'static Value = Box::leak(Box::new(default_value()));
    prop_oneof![
        6 => number_op(fields, base),
        2 => name_op(),
        1 => missing_op(),
        1 => unknown_key_op(),
        2 => points_op(),
        2 => conditions_op(),
        1 => velocities_op(),
        1 => analyses_op(),
        1 => solver_op(),
        3 => extremes_op(),
    ]
}
