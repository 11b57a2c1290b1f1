//! The end of every run: files committed whole (a run that fails leaves earlier output as it
//! was), and what a program or a reader is told of them on standard output.

use crate::cli::Common;
use crate::{note, out};
use coupled::plan::Results;
use impact::output::{Artifacts, OutputDir};
use impact::present::rows::{response_tables, yield_tables};
use impact::present::table::Table;
use impact::provenance::Provenance;
use impact::report::Failure;
use impact::scene::Scene;
use std::path::Path;

/// Checks an output directory before any computation: a run that cannot write fails
/// before it spends time, and a run that fails leaves earlier output as it was.
pub fn prepare(dir: Option<&Path>) -> Result<Option<OutputDir>, Failure> {
    Ok(match dir {
        Some(d) => Some(OutputDir::prepare(d)?),
        None => None,
    })
}

pub fn commit(target: OutputDir, artifacts: &Artifacts) -> Result<(), Failure> {
    let dir = target.path().to_path_buf();
    let written = target.commit(artifacts)?;
    note(&format!("wrote {} files under {}", written.len(), dir.display()));
    Ok(())
}

/// Commits a report's files and, with `json`, prints what a program needs to use them: the
/// provenance, the directory, every file with its size and SHA-256, and the findings the
/// report opens with (`findings.json`, when it has one).
pub fn commit_reporting(target: OutputDir, artifacts: &Artifacts, scene: &Scene, json: bool) -> Result<(), Failure> {
    let dir = target.path().to_path_buf();
    commit(target, artifacts)?;
    if json {
        // From the manifest just written: the files streamed during the run are in it too.
        let files: Vec<serde_json::Value> = impact::output::listed_files(&dir)?
            .into_iter()
            .map(|(path, bytes, sha256)| serde_json::json!({ "path": path, "bytes": bytes, "sha256": sha256 }))
            .collect();
        let findings: Vec<serde_json::Value> = artifacts
            .paths()
            .filter(|p| p.file_name().is_some_and(|n| n == "findings.json"))
            .filter_map(|p| serde_json::from_slice(artifacts.get(&p.to_string_lossy())?).ok())
            .collect();
        let doc = serde_json::json!({
            "provenance": Provenance::of(scene),
            "directory": dir.to_string_lossy(),
            "findings": findings,
            "files": files,
        });
        out(&format!("{}\n", serde_json::to_string_pretty(&doc)?))?;
    }
    Ok(())
}

/// Prints `value` as JSON with the scene's provenance as its first key.
pub fn print_json(scene: &Scene, value: &impl serde::Serialize) -> Result<(), Failure> {
    let doc = Provenance::of(scene).stamp_json(serde_json::to_string_pretty(value)?.as_bytes());
    out(&format!("{}\n", String::from_utf8(doc)?))
}

/// The JSON document of a run: the results with what a reader needs to trust them.
#[derive(serde::Serialize)]
struct Document<'a> {
    provenance: Provenance,
    program: &'static str,
    version: &'static str,
    units: &'static str,
    status: &'a str,
    summary: coupled::plan::Summary,
    /// The rows in the one column schema's keys (`contact_force_N`, ...), as in the CSV
    /// files and the Python columns.
    results: studies::columns::Rows<'a>,
}

pub fn emit(c: &Common, target: Option<OutputDir>, scene: &Scene, results: Results) -> Result<(), Failure> {
    let status = impact::run::status_line(&results);
    // Serialized straight from the rows (no intermediate JSON tree), and only when asked for:
    // a sweep of many points must not hold its results several times over.
    let json = || -> Result<String, Failure> {
        Ok(serde_json::to_string_pretty(&Document {
            provenance: Provenance::of(scene),
            program: "impact",
            version: env!("CARGO_PKG_VERSION"),
            units: "SI (m, m/s, N, m/N, J ratios)",
            status: &status,
            summary: results.summary(),
            results: studies::columns::Rows(&results),
        })?)
    };
    if let Some(target) = target {
        let mut a = Artifacts::new();
        // File names from the support set's position in the scene (unique), not its name.
        for (kind, tables) in [("responses", response_tables(&results)), ("yield", yield_tables(&results))] {
            for (i, t) in tables.iter().enumerate() {
                a.add(format!("{kind}-{}.csv", i + 1), t.to_csv());
            }
        }
        a.add("results.json", json()?);
        Provenance::of(scene).stamp(&mut a);
        commit(target, &a)?;
    }
    if c.json {
        out(&format!("{}\n", json()?))?;
        // The JSON carries the status too; the terminal gets it on standard error.
        note(&status);
    } else {
        let mut text = format!("scene: {}\n{}\n", scene.name, wrap(&scene.description, 100));
        let tables: Vec<Table> = response_tables(&results).into_iter().chain(yield_tables(&results)).collect();
        for t in c.view(&tables)? {
            text.push('\n');
            text.push_str(&t.to_text());
        }
        text.push_str(&format!("\n{}\n", if c.wide { status.clone() } else { wrap(&status, 118) }));
        out(&text)?;
    }
    Ok(())
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word stays whole).
fn wrap(text: &str, width: usize) -> String {
    let mut lines: Vec<String> = vec![String::new()];
    for word in text.split_whitespace() {
        let last = lines.last_mut().expect("one line at least");
        if !last.is_empty() && last.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_string());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    lines.join("\n")
}
