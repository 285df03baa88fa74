//! What each `verify` subcommand does, as library functions: a command takes its parsed
//! arguments ([`args`]) and returns a [`Reply`] (the text for standard output and whether every
//! verdict passed). The binary `src/bin/verify.rs` only parses, dispatches and prints.
//!
//! Tables come from [`crate::harness::report::table::Table`]; `--json` prints the typed results.

mod adhesion;
pub mod args;
pub mod calls;
pub mod choice;
mod dataset;
mod grade;
mod jkr;
mod operators;
mod plan;
mod pulloff;
mod solve;
mod studies;

use args::{Command, CompareArgs};

use crate::harness::report::document;
use ringcontact::scene::DEFAULT_TOLERANCE;

/// What a command prints on standard output, and its verdict (exit status 0 when `success`).
#[derive(Debug, Default)]
pub struct Reply {
    pub text: String,
    pub success: bool,
}

impl Reply {
    /// A successful reply printing `text`.
    pub fn ok(text: String) -> Self {
        Self {
            text,
            success: true,
        }
    }

    /// A reply printing `text` whose verdict is `success`.
    pub(crate) fn verdict(text: String, success: bool) -> Self {
        Self { text, success }
    }
}

/// Whether a command reads the project's data directory (meshes/, verify/).
pub fn needs_data(command: &Option<Command>) -> bool {
    matches!(
        command,
        None | Some(Command::Compare(_))
            | Some(Command::Fenicsx(_))
            | Some(Command::Mesh(_))
            | Some(Command::Convergence(_))
            | Some(Command::Stability(_))
            | Some(Command::Pulloff(_))
            | Some(Command::Run(_))
            | Some(Command::Merge(_))
            | Some(Command::Part(_))
    )
}

/// Run one subcommand (the default job, `verify compare` with its defaults, when none is given).
/// An `Err` is the message after `error: ` on standard error (exit status 1).
pub fn dispatch(command: Option<Command>) -> Result<Reply, String> {
    match command {
        None => studies::compare(CompareArgs {
            tol: DEFAULT_TOLERANCE,
            json: false,
            report: None,
            no_report: false,
            fem_tolerances: document::DEFAULT_FEM_TOLERANCES.to_vec(),
            fresh: None,
        }),
        Some(Command::Compare(args)) => studies::compare(args),
        Some(Command::Solve(args)) => solve::solve(args),
        Some(Command::Table(args)) => solve::table::table(args),
        Some(Command::Grade(args)) => grade::grade(args),
        Some(Command::Dataset(args)) => dataset::dataset(args),
        Some(Command::Fenicsx(args)) => operators::fenicsx(args),
        Some(Command::Mesh(args)) => operators::mesh(args),
        Some(Command::Export(args)) => operators::export(args),
        Some(Command::Convergence(args)) => studies::convergence(args),
        Some(Command::Jkr(args)) => jkr::jkr(args),
        Some(Command::Adhesion(args)) => adhesion::adhesion(args),
        Some(Command::Pulloff(args)) => pulloff::pulloff(args),
        Some(Command::Fit(args)) => studies::fit(args),
        Some(Command::History(args)) => studies::history(args),
        Some(Command::Stability(args)) => studies::stability(args),
        Some(Command::References(args)) => studies::references(args),
        Some(Command::Plan(args)) => plan::plan(args),
        Some(Command::Run(args)) => plan::run(args),
        Some(Command::Merge(args)) => plan::merge(args),
        Some(Command::Part(args)) => plan::part(args),
    }
}

/// Pretty JSON of `value` (the `--json` output of every subcommand), with a newline.
fn to_json<T: serde::Serialize>(value: &T) -> Result<String, String> {
    serde_json::to_string_pretty(value)
        .map(|s| s + "\n")
        .map_err(|e| e.to_string())
}

/// A result with a non-finite number is an error naming the field, never `inf` or `null` on
/// standard output with exit 0.
fn refuse_non_finite<T: serde::Serialize>(what: &str, value: &T) -> Result<(), String> {
    ringcontact::finite_guard::check_finite(value).map_err(|field| {
        format!(
            "{what} produced a non-finite result ({field}): the input is beyond the range where \
             the numbers are representable"
        )
    })
}

/// The punch named on the command line, with its `--exponent`, for the commands
/// built on punches with a rim (`plan`, and `pulloff`, `convergence` and `jkr` but for their
/// own free-band routes); a punch given by a file is read by the commands that take `--profile`
/// ([`punch_kind_with_profile`]).
pub(crate) fn punch_kind(
    name: ringcontact::punch::PunchName,
    exponent: Option<f64>,
) -> Result<ringcontact::punch::PunchKind, String> {
    let kind = name.with_exponent(exponent).map_err(|e| match &e {
        ringcontact::error::Error::InvalidScene { field, .. } if field == "profile" => format!(
            "{e}; the commands that take --profile read it (`verify solve`, `jkr`, `pulloff`, \
             `convergence`); plans of its convergence studies are not built"
        ),
        _ => message(e),
    })?;
    with_a_rim(kind)
}

/// `kind` if its contact has a rim; a free band's error names the commands that solve it.
fn with_a_rim(
    kind: ringcontact::punch::PunchKind,
) -> Result<ringcontact::punch::PunchKind, String> {
    if kind.has_rim() {
        return Ok(kind);
    }
    Err(format!(
        "the {kind} (two free edges) is solved by `verify solve --punch {kind}` (ring BEM, FEM, \
         grid BEM), `verify jkr --punch {kind}`, `verify pulloff --punch {kind} --d0h S` and \
         `verify convergence --punch {kind} --method fem|grid-bem --depth D`; plans of its \
         convergence studies are not built"
    ))
}

/// The punch of `--punch`, `--exponent` and `--profile`: one given a profile from its file (or
/// the shape's reason to take none), the others as [`punch_kind`] without its note on plans.
pub(crate) fn punch_kind_with_profile(
    name: ringcontact::punch::PunchName,
    exponent: Option<f64>,
    profile: Option<&std::path::Path>,
) -> Result<ringcontact::punch::PunchKind, String> {
    match profile {
        Some(_) => name.with_parameters(exponent, profile).map_err(message),
        None => with_a_rim(name.with_exponent(exponent).map_err(message)?),
    }
}

/// The punch of `--punch`, `--exponent` and `--profile` for the commands with a free-band
/// route (`jkr`, `pulloff`, `convergence`): a free band as it is, the others as
/// [`punch_kind_with_profile`].
pub(crate) fn punch_kind_or_free_band(
    name: ringcontact::punch::PunchName,
    exponent: Option<f64>,
    profile: Option<&std::path::Path>,
) -> Result<ringcontact::punch::PunchKind, String> {
    if name.contact() == ringcontact::punch::Contact::FreeBand && profile.is_none() {
        name.with_exponent(exponent).map_err(message)
    } else {
        punch_kind_with_profile(name, exponent, profile)
    }
}

/// The built-in punches whose contact is `contact`, as `--punch` takes them (`a, b`).
pub(crate) fn names_of(contact: ringcontact::punch::Contact) -> String {
    ringcontact::punch::PunchName::names(Some(contact), ", ")
}

/// Refuse a flag of the other punch family instead of ignoring it: `--eps` fixes a fixed
/// annulus's hole (a concave punch's contact ratio is found, not given), `--d0h` is a concave
/// punch's work of adhesion in units of `h` (the flat punches' results are in units of `d0`,
/// `F0` already). Used by `verify jkr` and `verify pulloff`.
fn refuse_other_family_flags(
    punch: ringcontact::punch::PunchKind,
    eps: Option<f64>,
    d0h: Option<f64>,
) -> Result<(), String> {
    if punch.is_concave() && eps.is_some() {
        return Err(format!(
            "--eps fixes the hole of a fixed annulus ({}); the {punch}'s contact ratio is \
             found, not given (use --d0h)",
            names_of(ringcontact::punch::Contact::FixedAnnulus)
        ));
    }
    if !punch.is_concave() && d0h.is_some() {
        return Err(format!(
            "--d0h is a concave punch's work of adhesion in units of h; the {punch}'s results \
             are in units of d0 and F0 already"
        ));
    }
    Ok(())
}

/// The mesh a FEM command reads: `--mesh FILE` as given, or the mesh gmsh makes (through the
/// cache) from `--mesh-parameters NAME=VALUE,...`; `None` when neither is given.
fn chosen_mesh(
    mesh: Option<&std::path::Path>,
    parameters: Option<&str>,
    why: &str,
) -> Result<Option<std::path::PathBuf>, String> {
    match (mesh, parameters) {
        (Some(path), _) => Ok(Some(path.to_path_buf())),
        (None, Some(text)) => {
            let parameters =
                ringcontact::mesh::provider::parse_parameters(text).map_err(message)?;
            let provided = ringcontact::mesh::provider::generate(
                &crate::harness::settings::data_paths(),
                &parameters,
                why,
            )
            .map_err(message)?;
            Ok(Some(provided.path))
        }
        (None, None) => Ok(None),
    }
}

/// An output directory: the one given, or `default` (relative) under the project's directory
/// (never under whichever directory the command runs in, such as `src/`); the current
/// directory only outside a project.
fn output_directory(given: Option<&std::path::Path>, default: &str) -> std::path::PathBuf {
    match given {
        Some(path) => path.to_path_buf(),
        None => crate::harness::settings::find_data()
            .map(|data| data.root)
            .map(|root| root.join(default))
            .unwrap_or_else(|_| default.into()),
    }
}

/// Any error of the library as the message of an `Err`.
fn message(e: impl std::fmt::Display) -> String {
    e.to_string()
}
