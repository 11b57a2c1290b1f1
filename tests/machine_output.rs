//! Machine output: every CSV and JSON file a command writes follows the convention of
//! docs/output-format.md, checked on the files themselves after running each command on a
//! small scene: the provenance (the CSV's first line, the JSON's first key) names the program
//! version, the scene and the SHA-256 of its canonical content; CSV column names are in the
//! one key style with SI units; every column is numeric (finite f64 or empty) unless its name
//! marks it as text ([`impact::present::columns`], the rule's one place); every command that
//! computes takes `--json` and prints JSON carrying the same provenance.
//!
//! The scene hash is recomputed outside the program's own SHA-256 (by `sha256sum`, where the
//! system has it) from the canonical content, and checked to follow the content: the same for
//! a scene that differs only in comments and number spelling, different for a changed value.

mod common;

use common::scenes::{edit, small_ensemble};
use common::{impact, tmp, Run, Tmp};
use impact::present::columns::{is_text_column, key_problem};
use impact::scene::{Scene, SceneSource};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The default scene cut to one body, two support sets (one with springs, for the spring
/// columns), two points, one velocity and one transient point.
fn small_scene() -> String {
    let mut s = edit(
        impact::scene::DEFAULT_SCENE,
        "x_mm = [0.0, 13.752, 114.6, 210.864, 229.2, 247.536, 343.8, 449.232, 458.4]",
        "x_mm = [0.0, 229.2]",
    );
    s = edit(
        &s,
        "pairs_mm = [[114.6, 180.0], [229.2, 180.0], [229.2, 0.0], [0.0, 180.0]]",
        "pairs_mm = [[229.2, 180.0]]",
    );
    s = edit(&s, "m_per_s = [0.008, 0.0025]", "m_per_s = [0.008]");
    // Only coal, and Con 1 and Con 2.
    let gangue = s.find("[[bodies]]\nname = \"gangue 1\"").expect("gangue 1");
    let conditions = s.find("[[conditions]]").expect("conditions");
    s.replace_range(gangue..conditions, "");
    let con3 = s.find("[[conditions]]\nname = \"Con 3\"").expect("Con 3");
    let points = s.find("[points]").expect("points");
    s.replace_range(con3..points, "");
    // The studies that take seconds here (regime maps and the paper's studies take minutes;
    // their files are checked in the committed reports, `committed_reports_follow_the_convention`).
    let start = s.find("analyses = [").unwrap();
    let end = start + s[start..].find("]\n").unwrap() + 1;
    s.replace_range(
        start..end,
        r#"analyses = ["responses", "yield-velocity", "width-maps", "aspect-ratio", "error-vs-time", "extreme-cases", "transient", "contact-laws"]"#,
    );
    s.push_str("\n[signals]\nwindow_ms = 5.0\nrate_hz = 10000.0\nmodes = 24\nsensors_mm = [[100.0, 100.0]]\n");
    s
}

fn run(args: &[&str], scene: Option<&Path>) -> Run {
    let mut c = impact(args);
    if let Some(s) = scene {
        c = c.arg("--scene").arg(s);
    }
    c.success()
}

/// The JSON a command printed; its provenance's scene hash.
fn printed(o: &Run) -> (serde_json::Value, String) {
    let v: serde_json::Value = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("--json printed no JSON ({e}): {}", String::from_utf8_lossy(&o.stdout)));
    let p = &v["provenance"];
    assert_eq!(p["program"], "impact", "{p}");
    assert_eq!(p["version"], VERSION, "{p}");
    assert_eq!(p["units"], "SI", "{p}");
    let hash = p["scene_sha256"].as_str().expect("provenance.scene_sha256").to_string();
    assert!(hash.len() == 64 && hash.bytes().all(|b| b.is_ascii_hexdigit()), "{hash}");
    (v, hash)
}

/// SHA-256 of `bytes` by the system's `sha256sum`, independent of the program's own; `None`
/// where the system has none.
fn system_sha256(bytes: &[u8]) -> Option<String> {
    use std::io::Write;
    let mut child = Command::new("sha256sum")
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .ok()?;
    child.stdin.take()?.write_all(bytes).ok()?;
    let o = child.wait_with_output().ok()?;
    Some(String::from_utf8(o.stdout).ok()?.split_whitespace().next()?.to_string())
}

/// The hash the files of a run on the scene file `path` must carry (as loaded, unchanged by
/// any flag), computed from the canonical content outside the program's hashing.
fn expected_hash(path: &Path) -> String {
    let scene = Scene::load(path).unwrap();
    let canonical = impact::provenance::canonical(&scene);
    let ours = impact::provenance::Provenance::of(&scene).scene_sha256;
    if let Some(theirs) = system_sha256(canonical.as_bytes()) {
        assert_eq!(ours, theirs, "the program's SHA-256 of the canonical scene against sha256sum's");
    }
    ours
}

/// Every file under `dir` (relative path, full path), sorted.
fn files(dir: &Path) -> Vec<(String, PathBuf)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, PathBuf)>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                out.push((p.strip_prefix(root).unwrap().to_string_lossy().into_owned(), p));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

fn is_number(cell: &str) -> bool {
    cell.parse::<f64>().is_ok_and(f64::is_finite)
}

/// Everything wrong with one CSV file (empty: nothing). `hash`: the scene hash its
/// provenance must carry (None: any well-formed one).
fn csv_problems(name: &str, text: &str, hash: Option<&str>) -> Vec<String> {
    let mut problems = Vec::new();
    let mut bad = |what: String| problems.push(format!("{name}: {what}"));
    let Some((first, rest)) = text.split_once('\n') else {
        bad("empty or one line".into());
        return problems;
    };
    // `# impact VERSION; scene NAME; scene_sha256 HEX; units SI`
    let fields: Vec<&str> = first.split("; ").collect();
    let ok = fields.len() == 4
        && fields[0] == format!("# impact {VERSION}")
        && fields[1].starts_with("scene ")
        && fields[2]
            .strip_prefix("scene_sha256 ")
            .is_some_and(|h| h.len() == 64 && h.bytes().all(|b| b.is_ascii_hexdigit()) && hash.is_none_or(|e| e == h))
        && fields[3] == "units SI";
    if !ok {
        bad(format!("provenance line '{first}' (expected scene_sha256 {})", hash.unwrap_or("of 64 hex digits")));
    }
    let mut reader = csv::ReaderBuilder::new().from_reader(rest.as_bytes());
    let headers: Vec<String> = match reader.headers() {
        Ok(h) => h.iter().map(str::to_string).collect(),
        Err(e) => {
            bad(format!("header: {e}"));
            return problems;
        }
    };
    for h in &headers {
        if let Some(why) = key_problem(h) {
            bad(format!("column '{h}': {why}"));
        }
        if headers.iter().filter(|o| *o == h).count() > 1 {
            bad(format!("column '{h}' appears twice"));
        }
    }
    let mut text_cells: BTreeMap<usize, (usize, String)> = BTreeMap::new();
    for (i, row) in reader.records().enumerate() {
        let row = match row {
            Ok(r) => r,
            Err(e) => {
                bad(format!("row {}: {e}", i + 1));
                break;
            }
        };
        for (j, cell) in row.iter().enumerate() {
            if !cell.is_empty() && !is_number(cell) && !is_text_column(&headers[j]) {
                let e = text_cells.entry(j).or_insert((0, cell.to_string()));
                e.0 += 1;
            }
        }
    }
    for (j, (n, example)) in text_cells {
        bad(format!(
            "column '{}' is numeric by its name but has {n} cells that are not finite numbers, e.g. '{example}'",
            headers[j]
        ));
    }
    problems
}

/// Everything wrong with one JSON file: it must be an object whose first key is the
/// provenance, with `hash` if given.
fn json_problems(name: &str, text: &str, hash: Option<&str>) -> Vec<String> {
    let v: serde_json::Value = match serde_json::from_str(text) {
        Ok(v) => v,
        Err(e) => return vec![format!("{name}: not JSON: {e}")],
    };
    let first = text.trim_start().strip_prefix('{').map(str::trim_start);
    if !first.is_some_and(|f| f.starts_with("\"provenance\"")) {
        return vec![format!("{name}: the first key is not \"provenance\"")];
    }
    let p = &v["provenance"];
    let ok = p["program"] == "impact"
        && p["version"] == VERSION
        && p["units"] == "SI"
        && p["scene_sha256"].as_str().is_some_and(|h| h.len() == 64 && hash.is_none_or(|e| e == h));
    if ok {
        vec![]
    } else {
        vec![format!("{name}: provenance {p} (expected scene_sha256 {})", hash.unwrap_or("of 64 hex digits"))]
    }
}

/// Checks every CSV and JSON file under `dir`; `hash_of(relative path)` is the hash each must
/// carry. Returns the problems and the number of CSV files checked.
fn check_dir(dir: &Path, hash_of: &dyn Fn(&str) -> Option<String>) -> (Vec<String>, usize) {
    let mut problems = Vec::new();
    let mut csvs = 0;
    for (rel, path) in files(dir) {
        let label = format!("{}/{rel}", dir.file_name().unwrap().to_string_lossy());
        if rel.ends_with(".csv") {
            csvs += 1;
            problems.extend(csv_problems(&label, &std::fs::read_to_string(&path).unwrap(), hash_of(&rel).as_deref()));
        } else if rel.ends_with(".json") && rel != ".impact-manifest.json" {
            problems.extend(json_problems(&label, &std::fs::read_to_string(&path).unwrap(), hash_of(&rel).as_deref()));
        }
    }
    (problems, csvs)
}

/// The small scenes written into a temporary directory.
struct Scenes {
    dir: Tmp,
    small: PathBuf,
    ensemble: PathBuf,
}

fn scenes() -> Scenes {
    let dir = tmp();
    let small = dir.write("small.toml", small_scene());
    let ensemble = dir.write("ensemble.toml", small_ensemble());
    Scenes { dir, small, ensemble }
}

impl Scenes {
    fn out(&self, name: &str) -> String {
        self.dir.join(name).to_string_lossy().into_owned()
    }

    /// Runs `impact <args> --json --out DIR` on `scene` and checks every CSV and JSON file in
    /// DIR against the provenance `--json` printed; returns that hash.
    fn check(&self, args: &[&str], scene: Option<&Path>) -> String {
        let dir = self.out(&args.join("-"));
        let o = run(&[args, &["--json", "--out", &dir]].concat(), scene);
        let (doc, hash) = printed(&o);
        // A command that reports its files lists every one written, streamed ones included.
        if let Some(listed) = doc["files"].as_array() {
            let mut listed: Vec<&str> = listed.iter().map(|f| f["path"].as_str().unwrap()).collect();
            listed.sort_unstable();
            let written: Vec<String> = files(Path::new(&dir))
                .into_iter()
                .map(|(rel, _)| rel)
                .filter(|r| r != ".impact-manifest.json")
                .collect();
            assert_eq!(listed, written, "impact {args:?} --json lists the files it wrote");
        }
        let (problems, n) = check_dir(Path::new(&dir), &|_| Some(hash.clone()));
        assert!(n > 0, "impact {args:?} wrote no CSV");
        assert!(problems.is_empty(), "impact {args:?}: {} problems:\n{}", problems.len(), problems.join("\n"));
        hash
    }
}

/// A coarse transient tolerance: these tests check the files, not the numbers.
const TOL: [&str; 2] = ["--tolerance", "0.01"];

#[test]
fn solve_sweep_and_yield_files_follow_the_convention() {
    let s = scenes();
    s.check(&[&["solve", "--model", "all"][..], &TOL].concat(), Some(&s.small));
    s.check(&["sweep", "--count", "3", "--model", "plate"], Some(&s.small));
    s.check(&["yield", "--model", "plate"], Some(&s.small));
}

#[test]
fn compare_files_follow_the_convention() {
    let s = scenes();
    s.check(&[&["compare"][..], &TOL].concat(), Some(&s.small));
}

#[test]
fn dynamic_files_follow_the_convention() {
    let s = scenes();
    s.check(&[&["dynamic"][..], &TOL].concat(), Some(&s.small));
}

/// signals, identify and field run the scene as loaded: their hash is the one computed
/// here from the canonical content.
#[test]
fn signals_identify_and_field_files_follow_the_convention() {
    let s = scenes();
    let small = expected_hash(&s.small);
    assert_eq!(s.check(&["signals"], Some(&s.small)), small);
    assert_eq!(s.check(&["identify"], Some(&s.ensemble)), expected_hash(&s.ensemble));
    let field = ["field", "--x-mm", "229.2", "--z-mm", "180", "--elements", "8"];
    assert_eq!(s.check(&[&field[..], &["--format", "pvd"]].concat(), Some(&s.small)), small);
    // The single JSON file, and the summary --json prints about it.
    let file = s.out("field.json");
    let o = run(&[&field[..], &["--json", "--out", &file]].concat(), Some(&s.small));
    let (doc, h) = printed(&o);
    assert_eq!(h, small);
    let bytes = std::fs::read(&file).unwrap();
    assert_eq!(doc["files"][0]["bytes"].as_u64(), Some(bytes.len() as u64));
    let p = json_problems("field.json", std::str::from_utf8(&bytes).unwrap(), Some(&small));
    assert!(p.is_empty(), "{p:?}");
    // --json describes files; with --out - the field itself is the output.
    let o = impact(field).args(["--json", "--out", "-"]).run();
    assert!(!o.status.success() && o.stderr.contains("--json"));
}

/// The paper's reproduction runs the paper's own scene (the embedded default), whatever the
/// command line; the FE verification (written only by `impact report`) is checked through
/// the library, stamped as the report stamps it.
#[test]
fn paper_and_fem_verification_files_follow_the_convention() {
    let s = scenes();
    let paper = impact::provenance::Provenance::of(&Scene::default_scene()).scene_sha256;
    assert_eq!(s.check(&["paper"], None), paper);
    let scene = impact::report::main_scene(&Scene::default_scene());
    let provenance = impact::provenance::Provenance::of(&scene);
    let mut a = impact::report::fem_verification::report(&scene).unwrap();
    provenance.stamp(&mut a);
    let mut problems = Vec::new();
    let mut n = 0;
    for p in a.paths() {
        let name = p.to_string_lossy();
        let text = std::str::from_utf8(a.get(&name).unwrap()).unwrap();
        if name.ends_with(".csv") {
            n += 1;
            problems.extend(csv_problems(&name, text, Some(&provenance.scene_sha256)));
        } else if name.ends_with(".json") {
            problems.extend(json_problems(&name, text, Some(&provenance.scene_sha256)));
        }
    }
    assert!(n >= 8, "{n} CSV files");
    assert!(problems.is_empty(), "{} problems:\n{}", problems.len(), problems.join("\n"));
}

/// The hash follows the scene's content, not its spelling: comments and how a number is
/// written leave it, a changed value changes it; and the files carry the new one.
#[test]
fn the_scene_hash_follows_the_content() {
    let dir = tmp();
    let text = small_scene();
    let hash_of = |name: &str, text: &str| {
        let path = dir.write(name, text);
        let o = run(
            &["solve", "--model", "beam", "--json", "--out", &dir.join(format!("{name}.d")).to_string_lossy()],
            Some(&path),
        );
        let (_, h) = printed(&o);
        let (p, _) = check_dir(&dir.join(format!("{name}.d")), &|_| Some(h.clone()));
        assert!(p.is_empty(), "{p:?}");
        assert_eq!(h, expected_hash(&path));
        h
    };
    let a = hash_of("a.toml", &text);
    let respelt = format!("# a comment\n{}", text.replace("length_mm = 458.4", "length_mm = 4.584e2   # the same"));
    assert_eq!(hash_of("b.toml", &respelt), a);
    assert_ne!(hash_of("c.toml", &text.replace("length_mm = 458.4", "length_mm = 458.5")), a);
    assert_ne!(hash_of("d.toml", &text.replace("m_per_s = [0.008]", "m_per_s = [0.009]")), a);
}

/// The committed reports (written by `impact report`) follow the convention too; each
/// directory's files carry the provenance of the scene its report ran, so only the form of
/// the hash is checked here.
#[test]
fn committed_reports_follow_the_convention() {
    let reports = Path::new(env!("CARGO_MANIFEST_DIR")).join("reports");
    let (problems, n) = check_dir(&reports, &|_| None);
    assert!(n > 50, "{n} CSV files under reports/");
    assert!(problems.is_empty(), "{} problems:\n{}", problems.len(), problems.join("\n"));
}

/// `--json` on every command that computes, and the completion scripts.
#[test]
fn json_on_every_command_and_completions() {
    let help = String::from_utf8(run(&["--help"], None).stdout).unwrap();
    let commands: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(commands.len() >= 12, "{commands:?}");
    // Only these print something that is not a result: a scene template, a shell script.
    let without = ["default-scene", "completions"];
    for c in &commands {
        let h = String::from_utf8(run(&[c, "--help"], None).stdout).unwrap();
        assert_eq!(h.contains("--json"), !without.contains(c), "impact {c} --help: {h}");
    }
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let script = String::from_utf8(run(&["completions", shell], None).stdout).unwrap();
        for c in &commands {
            assert!(script.contains(c), "{shell} completion lacks {c}");
        }
        assert!(script.contains("json"), "{shell} completion lacks --json");
    }
    // The bash script is valid bash.
    let dir = tmp();
    let path = dir.write("impact.bash", run(&["completions", "bash"], None).stdout);
    if let Ok(o) = Command::new("bash").arg("-n").arg(&path).output() {
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
}
