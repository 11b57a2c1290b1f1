//! One stream of the study, or one segment of it, computed alone: the study's numbers bit
//! for bit, so that streams and segments are computed apart (a task each) and put together.

use super::run::{lump_rows, record_one, Simulated, RECORDING_KEY};
use super::segments;
use super::{channel_name, LumpRow, RecordedSignal};
use crate::identify::sensors::{channel_infos, spec};
use crate::Failure;
use coupled::identification::Instrument;
use coupled::reduced::ReducedModel;
use identify::stream::{lumps, StreamSpec, StreamStudy};
use scene::{Scene, SupportSet};

/// Stream `r` of the scene's study on support set `set` alone, recorded as the study records
/// it (its lumps drawn with the seed `seed + r`, its background from its own stream of random
/// numbers): the same numbers, bit for bit, as the study's stream `r`, for any `r`, so that
/// streams can be computed apart (one per worker) and put together. With `segment`, only
/// that segment of a stream the scene cuts (`segment_s`): its samples and the lumps that
/// touched within it, the study's own bit for bit.
pub fn one_stream(
    scene: &Scene,
    (study, ensemble): (&StreamStudy, &identify::Study),
    set: &SupportSet,
    (r, segment): (usize, Option<usize>),
) -> Result<(RecordedSignal, Vec<LumpRow>), Failure> {
    if scene.identifies_on_tail_beam() {
        return Err(format!(
            "scene {}: its stream strikes the tail beam, whose streams are run together by the whole study (impact stream); one stream apart is built for the plate's support sets only",
            scene.name
        )
        .into());
    }
    // The recording's stream of random numbers is RECORDING_KEY + r.
    if r > usize::MAX - RECORDING_KEY {
        return Err(format!("stream {r}: allowed at most {}", usize::MAX - RECORDING_KEY).into());
    }
    if let Some(why) = segment.and_then(|b| segments::refusal(scene, study, b)) {
        return Err(why.into());
    }
    let plate = &scene.plate;
    let model = ReducedModel::new(plate, set, crate::identify::sensors::reduced_settings(scene, set)?)?;
    let sensors = scene.signals.sensors.clone();
    let instrument = Instrument::new(&model, plate, &spec(scene, sensors.clone()), scene)?;
    let names: Vec<String> = ensemble.ensemble.families.iter().map(|f| f.name.clone()).collect();
    let spec = StreamSpec { seed: study.spec.seed.wrapping_add(r as u64), ..study.spec };
    let mut lumps = lumps(&ensemble.ensemble, &spec).map_err(|e| format!("stream {r}: {e}"))?;
    let cutting = segments::cutting(&instrument, study)?;
    let (response, pieces) = match segment {
        None => segments::run(&instrument, (&lumps, &names), spec.duration, cutting)
            .map_err(|e| format!("stream {r}: {e}"))?,
        Some(b) => {
            let (alone, span) = segments::one(&instrument, (&lumps, &names), spec.duration, (cutting, b))?;
            let rate = instrument.model_rate_hz();
            lumps.retain(|l| span.reports(l.time, rate));
            alone
        }
    };
    let sim = Simulated { lumps, response, seconds: 0.0, pieces };
    let columns = record_one(&instrument, r, &sim, 1.0);
    let rate_hz = instrument.chain().map_or_else(|| instrument.model_rate_hz(), |c| c.spec().rate_hz);
    let names = channel_infos(&instrument, &sensors, plate).iter().map(channel_name).collect();
    let mut rows = lump_rows(ensemble, std::slice::from_ref(&sim));
    for row in &mut rows {
        row.stream = r;
    }
    Ok((RecordedSignal { rate_hz, names, columns }, rows))
}
