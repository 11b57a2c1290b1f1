//! The identification study on a small ensemble (24 impacts, one support set), its numbers
//! against references that share no code with the statistics: the AUC as the Mann-Whitney
//! count over every (coal, gangue) pair, DeLong's standard error from its structural
//! components summed pair by pair, and the placement maps and the ranking's order from those
//! counts; and the shards Python computes against the study's own impacts.

use coupled::identification::ImpactRecord;
use coupled::reduced::{ReducedModel, ReducedSettings};
use identify::{Class, FEATURES};
use scene::{Scene, SceneSource};
use std::sync::OnceLock;
use studies::channel::ChannelInfo;
use studies::identify::{check, compute_with, ensemble, run_sensors, IdentifyData, MainImpact, Ranked};
use studies::progress::Silent;
use test_scenes::TINY_IDENTIFY;

/// The AUC and every number derived from it are ratios of pair counts (halves for ties) to
/// n₀n₁ = 144, computed here pair by pair and in the study by sorted ranks: the two agree to
/// the rounding of sums of at most 144 terms of order 1, far below 1e-12.
const EXACT: f64 = 1e-12;

/// ψ(gangue, coal) of the Mann-Whitney statistic: 1 if gangue reads higher, ½ on a tie.
fn psi(g: f64, c: f64) -> f64 {
    if g > c {
        1.0
    } else if g == c {
        0.5
    } else {
        0.0
    }
}

/// P(gangue > coal) + ½P(=) by counting every pair, and DeLong's standard error from the
/// structural components V(gᵢ) = mean over coal of ψ, V(cⱼ) = mean over gangue of ψ:
/// SE² = s²(V(g))/n₁ + s²(V(c))/n₀ with sample variances (DeLong, DeLong and
/// Clarke-Pearson 1988).
fn mann_whitney(coal: &[f64], gangue: &[f64]) -> (f64, f64) {
    let (n0, n1) = (coal.len() as f64, gangue.len() as f64);
    let v_g: Vec<f64> = gangue.iter().map(|&g| coal.iter().map(|&c| psi(g, c)).sum::<f64>() / n0).collect();
    let v_c: Vec<f64> = coal.iter().map(|&c| gangue.iter().map(|&g| psi(g, c)).sum::<f64>() / n1).collect();
    let auc = v_g.iter().sum::<f64>() / n1;
    let var = |v: &[f64]| v.iter().map(|x| (x - auc).powi(2)).sum::<f64>() / (v.len() as f64 - 1.0);
    (auc, (var(&v_g) / n1 + var(&v_c) / n0).sqrt())
}

/// The main run as the sink saw it: every impact and the channels.
struct Seen {
    records: Vec<ImpactRecord>,
    channels: Vec<ChannelInfo>,
}

impl Seen {
    /// One column by class: `value` of every impact, coal's and gangue's.
    fn split(&self, value: impl Fn(&ImpactRecord) -> f64) -> (Vec<f64>, Vec<f64>) {
        let of = |k: Class| self.records.iter().filter(|r| r.draw.class == k).map(&value).collect();
        (of(Class::Coal), of(Class::Gangue))
    }

    /// Feature `f` (its index in FEATURES) of channel `c` by class.
    fn feature(&self, c: usize, f: usize) -> (Vec<f64>, Vec<f64>) {
        self.split(|r| r.features[c * FEATURES.len() + f])
    }

    /// The channel and feature a ranked entry names.
    fn column_of(&self, r: &Ranked) -> (usize, usize) {
        let c = self.channels.iter().position(|i| i.label() == r.channel).expect("a channel of the run");
        (c, FEATURES.iter().position(|f| f.key() == r.feature.key()).expect("a feature"))
    }
}

/// The study on [`TINY_IDENTIFY`], run once for both tests.
fn run() -> &'static (Scene, IdentifyData, Seen) {
    static RUN: OnceLock<(Scene, IdentifyData, Seen)> = OnceLock::new();
    RUN.get_or_init(|| {
        let scene = Scene::parse(TINY_IDENTIFY, "tiny").unwrap();
        let mut seen = Seen { records: Vec::new(), channels: Vec::new() };
        let data = compute_with(&scene, &Silent, &mut |m: &MainImpact<'_>| {
            seen.records.push(m.record.clone());
            seen.channels = m.channels.to_vec();
            Ok(())
        })
        .unwrap();
        (scene, data, seen)
    })
}

/// Every AUC of the support set's result is the pair count of its column, with DeLong's
/// error; the ranking is in order of max(AUC, 1 - AUC) and opens with the best column of the
/// run; each placement map is the pair counts of its feature at the grid's channels.
#[test]
fn aucs_are_the_pair_counts_of_the_impacts() {
    let (_, data, seen) = run();
    let c = &data.summary.conditions[0];
    assert_eq!(seen.records.len(), 24);
    assert_eq!((data.summary.impacts, data.summary.classes), (24, (12, 12)));
    assert_eq!(c.validity.impacts, 24);

    let check = |r: &Ranked, (coal, gangue): (Vec<f64>, Vec<f64>)| {
        let (auc, se) = mann_whitney(&coal, &gangue);
        assert!((r.auc.auc - auc).abs() < EXACT, "{} {}: {} against {auc}", r.channel, r.feature.key(), r.auc.auc);
        assert!((r.auc.standard_error - se).abs() < EXACT, "{}: {} against {se}", r.channel, r.auc.standard_error);
        assert!(r.interval.0 <= r.interval.1 && (0.0..=1.0).contains(&r.interval.0) && r.interval.1 <= 1.0);
    };
    check(&c.force_max, seen.split(|r| r.force_max));
    check(&c.contact_time, seen.split(|r| r.contact_time.unwrap_or(0.0)));
    assert!(!c.ranking.is_empty());
    for r in c.ranking.iter().chain(&c.best_converged).chain(&c.reference) {
        let (ch, f) = seen.column_of(r);
        check(r, seen.feature(ch, f));
    }

    // The order: by separability, and the first is the best of every column of the run.
    let separability = |a: f64| a.max(1.0 - a);
    for w in c.ranking.windows(2) {
        assert!(separability(w[0].auc.auc) >= separability(w[1].auc.auc));
    }
    let best = (0..seen.channels.len())
        .flat_map(|ch| (0..FEATURES.len()).map(move |f| (ch, f)))
        .map(|(ch, f)| {
            let (coal, gangue) = seen.feature(ch, f);
            separability(mann_whitney(&coal, &gangue).0)
        })
        .fold(0.0, f64::max);
    assert!((separability(c.ranking[0].auc.auc) - best).abs() < EXACT);

    // The maps: every quantity over the 2 x 2 grid, each point the pair count of its channel.
    let maps = &data.details[0].maps;
    assert_eq!(maps.len(), 3);
    for m in maps {
        let f = m.feature.index();
        for (i, x) in m.x_mm.iter().enumerate() {
            for (j, z) in m.z_mm.iter().enumerate() {
                let ch = seen
                    .channels
                    .iter()
                    .position(|k| {
                        k.quantity == m.quantity && (k.at.0 * 1e3 - x).abs() < 1e-9 && (k.at.1 * 1e3 - z).abs() < 1e-9
                    })
                    .expect("a channel at the grid point");
                let (coal, gangue) = seen.feature(ch, f);
                let s = separability(mann_whitney(&coal, &gangue).0);
                assert!((m.separability[i][j] - s).abs() < EXACT, "{} at ({x}, {z}) mm", m.quantity);
            }
        }
    }
    // The variability study: size held, then position, size and speed.
    assert_eq!(c.held.iter().map(|h| h.held.as_str()).collect::<Vec<_>>(), ["size", "position, size and speed"]);
    baselines_are_the_pair_counts(c, seen);
}

/// The headline's baselines: t_c and P_max as scored above, the mass as the pair count with
/// masses within 1 % counted as ties, each mass (4/3)πr³ρ of its draw; the verdict by the
/// rule of `studies::identify::baselines` applied to those numbers.
fn baselines_are_the_pair_counts(c: &studies::identify::ConditionResult, seen: &Seen) {
    let h = &c.headline;
    let names: Vec<&str> = h.baselines.iter().map(|b| b.quantity).collect();
    assert_eq!(names, ["contact time t_c", "contact force P_max", "lump mass m"]);
    assert_eq!(h.baselines[0].auc.auc, c.contact_time.auc.auc);
    assert_eq!(h.baselines[1].auc.auc, c.force_max.auc.auc);
    let (mc, mg) = seen.split(|r| 4.0 / 3.0 * std::f64::consts::PI * r.draw.radius.powi(3) * r.draw.density);
    let mut u = 0.0;
    for a in &mc {
        for b in &mg {
            u += if b > &(a * 1.01) {
                1.0
            } else if a > &(b * 1.01) {
                0.0
            } else {
                0.5
            };
        }
    }
    let mass_auc = u / (mc.len() * mg.len()) as f64;
    assert!((h.baselines[2].auc.auc - mass_auc).abs() < EXACT, "{} against {mass_auc}", h.baselines[2].auc.auc);

    let sep = |a: f64| a.max(1.0 - a);
    let best = (0..3).max_by(|&i, &j| sep(h.baselines[i].auc.auc).total_cmp(&sep(h.baselines[j].auc.auc))).unwrap();
    assert_eq!(h.best_baseline, best);
    // The feature compared is the best one if the model resolves it, else the best resolved.
    let compared =
        if c.ranking[0].converged() { &c.ranking[0] } else { c.best_converged.as_ref().unwrap_or(&c.ranking[0]) };
    assert_eq!(h.feature, format!("{} {}", compared.feature.name(), compared.channel));
    let gain = sep(compared.auc.auc) - sep(h.baselines[best].auc.auc);
    assert!((h.gain - gain).abs() < EXACT);
    use studies::identify::baselines::Verdict;
    if sep(h.baselines[best].auc.auc) >= 0.99 {
        assert_eq!(h.verdict, Verdict::BaselineSeparates);
    } else {
        assert_ne!(h.verdict, Verdict::BaselineSeparates);
    }
}

/// What Python's shards compute (any range of the ensemble on a kept reduced model) is, bit
/// for bit, what the study's main run handed its sink: the impacts depend only on the scene
/// and their index.
#[test]
fn shards_are_the_main_runs_impacts() {
    let (scene, data, seen) = run();
    let set = &scene.conditions[0];
    let model = ReducedModel::new(&scene.plate, set, scene.signals.reduced()).unwrap();
    let study = scene.ensemble.as_ref().unwrap();
    let sensors = run_sensors(&scene.signals.sensors, study, &scene.plate).0;
    let mut records = Vec::new();
    for range in [0..7, 7..7, 7..24] {
        let shard = ensemble::shard(scene, &model, &sensors, range).unwrap();
        if !shard.records.is_empty() {
            let labels = |c: &[ChannelInfo]| c.iter().map(|i| i.label()).collect::<Vec<_>>();
            assert_eq!(labels(&shard.channels), labels(&seen.channels));
        }
        records.extend(shard.records.into_iter().map(|(_, r)| r));
    }
    assert!(records == seen.records);
    assert_eq!(data.summary.conditions[0].validity.impacts, records.len());
}

/// The change AUC_b − AUC_a of two scores of the same impacts by pair counts, with DeLong's
/// paired standard error from the differences of the structural components (DeLong, DeLong
/// and Clarke-Pearson 1988): each argument is (coal, gangue) in the same impact order.
fn paired_by_pairs(a: (&[f64], &[f64]), b: (&[f64], &[f64])) -> (f64, f64) {
    let components = |(coal, gangue): (&[f64], &[f64])| {
        let v_g: Vec<f64> =
            gangue.iter().map(|&g| coal.iter().map(|&c| psi(g, c)).sum::<f64>() / coal.len() as f64).collect();
        let v_c: Vec<f64> =
            coal.iter().map(|&c| gangue.iter().map(|&g| psi(g, c)).sum::<f64>() / gangue.len() as f64).collect();
        (v_g, v_c)
    };
    let ((ag, ac), (bg, bc)) = (components(a), components(b));
    let diff = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(x, y)| x - y).collect::<Vec<f64>>();
    let (dg, dc) = (diff(&bg, &ag), diff(&bc, &ac));
    let var = |v: &[f64]| {
        let m = v.iter().sum::<f64>() / v.len() as f64;
        v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() as f64 - 1.0)
    };
    let change = dg.iter().sum::<f64>() / dg.len() as f64;
    (change, (var(&dg) / dg.len() as f64 + var(&dc) / dc.len() as f64).sqrt())
}

/// With `signals.truncation_check_fraction = 0.5` the check strikes half of each family
/// again: every shift shown is the pair-count change between those impacts of the main run
/// and the same impacts on the half-mode model (run here as Python's shards run them, every
/// impact of the ensemble, then those picked), with DeLong's paired error times the finite
/// population correction √(1 − 12/24); the same impacts on every mode give the main run's
/// AUCs untouched. On every impact (the default) each shift is the whole ensemble's.
#[test]
fn the_check_on_a_subsample_is_the_pair_counts_of_its_impacts() {
    let (whole_scene, whole, seen) = run();
    let text = test_scenes::edit(TINY_IDENTIFY, "[signals]\n", "[signals]\ntruncation_check_fraction = 0.5\n");
    let scene = Scene::parse(&text, "tiny").unwrap();
    let data = compute_with(&scene, &Silent, &mut |_: &MainImpact<'_>| Ok(())).unwrap();
    let (c, w) = (&data.summary.conditions[0], &whole.summary.conditions[0]);
    let study = scene.ensemble.as_ref().unwrap();
    let counts: Vec<usize> = study.ensemble.families.iter().map(|f| f.count).collect();
    let rows = check::checked_impacts(0.5, &counts, check::set_seed(study.ensemble.seed, 0)).unwrap();
    assert_eq!((c.truncation_check.impacts, c.truncation_check.of, rows.len()), (12, 24, 12));
    assert!(c.truncation_check.coverage.is_empty() && w.truncation_check.coverage.len() == 3);
    assert!(w.ranking.iter().all(|r| r.resolution_error.is_none()));

    // The half-mode model's features of every impact.
    let set = &whole_scene.conditions[0];
    let settings = scene.signals.reduced();
    let half = ReducedModel::new(&scene.plate, set, ReducedSettings { modes: settings.modes / 2, ..settings }).unwrap();
    let sensors = run_sensors(&scene.signals.sensors, study, &scene.plate).0;
    let coarse: Vec<ImpactRecord> =
        ensemble::shard(&scene, &half, &sensors, 0..24).unwrap().records.into_iter().map(|(_, r)| r).collect();
    let at = |records: &[ImpactRecord], value: &dyn Fn(&ImpactRecord) -> f64| -> (Vec<f64>, Vec<f64>) {
        let of = |k: Class| rows.iter().filter(|&&i| records[i].draw.class == k).map(|&i| value(&records[i])).collect();
        (of(Class::Coal), of(Class::Gangue))
    };
    let correction = (1.0 - 12.0 / 24.0f64).sqrt();
    let expect = |r: &Ranked, value: &dyn Fn(&ImpactRecord) -> f64| {
        let ((fc, fg), (hc, hg)) = (at(&seen.records, value), at(&coarse, value));
        let (change, se) = paired_by_pairs((&hc, &hg), (&fc, &fg));
        let shown = (r.resolution.unwrap(), r.resolution_error.unwrap());
        assert!((shown.0 - change).abs() < EXACT, "{} {}: {} against {change}", r.channel, r.feature.key(), shown.0);
        assert!((shown.1 - se * correction).abs() < EXACT, "{}: {} against {}", r.channel, shown.1, se * correction);
    };
    expect(&c.force_max, &|r| r.force_max);
    expect(&c.contact_time, &|r| r.contact_time.unwrap_or(0.0));
    let mut nonzero = 0;
    for r in c.ranking.iter().chain(&c.best_converged) {
        let (ch, f) = seen.column_of(r);
        expect(r, &|rec| rec.features[ch * FEATURES.len() + f]);
        nonzero += usize::from(r.resolution_error.unwrap() > 0.0);
        // The main run is the whole ensemble's, whatever the check struck again.
        let same = w.ranking.iter().chain(&w.best_converged).find(|x| x.channel == r.channel && x.feature == r.feature);
        if let Some(x) = same {
            assert_eq!(x.auc, r.auc);
        }
    }
    assert!(nonzero > 0, "some entry's change has an error on the subsample");

    // The check on every impact: each shift is AUC(N) - AUC(N/2) of the whole ensemble, with
    // no error, by pair counts against the same half-mode impacts.
    let all = |records: &[ImpactRecord], value: &dyn Fn(&ImpactRecord) -> f64| -> (Vec<f64>, Vec<f64>) {
        let of = |k: Class| records.iter().filter(|r| r.draw.class == k).map(value).collect();
        (of(Class::Coal), of(Class::Gangue))
    };
    let whole_shift = |r: &Ranked, value: &dyn Fn(&ImpactRecord) -> f64| {
        let ((fc, fg), (hc, hg)) = (all(&seen.records, value), all(&coarse, value));
        let change = mann_whitney(&fc, &fg).0 - mann_whitney(&hc, &hg).0;
        assert!(r.resolution_error.is_none());
        assert!((r.resolution.unwrap() - change).abs() < EXACT, "{}: {:?} against {change}", r.channel, r.resolution);
    };
    whole_shift(&w.force_max, &|r| r.force_max);
    whole_shift(&w.contact_time, &|r| r.contact_time.unwrap_or(0.0));
    for r in w.ranking.iter().chain(&w.best_converged) {
        let (ch, f) = seen.column_of(r);
        whole_shift(r, &|rec| rec.features[ch * FEATURES.len() + f]);
    }
    assert!(!w.truncation_check.sampled && c.truncation_check.sampled);
}
