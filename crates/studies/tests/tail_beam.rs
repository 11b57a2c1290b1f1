//! The tail-beam study on the shipped scene, against what statics and the regime limits say
//! independently of the shell model; and the `[tail_beam]` table's refusals.

use coupled::reduced::ModalDamping;
use scene::SceneSource;
use std::sync::OnceLock;
use studies::tail_beam::TailBeamData;
use test_scenes::{edit, expect_refused as expect};

const SCENE: &str = include_str!("../../../scenes/tail-beam.toml");

/// The shipped scene and its study, computed once for the tests that read it.
fn shipped() -> &'static (scene::Scene, TailBeamData) {
    static RUN: OnceLock<(scene::Scene, TailBeamData)> = OnceLock::new();
    RUN.get_or_init(|| {
        let scene = scene::Scene::parse(SCENE, "scenes/tail-beam.toml").unwrap();
        let d = studies::tail_beam::compute(&scene).unwrap();
        (scene, d)
    })
}

/// The box in time is damped as the scene says: at ζ = 4 % instead of the default 0.5 % the
/// model reads it back, the jacks' largest force over the fundamental period falls at every
/// impact (the ringing after the contact decays e^(-ζωt); measured 13-39 % lower, the box's
/// own modes, which decay fastest, making much of that force), and P_max, reached within a
/// contact far shorter than any damped period, moves by under 0.1 % (measured at most 2.3e-4).
#[test]
fn the_box_in_time_takes_the_scenes_damping() {
    let (_, light) = shipped();
    let text = format!("{SCENE}\n[signals]\ndamping_ratio = 0.04\n");
    let scene = scene::Scene::parse(&text, "scenes/tail-beam.toml").unwrap();
    let heavy = studies::tail_beam::compute(&scene).unwrap();
    assert_eq!(light.in_time.damping, ModalDamping::Ratio(0.005));
    assert_eq!(heavy.in_time.damping, ModalDamping::Ratio(0.04));
    for (l, h) in light.in_time.rows.iter().zip(&heavy.in_time.rows) {
        assert!(h.spring_force < l.spring_force, "{h:?} against {l:?}");
        assert!((h.p_max / l.p_max - 1.0).abs() < 1e-3, "{h:?} against {l:?}");
    }
}

/// The shipped tail beam: the jacks' share of each compliance meets the rigid box turning about
/// the pins on its jacks, (x/a)²/Σk (statics and the jacks' stiffness alone; measured within
/// 0.14 %: the pads and the box's own deformation move the jacks' line of action slightly);
/// every impact is wave controlled by Olsson's mass ratio and far from quasi-static; the
/// compliance's error estimate is within 5 %
/// (measured 1.4-3.1 % of C, the most near the pins).
#[test]
fn the_shipped_tail_beam_meets_statics_and_its_regime() {
    let (scene, d) = shipped();
    let b = &d.scene.beam;
    let j = b.jacks[0];
    let arm = b.pin_height * j.angle.cos() + j.x * j.angle.sin();
    let k: f64 = b.jacks.iter().map(|j| j.stiffness).sum();
    for r in &d.rows {
        let rigid = (r.x / arm).powi(2) / k;
        let jacks = r.shares[3] * r.compliance;
        assert!(
            (jacks / rigid - 1.0).abs() < 5e-3,
            "({}, {}): jacks {jacks:e} against the rigid box {rigid:e}",
            r.x,
            r.z
        );
        assert!(r.compliance_error < 5e-2 * r.compliance, "{r:?}");
        assert_eq!(r.regime, coupled::regimes::OlssonRegime::WaveControlled);
        assert!(!r.quasi_static.valid && r.quasi_static.value < 0.05);
        let share_sum: f64 = r.shares.iter().sum();
        assert!((share_sum - 1.0).abs() < 1e-9, "{r:?}");
    }
    assert!(d.resolution.valid && d.thickness_range.valid);
    // The fundamental frequency against the box turning rigidly about the pins on its jacks,
    // f_r = √(k_θ/I)/2π from the walls' moment of inertia (closed form): the shell model's lies
    // below it (Rayleigh: the box's own flexibility lowers it; measured 23.02 against 25.9 Hz),
    // and the shell model with walls a thousand times stiffer meets it (the model's lumped mass
    // and the jacks' pads against the closed form; measured +0.15 %, the pads' spread of arms).
    let f = d.frequency.0;
    assert!(f < 1.002 * d.rigid_frequency, "{f} against {}", d.rigid_frequency);
    let built = b.build(210e12, 0.3, d.scene.element, 1).unwrap();
    let factor = built.structure.factorize(&built.restraints).unwrap();
    let f_stiff = factor.fundamental(&built.structure.lumped_mass(7850.0)).0 / (2.0 * std::f64::consts::PI);
    assert!((f_stiff / d.rigid_frequency - 1.0).abs() < 5e-3, "stiff box {f_stiff} against {}", d.rigid_frequency);
    eprintln!("f {f} rigid {} stiff {f_stiff}", d.rigid_frequency);
    // The wave-controlled answer against an independent model: the transient Kirchhoff plate
    // (Newmark, the same contact law) on the top panel holding the first point. Measured: the
    // clamped and simply supported panels within 0.025 % of each other (the edges do not matter,
    // which is what wave controlled means), and 0.34-0.95 % below Christoforou and Yigit's
    // asymptote (its contact is linearised); held to 0.1 % and 1.5 %.
    assert_eq!(d.panel_checks.len(), scene.bodies.len() * scene.velocities.len());
    for c in &d.panel_checks {
        assert!((c.clamped.0 / c.simple.0 - 1.0).abs() < 1e-3, "{c:?}");
        assert!((c.clamped.0 / c.wave.unwrap() - 1.0).abs() < 1.5e-2, "{c:?}");
    }
    assert_eq!(d.paper.len(), scene.bodies.len() * scene.velocities.len());
    in_time_against_independent_models(d);
}

/// The box in time (its own 200 modes and the static correction) against three models that
/// share none of its code.
///
/// - P_max at the first point against the transient Kirchhoff plate on the top panel (BFS
///   elements, Newmark, a point contact): measured +0.11 % (coal, 0.5 m/s) to +1.7 % (the
///   heavier gangue at 5 m/s, the shortest contact), growing as the contact shortens; held to
///   2.5 %. The shell's contact is the 30 mm patch; the plate's a point.
/// - P_max away from the walls against Christoforou and Yigit's wave-controlled asymptote:
///   measured -0.40 % to +1.18 %; held to 2 %.
/// - The jacks: the rigid box turning on them under the contact's impulse J at x,
///   Σk_j a_j J x/(I ω_r), is the first mode's answer alone; the box's own modes add to it
///   where the point lies far from the tip (measured: +0.3 % to +10 % at the tip, +21 % to
///   +53 % mid-length, 2.1 to 2.8 times near the pins). Held: at the tip within 15 %, everywhere at least 0.9 of it; and the
///   dynamic jack force at most a quarter of the quasi-static balance's (measured 2-21 %, the
///   most for the slowest lumps, whose contacts are the longest).
fn in_time_against_independent_models(d: &TailBeamData) {
    let t = &d.in_time;
    assert_eq!(t.rows.len(), d.rows.len());
    assert_eq!(d.jacks_rigid_box.len(), d.rows.len());
    let first = d.scene.points[0];
    let tip = d.scene.points.iter().map(|p| p.0).fold(0.0, f64::max);
    for ((r, q), &rigid_box) in t.rows.iter().zip(&d.rows).zip(&d.jacks_rigid_box) {
        assert!(r.p_max_error < 1e-2 * r.p_max && r.contacts == 1, "{r:?}");
        assert_eq!(d.scene.points[r.point], (q.x, q.z));
        if (q.x, q.z) == first {
            let c = d.panel_checks.iter().find(|c| c.body == r.body && c.velocity == r.velocity).unwrap();
            assert!((r.p_max / c.clamped.0 - 1.0).abs() < 2.5e-2, "{r:?} against the panel {c:?}");
        }
        if !q.over_wall {
            assert!((r.p_max / q.p_wave - 1.0).abs() < 2e-2, "{r:?} against {}", q.p_wave);
        }
        assert!(r.spring_force >= 0.9 * rigid_box, "{r:?} against {rigid_box}");
        if q.x == tip {
            assert!((r.spring_force / rigid_box - 1.0).abs() < 0.15, "{r:?} against {rigid_box}");
        }
        assert!(r.spring_force < 0.25 * q.jack_force, "{r:?} against {}", q.jack_force);
    }
}

fn with(from: &str, to: &str) -> String {
    edit(SCENE, from, to)
}

#[test]
fn a_bad_tail_beam_is_refused_naming_its_field() {
    expect(
        &with("analyses = [\"tail-beam\"]", "analyses = [\"responses\"]"),
        &["tail_beam", "read only by the \"tail-beam\""],
    );
    expect(&with("top_mm = 30.0", "top_mm = 300.0"), &["tail_beam.top_mm", "300 mm", "smallest side"]);
    expect(&with("top_mm = 30.0", "top_mm = nan"), &["tail_beam.top_mm"]);
    expect(&with("element_mm = 100.0", "element_mm = 5.0"), &["tail_beam.element_mm", "unknowns", "budget"]);
    expect(
        &with("pins_z_mm = [[100.0, 300.0], [1100.0, 1300.0]]", "pins_z_mm = [[300.0, 100.0]]"),
        &["tail_beam.pins_z_mm[0]", "[300, 100]"],
    );
    expect(
        &with("pins_z_mm = [[100.0, 300.0], [1100.0, 1300.0]]", "pins_z_mm = []"),
        &["tail_beam.pins_z_mm", "at least one"],
    );
    expect(&with("ribs_z_mm = [466.7, 933.3]", "ribs_z_mm = [466.7, 1400.0]"), &["tail_beam.ribs_z_mm[1]", "1400"]);
    let ribs = "ribs_z_mm = [466.7, 933.3]";
    expect(&with(ribs, &format!("{ribs}\ndiaphragms_x_mm = [800.0]")), &["tail_beam.diaphragm_mm", "required"]);
    // A thickness given for walls that are not there is refused, not ignored.
    expect(
        &with(ribs, &format!("{ribs}\ndiaphragm_mm = 16.0")),
        &["tail_beam.diaphragm_mm", "= 16", "diaphragms_x_mm is empty"],
    );
    expect(&with(ribs, "ribs_z_mm = []"), &["tail_beam.rib_mm", "= 16", "ribs_z_mm is empty"]);
    let diaphragms = |x: &str| with(ribs, &format!("{ribs}\ndiaphragms_x_mm = [{x}]\ndiaphragm_mm = 16.0"));
    expect(&diaphragms("2000.0"), &["tail_beam.diaphragms_x_mm[0]", "2000", "length"]);
    expect(&diaphragms("800.0, 810.0"), &["tail_beam", "closer than their thickness"]);
    let accepted = scene::Scene::parse(&diaphragms("800.0"), "d.toml").unwrap();
    let beam = &accepted.tail_beam.as_ref().unwrap().beam;
    assert_eq!(beam.diaphragm_walls(), vec![(0.8, 0.016)]);
    expect(&with("pin_height_mm = 125.0", "pin_height_mm = 260.0"), &["tail_beam.pin_height_mm", "260"]);
    expect(
        &with("x_mm = 600.0\nz_mm = 350.0", "x_mm = 1590.0\nz_mm = 350.0"),
        &["tail_beam.jacks[0]", "1590", "bottom plate"],
    );
    expect(
        &with("stiffness_n_per_m = 4.3e7\nangle_deg = 60.0\n\n", "stiffness_n_per_m = -1.0\nangle_deg = 60.0\n\n"),
        &["tail_beam.jacks[0].stiffness_n_per_m", "-1"],
    );
    expect(&with("[800.0, 700.0], ", "[1800.0, 700.0], "), &["tail_beam.points_mm[0]", "[1800, 700]", "top plate"]);
    expect(&with("[800.0, 700.0], ", "[800.0], "), &["tail_beam.points_mm[0]", "exactly two"]);
    // A jack whose axis passes through the pins holds nothing.
    let through = with("pin_height_mm = 125.0", "pin_height_mm = 0.0").replace("angle_deg = 60.0", "angle_deg = 0.0");
    expect(&through, &["tail_beam", "holds nothing"]);
    let no_table = SCENE.split("\n[tail_beam]").next().unwrap().to_string();
    expect(&no_table, &["tail_beam", "needs a [tail_beam] table"]);
}
