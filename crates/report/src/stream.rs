//! `impact stream` rendered: the detection page (findings, the simulation, the detector on
//! each group of channels beside the baselines, the noise and arrival-rate sweeps), the
//! windows' and lumps' truth as CSV, the first stream's recorded signals as CSV with a JSON
//! sidecar of their metadata where the scene asks for them, and the data as JSON.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use analytic::params::compact;
use identify::stream::SignalFormat;
use output::Artifacts;
use scene::Scene;
use studies::progress::Progress;
pub use studies::stream::check;
use studies::stream::{compute, ConditionStream, RecordedSignal, Score, StreamData};

const PAGE: &str = include_str!("templates/stream/page.md");
const STRUCK_PLATE: &str = include_str!("templates/stream/struck-plate.md");
const STRUCK_BOX: &str = include_str!("templates/stream/struck-box.md");
const SIMULATION_PLATE: &str = include_str!("templates/stream/simulation-plate.md");
const SIMULATION_BOX: &str = include_str!("templates/stream/simulation-box.md");
const SEGMENTS: &str = include_str!("templates/stream/segments.md");

/// Runs the stream study of `scene` and returns its files and data.
pub fn report(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, StreamData), Failure> {
    let data = compute(scene, progress)?;
    let mut a = Artifacts::new();
    a.add("index.md", page(scene, &data)?);
    a.add("stream.json", serde_json::to_string_pretty(&data)?);
    let stamp = crate::provenance::Provenance::of(scene);
    for c in &data.conditions {
        let dir = crate::present::rows::slug(&c.name);
        let mut detector = c.detector.clone();
        detector.provenance.scene_sha256 = Some(stamp.scene_sha256.clone());
        a.add(format!("{dir}/detector.json"), detector.to_json());
        a.add(format!("{dir}/windows.csv"), windows_table(c).to_csv());
        a.add(format!("{dir}/lumps.csv"), lumps_table(c).to_csv());
        if let Some(s) = &c.signal {
            let format = data.study.signal_format;
            let keys = signal_keys(s);
            let meta = serde_json::to_string_pretty(&serde_json::json!({
                "format": identify::recording::FORMAT,
                "data": format.file_name(),
                "rate_hz": s.rate_hz,
                "samples": s.columns.first().map_or(0, Vec::len),
                "stream": 0,
                "time_column": keys.first(),
                "columns": keys.get(1..).unwrap_or_default(),
                "channels": s.names,
                "onset_s": data.study.spec.profile.onset,
                "measured": data.measured,
            }))?;
            let bytes = match format {
                SignalFormat::Csv => signal_table(s).to_csv().into_bytes(),
                // The sidecar inside the file as the sidecar file will read, stamped.
                SignalFormat::Parquet => {
                    let stamped = String::from_utf8(stamp.stamp_json(meta.as_bytes())).unwrap_or_else(|_| meta.clone());
                    signal_parquet(s, &keys, &stamped)?
                }
            };
            a.add(format!("{dir}/{}", format.file_name()), bytes);
            a.add(format!("{dir}/signal.json"), meta);
        }
    }
    Ok((a, data))
}

/// The signal file's column keys, the time's first: those of its CSV header.
fn signal_keys(s: &studies::stream::RecordedSignal) -> Vec<String> {
    let csv =
        signal_table(&RecordedSignal { rate_hz: s.rate_hz, names: s.names.clone(), columns: Vec::new() }).to_csv();
    let header = csv.lines().find(|l| !l.starts_with('#')).unwrap_or_default();
    header.split(',').map(str::to_string).collect()
}

/// The signal as Parquet: the CSV's columns under its keys, the same numbers to the bit
/// (the channels' units are SI already; a column whose header names another unit is
/// converted as the CSV converts it), with the sidecar `meta` inside.
fn signal_parquet(s: &studies::stream::RecordedSignal, keys: &[String], meta: &str) -> Result<Vec<u8>, Failure> {
    let n = s.columns.first().map_or(0, Vec::len);
    let time: Vec<f64> = (0..n).map(|k| k as f64 / s.rate_hz).collect();
    let scaled: Vec<Vec<f64>> = s
        .columns
        .iter()
        .zip(&s.names)
        .map(|(c, h)| match crate::present::table::csv_key(h).1 {
            1.0 => c.clone(),
            f => c.iter().map(|v| v * f).collect(),
        })
        .collect();
    let columns: Vec<(&str, &[f64])> = std::iter::once(time.as_slice())
        .chain(scaled.iter().map(Vec::as_slice))
        .zip(keys)
        .map(|(c, k)| (k.as_str(), c))
        .collect();
    Ok(identify::recording::parquet::write(&columns, Some(meta))?)
}

/// The page.
fn page(scene: &Scene, d: &StreamData) -> Result<String, Failure> {
    let s = &d.study;
    let p = s.spec.profile;
    let main = summary_table(d).to_markdown();
    let baselines = baselines_table(d).to_markdown();
    let groups = groups_table(d).to_markdown();
    let sweeps = [noise_table(d), rate_table(d)]
        .into_iter()
        .filter(|t| !t.rows.is_empty())
        .map(|t| t.to_markdown())
        .collect::<Vec<_>>()
        .join("\n");
    let transfer = transfer_table(d);
    let (struck, mut simulation_prose) = struck(d)?;
    let modes = d.structure.as_ref().map_or(scene.signals.modes, |f| f.modes);
    let fast = crate::arithmetic::paragraph(scene.signals.arithmetic, modes)?;
    if !fast.is_empty() {
        simulation_prose = format!("{simulation_prose}\n{}", fast.trim_end());
    }
    if let Some(cut) = segments(d)? {
        simulation_prose = format!("{simulation_prose}\n\n{}", cut.trim_end());
    }
    Ok(render(
        "stream/page.md",
        PAGE,
        &[
            ("scene", scene.name.clone()),
            ("streams", s.streams.to_string()),
            ("duration", compact(s.spec.duration)),
            ("rate", compact(s.spec.rate_per_s)),
            ("before", compact(p.before)),
            ("after", compact(p.after)),
            ("onset", compact(p.onset)),
            ("ramp", compact(p.ramp)),
            ("window", compact(s.window)),
            ("hop", compact(s.hop)),
            ("blocks", s.blocks.to_string()),
            ("alarm", compact(s.alarm_probability)),
            (
                "signals",
                if d.measured {
                    "through the scene's measurement chain".into()
                } else {
                    "noise-free, as the model gives them".into()
                },
            ),
            ("summary", main),
            ("baselines", baselines),
            ("groups", groups),
            ("sweeps", sweeps),
            ("simulation", simulation_table(d).to_markdown()),
            ("struck", struck),
            ("simulation_prose", simulation_prose),
            ("transfer", transfer.0.to_markdown()),
            ("worst", transfer.1),
            ("design", crate::stream_design::section(d)?),
            ("band", crate::stream_band::section(d, scene.measurement.as_ref().map(|m| m.band_tolerance))?),
        ],
    )?)
}

/// What the lumps strike and how their simulation is told: the plate's sentences, or the
/// tail beam's with its model and the chain's band against its highest mode.
fn struck(d: &StreamData) -> Result<(String, String), Failure> {
    let Some(f) = &d.structure else {
        return Ok((STRUCK_PLATE.trim_end().to_string(), SIMULATION_PLATE.trim_end().to_string()));
    };
    let highest = sig(f.frequencies_hz.1, 3);
    let band = match (f.resolved, f.gain_above_highest) {
        (Some(true), Some(g)) => format!("The chain passes at most {} of a response above the highest kept mode ({highest} Hz), within its band tolerance: the recorded features are resolved by the modes.", sig(g, 2)),
        (Some(false), Some(g)) => format!("**Not resolved:** the chain passes up to {} of a response above the highest kept mode ({highest} Hz), beyond its band tolerance, so the accelerometers' features miss what the box does above it (the jacks' forces, carried by the box's low modes and the static correction, much less); the detector's scores on the accelerometers are those of a model truncated inside the chain's band.", sig(g, 2)),
        _ => "The signals are the model's, without a chain: the accelerometers' features carry the truncation at the highest kept mode.".to_string(),
    };
    let main = d.conditions.first().and_then(|c| c.groups.first());
    let band = match (&f.truncation, main) {
        (Some((half, score)), Some(main)) => format!(
            "{band} The truncation's check: on the lowest {half} modes (the rest joining the static correction) the every-channel detector scores {} against {} on all {} (the transfer table carries the accelerometers' detector there too).",
            auc_text(score),
            auc_text(main),
            f.modes,
        ),
        _ => band,
    };
    let struck = render(
        "stream/struck-box.md",
        STRUCK_BOX,
        &[
            ("unknowns", f.unknowns.to_string()),
            ("modes", f.modes.to_string()),
            ("f1", sig(f.frequencies_hz.0, 3)),
            ("fn", highest),
            ("points", f.load_points.to_string()),
            ("spacing", sig(f.spacing * 1e3, 3)),
            ("band", band),
        ],
    )?;
    Ok((struck.trim_end().to_string(), SIMULATION_BOX.trim_end().to_string()))
}

/// How the streams were cut in time, where they were: the segments and each support set's
/// warm-up with the decay rate it follows from.
fn segments(d: &StreamData) -> Result<Option<String>, Failure> {
    let cut: Vec<_> = d.conditions.iter().filter_map(|c| c.simulation.segments.map(|s| (c.name.as_str(), s))).collect();
    let Some(&(_, first)) = cut.first() else { return Ok(None) };
    let warm_ups = cut
        .iter()
        .map(|(name, s)| format!("{name}: {} s at r = {} 1/s", sig(s.warm_up_s, 3), sig(s.slowest_decay_per_s, 3)))
        .collect::<Vec<_>>()
        .join("; ");
    let added = cut.iter().map(|(_, s)| s.added_share).fold(0.0, f64::max);
    // A segment alone is built for the plate's support sets; the box's streams run whole.
    let alone = if d.structure.is_some() {
        String::new()
    } else {
        " A segment computed alone (`impact.stream_recording(..., segment=b)`, or every segment as a Dask task with `impact.shards.run_stream`) is this page's, bit for bit.".into()
    };
    Ok(Some(render(
        "stream/segments.md",
        SEGMENTS,
        &[
            ("segments", first.segments.to_string()),
            ("length", compact(first.length_s)),
            ("warm_ups", warm_ups),
            ("tolerance", sig(first.tolerance, 2)),
            ("alone", alone),
            ("added", format!("{} %", sig(100.0 * added, 2))),
        ],
    )?))
}

/// "0.97 (0.95-0.98)".
fn auc_text(s: &Score) -> String {
    format!("{} ({}-{})", sig(s.auc, 3), sig(s.interval.0, 3), sig(s.interval.1, 3))
}

/// A score's AUC with its interval.
fn auc_cell(s: &Score) -> Cell {
    format!("{} ({}-{})", sig(s.auc, 3), sig(s.interval.0, 3), sig(s.interval.1, 3)).into()
}

/// A delay in seconds, or "none".
fn delay_cell(d: Option<f64>) -> Cell {
    d.map_or_else(|| "none".into(), |d| format!("{} s", sig(d, 3)).into())
}

/// False alarms per hour.
fn alarm_cell(s: &Score) -> Cell {
    s.false_alarms_per_hour.map_or_else(|| "n/a".into(), |f| format!("{} ({})", sig(f, 3), s.false_alarms).into())
}

/// Per support set: the every-channel detector, its delay and false alarms, beside the best baseline.
pub fn summary_table(d: &StreamData) -> Table {
    let mut t = Table::new(
        "window detection on every channel: AUC over windows (95 % block-bootstrap interval), median delay from the onset, false alarms per hour (count)",
        &["support set", "signals", "AUC", "median delay", "false alarms/h", "best baseline", "its AUC", "detector against it"],
    );
    for c in &d.conditions {
        let Some(every) = c.groups.first() else { continue };
        let best = c.baselines.iter().max_by(|a, b| a.auc.total_cmp(&b.auc));
        t.push(vec![
            c.name.as_str().into(),
            (if d.measured { "measured" } else { "noise-free" }).into(),
            auc_cell(every),
            delay_cell(every.median_delay_s),
            alarm_cell(every),
            best.map_or("".into(), |b| b.quantity.into()),
            best.map_or("".into(), |b| {
                format!("{} ({}-{})", sig(b.auc, 3), sig(b.interval.0, 3), sig(b.interval.1, 3)).into()
            }),
            best.map_or("".into(), |b| against(every, b).into()),
        ]);
    }
    t
}

/// The detector's AUC against a baseline's, by their intervals.
fn against(s: &Score, b: &studies::stream::Baseline) -> &'static str {
    if s.interval.0 > b.interval.1 {
        "above, beyond both intervals"
    } else if s.interval.1 < b.interval.0 {
        "below, beyond both intervals"
    } else {
        "within the intervals"
    }
}

fn baselines_table(d: &StreamData) -> Table {
    let mut t = Table::new(
        "baselines: a window's lumps' own truth as its score, separation max(AUC, 1 - AUC) with 95 % block-bootstrap interval",
        &["support set", "quantity", "separation", "interval"],
    );
    for c in &d.conditions {
        for b in &c.baselines {
            t.push(vec![
                c.name.as_str().into(),
                b.quantity.into(),
                Cell::Sig(b.auc, 3),
                format!("{}-{}", sig(b.interval.0, 3), sig(b.interval.1, 3)).into(),
            ]);
        }
    }
    t
}

fn groups_table(d: &StreamData) -> Table {
    let mut t = Table::new(
        "the detector by channel group: AUC over windows, delay per stream, false alarms",
        &["support set", "channels", "AUC", "delays", "false alarms/h", "windows scored"],
    );
    for c in &d.conditions {
        for g in &c.groups {
            let delays: Vec<String> = g.delays_s.iter().map(|d| d.map_or("none".into(), |d| sig(d, 3))).collect();
            t.push(vec![
                c.name.as_str().into(),
                g.group.as_str().into(),
                auc_cell(g),
                format!("{} s", delays.join(", ")).into(),
                alarm_cell(g),
                Cell::Int(g.scored_windows as u64),
            ]);
        }
    }
    t
}

fn noise_table(d: &StreamData) -> Table {
    let mut t = Table::new(
        "what survives the noise: the chain's background as stated (1) and scaled (0: the ADC's step alone), every channel",
        &["support set", "background scale", "best channel's SNR (dB)", "AUC", "median delay", "false alarms/h"],
    );
    for c in &d.conditions {
        for n in &c.noise_sweep {
            t.push(vec![
                c.name.as_str().into(),
                Cell::Given(n.scale),
                n.snr_db.map_or("ADC step only".into(), |s| Cell::Sig(s, 3)),
                auc_cell(&n.score),
                delay_cell(n.score.median_delay_s),
                alarm_cell(&n.score),
            ]);
        }
    }
    t
}

/// The shift that costs the most AUC, in words.
pub fn worst_transfer(d: &StreamData) -> String {
    transfer_table(d).1
}

/// Every transfer, and the shift that costs the most AUC in words.
fn transfer_table(d: &StreamData) -> (Table, String) {
    let mut t = Table::new(
        "transfer: a detector on the sensors' channels fitted on one support set's main run (its training blocks), carried to another condition's held-out block; beside it the matched detector, cross-validated on the test condition itself",
        &["trained on", "carried to", "shift", "AUC carried", "AUC matched", "loss", "median delay", "false alarms/h"],
    );
    for p in &d.transfer {
        t.push(vec![
            p.trained_on.as_str().into(),
            p.tested_on.as_str().into(),
            (if p.shift.is_empty() { "support set" } else { p.shift.as_str() }).into(),
            auc_cell(&p.transferred),
            auc_cell(&p.matched),
            Cell::Sig(p.loss(), 2),
            delay_cell(p.transferred.median_delay_s),
            alarm_cell(&p.transferred),
        ]);
    }
    let worst = d.transfer.iter().max_by(|a, b| a.loss().total_cmp(&b.loss()));
    let words = worst.map_or("No transfer ran (one support set, no sweeps, or no sensor channels).".to_string(), |w| {
        let shift = if w.shift.is_empty() {
            format!("to {}", w.tested_on)
        } else {
            format!("to {} on {}", w.shift, w.tested_on)
        };
        format!(
            "The shift that costs the most: {} carried {shift}, AUC {} against {} matched (loss {}).",
            w.trained_on,
            sig(w.transferred.auc, 3),
            sig(w.matched.auc, 3),
            sig(w.loss(), 2)
        )
    });
    (t, words)
}

fn rate_table(d: &StreamData) -> Table {
    let mut t = Table::new(
        "what survives crowding: other arrival rates, the chain as stated, every channel",
        &["support set", "lumps/s", "in contact together", "AUC", "median delay", "false alarms/h"],
    );
    for c in &d.conditions {
        for r in &c.rate_sweep {
            t.push(vec![
                c.name.as_str().into(),
                Cell::Given(r.rate_per_s),
                Cell::Rel(r.overlapped_share),
                auc_cell(&r.score),
                delay_cell(r.score.median_delay_s),
                alarm_cell(&r.score),
            ]);
        }
    }
    t
}

fn simulation_table(d: &StreamData) -> Table {
    let free = if d.structure.is_some() { "free box, real time ×" } else { "free plate, real time ×" };
    let mut t = Table::new(
        "the simulation: lumps, simultaneous contacts, lumps let go while resting on the plate, the left-out cross static correction's bound, and the cost against the free plate measured in the same run",
        &[
            "support set",
            "lumps",
            "contact steps a lump",
            "in contact together",
            "joint steps",
            "unconverged",
            "let go in contact",
            "cross correction bound",
            "modes",
            "model rate (Hz)",
            "real time ×",
            free,
        ],
    );
    for c in &d.conditions {
        let s = &c.simulation;
        t.push(vec![
            c.name.as_str().into(),
            Cell::Int(s.lumps as u64),
            Cell::Sig(s.steps_per_lump, 3),
            Cell::Rel(s.overlapped_share),
            Cell::Int(s.joint_steps as u64),
            Cell::Int(s.unconverged_steps as u64),
            Cell::Int(s.released_in_contact as u64),
            Cell::Rel(s.cross_residual_bound),
            Cell::Int(s.modes as u64),
            Cell::Given(s.model_rate_hz),
            Cell::Sig(s.real_time_factor, 3),
            Cell::Sig(s.free_real_time_factor, 3),
        ]);
    }
    t
}

fn windows_table(c: &ConditionStream) -> Table {
    let mut t = Table::new(
        "",
        &[
            "stream",
            "start (s)",
            "end (s)",
            "lumps",
            "gangue lumps",
            "expected gangue share",
            "gangue-rich",
            "P(gangue-rich)",
        ],
    );
    for w in &c.windows {
        t.push(vec![
            Cell::Int(w.stream as u64),
            Cell::Num(w.start),
            Cell::Num(w.end),
            Cell::Int(w.lumps as u64),
            Cell::Int(w.gangue as u64),
            Cell::Num(w.expected_share),
            w.gangue_rich.into(),
            w.score.map_or("".into(), Cell::Num),
        ]);
    }
    t
}

fn lumps_table(c: &ConditionStream) -> Table {
    let mut t = Table::new(
        "",
        &[
            "stream",
            "t (s)",
            "family",
            "gangue",
            "m (kg)",
            "v0 (m/s)",
            "x (m)",
            "z (m)",
            "contacts",
            "t_c (s)",
            "P_max (N)",
            "in contact with another",
        ],
    );
    for l in &c.lumps {
        t.push(vec![
            Cell::Int(l.stream as u64),
            Cell::Num(l.time),
            l.family.as_str().into(),
            l.gangue.into(),
            Cell::Num(l.mass),
            Cell::Num(l.velocity),
            Cell::Num(l.x),
            Cell::Num(l.z),
            Cell::Int(l.contacts as u64),
            Cell::Num(l.contact_time),
            Cell::Num(l.force_max),
            l.overlapped.into(),
        ]);
    }
    t
}

fn signal_table(s: &studies::stream::RecordedSignal) -> Table {
    let mut headers = vec!["t (s)".to_string()];
    headers.extend(s.names.iter().cloned());
    let refs: Vec<&str> = headers.iter().map(String::as_str).collect();
    let mut t = Table::new("", &refs);
    let n = s.columns.first().map_or(0, Vec::len);
    for k in 0..n {
        let mut row = vec![Cell::Num(k as f64 / s.rate_hz)];
        row.extend(s.columns.iter().map(|c| Cell::Num(c.get(k).copied().unwrap_or(0.0))));
        t.push(row);
    }
    t
}
