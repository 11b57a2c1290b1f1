//! What strikes a stream and records it, on the plate or on a tail beam alike: the struck
//! model with its probes, how the lumps strike it, and the measurement chain.

use coupled::error::ModelError;
use coupled::identification::Instrument;
use coupled::reduced::stream::{Span, StreamResponse};
use coupled::reduced::ChannelKind;
use identify::measurement::Chain;
use identify::stream::Lump;

/// A struck model with its channels and its chain.
pub(crate) trait Recorder: Sync {
    /// The model's signals of the stream `lumps` (their families named by `names`) over
    /// `duration` seconds, or of its segment `span` run alone.
    fn stream(&self, lumps: &[Lump], names: &[String], at: (f64, Option<Span>)) -> Result<StreamResponse, ModelError>;
    /// The slowest decay rate of the model's kept modes, 1/s.
    fn slowest_decay(&self) -> f64;
    /// The measurement chain, if the scene has one.
    fn chain(&self) -> Option<&Chain>;
    /// The channels, in recording order.
    fn channels(&self) -> Vec<ChannelKind>;
    /// The model's sample rate, Hz.
    fn model_rate_hz(&self) -> f64;
    /// The modes the model keeps.
    fn modes(&self) -> usize;
}

impl Recorder for Instrument<'_> {
    fn stream(&self, lumps: &[Lump], names: &[String], at: (f64, Option<Span>)) -> Result<StreamResponse, ModelError> {
        Instrument::stream(self, lumps, names, at)
    }

    fn slowest_decay(&self) -> f64 {
        Instrument::slowest_decay(self)
    }

    fn chain(&self) -> Option<&Chain> {
        Instrument::chain(self)
    }

    fn channels(&self) -> Vec<ChannelKind> {
        Instrument::channels(self)
    }

    fn model_rate_hz(&self) -> f64 {
        Instrument::model_rate_hz(self)
    }

    fn modes(&self) -> usize {
        Instrument::modes(self)
    }
}
