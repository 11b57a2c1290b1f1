//! The `impact` command line: clap reads the arguments ([`cli`]), each command runs in the
//! shape plan → compute → render → commit ([`commands`], [`field`]), and the files of a run
//! are committed whole ([`commit`]).

use clap::Parser;
use std::io::Write as _;
use std::process::ExitCode;

mod cli;
mod cli_doc;
mod commands;
mod commit;
mod field;
mod progress;
#[cfg(unix)]
mod signals;
mod written;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    #[cfg(unix)]
    signals::remove_unfinished_output_on_stop();
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // A closed pipe (`impact solve | head -1`) is the reader's normal end, not ours.
            if e.downcast_ref::<std::io::Error>().is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) {
                return ExitCode::SUCCESS;
            }
            note(&format!("error: {e}"));
            ExitCode::FAILURE
        }
    }
}

/// Writes a line to standard error, ignoring a failed write: a message nobody can receive (a
/// closed pipe, `2>&1 | head`) must neither panic, as `eprintln!` does, nor turn the run's own
/// outcome into another one; the exit code still says how the run ended.
pub(crate) fn note(text: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}

/// Writes to standard output; a closed pipe ends the program quietly (see `main`), any other
/// error (a full disk behind `> file`) is reported as a failure to write standard output.
pub(crate) fn out(text: &str) -> Result<(), impact::report::Failure> {
    let mut o = std::io::stdout().lock();
    o.write_all(text.as_bytes()).and_then(|()| o.flush()).map_err(|e| {
        // The kind is kept: `main` tells a closed pipe by it.
        std::io::Error::new(e.kind(), format!("writing to standard output: {e}"))
    })?;
    Ok(())
}
