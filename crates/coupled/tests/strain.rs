//! The reduced model's strain channel (a strain gauge along x on the unstruck face) against
//! its definition read off three deflection channels.
//!
//! Within one Bogner-Fox-Schmit element the deflection is a cubic in x along a line of
//! constant z, so its second derivative is exactly the central difference
//! (w(x+d) - 2w(x) + w(x-d))/d² for any d that keeps the three points in the element. Both
//! the modal part and the static correction of a channel are linear in its point functional,
//! so the strain channel, built from ∂²N/∂x² (`plate_fem::Model::bending_strain`) and its own
//! residual solve, must equal -(h/2) times that difference of the deflection channels, built
//! from N alone, at every sample: a check that shares neither the second derivatives nor the
//! strain's residual field with the channel under test.

use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::reduced::{ChannelKind, Quantity, ReducedModel, ReducedSettings, SignalSpec};
use coupled::transient::case::striker;
use coupled::SupportSet;
use plate_fem::Supports;

#[test]
fn strain_is_the_second_difference_of_the_deflection() {
    let h = 0.008;
    let plate = Plate::new(0.4584, 0.360, h, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
    let gangue = Sphere::new(
        "gangue",
        2400.0,
        0.025,
        Elastic::new(16e9, 0.28).unwrap(),
        RockStrength::new(37.68e6, 37.0).unwrap(),
    )
    .unwrap();
    for set in [SupportSet::new("Con 1", Supports::con1()), SupportSet::new("Con 3", Supports::con3(5.11545e8))] {
        // 8 elements along x (57.3 mm each): x = 95-105 mm lies inside the second one.
        let settings = ReducedSettings { modes: 30, elements: 8, ..ReducedSettings::default() };
        let model = ReducedModel::new(&plate, &set, settings).unwrap();
        let (x, z, d) = (0.1, 0.1, 0.005);
        let sensors = vec![(x - d, z), (x, z), (x + d, z)];
        let spec = SignalSpec {
            window: 0.005,
            quantities: vec![Quantity::Displacement, Quantity::Strain],
            corners: false,
            ..SignalSpec::new(sensors)
        };
        let probes = model.probes(&spec).unwrap();
        // Struck away from the gauge and on it: the static correction differs in the two.
        for (px, pz) in [(0.3, 0.2), (0.1, 0.1)] {
            let s = striker(&plate, &gangue, 0.65, 1.0);
            let out = model.impact(&s, px, pz, &probes).unwrap();
            let channel = |k: ChannelKind| &out.signals.channel(k).unwrap().samples;
            let w: Vec<&Vec<f64>> = (0..3).map(|s| channel(ChannelKind::Displacement { sensor: s })).collect();
            let strain = channel(ChannelKind::Strain { sensor: 1 });
            let peak = strain.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(peak > 1e-6, "{}: a gauge near the impact reads microstrains, not {peak}", set.name);
            for (k, e) in strain.iter().enumerate() {
                let difference = -0.5 * h * (w[2][k] - 2.0 * w[1][k] + w[0][k]) / (d * d);
                // Round-off: the difference cancels w to (d/ℓ)² ≈ 1e-3 of itself, so 1e-16 of w
                // becomes ~1e-13 of the strain; 1e-9 of the peak leaves room for the solves.
                assert!(
                    (e - difference).abs() <= 1e-9 * peak,
                    "{} at ({px}, {pz}), sample {k}: {e} against {difference}",
                    set.name
                );
            }
        }
    }
}
