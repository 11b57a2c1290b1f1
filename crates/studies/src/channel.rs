//! The channels of an identification run named alike everywhere: the report's rankings, the
//! CSV fields and the Python package's column names.

use coupled::reduced::ChannelKind;

/// A length in metres as millimetres with one decimal, the trailing ".0" dropped (the
/// scene's rule, by which it refuses two sensors of one label).
pub use scene::mm_label as mm;

/// What a channel is and where, in words and as CSV fields (also the Python package's column
/// names, so that its features and this report's rankings name a channel alike).
#[derive(Debug, Clone)]
pub struct ChannelInfo {
    pub kind: ChannelKind,
    pub quantity: &'static str,
    /// (x, z) of the sensor or corner, m.
    pub at: (f64, f64),
    /// The sensor's index among the run's sensors (None for corners).
    pub sensor: Option<usize>,
    pub unit: &'static str,
}

impl ChannelInfo {
    /// The channel `kind` of a run with `sensors` on `plate`.
    pub fn new(kind: ChannelKind, sensors: &[(f64, f64)], plate: &analytic::Plate) -> Self {
        let (quantity, sensor) = match kind {
            ChannelKind::Displacement { sensor } => ("displacement", Some(sensor)),
            ChannelKind::Velocity { sensor } => ("velocity", Some(sensor)),
            ChannelKind::Acceleration { sensor } => ("acceleration", Some(sensor)),
            ChannelKind::Strain { sensor } => ("strain", Some(sensor)),
            ChannelKind::SpringForce { .. } => ("spring force", None),
            ChannelKind::Reaction { .. } => ("reaction", None),
            ChannelKind::JackForce { .. } => ("jack force", None),
        };
        let at = match kind {
            ChannelKind::SpringForce { corner } | ChannelKind::Reaction { corner } => {
                corner.position(plate.length(), plate.width())
            }
            // A plate has no jack groups; a structure's channels are named where they are built.
            ChannelKind::JackForce { .. } => (0.0, 0.0),
            _ => sensors[sensor.unwrap_or(0)],
        };
        Self { kind, quantity, at, sensor, unit: kind.unit() }
    }

    /// "acceleration at (229.2, 180) mm", "spring force at (458.4, 0) mm".
    pub fn label(&self) -> String {
        format!("{} at ({}, {}) mm", self.quantity, mm(self.at.0), mm(self.at.1))
    }
}
