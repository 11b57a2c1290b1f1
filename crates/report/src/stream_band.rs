//! The modes against the chain's band on a plate stream ([`studies::stream::plates::Band`]):
//! every plate struck (the scene's and each swept one) on every support set, its highest kept
//! mode and what the chain passes above it, with the verdict.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use studies::stream::plates::Band;
use studies::stream::StreamData;

const BAND: &str = include_str!("templates/stream/band.md");

/// The band paragraph and table of the stream page, a blank line after it; empty on the tail
/// beam (whose model's band is told with the model) and where no plate was struck.
pub(crate) fn section(d: &StreamData, tolerance: Option<f64>) -> Result<String, Failure> {
    if d.bands.is_empty() {
        return Ok(String::new());
    }
    let text = render(
        "stream/band.md",
        BAND,
        &[("verdict", verdict(&d.bands, tolerance)), ("table", table(&d.bands).to_markdown())],
    )?;
    // A paragraph of its own before what follows it on the page.
    Ok(format!("{}\n\n", text.trim_end()))
}

/// Whether every plate's features are resolved by its modes, naming those that are not.
fn verdict(bands: &[Band], tolerance: Option<f64>) -> String {
    let Some(tolerance) = tolerance else {
        return "The signals are the model's, without a chain: every feature carries the truncation at the highest kept mode, which no band tolerance bounds.".into();
    };
    let tol = sig(tolerance, 2);
    let short: Vec<&Band> = bands.iter().filter(|b| b.resolved == Some(false)).collect();
    if short.is_empty() {
        let most = bands.iter().filter_map(|b| b.gain_above_highest).fold(0.0, f64::max);
        return format!("On every plate and support set that gain is at most {}, within the chain's band tolerance of {tol}: the recorded features are resolved by the modes.", sig(most, 2));
    }
    let named: Vec<String> = short
        .iter()
        .map(|b| format!("{} on {} ({})", b.plate, b.support_set, sig(b.gain_above_highest.unwrap_or(f64::NAN), 2)))
        .collect();
    format!(
        "**Not resolved:** {}: there the chain passes more than its band tolerance of {tol} above the highest kept mode, so the features recorded on that plate carry the truncation, and a detector carried to it reads a model truncated inside the chain's band.",
        named.join("; ")
    )
}

/// One row per plate and support set.
fn table(bands: &[Band]) -> Table {
    let mut t = Table::new(
        "the modes kept on each plate struck, and the chain's largest gain at or above the highest",
        &["plate", "support set", "modes", "highest mode (Hz)", "chain's gain above it", "resolved"],
    );
    for b in bands {
        t.push(vec![
            b.plate.as_str().into(),
            b.support_set.as_str().into(),
            Cell::Int(b.modes as u64),
            Cell::Sig(b.highest_mode_hz, 4),
            b.gain_above_highest.map_or_else(|| "no chain".into(), |g| Cell::Sig(g, 2)),
            match b.resolved {
                Some(true) => Cell::Flag { yes: true, shown: "yes" },
                Some(false) => Cell::Flag { yes: false, shown: "**no**" },
                None => "no chain".into(),
            },
        ]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn band(plate: &str, gain: f64, tolerance: f64) -> Band {
        Band {
            plate: plate.into(),
            support_set: "Con 1".into(),
            modes: 160,
            highest_mode_hz: 2e4,
            gain_above_highest: Some(gain),
            resolved: Some(gain <= tolerance),
        }
    }

    /// The verdict names every plate whose chain passes more than the tolerance above its
    /// highest mode, and only those; with all within, it quotes the largest gain.
    #[test]
    fn the_verdict_names_the_plates_not_resolved() {
        let ok = [band("the scene's plate", 1e-4, 1e-2), band("plate 12 mm thick", 3e-3, 1e-2)];
        let v = verdict(&ok, Some(1e-2));
        assert!(v.contains("at most 0.0030") && !v.contains("Not resolved"), "{v}");
        let short = [band("the scene's plate", 1e-4, 1e-2), band("plate 600 mm long", 0.2, 1e-2)];
        let v = verdict(&short, Some(1e-2));
        assert!(v.contains("**Not resolved:** plate 600 mm long on Con 1 (0.20)"), "{v}");
        assert!(!v.contains("the scene's plate"), "{v}");
        assert!(verdict(&short, None).contains("without a chain"));
    }
}
