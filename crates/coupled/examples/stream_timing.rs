use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::reduced::stream::Arrival;
use coupled::reduced::{Quantity, ReducedModel, ReducedSettings, SignalSpec};
use coupled::transient::case::striker;
use coupled::SupportSet;
use plate_fem::Supports;
fn main() {
    let args: Vec<f64> = std::env::args().skip(1).map(|a| a.parse().unwrap()).collect();
    let (modes, rate, lam, dur) = (args[0] as usize, args[1], args[2], args[3]);
    let plate = Plate::new(0.4584, 0.360, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
    let set = SupportSet::new("Con 3", Supports::con3(5.11545e8));
    let t0 = std::time::Instant::now();
    let model = ReducedModel::new(&plate, &set, ReducedSettings { modes, ..ReducedSettings::default() }).unwrap();
    eprintln!("model {:?}", t0.elapsed());
    let spec = SignalSpec {
        rate_hz: rate,
        quantities: vec![Quantity::Acceleration],
        corners: false,
        ..SignalSpec::new(vec![(0.2292, 0.18), (0.4584, 0.18)])
    };
    let probes = model.probes(&spec).unwrap();
    let coal = Sphere::new(
        "coal",
        1380.0,
        0.025,
        Elastic::new(2.26e9, 0.28).unwrap(),
        RockStrength::new(8.39e6, 25.0).unwrap(),
    )
    .unwrap();
    let mut arr = vec![];
    let mut t = 0.0;
    let mut k = 0u64;
    while t < dur {
        k += 1;
        let u = ((k * 2654435761) % 1000) as f64 / 1000.0 + 0.0005;
        t += -u.ln() / lam;
        arr.push(Arrival { time: t, striker: striker(&plate, &coal, 0.65, 2.0), x: 0.05 + 0.35 * u, z: 0.3 - 0.2 * u });
    }
    arr.pop();
    let t0 = std::time::Instant::now();
    let s = model.stream(&arr, &probes, dur).unwrap();
    let el = t0.elapsed().as_secs_f64();
    eprintln!("{} lumps, {} s in {el:.3} s: {:.0}x real time; joint {}", s.lumps.len(), dur, dur / el, s.joint_steps);
}
