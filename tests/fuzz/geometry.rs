//! Mutations of where the bodies strike and how the plate is held: points and support sets.

#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![allow(dead_code)]

use super::*;

pub fn points_op() -> impl Strategy<Value = Op> {
    let xs = prop::collection::vec(prop::sample::select(position_values(458.4)), 0..5);
    let zs = prop::collection::vec(prop::sample::select(position_values(360.0)), 0..5);
    let counts = prop::sample::select(vec![
        f(0.0),
        f(1.0),
        f(2.0),
        f(3.0),
        f(2.5),
        f(-2.0),
        f(f64::NAN),
        f(1e300),
        f(100_000.0),
        f(100_001.0),
        Value::Integer(4),
        Value::Integer(1_000_000),
        Value::String("3".into()),
    ]);
    let pair = (prop::sample::select(position_values(458.4)), prop::sample::select(position_values(360.0)))
        .prop_map(|(x, z)| arr(vec![x, z]));
    let bad_pair =
        prop::sample::select(vec![arr(vec![f(1.0)]), arr(vec![f(1.0), f(2.0), f(3.0)]), arr(vec![]), f(1.0)]);
    let layout = (0..9usize, xs, zs, counts.clone(), counts, prop::collection::vec(pair, 0..5), bad_pair);
    layout.prop_map(|(kind, xs, zs, c1, c2, pairs, bad)| {
        let (t, what) = points_table(kind, xs, zs, c1, c2, pairs, bad);
        let v = Value::Table(t);
        Op {
            label: format!("points = {what}: {v}"),
            hints: keys(&["points", "x_mm", "z_mm", "count", "pairs_mm", "grid", "x_count", "z_count"]),
            expect: Expect::Unknown,
            edit: Edit::Set("points".into(), v),
        }
    })
}

/// The `[points]` table of layout `kind` (a list, a count, pairs, grids, and the mixtures a
/// scene must refuse), with its description.
#[allow(clippy::too_many_arguments)]
fn points_table(
    kind: usize,
    xs: Vec<Value>,
    zs: Vec<Value>,
    c1: Value,
    c2: Value,
    pairs: Vec<Value>,
    bad: Value,
) -> (toml::Table, &'static str) {
    let mut t = toml::Table::new();
    let what = match kind {
        0 => {
            t.insert("x_mm".into(), arr(xs));
            "x_mm"
        }
        1 => {
            t.insert("count".into(), c1);
            "count"
        }
        2 => {
            t.insert("pairs_mm".into(), arr(pairs));
            "pairs_mm"
        }
        3 => {
            let mut g = toml::Table::new();
            g.insert("x_mm".into(), arr(xs));
            g.insert("z_mm".into(), arr(zs));
            t.insert("grid".into(), Value::Table(g));
            "grid of lists"
        }
        4 => {
            let mut g = toml::Table::new();
            g.insert("x_count".into(), c1);
            g.insert("z_count".into(), c2);
            t.insert("grid".into(), Value::Table(g));
            "grid of counts"
        }
        5 => {
            let mut g = toml::Table::new();
            g.insert("x_mm".into(), arr(xs));
            g.insert("x_count".into(), c1);
            g.insert("z_count".into(), c2);
            t.insert("grid".into(), Value::Table(g));
            "grid with x twice"
        }
        6 => {
            t.insert("x_mm".into(), arr(xs));
            t.insert("z_mm".into(), arr(zs));
            "x_mm beside z_mm"
        }
        7 => {
            t.insert("x_mm".into(), arr(xs));
            t.insert("count".into(), c1);
            "x_mm and count"
        }
        _ => {
            let mut p = pairs;
            p.push(bad);
            t.insert("pairs_mm".into(), arr(p));
            "pairs with a malformed pair"
        }
    };
    (t, what)
}

pub fn spring_values() -> Vec<Value> {
    vec![
        f(1e-6),
        f(1e18),
        f(1e6),
        f(5.11545e8),
        f(0.0),
        f(-1.0),
        f(f64::NAN),
        f(f64::INFINITY),
        f(5e-324),
        f(next_down(1e-6)),
        f(next_up(1e18)),
        f(1e300),
        Value::Integer(1_000_000),
        Value::String("1e6".into()),
    ]
}

pub fn corner_strategy() -> impl Strategy<Value = Option<Value>> {
    let spring = prop::sample::select(spring_values());
    (0..8usize, spring).prop_map(|(k, s)| match k {
        0 | 1 => None,
        2 => Some(Value::String("fixed".into())),
        3 => Some(Value::String("free".into())),
        4 | 5 => {
            let mut t = toml::Table::new();
            t.insert("spring_n_per_m".into(), s);
            Some(Value::Table(t))
        }
        6 => Some(Value::String("pinned".into())),
        _ => {
            let mut t = toml::Table::new();
            t.insert("spring_n_per_m".into(), s);
            t.insert("damping".into(), f(1.0));
            Some(Value::Table(t))
        }
    })
}

pub fn edge_strategy() -> impl Strategy<Value = Option<Value>> {
    prop::sample::select(vec![None, None, Some("free"), Some("simply-supported"), Some("clamped"), Some("hinged")])
        .prop_map(|e| e.map(|s| Value::String(s.into())))
}

pub fn condition_strategy() -> impl Strategy<Value = Value> {
    let preset = (
        prop::sample::select(vec!["both-fixed", "both-springs", "fixed-and-springs", "pinned"]),
        prop::option::of(prop::sample::select(spring_values())),
    );
    let corners = prop::collection::vec(corner_strategy(), 4);
    let edges = prop::collection::vec(edge_strategy(), 4);
    let names = prop::sample::select(vec![None, Some("set"), Some("Con 1"), Some("con 1"), Some(""), Some("props")]);
    (any::<bool>(), preset, corners, edges, names).prop_map(|(general, (p, k), corners, edges, name)| {
        let mut t = toml::Table::new();
        if let Some(n) = name {
            t.insert("name".into(), Value::String(n.into()));
        }
        if general {
            let mut c = toml::Table::new();
            for (key, v) in ["left_near", "right_near", "left_far", "right_far"].iter().zip(corners) {
                if let Some(v) = v {
                    c.insert((*key).into(), v);
                }
            }
            let mut e = toml::Table::new();
            for (key, v) in ["left", "right", "near", "far"].iter().zip(edges) {
                if let Some(v) = v {
                    e.insert((*key).into(), v);
                }
            }
            t.insert("corners".into(), Value::Table(c));
            t.insert("edges".into(), Value::Table(e));
        } else {
            t.insert("supports".into(), Value::String(p.into()));
            if let Some(k) = k {
                t.insert("spring_stiffness_n_per_m".into(), k);
            }
        }
        Value::Table(t)
    })
}

pub fn conditions_op() -> impl Strategy<Value = Op> {
    prop::collection::vec(condition_strategy(), 0..4).prop_map(|list| {
        let v = arr(list);
        Op {
            label: format!("conditions = {v}"),
            // A TOML error inside a support set names the key and shows its line.
            hints: keys(&[
                "conditions",
                "supports",
                "spring_stiffness_n_per_m",
                "corners",
                "edges",
                "left_near",
                "right_near",
                "left_far",
                "right_far",
                "left",
                "right",
                "near",
                "far",
                "spring_n_per_m",
                "damping",
                "name",
            ]),
            expect: Expect::Unknown,
            edit: Edit::Set("conditions".into(), v),
        }
    })
}
