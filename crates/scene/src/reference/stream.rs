//! The reference's section of `[stream]`: the caving-stream detection study
//! (`identify::stream`, `identify::detect`).

use super::{key, num, whole, Section, NO_UNIT, REQUIRED};
use crate::limits;
use analytic::params::Range;

/// `[stream]`.
pub(super) fn sections() -> Vec<Section> {
    let share = Range::closed(0.0, 1.0);
    vec![Section {
        title: "[stream]",
        about: "A caving-stream detection study on the scene's `[ensemble]` (\"identify\" only; `impact stream`): the ensemble's lumps arrive as a Poisson process whose gangue share steps from `gangue_before` to `gangue_after`, the plate carries every lump's response into the next, the channels are recorded through `[measurement]` if given, and a logistic detector scores sliding windows, cross-validated by time blocks. The streams are held at once: their model signals and recordings must fit in 4 GB, the lumps of every stream, rate and support set in ten million, and the windows in a million. With as many `blocks` as `streams` the cross-validation is leave-one-stream-out and every window is scored; a block whose training windows hold one class only is refused before anything runs.".into(),
        keys: vec![
            num("rate_per_s", "1/s", limits::STREAM_RATE_PER_S, REQUIRED, "Lumps per second λ"),
            num("duration_s", "s", limits::STREAM_DURATION_S, REQUIRED, "Length of each stream"),
            whole("streams", limits::STREAMS, "1", "Independent streams (stream r drawn with seed + r)"),
            key("seed", "whole number", NO_UNIT, "0 to 2^63 - 1 (a TOML integer)", "1", "Seed of the arrivals and their classes"),
            num("gangue_before", NO_UNIT, share, REQUIRED, "Gangue share before the change"),
            num("gangue_after", NO_UNIT, share, REQUIRED, "Gangue share after it; above `gangue_before` (the detector looks for a turn to gangue-rich)"),
            key("onset_s", "number", "s", "(0, duration_s)", REQUIRED, "When the change starts"),
            key("ramp_s", "number", "s", "[0, duration_s - onset_s]", "0", "How long the change takes (linear)"),
            key(
                "window_s",
                "number",
                "s",
                "[16 samples of the recording, min(onset_s, duration_s - onset_s)]",
                REQUIRED,
                "The detector's window W",
            ),
            key("hop_s", "number", "s", "[one sample, window_s]", REQUIRED, "Its hop H"),
            whole("blocks", limits::STREAM_BLOCKS, "5", "Time blocks of the cross-validation over the streams laid end to end, at most one per window"),
            num("alarm_probability", NO_UNIT, Range::open(0.0, 1.0), "0.5", "The out-of-fold probability that raises an alarm"),
            key("rate_sweep_per_s", "list of numbers", "1/s", limits::STREAM_RATE_PER_S.to_string(), "none", "Further arrival rates, each a whole study"),
            key("noise_sweep", "list of numbers", NO_UNIT, "[0, 1e6]; needs `[measurement]`", "none", "Scales of the chain's background, each scored on the same streams"),
            key("size_sweep", "list of numbers", NO_UNIT, limits::STREAM_SIZE_SCALE.to_string(), "none", "Scales of every family's radius law (median and bounds), each a whole study at the main rate, to which each support set's detector is carried"),
            key("plate_sweep", "list of tables", NO_UNIT, "each `{ key = value, ... }` with at least one of `[plate]`'s keys (`length_mm`, `width_mm`, `thickness_mm`, `youngs_modulus_gpa`, `poisson_ratio`, `density_kg_m3`) in its `[plate]` range; the plate it makes must carry the support sets, the sensors (at their points in mm), `[ensemble.region]` if given, and `signals.modes`; not on a tail beam", "none", "Other plates, each `[plate]` with the keys given changed and a whole study at the main rate on it (its own reduced model; the same supports, sensor points and chain; the lumps' uniforms over its whole face unless `[ensemble.region]` is given), to which each support set's detector is carried"),
            key("thickness_sweep_mm", "-", NO_UNIT, "none: refused", "none", "Replaced by `plate_sweep`; a scene that still names it is refused with the entry to write (`plate_sweep = [{ thickness_mm = 12.0 }]`)"),
            key("law_sweep", "list of strings", NO_UNIT, "keys of `contact_law`", "none", "Other contact laws, each a whole study at the main rate, to which each support set's detector is carried"),
            key("segment_s", "number", "s", format!("[max({}, window_s), duration_s]", limits::MIN_SEGMENT_S), "none", "Cut every stream into segments this long, each run and recorded alone from rest after a warm-up (the plate's and the chain's slowest decay to `segment_tolerance`), so that segments computed apart (`impact.stream_recording(..., segment=b)`) put together to the stream bit for bit; the backgrounds are drawn in blocks joined by cross-fades over the warm-up. None: each stream in one piece"),
            num("segment_tolerance", NO_UNIT, limits::SEGMENT_TOLERANCE, "1e-9", "The share of the plate's and the chain's state at a warm-up's start its end may keep; needs `segment_s`"),
            key("design_sensors", "whole number", NO_UNIT, format!("{}; needs `[ensemble.placement]`; not on a tail beam", crate::ensemble::DESIGN_SENSORS), "none", "Sensors of `design_quantity` chosen one at a time among `[ensemble.placement]`'s candidate points by the window AUC of the detector on their features (greedy, out of fold by the study's time blocks), each with its gain and its paired block-bootstrap interval; the streams are run again with a sensor at every candidate, one stream at a time (its channels at every candidate, recorded, must fit the 4 GB budget)"),
            key("design_quantity", "string", NO_UNIT, "\"acceleration\", \"velocity\", \"displacement\", \"strain\"; one `[measurement]` records, if the scene has one; needs `design_sensors`", "\"acceleration\"", "What each designed sensor records"),
            key("write_signal", "boolean", NO_UNIT, "true, false", "false", "Write the first stream's recorded signals (`signal.csv` or `signal.parquet`, with `signal.json`)"),
            key("signal_format", "string", NO_UNIT, "\"csv\", \"parquet\"; needs `write_signal = true`", "\"csv\"", "The signal file's format: CSV text, or Parquet columns of doubles (8 bytes a sample, for long streams; pandas, xarray and Dask read it as written)"),
        ],
    }]
}
