//! A run stopped by SIGTERM, SIGINT or SIGHUP removes its unfinished output (its staging
//! folders and their lock files) before it exits, with 128 + the signal's number as a shell
//! reports a run ended by that signal. Without this the default action would end the process
//! at once and leave its stage for a later run to clean.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

use crate::note;

/// Starts the thread that waits for the stopping signals. If they cannot be caught, the run
/// goes on with their default action: its stage is then left behind, to be removed by a later
/// run once its lock is free.
pub fn remove_unfinished_output_on_stop() {
    let signals = match Signals::new([SIGTERM, SIGINT, SIGHUP]) {
        Ok(s) => s,
        Err(e) => {
            return note(&format!(
                "warning: cannot catch SIGTERM/SIGINT/SIGHUP ({e}); a stopped run will leave its staging folder behind"
            ))
        }
    };
    let spawned = std::thread::Builder::new().name("stop-signals".into()).spawn(move || {
        let mut signals = signals;
        if let Some(signal) = signals.forever().next() {
            let name = match signal {
                SIGTERM => "SIGTERM",
                SIGINT => "SIGINT",
                _ => "SIGHUP",
            };
            let removed = impact::output::abandon_all();
            let what = if removed == 0 { String::new() } else { "; its unfinished output was removed".to_string() };
            note(&format!("impact: stopped by {name}{what}"));
            std::process::exit(128 + signal);
        }
    });
    if let Err(e) = spawned {
        note(&format!(
            "warning: cannot watch for SIGTERM/SIGINT/SIGHUP ({e}); a stopped run will leave its staging folder behind"
        ));
    }
}
