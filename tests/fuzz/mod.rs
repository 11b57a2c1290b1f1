//! The scene fuzzer's parts: quiet panics, editing TOML by path, the numeric fields with
//! their hostile values, the mutations, and the checks every accepted scene must pass.

#![allow(dead_code)]

pub mod checks;
pub mod ensembles;
pub mod fields;
pub mod geometry;
pub mod mutations;

pub use checks::*;
pub use ensembles::*;
pub use fields::*;
pub use geometry::*;
pub use mutations::*;

pub use crate::common::scenes::edit;
use analytic::params::{Range, FRICTION_ANGLE_DEG, POISSON_RATIO};
use analytic::Method;
use coupled::plan::{fundamental_periods, run, Evidence, ModelKind, Results};
use coupled::{BeamModel, PlateModel};
use impact::present::rows::slug;
use impact::present::rows::{response_tables, yield_tables};
use impact::scene::{limits, Points, Scene, SceneSource, DEFAULT_SCENE, MAX_NAME_CHARS};
use proptest::prelude::*;
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;
use toml::Value;

// ---------------------------------------------------------------- panics, quietly

thread_local! {
    static QUIET: Cell<bool> = const { Cell::new(false) };
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// A panic hook that records panics raised inside [`guarded`] on this thread instead of
/// printing them, and leaves every other panic (a failing assertion) to the default hook.
pub fn install_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if QUIET.with(Cell::get) {
                LAST_PANIC.with(|p| *p.borrow_mut() = Some(info.to_string()));
            } else {
                default(info);
            }
        }));
    });
}

/// Runs `f`, turning a panic into its message.
pub fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    install_hook();
    QUIET.with(|q| q.set(true));
    let r = catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(false));
    r.map_err(|_| LAST_PANIC.with(|p| p.borrow_mut().take()).unwrap_or_else(|| "panic without a message".into()))
}

// ---------------------------------------------------------------- editing TOML by path

pub enum Seg {
    Key(String),
    Idx(usize),
}

/// "bodies[1].radius_mm" -> bodies, 1, radius_mm.
pub fn segments(path: &str) -> Vec<Seg> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let mut rest = part;
        if let Some(b) = rest.find('[') {
            out.push(Seg::Key(rest[..b].to_string()));
            rest = &rest[b..];
            while let Some(stripped) = rest.strip_prefix('[') {
                let e = stripped.find(']').expect("test setup: closed index");
                out.push(Seg::Idx(stripped[..e].parse().expect("test setup: numeric index")));
                rest = &stripped[e + 1..];
            }
        } else {
            out.push(Seg::Key(rest.to_string()));
        }
    }
    out
}

/// The value at `segs`, creating missing tables on the way when `create`.
pub fn walk<'a>(root: &'a mut Value, segs: &[Seg], create: bool) -> Option<&'a mut Value> {
    let mut v = root;
    for s in segs {
        v = match s {
            Seg::Key(k) => {
                let t = v.as_table_mut()?;
                if create && !t.contains_key(k) {
                    t.insert(k.clone(), Value::Table(toml::Table::new()));
                }
                t.get_mut(k)?
            }
            Seg::Idx(i) => v.as_array_mut()?.get_mut(*i)?,
        };
    }
    Some(v)
}

pub fn set(root: &mut Value, path: &str, value: Value) {
    let segs = segments(path);
    let (last, parent) = segs.split_last().expect("non-empty path");
    let Some(p) = walk(root, parent, true) else { return };
    match last {
        Seg::Key(k) => {
            if let Some(t) = p.as_table_mut() {
                t.insert(k.clone(), value);
            }
        }
        Seg::Idx(i) => {
            if let Some(a) = p.as_array_mut() {
                if *i < a.len() {
                    a[*i] = value;
                } else {
                    a.push(value);
                }
            }
        }
    }
}

pub fn remove(root: &mut Value, path: &str) {
    let segs = segments(path);
    let (last, parent) = segs.split_last().expect("non-empty path");
    let Some(p) = walk(root, parent, false) else { return };
    match last {
        Seg::Key(k) => {
            if let Some(t) = p.as_table_mut() {
                t.remove(k);
            }
        }
        Seg::Idx(i) => {
            if let Some(a) = p.as_array_mut() {
                if *i < a.len() {
                    a.remove(*i);
                }
            }
        }
    }
}

pub fn get(root: &Value, path: &str) -> Option<Value> {
    let mut r = root.clone();
    walk(&mut r, &segments(path), false).cloned()
}

pub fn default_value() -> Value {
    Value::Table(toml::from_str(&base()).expect("the default scene is TOML"))
}

/// The default scene without its [transient] points: the mutations change the plate's size,
/// and fixed transient points would then fall off it (a refusal, but not the one studied).
pub fn base() -> String {
    let start = DEFAULT_SCENE.find("[transient]").expect("the default scene has transient points");
    let end = start + DEFAULT_SCENE[start..].find("[velocities]").expect("velocities follow");
    format!("{}{}", &DEFAULT_SCENE[..start], &DEFAULT_SCENE[end..])
}

pub fn num(v: &Value) -> Option<f64> {
    match v {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

pub fn next_up(v: f64) -> f64 {
    if v == 0.0 {
        f64::from_bits(1)
    } else if v > 0.0 {
        f64::from_bits(v.to_bits() + 1)
    } else {
        f64::from_bits(v.to_bits() - 1)
    }
}

pub fn next_down(v: f64) -> f64 {
    -next_up(-v)
}
