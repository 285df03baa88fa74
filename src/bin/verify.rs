//! `verify`: the command line of the cross-verification harness. It parses the arguments
//! ([`ringcontact_verify::cli::args`]), hands them to [`ringcontact_verify::cli::dispatch`] and
//! prints the reply; every subcommand's work lives in the harness and the library.

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

use ringcontact::sparse::{self, Backend};
use ringcontact_verify::cli::{self, args::Cli};
use ringcontact_verify::harness::settings;

/// Write `text` to standard output and flush. A reader that went away (`verify ... | head`)
/// ends the program quietly with status 141 (as if by SIGPIPE); any other write error (a full
/// device) is reported on standard error with status 1. Output errors are never a panic.
fn emit(text: &str) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let written = stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush());
    if let Err(e) = written {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(141);
        }
        eprintln!("error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

/// A panic is a defect of this program, never the user's input: say so in one line (the fuzz
/// and CLI tests keep it from happening; RUST_BACKTRACE=1 still gives the trace). A panic inside
/// the mesh parser is the input's, already an error naming the file: nothing is printed.
fn report_panics_in_one_line() {
    let with_trace = std::env::var_os("RUST_BACKTRACE").is_some();
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if ringcontact::mesh::msh::inside_mesh_parser() {
            return;
        }
        if with_trace {
            return default(info);
        }
        let place = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        let payload = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        eprintln!(
            "error: internal defect in verify{place}: {payload}; please report it with the \
             command line"
        );
    }));
}

fn main() -> ExitCode {
    report_panics_in_one_line();
    // Numbers may be negative everywhere (`--tol -1` is a value to reject with a reason, not an
    // unknown flag).
    let command = Cli::command()
        .allow_negative_numbers(true)
        .mut_subcommands(|sub| sub.allow_negative_numbers(true));
    let cli = match Cli::from_arg_matches(&command.get_matches()) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    if let Some(dir) = &cli.data_dir {
        // Read by this program's data lookups (settings::find_data), passed to the library.
        settings::choose_data_directory(dir.clone());
    }
    // Chosen before any model is built; plan jobs get it passed on (harness::plan). The
    // environment's choice is read by `harness::settings::linear_solver`: here an unknown name
    // is refused rather than ignored.
    match cli.linear_solver.as_deref().map(str::parse::<Backend>) {
        Some(Ok(backend)) => {
            settings::choose_linear_solver(backend);
        }
        Some(Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
        None => {
            if let Ok(Err(e)) =
                std::env::var(sparse::ENVIRONMENT_VARIABLE).map(|n| n.parse::<Backend>())
            {
                eprintln!("error: {}: {e}", sparse::ENVIRONMENT_VARIABLE);
                return ExitCode::from(2);
            }
        }
    }
    if cli::needs_data(&cli.command) {
        if let Err(e) = settings::find_data() {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    }
    match cli::dispatch(cli.command) {
        Ok(reply) => {
            emit(&reply.text);
            if reply.success {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}
