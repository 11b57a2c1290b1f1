//! The caving stream on the tail beam (`scenes/tail-beam-stream.toml`, on a coarser mesh and a
//! shorter stream): each stream's first lump, which finds the box at rest, against the same
//! impact on the box's reduced model through the single-impact path
//! ([`coupled::reduced::structure::StructureModel::impact`], verified against the full
//! structure in `coupled/tests/structure_impact.rs`), which shares no time stepping with the
//! stream's; and the scene's refusals where the stream is on the box.

use coupled::compliance::tail_beam::contact_patch;
use coupled::identification::Striking;
use coupled::reduced::structure::{Readings, StructureModel, StructureSettings};
use identify::stream::{lumps, StreamSpec};
use plate_fem::shell::ShellMass;
use scene::SceneSource;
use studies::in_time::IN_TIME_LEVEL;
use test_scenes::{edits, expect_refused as expect};

const SCENE: &str = include_str!("../../../scenes/tail-beam-stream.toml");

/// The shipped scene on 200 mm elements (100 mm on the stream's mesh), 2 streams of 20 s at 2
/// lumps a second, no sweeps, the lumps struck over the middle of the top plate.
fn small() -> String {
    edits(
        SCENE,
        &[
            ("element_mm = 100.0", "element_mm = 200.0"),
            ("rate_per_s = 20.0", "rate_per_s = 2.0"),
            ("duration_s = 90.0", "duration_s = 20.0"),
            ("streams = 3", "streams = 2"),
            ("onset_s = 45.0", "onset_s = 10.0"),
            ("blocks = 3", "blocks = 2"),
            ("rate_sweep_per_s = [5.0, 50.0]", "rate_sweep_per_s = []"),
            ("noise_sweep = [0.0, 10.0, 100.0]", "noise_sweep = []"),
            ("size_sweep = [1.5]", "size_sweep = []"),
            ("law_sweep = [\"flores\"]", "law_sweep = []"),
            ("[ensemble]\n", "[ensemble]\nregion = { x_mm = [400.0, 1400.0], z_mm = [200.0, 1200.0] }\n"),
        ],
    )
}

/// Each stream's first lump against the single impact at the same mesh node, from rest: P_max
/// within 1e-4 (both step Newmark's rule in contact, the stream at T_s/m ≤ t_H/100, the
/// single impact at t_H/100: their period errors differ by O((ωΔt)²); measured 1.2e-5 and
/// 5.8e-6), the first contact's duration within two steps (measured within one: the two
/// grids end the contact at different steps); the jack forces and accelerometers recorded
/// and named.
#[test]
fn a_stream_on_the_tail_beam_strikes_as_single_impacts_do() {
    let scene = scene::Scene::parse(&small(), "tail-beam-stream (small)").unwrap();
    assert!(scene.identifies_on_tail_beam());
    let data = studies::stream::compute(&scene, &studies::progress::Silent).unwrap();
    assert_eq!(data.conditions.len(), 1);
    let c = &data.conditions[0];
    assert!(c.name.starts_with("tail beam"), "{}", c.name);
    assert_eq!(c.channels.len(), 4, "{:?}", c.channels);
    assert!(c.channels[0].starts_with("jack force at (600, 350) mm"), "{:?}", c.channels);
    assert!(c.channels[2].starts_with("acceleration at (1200, 350) mm"), "{:?}", c.channels);
    assert!(c.groups.iter().all(|g| g.auc.is_finite()));

    // The reference: the box's reduced model built here from the scene, struck once per lump.
    let tb = scene.tail_beam.as_ref().unwrap();
    let (steel, rho) = (scene.plate.material(), scene.plate.density());
    let built = tb.beam.build(steel.youngs_modulus(), steel.poisson_ratio(), tb.element, IN_TIME_LEVEL).unwrap();
    let [xs, _, zs] = tb.beam.lines(tb.element, IN_TIME_LEVEL).unwrap();
    let ensemble = scene.ensemble.as_ref().unwrap();
    let region = ensemble.ensemble.region;
    let nearest = |v: f64, lines: &[f64], (lo, hi): (f64, f64)| {
        let inside = lines.iter().copied().filter(|&l| l >= lo - 1e-9 && l <= hi + 1e-9);
        inside.min_by(|a, b| (a - v).abs().total_cmp(&(b - v).abs())).unwrap()
    };
    let study = scene.stream.as_ref().unwrap();
    let names: Vec<String> = ensemble.ensemble.families.iter().map(|f| f.name.clone()).collect();
    let mass = ShellMass::lumped(&built.structure, rho);
    let fact = built.structure.factorize(&built.restraints).unwrap();
    let groups: Vec<_> = built.jack_groups();
    let reduced = scene.signals.reduced();
    let (free, massive) = mass.free_dofs(&built.restraints);
    let settings = StructureSettings {
        modes: reduced.modes.min(studies::in_time::modes_for(free, massive)),
        damping: reduced.damping(),
        steps_per_contact: reduced.steps_per_contact,
        arithmetic: reduced.arithmetic,
    };
    // Each stream's first lump, its row and its load: one model (one modal search) for all.
    let firsts: Vec<_> = (0..study.streams)
        .map(|r| {
            let spec = StreamSpec { seed: study.spec.seed.wrapping_add(r as u64), ..study.spec };
            lumps(&ensemble.ensemble, &spec).unwrap().swap_remove(0)
        })
        .collect();
    let loads: Vec<Vec<f64>> = (firsts.iter())
        .map(|first| {
            let (x, z) = (nearest(first.draw.x, &xs, region.x), nearest(first.draw.z, &zs, region.z));
            built.structure.patch_load(built.top, &contact_patch(&tb.beam, x, z)).unwrap()
        })
        .collect();
    let readings = Readings { groups: &groups, ..Readings::default() };
    let model = StructureModel::new(&fact, &mass, &loads, readings, settings).unwrap();
    for (r, first) in firsts.iter().enumerate() {
        let row = c.lumps.iter().find(|l| l.stream == r).unwrap();
        assert_eq!((row.x, row.z, row.velocity), (first.draw.x, first.draw.z, first.draw.velocity));
        let (_, striker) = Striking::of(&scene).striker(&first.draw, &names[first.draw.family]).unwrap();
        let hit = model.impact(&striker, r, scene.signals.window).unwrap();
        let e = (row.force_max / hit.outcome.force_max - 1.0).abs();
        assert!(e < 1e-4, "stream {r}: P_max {} against {} ({e:e})", row.force_max, hit.outcome.force_max);
        let t_c = hit.outcome.contact_time.unwrap();
        eprintln!("stream {r}: P_max {e:.2e}, t_c {:.2e} steps", (row.contact_time - t_c).abs() / hit.dt);
        assert!((row.contact_time - t_c).abs() < 2.0 * hit.dt, "stream {r}: t_c {} against {t_c}", row.contact_time);
    }
}

/// A box asked for more modes than its mesh allows is refused by name before its modes are
/// sought.
#[test]
fn more_modes_than_the_box_allows_are_refused() {
    let text = edits(&small(), &[("modes = 200", "modes = 210")]);
    let scene = scene::Scene::parse(&text, "tail-beam-stream (210 modes)").unwrap();
    let e = studies::stream::compute(&scene, &studies::progress::Silent).unwrap_err().to_string();
    assert!(e.contains("signals.modes = 210") && e.contains("at most 200"), "{e}");
}

/// Where the stream is on the box, its region and sensors lie on the box's top plate (beyond
/// the paper's plate, within the box), and what only a plate has is refused by name.
#[test]
fn the_box_stream_scene_is_checked_against_the_box() {
    let s = small();
    expect(
        &edits(&s, &[("sensors_mm = [[1200.0, 350.0], [800.0, 1050.0]]", "sensors_mm = [[1700.0, 350.0]]")]),
        &["signals.sensors_mm", "1700"],
    );
    expect(
        &edits(&s, &[("region = { x_mm = [400.0, 1400.0]", "region = { x_mm = [400.0, 1650.0]")]),
        &["ensemble.region.x_mm[1]", "1650"],
    );
    expect(
        &edits(&s, &[("write_signal = false", "write_signal = false\nplate_sweep = [{ thickness_mm = 12.0 }]")]),
        &["stream.plate_sweep", "a tail beam's stream strikes the box"],
    );
    expect(
        &edits(&s, &[("write_signal = false", "write_signal = false\ndesign_sensors = 2")]),
        &["stream.design_sensors", "a tail beam's stream strikes the box"],
    );
    expect(&edits(&s, &[("modes = 200", "modes = \"chain\"")]), &["signals.modes", "chain"]);
    // The chain must record what the box's channels are.
    let jacks =
        "[measurement.support_force]\nadc_range_kn = 2000.0\nadc_bits = 16\nnoise = \"white\"\nnoise_rms_kn = 1.0\n";
    expect(&edits(&s, &[(jacks, "")]), &["measurement.support_force", "missing"]);
}
