//! Scene files: what to compute, in TOML with units in the key names, validated once into
//! a [`Scene`] in SI units. Every error names the TOML field, the value as written and its
//! allowed range; ranges are checked in the file's units and chosen so that nothing
//! overflows or underflows after conversion to SI (a length of 1e300 mm is refused, not
//! turned into inf).

use analytic::InvalidParameter;
pub use coupled::scene::{even_points, Analysis, Points, Scene};
pub use coupled::SupportSet;
use raw::*;
use std::path::Path;
use validate::{check_name, count, other, pair, validate, Invalid};

pub mod drops;
mod ensemble;
pub mod limits;
mod raw;
pub mod reference;
mod validate;
pub use ensemble::{CANDIDATES_PER_SIDE, FALL_HEIGHT_M, FAMILY_COUNT, MAX_CANDIDATES_PER_SIDE, MAX_IMPACTS};

/// The embedded default scene: the paper's Table 1.
pub const DEFAULT_SCENE: &str = include_str!("../../../scenes/paper-table-1.toml");
/// How the default scene is named in messages.
pub const DEFAULT_ORIGIN: &str = "<default scene: paper Table 1>";
/// Largest scene file read, bytes: a scene is a few kilobytes; anything near this is not one.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;
/// Most impact points a scene may name (each costs one solve per mesh and one balance per
/// body, velocity and model; 1e5 points stay well inside this machine's memory).
pub const MAX_POINTS: usize = 100_000;

/// Longest name of a scene, body or support set, in characters: names title tables and
/// plots, and a name is not a description.
pub const MAX_NAME_CHARS: usize = 200;

/// An invalid scene, with where it came from.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene file {path}: {source}")]
    Read { path: String, source: std::io::Error },
    /// The file is not one a scene can be (a device, a FIFO, a directory, too large).
    #[error("scene file {path}: {message}")]
    NotAFile { path: String, message: String },
    /// TOML syntax or layout.
    #[error("scene {origin}: {message}")]
    Syntax {
        origin: String,
        /// The parser's message with the offending line shown.
        message: String,
        /// The same without the line ("unknown field `colour`, expected one of ...").
        reason: String,
        /// Byte range of the offending key or value in the text, where the parser knows it.
        span: Option<std::ops::Range<usize>>,
    },
    /// A value outside its range.
    #[error("scene {origin}: {source}")]
    OutOfRange { origin: String, source: InvalidParameter },
    /// Values that do not fit together.
    #[error("scene {origin}: {field}: {message}")]
    Inconsistent { origin: String, field: String, message: String },
}

/// Reading a [`Scene`] from scene text or files.
pub trait SceneSource: Sized {
    /// The embedded default scene (the paper's Table 1).
    fn default_scene() -> Self;
    /// Reads and validates a scene file (a regular file of at most [`MAX_SCENE_BYTES`]).
    fn load(path: &Path) -> Result<Self, SceneError>;
    /// Parses and validates scene text; `origin` names it in errors.
    fn parse(text: &str, origin: &str) -> Result<Self, SceneError>;
}

impl SceneSource for Scene {
    fn default_scene() -> Self {
        // The embedded text is part of the program and is checked by a test; a failure
        // here is a build defect, not a user error.
        Self::parse(DEFAULT_SCENE, DEFAULT_ORIGIN).expect("the embedded default scene is valid")
    }

    fn load(path: &Path) -> Result<Self, SceneError> {
        let shown = path.display().to_string();
        let meta = std::fs::metadata(path).map_err(|source| SceneError::Read { path: shown.clone(), source })?;
        if !meta.is_file() {
            return Err(SceneError::NotAFile {
                path: shown,
                message: "is not a regular file (a directory, device or FIFO cannot hold a scene)".into(),
            });
        }
        if meta.len() > MAX_SCENE_BYTES {
            return Err(SceneError::NotAFile {
                path: shown,
                message: format!("is {} bytes; a scene file has at most {MAX_SCENE_BYTES} bytes", meta.len()),
            });
        }
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read { path: shown.clone(), source })?;
        parse_in(&text, &shown, path.parent())
    }

    fn parse(text: &str, origin: &str) -> Result<Self, SceneError> {
        parse_in(text, origin, None)
    }
}

/// Parses and validates scene text read from a file in `folder`: the files it names (a
/// measured PSD) are read relative to that folder, as [`SceneSource::load`] reads them (a
/// scene's text sent to another process, read there).
pub fn parse_in_folder(text: &str, origin: &str, folder: &Path) -> Result<Scene, SceneError> {
    parse_in(text, origin, Some(folder))
}

/// Parses and validates scene text; files it names (a measured PSD) are read relative to
/// `base`, the scene file's folder (the working folder when None).
fn parse_in(text: &str, origin: &str, base: Option<&Path>) -> Result<Scene, SceneError> {
    parse_with(text, origin, base, &[])
}

/// Parses and validates scene text whose mesh file (`[shell_mesh] file`) is one of
/// `embedded` (name as the scene writes it, contents): a scene shipped inside the program
/// with its mesh.
pub fn parse_with_files(text: &str, origin: &str, embedded: &[(&str, &str)]) -> Result<Scene, SceneError> {
    parse_with(text, origin, None, embedded)
}

fn parse_with(text: &str, origin: &str, base: Option<&Path>, embedded: &[(&str, &str)]) -> Result<Scene, SceneError> {
    let mut raw: RawScene = toml::from_str(text).map_err(|e| SceneError::Syntax {
        origin: origin.to_string(),
        message: e.to_string().trim_end().to_string(),
        reason: e.message().trim_end().to_string(),
        span: e.span(),
    })?;
    let read = match raw.measurement.as_mut() {
        Some(m) => validate::measurement::read_psd_files(m, base),
        None => Ok(()),
    };
    let read = read.and_then(|()| match raw.shell_mesh.as_mut() {
        Some(m) => validate::shell_mesh::read_file(m, base, embedded),
        None => Ok(()),
    });
    read.and_then(|()| validate(raw)).map_err(|e| match e {
        Invalid::Range(source) => SceneError::OutOfRange { origin: origin.to_string(), source },
        Invalid::Other { field, message } => SceneError::Inconsistent { origin: origin.to_string(), field, message },
    })
}

/// A length in metres as millimetres with one decimal, the trailing ".0" dropped: how a
/// sensor's position names its channels (report rankings, CSV fields, Python columns).
pub fn mm_label(v: f64) -> String {
    let t = format!("{:.1}", v * 1e3);
    t.strip_suffix(".0").map_or(t.clone(), str::to_string)
}

/// The first sensor (by index) whose label, (x, z) at [`mm_label`]'s 0.1 mm, is an earlier
/// sensor's: `(earlier, later, label)`. Two such sensors would share every column name.
pub fn sensor_label_clash(sensors: &[(f64, f64)]) -> Option<(usize, usize, String)> {
    let mut seen = std::collections::HashMap::new();
    for (j, &(x, z)) in sensors.iter().enumerate() {
        let label = format!("({}, {}) mm", mm_label(x), mm_label(z));
        if let Some(&i) = seen.get(&label) {
            return Some((i, j, label));
        }
        seen.insert(label, j);
    }
    None
}

/// [`sensor_label_clash`] as both readers of sensors refuse it (the scene's
/// `signals.sensors_mm`, Python's `sensors_mm` argument): the later sensor's field in `list`
/// and the message.
pub fn sensor_label_refusal(list: &str, sensors: &[(f64, f64)]) -> Option<(String, String)> {
    sensor_label_clash(sensors).map(|(i, j, label)| {
        (
            format!("{list}[{j}]"),
            format!("is labelled {label} like {list}[{i}] (channel names give positions to 0.1 mm); place the sensors at least 0.1 mm apart"),
        )
    })
}

/// The file-name stem of a display name: lower-case ASCII letters and digits, every other run
/// of characters one `-`, no `-` at either end. Two names are distinct only if their stems are.
pub fn slug(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_matches('-').to_string()
}
