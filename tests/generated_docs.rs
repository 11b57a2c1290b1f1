//! The generated references: docs/cli.md and docs/scenes.md are, byte for byte, what
//! `impact reference cli` and `impact reference scenes` print, and the ranges they state are
//! the ones the command line checks.

use impact::scene::limits;
use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_impact");

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("the impact binary runs")
}

/// Asserts that the committed `doc` equals the output of `impact reference <what>`.
fn committed_equals_generated(what: &str, doc: &str) {
    let o = run(&["reference", what]);
    assert!(o.status.success(), "impact reference {what}: {}", String::from_utf8_lossy(&o.stderr));
    let regenerate = format!("regenerate it with `cargo run --release -- reference {what} > {doc}` and commit it");
    let committed = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join(doc))
        .unwrap_or_else(|e| panic!("{doc} cannot be read ({e}): {regenerate}"));
    if committed == o.stdout {
        return;
    }
    let (old, new) = (String::from_utf8_lossy(&committed), String::from_utf8_lossy(&o.stdout));
    let line =
        old.lines().zip(new.lines()).position(|(a, b)| a != b).unwrap_or(old.lines().count().min(new.lines().count()));
    panic!(
        "{doc} is not what `impact reference {what}` prints (first difference at line {}:\n  committed: {:?}\n  generated: {:?});\n{regenerate}",
        line + 1,
        old.lines().nth(line).unwrap_or("<end of file>"),
        new.lines().nth(line).unwrap_or("<end of file>"),
    );
}

#[test]
fn cli_reference_is_generated() {
    committed_equals_generated("cli", "docs/cli.md");
}

#[test]
fn scene_reference_is_generated() {
    committed_equals_generated("scenes", "docs/scenes.md");
}

#[test]
fn the_reference_command_is_hidden_and_documents_every_command() {
    let help = String::from_utf8(run(&["--help"]).stdout).unwrap();
    assert!(!help.lines().any(|l| l.trim_start().starts_with("reference ")), "{help}");
    let md = String::from_utf8(run(&["reference", "cli"]).stdout).unwrap();
    assert!(!md.contains("## `impact reference`"));
    for command in ["solve", "sweep", "yield", "compare", "dynamic", "signals", "identify", "paper", "report"] {
        assert!(md.contains(&format!("\n## `impact {command}`\n")), "{command}");
    }
    assert!(md.contains(&format!("in {}", limits::TRANSIENT_TOLERANCE)), "--tolerance states its range");
}

/// Asserts that `args` fail with a message naming the flag, the value as written and `range`.
fn refused(args: &[&str], flag_and_value: &str, range: String) {
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} should fail");
    assert!(err.contains(&format!("{flag_and_value} is outside the allowed range {range}")), "{args:?}: {err}");
}

#[test]
fn range_errors_name_the_flag_the_value_as_written_and_the_range() {
    refused(&["solve", "--tolerance", "1E-7"], "--tolerance 1E-7", limits::TRANSIENT_TOLERANCE.to_string());
    refused(&["fem-bench", "--tolerance", "1"], "--tolerance 1", limits::FEM_BENCH_TOLERANCE.to_string());
    refused(&["fem-bench", "--nz", "1002"], "--nz 1002", limits::FEM_BENCH_POINTS.to_string());
    let field = ["field", "--x-mm", "100", "--z-mm", "100"];
    refused(&[&field[..], &["--elements", "1"]].concat(), "--elements 1", limits::FIELD_ELEMENTS.to_string());
    refused(
        &[&field[..], &["--format", "pvd", "--velocity-m-per-s", "1e4"]].concat(),
        "--velocity-m-per-s 1e4",
        format!("{} m/s", limits::VELOCITY_M_PER_S),
    );
}
