//! The small scenes the tests compute on, each written once for every test crate (the command
//! line's and the studies'): a base, and each variant a test needs as the edits that make it
//! from its base, so that what differs is in plain sight.
//!
//! Three bases: [`ONE_IMPACT`] (scene text: coal on the paper's plate, one point, one
//! velocity), [`ENSEMBLE`] (scene text: coal and gangue ensembles for `impact identify`) and
//! [`coal_con1`] (the default scene cut down, as a [`Scene`]); and [`TINY_IDENTIFY`], the
//! identification study's own ensemble.

use scene::{Analysis, Points, Scene, SceneSource};

/// `base` with the first `from` replaced by `to`. `from` must be there: an edit that no
/// longer matches would otherwise leave the scene as it was and the test testing another.
pub fn edit(base: &str, from: &str, to: &str) -> String {
    assert!(base.contains(from), "test set-up: '{from}' is in the scene");
    base.replacen(from, to, 1)
}

/// [`edit`] applied in turn for each `(from, to)`.
pub fn edits(base: &str, changes: &[(&str, &str)]) -> String {
    changes.iter().fold(base.to_string(), |text, (from, to)| edit(&text, from, to))
}

/// Asserts that `text` is refused, with a message that names every one of `needles`.
pub fn expect_refused(text: &str, needles: &[&str]) {
    let e = match Scene::parse(text, "test.toml") {
        Ok(_) => panic!("scene was accepted"),
        Err(e) => e.to_string(),
    };
    for n in needles {
        assert!(e.contains(n), "error '{e}' does not mention '{n}'");
    }
}

// ---------------------------------------------------------------- support sets, as text

/// The paper's Con 1, both ends fixed (the text of a `[[conditions]]` entry).
pub const CON_1: &str = "[[conditions]]\nname = \"Con 1\"\nsupports = \"both-fixed\"\n";
/// The paper's Con 2, both ends on springs of k_T = K_coal.
pub const CON_2: &str =
    "[[conditions]]\nname = \"Con 2\"\nsupports = \"both-springs\"\nspring_stiffness_n_per_m = 5.11545e8\n";
/// The paper's Con 3, one end fixed and one on springs of k_T = K_coal.
pub const CON_3: &str =
    "[[conditions]]\nname = \"Con 3\"\nsupports = \"fixed-and-springs\"\nspring_stiffness_n_per_m = 5.11545e8\n";
/// A general support set the beam cannot describe: the left edge clamped, the two right
/// corners on 1e6 N/m springs.
pub const CLAMPED_PROPS: &str = "[[conditions]]\nname = \"clamped + props\"\n[conditions.edges]\nleft = \"clamped\"\n[conditions.corners]\nright_near = { spring_n_per_m = 1e6 }\nright_far = { spring_n_per_m = 1e6 }\n";

// ---------------------------------------------------------------- one impact, as text

/// Table 1's coal sphere striking Table 1's plate at its centre, held as Con 1, at 0.008
/// m/s, responses only.
pub const ONE_IMPACT: &str = r#"
name = "one impact"
restitution = 0.65
analyses = ["responses"]

[plate]
length_mm = 458.4
width_mm = 360.0
thickness_mm = 8.0
youngs_modulus_gpa = 210.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0

[[bodies]]
name = "coal"
density_kg_m3 = 1380.0
youngs_modulus_gpa = 2.26
poisson_ratio = 0.28
cohesion_mpa = 8.39
friction_angle_deg = 25.0
radius_mm = 25.0

[[conditions]]
name = "Con 1"
supports = "both-fixed"

[points]
pairs_mm = [[229.2, 180.0]]

[velocities]
m_per_s = [0.008]
"#;

/// [`ONE_IMPACT`] as "small": with its yield velocity, off the centreline (z = 120 mm), and
/// under [`CLAMPED_PROPS`] beside Con 1 (a set the beam answers "not applicable" for);
/// small enough for the transient yield search.
pub fn two_sets() -> String {
    edits(
        ONE_IMPACT,
        &[
            ("name = \"one impact\"", "name = \"small\""),
            ("analyses = [\"responses\"]", "analyses = [\"responses\", \"yield-velocity\"]"),
            (CON_1, &format!("{CON_1}{CLAMPED_PROPS}")),
            ("pairs_mm = [[229.2, 180.0]]", "pairs_mm = [[229.2, 120.0]]"),
        ],
    )
}

/// [`ONE_IMPACT`] under Con 3 (fixed end and springs: corner reactions and spring forces)
/// with a `[signals]` table: 5 ms at 10 kHz, 40 modes, one sensor at (100, 100) mm.
pub fn signals() -> String {
    let text = edit(ONE_IMPACT, CON_1, CON_3);
    format!("{text}\n[signals]\nwindow_ms = 5.0\nrate_hz = 10000.0\nmodes = 40\nsensors_mm = [[100.0, 100.0]]\n")
}

// ---------------------------------------------------------------- ensembles, as text

/// A small identification scene: Table 1's coal and gangue (fixed materials, the paper's
/// radius with a spread), two support sets, a 3 x 2 candidate grid.
pub const ENSEMBLE: &str = r#"
name = "small-identify"
restitution = 0.65
analyses = ["identify"]

[plate]
length_mm = 458.4
width_mm = 360.0
thickness_mm = 8.0
youngs_modulus_gpa = 210.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0

[[conditions]]
name = "Con 1"
supports = "both-fixed"

[[conditions]]
name = "Con 2"
supports = "both-springs"
spring_stiffness_n_per_m = 5.11545e8

[signals]
# Fewer modes than the default keep the test fast; the statistics do not need them.
modes = 24

[ensemble]
seed = 11
placement = { x_count = 3, z_count = 2 }
velocity_m_per_s = { distribution = "uniform", min = 0.002, max = 0.008 }

[[ensemble.families]]
name = "coal"
class = "coal"
count = 20
density_kg_m3 = 1380.0
youngs_modulus_gpa = 2.26
poisson_ratio = 0.28
cohesion_mpa = 8.39
friction_angle_deg = 25.0
radius_mm = { distribution = "lognormal", median = 25.0, sigma_log = 0.2, min = 15.0, max = 40.0 }

[[ensemble.families]]
name = "gangue"
class = "gangue"
count = 20
density_kg_m3 = 2400.0
youngs_modulus_gpa = 16.0
poisson_ratio = 0.28
cohesion_mpa = 37.68
friction_angle_deg = 37.0
radius_mm = { distribution = "lognormal", median = 25.0, sigma_log = 0.2, min = 15.0, max = 40.0 }
"#;

/// [`ENSEMBLE`] made smaller still, for checks of the files rather than the statistics: 8
/// spheres a family of uniformly spread size (held), Con 2 alone, a 2 x 2 grid, 16 modes over
/// 5 ms and a named sensor.
pub fn small_ensemble() -> String {
    let lognormal =
        "radius_mm = { distribution = \"lognormal\", median = 25.0, sigma_log = 0.2, min = 15.0, max = 40.0 }";
    let uniform = "radius_mm = { distribution = \"uniform\", min = 20.0, max = 30.0 }";
    edits(
        ENSEMBLE,
        &[
            ("name = \"small-identify\"", "name = \"small-ensemble\""),
            (CON_1, ""),
            ("modes = 24", "modes = 16\nwindow_ms = 5.0\nsensors_mm = [[229.2, 180.0]]"),
            ("seed = 11", "seed = 3"),
            ("x_count = 3, z_count = 2 }", "x_count = 2, z_count = 2 }\nhold = [\"size\"]"),
            ("count = 20", "count = 8"),
            ("count = 20", "count = 8"),
            (lognormal, uniform),
            (lognormal, uniform),
        ],
    )
}

/// Twelve coal and twelve gangue spheres of spread size at low speed (elastic contacts) on
/// Con 1, 16 modes over a 5 ms window, a named sensor at the centre, a 2 x 2 candidate grid,
/// and size held in the variability study.
pub const TINY_IDENTIFY: &str = r#"
name = "tiny-identify"
restitution = 0.65
analyses = ["identify"]

[plate]
length_mm = 458.4
width_mm = 360.0
thickness_mm = 8.0
youngs_modulus_gpa = 210.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0

[[conditions]]
name = "Con 1"
supports = "both-fixed"

[signals]
modes = 16
window_ms = 5.0
sensors_mm = [[229.2, 180.0]]

[ensemble]
seed = 5
placement = { x_count = 2, z_count = 2 }
hold = ["size"]
velocity_m_per_s = { distribution = "uniform", min = 0.002, max = 0.008 }

[[ensemble.families]]
name = "coal"
class = "coal"
count = 12
density_kg_m3 = 1380.0
youngs_modulus_gpa = 2.26
poisson_ratio = 0.28
cohesion_mpa = 8.39
friction_angle_deg = 25.0
radius_mm = { distribution = "uniform", min = 15.0, max = 35.0 }

[[ensemble.families]]
name = "gangue"
class = "gangue"
count = 12
density_kg_m3 = 2400.0
youngs_modulus_gpa = 16.0
poisson_ratio = 0.28
cohesion_mpa = 37.68
friction_angle_deg = 37.0
radius_mm = { distribution = "uniform", min = 15.0, max = 35.0 }
"#;

// ---------------------------------------------------------------- the default scene cut down

/// The default scene (the paper's Table 1) cut to coal under Con 1 at 0.008 m/s; its points,
/// transient points, analyses and settings as the default has them.
pub fn coal_con1() -> Scene {
    let scene = Scene::default_scene();
    Scene {
        bodies: vec![scene.bodies[0].clone()],
        conditions: vec![scene.conditions[0].clone()],
        velocities: vec![0.008],
        ..scene
    }
}

/// [`coal_con1`] at one point, the plate's centre, which is its one transient point too,
/// asking for `analyses`; each transient case on the starting discretisation (20 elements,
/// 200 steps per Hertz time).
pub fn coal_con1_centre(analyses: Vec<Analysis>) -> Scene {
    let scene = coal_con1();
    let centre = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    Scene {
        points: Points::Pairs { pairs: vec![centre] },
        transient_points: vec![centre],
        analyses,
        transient_discretisation: coupled::transient::Discretisation::Fixed {
            settings: coupled::transient::TransientSettings::default(),
        },
        ..scene
    }
}

/// A small `[stream]`: two streams of 6 s at 12 lumps a second, all coal then all gangue from
/// 3 s, windows of 0.5 s every 0.25 s in four time blocks, the first stream's signal written.
pub const STREAM: &str = r#"
[stream]
rate_per_s = 12.0
duration_s = 6.0
streams = 2
seed = 3
gangue_before = 0.0
gangue_after = 1.0
onset_s = 3.0
ramp_s = 0.5
window_s = 0.5
hop_s = 0.25
blocks = 4
alarm_probability = 0.5
write_signal = true
"#;

/// [`ENSEMBLE`] with two sensors, a 5 ms window (each lump's longest follow) and `stream`.
pub fn with_stream(stream: &str) -> String {
    let signals = "modes = 24\nwindow_ms = 5.0\nsensors_mm = [[229.2, 180.0], [400.0, 90.0]]";
    format!("{}\n{stream}", edit(ENSEMBLE, "modes = 24", signals))
}
