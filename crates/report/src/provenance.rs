//! Where a result came from: the program, its version, the scene's name and a hash of the
//! scene's canonical content, carried by every JSON and CSV the program writes.
//!
//! **Canonical content.** The scene as the program uses it: parsed, validated and converted
//! to SI ([`scene::Scene`]), serialised as compact JSON with serde's field order
//! (the struct's declaration order) and serde_json's shortest round-trip numbers. Two scene
//! files that differ only in comments, key order, whitespace or units (`length_mm = 458.4`
//! against the same length written another way that converts to the same SI value) hash the
//! same; any difference in what is computed changes it. The hash is the SHA-256 of that JSON
//! text, in hex.
//!
//! **Where it goes.** A JSON document gets a `"provenance"` object as its first key. A CSV
//! gets one comment line first, `# impact 0.1.0; scene NAME; scene_sha256 HEX; units SI`:
//! a sidecar file would be lost when a CSV is copied on its own, and a leading `#` line is
//! skipped by the usual readers when told (pandas `comment="#"`, numpy `loadtxt`, R
//! `comment.char`, the Rust csv crate's `comment(Some(b'#'))`).

use output::{sha256_hex, Artifacts};
use scene::Scene;
#[cfg(test)]
use scene::SceneSource;
use serde::Serialize;

/// The provenance of one run on one scene.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Provenance {
    pub program: &'static str,
    pub version: &'static str,
    pub scene: String,
    /// SHA-256 (hex) of [`canonical`].
    pub scene_sha256: String,
    /// The unit system of every number in the files.
    pub units: &'static str,
}

/// The scene's canonical content (see the module documentation).
pub fn canonical(scene: &Scene) -> String {
    serde_json::to_string(scene).expect("a validated scene serializes")
}

impl Provenance {
    pub fn of(scene: &Scene) -> Self {
        Self {
            program: "impact",
            version: env!("CARGO_PKG_VERSION"),
            scene: scene.name.clone(),
            scene_sha256: sha256_hex(canonical(scene).as_bytes()),
            units: "SI",
        }
    }

    /// The first line of a CSV, with its newline.
    pub fn csv_line(&self) -> String {
        // A name with a line break or ';' would break the one-line form.
        let name: String = self.scene.chars().map(|c| if c.is_control() || c == ';' { ' ' } else { c }).collect();
        format!(
            "# {} {}; scene {name}; scene_sha256 {}; units {}\n",
            self.program, self.version, self.scene_sha256, self.units
        )
    }

    /// `csv` with the provenance line first (unchanged if it already has one).
    pub fn stamp_csv(&self, csv: &[u8]) -> Vec<u8> {
        if csv.starts_with(b"# impact ") {
            return csv.to_vec();
        }
        let mut out = self.csv_line().into_bytes();
        out.extend_from_slice(csv);
        out
    }

    /// A JSON object with `"provenance"` inserted as its first key (unchanged if it has one,
    /// or if it is not an object).
    pub fn stamp_json(&self, json: &[u8]) -> Vec<u8> {
        let Ok(text) = std::str::from_utf8(json) else { return json.to_vec() };
        let trimmed = text.trim_start();
        if !trimmed.starts_with('{')
            || serde_json::from_str::<serde_json::Value>(text)
                .map_or(true, |v| v.as_object().is_none_or(|o| o.contains_key("provenance")))
        {
            return json.to_vec();
        }
        let at = text.len() - trimmed.len() + 1;
        let me = serde_json::to_string(self).expect("provenance serializes");
        let rest = &text[at..];
        let empty = rest.trim_start().starts_with('}');
        let sep = if empty { "" } else { "," };
        let pretty = rest.starts_with('\n');
        let mut out = String::with_capacity(text.len() + me.len() + 24);
        out.push_str(&text[..at]);
        if pretty {
            out.push_str(&format!("\n  \"provenance\": {me}{sep}"));
        } else {
            out.push_str(&format!("\"provenance\":{me}{sep}"));
        }
        out.push_str(rest);
        out.into_bytes()
    }

    /// Every CSV and JSON file of `a` stamped (files stamped before, by a nested report on
    /// another scene, keep theirs).
    pub fn stamp(&self, a: &mut Artifacts) {
        a.map_files(|path, bytes| match path.extension().and_then(|e| e.to_str()) {
            Some("csv") => self.stamp_csv(bytes),
            Some("json") => self.stamp_json(bytes),
            _ => bytes.to_vec(),
        });
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_file_mark_is_the_provenance_opening() {
        let p = super::Provenance::of(&scene::Scene::default_scene());
        assert!(serde_json::to_string(&p).unwrap().starts_with(output::FILE_MARK));
    }

    use super::*;

    #[test]
    fn the_hash_follows_content_not_spelling() {
        let a = Scene::default_scene();
        let mut text = scene::DEFAULT_SCENE.replace("length_mm = 458.4", "length_mm = 458.40  # same length");
        text.insert_str(0, "# a comment\n");
        let b = Scene::parse(&text, "same").unwrap();
        assert_eq!(Provenance::of(&a).scene_sha256, Provenance::of(&b).scene_sha256);
        let c = Scene::parse(&scene::DEFAULT_SCENE.replace("length_mm = 458.4", "length_mm = 458.5"), "x").unwrap();
        assert_ne!(Provenance::of(&a).scene_sha256, Provenance::of(&c).scene_sha256);
        assert_eq!(Provenance::of(&a).scene_sha256.len(), 64);
    }

    #[test]
    fn stamps_csv_and_json_once() {
        let p = Provenance::of(&Scene::default_scene());
        let csv = p.stamp_csv(b"a,b\n1,2\n");
        assert!(String::from_utf8(csv.clone()).unwrap().lines().next().unwrap().contains(&p.scene_sha256));
        assert_eq!(p.stamp_csv(&csv), csv);
        for doc in ["{\n  \"a\": 1\n}", "{\"a\":1}", "{}", "{ }"] {
            let out = p.stamp_json(doc.as_bytes());
            let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
            assert_eq!(v["provenance"]["scene_sha256"], p.scene_sha256.as_str(), "{doc}");
            assert_eq!(p.stamp_json(&out), out);
        }
        assert_eq!(p.stamp_json(b"[1]"), b"[1]");
    }
}
