//! `verify`: the command line of the cross-verification harness.
//!
//! Run without a subcommand it prints the comparison of every available method with the analytic
//! references on the three punches. `verify solve` solves one scene.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, CommandFactory, FromArgMatches, Parser, Subcommand};

use ringcontact::adhesion;
use ringcontact::fem::mesh::Degree;
use ringcontact::harness::{
    comparison, convergence, fenicsx, operator, peers, report, svg, sweeps,
};
use ringcontact::methods::{self, Method};
use ringcontact::punch::PunchKind;
use ringcontact::reference;
use ringcontact::scene::{SceneSpec, DEFAULT_TOLERANCE};
use ringcontact::solution::Solution;

/// Cross-verification harness for rigid punches with ring-shaped contact on an elastic
/// half-space (flat annular, conical concave, spherical concave; flat circular as a check).
///
/// Without a subcommand: compare every method with the analytic references on all punches.
#[derive(Parser)]
#[command(name = "verify", version, about, long_about = None, after_help = "\
Examples:
  verify                                   comparison table of all methods and references
  verify solve --punch flat-annulus --eps 0.5
  verify solve --punch cone --depth 2 --json
  verify solve --scene verify/scenes/cone-depth.toml
  verify fenicsx                           stored FEniCSx results against our FEM")]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The project's data directory (holding meshes/ and verify/) [default: found upward from the
    /// current directory; RINGCONTACT_DATA_DIR also sets it].
    #[arg(long, global = true, value_name = "DIR")]
    data_dir: Option<PathBuf>,
}

#[derive(Subcommand)]
enum Command {
    /// Solve one scene with one method and print the state (or JSON).
    #[command(after_help = "\
Defaults: a = 1, E* = 1, h = 1, so the outputs are the paper's dimensionless functions
(flat punches: F = 2 E* d a gamma; concave: d = h gamma1, F = 2 E* h a gamma2).

Examples:
  verify solve --punch flat-annulus --eps 0.5            gamma(0.5) at unit depth
  verify solve --punch cone --depth 2 --json             eps and gamma2 at d = 2h
  verify solve --punch sphere --eps 0.3                  gamma1(0.3), gamma2(0.3)
  verify solve --punch sphere --force 3                  F/(2E*ha) = 1.5: eps and depth
  verify solve --punch flat-annulus --eps 0.5 --method reference
  verify solve --punch cone --depth 2 --method fem --json        FEM, tolerance 1e-3
  verify solve --punch sphere --depth 1 --method fem --tol 1e-6  meshes made by gmsh for the scene
  verify solve --punch flat-annulus --eps 0.3 --method fem       any b/a (gmsh; cached in .mesh-cache/)
  verify solve --punch flat --method fem --mesh meshes/disk-L1.msh --degree 1
  verify solve --punch sphere --depth 1.5 --method grid-bem --grid 256 --json
  verify solve --punch cone --depth 2 --method auto --tol 1e-6   cheapest method meeting 1e-6
  verify solve --punch sphere --depth 1 --method fem --vtu sphere.vtu   field for ParaView
  verify solve --scene verify/scenes/cone-depth.toml --json")]
    Solve(SolveArgs),
    /// Compare the methods with the analytic references on all punches (the default job).
    #[command(after_help = "Example:\n  verify compare --tol 1e-10 --json > comparison.json")]
    Compare(CompareArgs),
    /// Compare every stored FEniCSx result (verify/fenicsx/) with our FEM on the identical problem.
    #[command(after_help = "\
Each result is re-solved with FEniCSx's model (same mesh, degree, quadrature, supports): the force
must agree within 1e-8 and the active contact set must be the same. Results whose mesh changed
since they were stored are reported as stale and not used.

Refresh the stored results (installs FEniCSx from Debian when missing):
  bash scripts/fenicsx/run_all.sh

Example:
  verify fenicsx --json
  verify fenicsx --operators --json   the stored operator comparisons (bash
                                      scripts/fenicsx/run_operators.sh remakes them)")]
    Fenicsx(FenicsxArgs),
    /// Make (or find in the cache) a mesh of the adapted family with gmsh and print where it is.
    #[command(after_help = "\
The adapted family is what the FEM climbs: level k (-2 to 7) is graded toward the rim (and r = b),
with g = 0.32 * 0.6^k; --free-edge refines around a located inner contact radius; --tol and
--degree make it as `verify solve --method fem --tol X` does (rim and edge sizes follow X).
Prints one JSON object: path, sha256, origin (cache or gmsh), gmsh_version, corner_refinement (the
halvings around the singular edges the solver applies to the file when its rim size is below
1e-8 a, which gmsh does not mesh well; null when none), parameters (the gmsh
-setnumber values, which reproduce the mesh from meshes/half_space.geo).

Examples:
  verify mesh --eps 0.3 --level 2                 flat annulus b/a = 0.3, level 2
  verify mesh --level 1 --free-edge 0.4505        disk, refined around r = 0.4505 a
  verify mesh --level 0 --free-edge 0.4505 --edge-uncertainty 1e-4 --tol 1e-6 --degree 3")]
    Mesh(MeshArgs),
    /// Write our assembled stiffness matrix, load vector and dof table for a mesh (Matrix Market).
    #[command(after_help = "\
Writes into --out: stiffness.mtx (K of the axisymmetric solid, E = 1, nu = 0, no boundary
conditions), load.mtx (an n x 1 matrix: the consistent nodal forces of a unit pressure on the
contact line, f_i = -int phi_i e_z 2 pi r dr), dofs.csv (index,node_tag,r,z,component; dof 2n + c
is component c of node n; node_tag is the file's, empty for nodes added for P2/P3). Matrix Market
coordinate real general, written with sprs.

FEniCSx writes the same three files for its assembly of the same mesh and degree:
  /usr/bin/python3 scripts/fenicsx/export.py --mesh M --degree P --out DIR
and --compare DIR matches the dofs by position and component and prints the largest entry-wise
difference relative to the largest entry, for the matrix and the load (goal 1e-12; exit status 1
above it). scripts/fenicsx/run_operators.sh stores such comparisons in verify/fenicsx/operators/,
which `verify fenicsx` and the report show.

Examples:
  verify export --mesh meshes/disk-L0.msh --degree 2 --out /tmp/ours
  verify export --mesh meshes/disk-L0.msh --degree 2 --out /tmp/ours --compare /tmp/fenicsx --json")]
    Export(ExportArgs),
    /// Mesh-convergence study of one method: error against the ring BEM, observed order,
    /// Richardson extrapolate and GCI; writes CSV and an SVG chart.
    #[command(after_help = "\
Levels: grid-bem 64, 128, 256, ... cells per side; fem the committed mesh levels L0-L2, then the
adapted levels made by gmsh (graded toward the edges, refined at the located free edge)
(P2); ring-bem 6, 8, 10, ... collocation nodes (flat punches).

Examples:
  verify convergence --punch flat --method grid-bem --levels 5          64 .. 1024
  verify convergence --punch sphere --depth 1.5 --method fem --levels 4
  verify convergence --punch flat-annulus --eps 0.5 --method ring-bem --levels 6 --json")]
    Convergence(ConvergenceArgs),
    /// JKR adhesion from the converged non-adhesive solutions: detachment of the flat annulus,
    /// pull-off of the concave punches under fixed load and fixed grips.
    #[command(after_help = "\
Units: depths in d0 = sqrt(2 pi a dw / E*) (and d/h), forces in F0 = sqrt(8 pi a^3 E* dw)
(Kendall's flat punch of radius a); negative = tensile.

Examples:
  verify jkr --punch flat-annulus --eps 0.5 --json
  verify jkr --punch sphere --d0h 1
  verify jkr --punch cone --d0h 10 --json")]
    Jkr(JkrArgs),
    /// Refit the paper's approximations (3), (8), (10) to converged ring-BEM data on
    /// 0.05 <= eps <= 0.99 and propose better forms.
    #[command(after_help = "Example:\n  verify fit --json")]
    Fit(JsonArgs),
    /// Drive every method toward its limits; report where each meets its tolerance, how it fails
    /// outside, and any wrong number returned without an error (exit status 1 if one is found).
    #[command(after_help = "Example:\n  verify stability --json > stability.json")]
    Stability(JsonArgs),
    /// Append a report's headline figures to the history file, compare with the previous run
    /// (accuracy beyond tolerance, or time > 1.5x, is a regression: exit status 1) and write the
    /// trend into the report directory. Used by scripts/nightly.sh.
    #[command(
        after_help = "Example:\n  verify history --report reports/2026-11-22 --history reports/history.jsonl"
    )]
    History(HistoryArgs),
    /// List the analytic references and the range of eps where each is valid.
    #[command(after_help = "Examples:\n  verify references\n  verify references --json")]
    References(JsonArgs),
}

#[derive(Args)]
struct HistoryArgs {
    /// Report directory written by `verify compare --report DIR` (and `stability.json` in it).
    #[arg(long)]
    report: PathBuf,
    /// JSON-lines history file.
    #[arg(long, default_value = "reports/history.jsonl")]
    history: PathBuf,
    /// Whether the FEniCSx results were refreshed (`fresh`) or read from the repository (`stored`).
    #[arg(long, default_value = "stored")]
    fenicsx: String,
    /// The same for the Tamaas/ContactMechanics results.
    #[arg(long, default_value = "stored")]
    peers: String,
    /// Date label of this run [default: the report directory's name].
    #[arg(long)]
    date: Option<String>,
}

#[derive(Args)]
struct JkrArgs {
    /// Punch shape: flat-annulus, cone or sphere.
    #[arg(long, value_enum)]
    punch: PunchKind,
    /// b/a of the flat annulus.
    #[arg(long)]
    eps: Option<f64>,
    /// Dimensionless work of adhesion d0/h of a concave punch.
    #[arg(long)]
    d0h: Option<f64>,
    /// Concave punches: sweep d0/h from 0.1 to 100 (the paper's Fig. 10), writing CSV and SVG
    /// into --out.
    #[arg(long)]
    sweep: bool,
    /// Directory for the sweep's CSV and SVG.
    #[arg(long, default_value = "reports/jkr")]
    out: PathBuf,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct ConvergenceArgs {
    /// Punch shape.
    #[arg(long, value_enum)]
    punch: PunchKind,
    /// Method to refine.
    #[arg(long, value_enum)]
    method: Method,
    /// Number of refinement levels.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u64).range(2..=8))]
    levels: u64,
    /// b/a of the flat annulus.
    #[arg(long, default_value_t = 0.5)]
    eps: f64,
    /// d/h of a concave punch.
    #[arg(long, default_value_t = 1.5)]
    depth: f64,
    /// Directory for the CSV and SVG files.
    #[arg(long, default_value = "reports/convergence")]
    out: PathBuf,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct MeshArgs {
    /// Start of the contact line `b/a` (the flat annulus' inner radius; 0 for the disk).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    eps: f64,
    /// Level of the adapted family (-2 to 7; grading g = 0.32 * 0.6^level).
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    level: i32,
    /// Refine around this inner contact radius `b/a` (concave punches).
    #[arg(long, allow_negative_numbers = true)]
    free_edge: Option<f64>,
    /// How well that radius is known (the coarser solve's error estimate): the element size at
    /// the free edge puts about 24 contact nodes between it and that distance.
    #[arg(long, default_value_t = 0.0)]
    edge_uncertainty: f64,
    /// Make the mesh for a solve at this relative tolerance (rim and edge sizes follow it), as
    /// `verify solve --method fem --tol X` does.
    #[arg(long)]
    tol: Option<f64>,
    /// Element degree of that solve (with --tol).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=3))]
    degree: u8,
}

#[derive(Args)]
struct ExportArgs {
    /// gmsh .msh file (physical groups as in meshes/half_space.geo).
    #[arg(long)]
    mesh: PathBuf,
    /// Element degree: 1, 2 or 3.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=3))]
    degree: u8,
    /// Directory to write stiffness.mtx, load.mtx and dofs.csv into (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// FEniCSx's export of the same mesh and degree (scripts/fenicsx/export.py --out DIR):
    /// compare the two operators and print the differences (JSON with --json).
    #[arg(long, value_name = "DIR")]
    compare: Option<PathBuf>,
    /// With --compare: print the comparison as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct FenicsxArgs {
    /// Print JSON instead of the table (the force comparisons; with --operators, the operator
    /// comparisons).
    #[arg(long)]
    json: bool,
    /// Show only the stored comparisons of the assembled operator (stiffness matrix and load
    /// vector, entry by entry, dofs matched by position) with FEniCSx's.
    #[arg(long)]
    operators: bool,
}

#[derive(Args)]
struct JsonArgs {
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SolveArgs {
    /// Punch shape.
    #[arg(long, value_enum)]
    punch: Option<PunchKind>,
    /// Contact ratio b/a: fixes the flat annulus; for cone and sphere it prescribes the contact
    /// (depth and force are then computed).
    #[arg(long, allow_negative_numbers = true)]
    eps: Option<f64>,
    /// Indentation depth d of the rim (for concave punches with h = 1 this is d/h).
    #[arg(long, conflicts_with = "force", allow_negative_numbers = true)]
    depth: Option<f64>,
    /// Normal force F, compression positive.
    #[arg(long, allow_negative_numbers = true)]
    force: Option<f64>,
    /// Method.
    #[arg(long, value_enum, default_value = "ring-bem")]
    method: Method,
    /// Scene file (TOML, see verify/scenes/); flags given as well override its values.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Relative tolerance wanted in the dimensionless results [default: the scene's, else the
    /// method's: 1e-9 ring-bem, 1e-3 fem]. The FEM climbs meshes gmsh makes for the scene and
    /// tolerance (found at run time: `bash scripts/install_gmsh.sh` installs it; without it, the
    /// committed meshes serve tolerances down to 1e-4) until its error estimate meets it.
    #[arg(long)]
    tol: Option<f64>,
    /// FEM only: a gmsh .msh file (units of a; physical groups as in meshes/half_space.geo)
    /// instead of the committed mesh family. No error estimate is made on a single mesh.
    #[arg(long)]
    mesh: Option<PathBuf>,
    /// FEM only: element degree, 1 (linear), 2 (quadratic) or 3 (cubic) [default: 3 on meshes
    /// made by gmsh, 2 on the committed meshes and with --mesh].
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=3))]
    degree: Option<u8>,
    /// FEM only: write the displacement field of the finest model as VTK (.vtu) for ParaView.
    #[arg(long)]
    vtu: Option<PathBuf>,
    /// Grid BEM only: cells per side of the square grid on [-a, a]^2 [default: 256].
    #[arg(long, value_parser = clap::value_parser!(u64).range(8..=2048))]
    grid: Option<u64>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct CompareArgs {
    /// Relative tolerance of the ring BEM.
    #[arg(long, default_value_t = DEFAULT_TOLERANCE)]
    tol: f64,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Report directory (Markdown, JSON, SVG charts).
    #[arg(long, default_value = "reports/latest")]
    report: PathBuf,
    /// Skip the report directory (tables only).
    #[arg(long)]
    no_report: bool,
    /// Tolerances of the FEM's full solve in the report's speed-against-accuracy charts (meshes
    /// made by gmsh; left out without it), comma-separated. The nightly run adds 1e-8.
    #[arg(long, value_delimiter = ',', default_values_t = report::DEFAULT_FEM_TOLERANCES)]
    fem_tolerances: Vec<f64>,
}

/// `print!` that never panics: see [`emit`].
macro_rules! out {
    ($($arg:tt)*) => {
        emit(format_args!($($arg)*), false)
    };
}

/// `println!` that never panics: see [`emit`].
macro_rules! outln {
    () => {
        emit(format_args!(""), true)
    };
    ($($arg:tt)*) => {
        emit(format_args!($($arg)*), true)
    };
}

/// Write to standard output and flush. A reader that went away (`verify ... | head`) ends the
/// program quietly with status 141 (as if by SIGPIPE); any other write error (a full device) is
/// reported on standard error with status 1. Output errors are never a panic.
fn emit(args: std::fmt::Arguments, newline: bool) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let written = stdout
        .write_fmt(args)
        .and_then(|()| {
            if newline {
                stdout.write_all(b"\n")
            } else {
                Ok(())
            }
        })
        .and_then(|()| stdout.flush());
    if let Err(e) = written {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(141);
        }
        eprintln!("error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

fn main() -> ExitCode {
    // A panic is a defect of this program, never the user's input: say so in one line (the fuzz
    // and CLI tests keep it from happening; RUST_BACKTRACE=1 still gives the trace).
    if std::env::var_os("RUST_BACKTRACE").is_none() {
        std::panic::set_hook(Box::new(|info| {
            let place = info
                .location()
                .map(|l| format!(" at {}:{}", l.file(), l.line()))
                .unwrap_or_default();
            eprintln!(
                "error: internal defect in verify{place}: {}; please report it with the command line",
                info.payload()
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| info.payload().downcast_ref::<String>().cloned())
                    .unwrap_or_default()
            );
        }));
    }
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
        // Read by the data lookups of the library (mesh_provider::find_project_root); set once,
        // before any thread starts.
        std::env::set_var(ringcontact::fem::mesh_provider::DATA_DIR_VARIABLE, dir);
    }
    let needs_data = matches!(
        cli.command,
        None | Some(Command::Compare(_))
            | Some(Command::Fenicsx(_))
            | Some(Command::Mesh(_))
            | Some(Command::Convergence(_))
            | Some(Command::Stability(_))
    );
    if needs_data {
        if let Err(e) = ringcontact::fem::mesh_provider::find_project_root() {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    }
    let outcome = match cli.command {
        None => run_compare(CompareArgs {
            tol: DEFAULT_TOLERANCE,
            json: false,
            report: PathBuf::from("reports/latest"),
            no_report: false,
            fem_tolerances: report::DEFAULT_FEM_TOLERANCES.to_vec(),
        }),
        Some(Command::Compare(args)) => run_compare(args),
        Some(Command::Solve(args)) => run_solve(args),
        Some(Command::Fenicsx(args)) => run_fenicsx(args),
        Some(Command::Mesh(args)) => run_mesh(args),
        Some(Command::Export(args)) => run_export(args),
        Some(Command::Convergence(args)) => run_convergence(args),
        Some(Command::Jkr(args)) => run_jkr(args),
        Some(Command::Fit(args)) => run_fit(args),
        Some(Command::History(args)) => run_history(args),
        Some(Command::Stability(args)) => run_stability(args),
        Some(Command::References(args)) => run_references(args),
    };
    match outcome {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Pretty JSON of `value` (the `--json` output of every subcommand).
fn to_json<T: serde::Serialize>(value: &T) -> Result<String, String> {
    serde_json::to_string_pretty(value).map_err(|e| e.to_string())
}

/// A result with a non-finite number is an error naming the field, never `inf` or `null` on
/// standard output with exit 0.
fn refuse_non_finite<T: serde::Serialize>(what: &str, value: &T) -> Result<(), String> {
    ringcontact::finite::check_finite(value).map_err(|field| {
        format!(
            "{what} produced a non-finite result ({field}): the input is beyond the range where \
             the numbers are representable"
        )
    })
}

fn run_stability(args: JsonArgs) -> Result<ExitCode, String> {
    use ringcontact::harness::stability;
    let mut bar = ringcontact::harness::progress::Progress::new("stability", stability::PROBES);
    let probes = stability::run(|p| bar.tick(&format!("{} {}", p.method, p.probe)));
    if args.json {
        outln!("{}", to_json(&probes)?);
    } else {
        out!("{}", stability::render(&probes));
    }
    Ok(if stability::wrong_numbers(&probes) == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn run_references(args: JsonArgs) -> Result<ExitCode, String> {
    if !args.json {
        print_references();
        return Ok(ExitCode::SUCCESS);
    }
    let list: Vec<serde_json::Value> = reference::catalogue()
        .iter()
        .map(|r| {
            serde_json::json!({
                "name": r.name,
                "quantity": r.quantity,
                "kind": r.kind,
                "eps_range": [r.eps_range.0, r.eps_range.1],
                "source": r.source,
            })
        })
        .collect();
    outln!("{}", to_json(&list)?);
    Ok(ExitCode::SUCCESS)
}

fn run_compare(args: CompareArgs) -> Result<ExitCode, String> {
    let floor = ringcontact::fem::solver::MIN_TOLERANCE;
    if let Some(t) = args
        .fem_tolerances
        .iter()
        .find(|&&t| !(t >= floor && t < 1.0))
    {
        return Err(format!(
            "--fem-tolerances: {t} is outside [{floor:e}, 1), the FEM's tolerance range"
        ));
    }
    let report = comparison::run(args.tol).map_err(|e| e.to_string())?;
    let external = fenicsx::run().map_err(|e| e.to_string())?;
    let peer_rows = peers::run(256).map_err(|e| e.to_string())?;
    let operators = operator::load_records().map_err(|e| e.to_string())?;
    if !args.no_report {
        let mut bar = ringcontact::harness::progress::Progress::new("report", report::STAGES);
        report::write_report(
            &args.report,
            &report,
            &external,
            &operators,
            &peer_rows,
            &args.fem_tolerances,
            |stage| bar.tick(stage),
        )
        .map_err(|e| e.to_string())?;
    }
    if args.json {
        let both = serde_json::json!({
            "comparison": report,
            "fenicsx": external,
            "fenicsx_operators": operators,
            "peers": peer_rows
        });
        outln!("{}", to_json(&both)?);
    } else {
        out!("{}", comparison::render(&report));
        out!("{}", fenicsx::render(&external));
        out!("{}", operator::render_records(&operators));
        out!("{}", peers::render(&peer_rows));
        outln!(
            "\n{} of {} stored FEniCSx results compared, {} failed; {} peer comparisons, {} failed.",
            external.iter().filter(|r| r.status == "current").count(),
            external.len(),
            fenicsx::failures(&external),
            peer_rows.len(),
            peers::failures(&peer_rows)
        );
        if !args.no_report {
            outln!(
                "Report: {}/index.html (web page), report.md, report.json, SVG charts",
                args.report.display()
            );
        }
    }
    Ok(
        if report.failures()
            + fenicsx::failures(&external)
            + operator::failures(&operators)
            + peers::failures(&peer_rows)
            == 0
        {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        },
    )
}

fn run_convergence(args: ConvergenceArgs) -> Result<ExitCode, String> {
    use std::io::IsTerminal;
    let eps = if args.punch == PunchKind::FlatAnnulus {
        args.eps
    } else {
        0.0
    };
    if !(0.0..1.0).contains(&eps) {
        return Err(format!("--eps {eps}: need 0 <= b/a < 1"));
    }
    if !(args.depth.is_finite() && args.depth > 0.0) {
        return Err(format!("--depth {}: need a positive d/h", args.depth));
    }
    let case = convergence::StudyCase {
        punch: args.punch,
        eps,
        depth: args.depth,
    };
    let show = std::io::stderr().is_terminal();
    let study = convergence::run(case, args.method, args.levels as usize, |level| {
        if show {
            eprintln!(
                "  level {} done: {} unknowns, {:.2} s",
                level.label, level.unknowns, level.wall_s
            );
        }
    })
    .map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let stem = format!("{}-{}", args.punch.name(), args.method.name());
    let csv_path = args.out.join(format!("{stem}.csv"));
    let svg_path = args.out.join(format!("{stem}.svg"));
    std::fs::write(&csv_path, convergence::csv(&study)).map_err(|e| e.to_string())?;
    let series = vec![svg::Series {
        name: args.method.name().to_string(),
        points: study
            .levels
            .iter()
            .map(|l| (l.size, l.error.abs()))
            .collect(),
        bars: Vec::new(),
    }];
    let chart = svg::log_log_chart(
        &format!(
            "{} {}: |relative error| against the ring BEM",
            args.punch.name(),
            study.quantity
        ),
        "size h",
        "|relative error|",
        &series,
    );
    std::fs::write(&svg_path, chart).map_err(|e| e.to_string())?;
    if args.json {
        outln!("{}", to_json(&study)?);
    } else {
        out!("{}", convergence::render(&study));
        outln!("  wrote {} and {}", csv_path.display(), svg_path.display());
    }
    Ok(ExitCode::SUCCESS)
}

fn run_jkr(args: JkrArgs) -> Result<ExitCode, String> {
    let solver = ringcontact::bem::ring_contact::RingBemSolver::new();
    let text = match args.punch {
        PunchKind::FlatAnnulus if args.sweep => sweep_output(
            &sweeps::flat_annulus_sweep(&solver, &args.out).map_err(|e| e.to_string())?,
            args.json,
        )?,
        PunchKind::FlatAnnulus => {
            let eps = args
                .eps
                .ok_or("flat-annulus needs --eps B_OVER_A (or --sweep)")?;
            let r = adhesion::flat_annulus(&solver, eps).map_err(|e| e.to_string())?;
            refuse_non_finite(&format!("jkr flat-annulus --eps {eps}"), &r)?;
            if args.json {
                to_json(&r)?
            } else {
                let mut t = format!(
                    "flat annulus b/a = {eps}: gamma = {:.12}, gamma' = {:.9}\n  outer edge: d_c/d0 = {:.9}, F_c/F0 = {:.9}\n  inner edge: d_c/d0 = {:.9}, F_c/F0 = {:.9}\n  governing: {} edge (smaller |d_c|); kappa from the field vs from gamma': {:.1e}\n",
                    r.gamma, r.gamma_prime, r.dc_outer, r.fc_outer, r.dc_inner, r.fc_inner, r.governing_edge, r.kappa_consistency
                );
                if let Some(c) = r.collins {
                    t += &format!(
                        "  Collins' series in (16)-(17): d_c/d0 = {:.9}, F_c/F0 = {:.9}\n",
                        c.depth, c.force
                    );
                }
                if let Some(c) = r.argatov {
                    t += &format!(
                        "  Argatov's asymptote (22): d_c/d0 = {:.9}, F_c/F0 = {:.9}\n",
                        c.depth, c.force
                    );
                }
                t
            }
        }
        PunchKind::Cone | PunchKind::Sphere if args.sweep => {
            let mut bar = ringcontact::harness::progress::Progress::new("sweep", 25);
            let sweep = sweeps::pulloff_sweep(&solver, args.punch, &args.out, |s| bar.tick(s))
                .map_err(|e| e.to_string())?;
            sweep_output(&sweep, args.json)?
        }
        PunchKind::Cone | PunchKind::Sphere => {
            let s = args
                .d0h
                .ok_or("cone and sphere need --d0h D0_OVER_H (or --sweep)")?;
            let r = adhesion::concave(&solver, args.punch, s).map_err(|e| e.to_string())?;
            refuse_non_finite(&format!("jkr {} --d0h {s:e}", args.punch), &r)?;
            if args.json {
                to_json(&r)?
            } else {
                let show = |name: &str, c: &Option<adhesion::Critical>, note: &Option<String>| {
                    match c {
                    Some(c) => format!(
                        "  {name:<11} eps = {:.6}, d/h = {:+.6}, F/F0 = {:+.6}, governing edge: {}\n",
                        c.eps, c.depth, c.force, c.governing_edge
                    ),
                    None => format!("  {name:<11} {}\n", note.clone().unwrap_or_default()),
                }
                };
                let paper = |name: &str, c: &Option<adhesion::Critical>| {
                    match c {
                    Some(c) => format!("  {name:<11} (inner edge only, the paper's route) eps = {:.6}, F/F0 = {:+.6}\n", c.eps, c.force),
                    None => String::new(),
                }
                };
                let fits = |name: &str, c: Option<(f64, f64)>| {
                    match c {
                    Some((e, f)) => format!("  {name:<11} (the paper's route on the paper's fitted formulas) eps = {e:.6}, F/F0 = {f:+.6}\n"),
                    None => format!("  {name:<11} (the paper's route on the paper's fitted formulas) no critical state\n"),
                }
                };
                let f = &r.full_contact;
                format!(
                    "{} d0/h = {}: pull-off from the annular contact\n{}{}  full contact (reached when pressed past d/h = {:.4}): pull-off at d/h = {:+.6}, F/F0 = {:+.6} (rim)\n  direct check at the fixed-load critical state: G_inner/dw = {:.9}, rim intensity difference {:.1e}\n",
                    args.punch,
                    ringcontact::error::show(s),
                    show("fixed load", &r.fixed_load, &r.fixed_load_note)
                        + &paper("fixed load", &r.inner_edge_only_fixed_load)
                        + &fits("fixed load", r.paper_fits_fixed_load),
                    show("fixed grips", &r.fixed_grips, &r.fixed_grips_note)
                        + &paper("fixed grips", &r.inner_edge_only_fixed_grips)
                        + &fits("fixed grips", r.paper_fits_fixed_grips),
                    f.closing_depth.unwrap_or(f64::NAN),
                    f.pulloff.depth,
                    f.pulloff.force,
                    r.direct_inner_energy_ratio.unwrap_or(f64::NAN),
                    r.direct_rim_difference.unwrap_or(f64::NAN)
                )
            }
        }
        PunchKind::Flat => {
            return Err(
                "the flat circular punch is Kendall's: F_c = -F0 (use flat-annulus --eps)".into(),
            )
        }
    };
    outln!("{text}");
    Ok(ExitCode::SUCCESS)
}

/// The sweep's table (or its rows as JSON) and the files it wrote.
fn sweep_output<R: serde::Serialize>(
    sweep: &ringcontact::harness::sweeps::Sweep<R>,
    json: bool,
) -> Result<String, String> {
    if json {
        return to_json(&sweep.rows);
    }
    let files: Vec<String> = sweep
        .files
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    Ok(sweep.table.to_terminal() + &format!("  wrote {}", files.join(", ")))
}

fn run_history(args: HistoryArgs) -> Result<ExitCode, String> {
    use ringcontact::harness::history;
    let date = args.date.clone().unwrap_or_else(|| {
        args.report
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "run".into())
    });
    let current = history::headline(&args.report, &date, &args.fenicsx, &args.peers)
        .map_err(|e| e.to_string())?;
    let previous = history::append(&args.history, &current).map_err(|e| e.to_string())?;
    let found = history::regressions(&current, previous.as_ref());
    std::fs::write(
        args.report.join("trend.md"),
        history::trend(&args.history, 30).map_err(|e| e.to_string())?,
    )
    .map_err(|e| e.to_string())?;
    let recorded = history::read_history(&args.history).map_err(|e| e.to_string())?;
    let page = ringcontact::harness::html::write_index(&args.report, Some(&recorded))
        .map_err(|e| e.to_string())?;
    outln!("web page with trend charts: {}", page.display());
    outln!(
        "history: {} ({} runs recorded); FEniCSx {}, peers {}",
        args.history.display(),
        std::fs::read_to_string(&args.history)
            .map(|t| t.lines().count())
            .unwrap_or(0),
        current.fenicsx,
        current.peers
    );
    if found.is_empty() {
        outln!(
            "no regression against the tolerances{}",
            if previous.is_some() {
                " or the previous run"
            } else {
                " (first run)"
            }
        );
        Ok(ExitCode::SUCCESS)
    } else {
        for r in &found {
            outln!("REGRESSION: {r}");
        }
        Ok(ExitCode::FAILURE)
    }
}

fn run_fit(args: JsonArgs) -> Result<ExitCode, String> {
    let solver = ringcontact::bem::ring_contact::RingBemSolver::new();
    let reports = ringcontact::fit::run(&solver).map_err(|e| e.to_string())?;
    if args.json {
        // One entry per function, keyed by its name.
        let map: serde_json::Map<String, serde_json::Value> = reports
            .iter()
            .map(|r| {
                Ok((
                    r.name.clone(),
                    serde_json::to_value(r).map_err(|e| e.to_string())?,
                ))
            })
            .collect::<Result<_, String>>()?;
        outln!("{}", to_json(&map)?);
        return Ok(ExitCode::SUCCESS);
    }
    outln!("Refits on ring-BEM data, 0.05 <= eps <= 0.99 (max relative error on 301 points, and where):");
    for r in &reports {
        outln!("{}: {}", r.name, r.paper_form);
        outln!(
            "  paper params {:?}: max rel. err {:.2e} at eps = {:.3}",
            r.paper_params,
            r.paper_max_rel_err,
            r.paper_max_rel_err_eps
        );
        outln!(
            "  refit params {:?}: max rel. err {:.2e} at eps = {:.3}",
            r.params
                .iter()
                .map(|p| (p * 1e4).round() / 1e4)
                .collect::<Vec<_>>(),
            r.max_rel_err,
            r.max_rel_err_eps
        );
        outln!(
            "  best form {}\n    params {:?}: max rel. err {:.2e} at eps = {:.3}",
            r.best_form,
            r.best_params
                .iter()
                .map(|p| (p * 1e6).round() / 1e6)
                .collect::<Vec<_>>(),
            r.best_max_rel_err,
            r.best_max_rel_err_eps
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn run_mesh(args: MeshArgs) -> Result<ExitCode, String> {
    use ringcontact::fem::mesh_provider::{self, MeshRequest};
    if !(0.0..1.0).contains(&args.eps) {
        return Err(format!("--eps {}: need 0 <= b/a < 1", args.eps));
    }
    if !(mesh_provider::ADAPTED_MIN_LEVEL..=mesh_provider::ADAPTED_MAX_LEVEL).contains(&args.level)
    {
        return Err(format!(
            "--level {}: the adapted family has levels {} to {}",
            args.level,
            mesh_provider::ADAPTED_MIN_LEVEL,
            mesh_provider::ADAPTED_MAX_LEVEL
        ));
    }
    if !(args.edge_uncertainty >= 0.0 && args.edge_uncertainty < 1.0) {
        return Err(format!(
            "--edge-uncertainty {}: need 0 <= uncertainty < 1 (units of a)",
            args.edge_uncertainty
        ));
    }
    if let Some(b) = args.free_edge {
        if !(0.0..1.0).contains(&b) {
            return Err(format!("--free-edge {b}: need 0 <= b/a < 1"));
        }
    }
    if let Some(tol) = args.tol {
        if !(tol > 0.0 && tol < 1.0) {
            return Err(format!("--tol {tol}: need 0 < tolerance < 1"));
        }
    }
    let target = args.tol.map(|tolerance| mesh_provider::SizeTarget {
        tolerance,
        degree: args.degree as usize,
    });
    let request = MeshRequest::Adapted {
        contact_start: args.eps,
        level: args.level,
        free_edge: args.free_edge.filter(|&b| b > 0.0),
        edge_uncertainty: args.edge_uncertainty,
        target,
    };
    let provided = mesh_provider::provide(&request, "verify mesh").map_err(|e| e.to_string())?;
    let parameters = mesh_provider::adapted_parameters(
        args.eps,
        args.level,
        args.free_edge,
        args.edge_uncertainty,
        target,
    );
    let out = serde_json::json!({
        "path": provided.path.display().to_string(),
        "sha256": provided.sha256,
        "origin": provided.origin,
        "gmsh_version": provided.gmsh_version,
        "label": request.label(),
        "parameters": parameters,
        "corner_refinement": provided.corner_refinement.as_ref().map(|r| r.describe()),
    });
    outln!("{}", to_json(&out)?);
    Ok(ExitCode::SUCCESS)
}

fn run_export(args: ExportArgs) -> Result<ExitCode, String> {
    let degree = ringcontact::fem::mesh::Degree::from_number(args.degree)
        .ok_or_else(|| format!("--degree {}: need 1, 2 or 3", args.degree))?;
    let written = ringcontact::fem::export::export_mesh(&args.mesh, degree, &args.out)
        .map_err(|e| e.to_string())?;
    if args.json && args.compare.is_none() {
        return Err("--json prints the comparison: give --compare DIR as well".into());
    }
    if !args.json {
        for path in &written {
            outln!("wrote {}", path.display());
        }
    }
    let Some(fenicsx_dir) = &args.compare else {
        return Ok(ExitCode::SUCCESS);
    };
    let comparison =
        ringcontact::harness::operator::compare_operator(&args.mesh, degree, fenicsx_dir)
            .map_err(|e| e.to_string())?;
    let met = comparison.meets_goal();
    if args.json {
        outln!("{}", to_json(&comparison)?);
    } else {
        out!("{}", ringcontact::harness::operator::render(&[comparison]));
    }
    Ok(if met {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn run_fenicsx(args: FenicsxArgs) -> Result<ExitCode, String> {
    let operators = operator::load_records().map_err(|e| e.to_string())?;
    if args.operators {
        if args.json {
            outln!("{}", to_json(&operators)?);
        } else {
            out!("{}", operator::render_records(&operators));
        }
        return Ok(exit_code(operator::failures(&operators) == 0));
    }
    let rows = fenicsx::run().map_err(|e| e.to_string())?;
    if args.json {
        outln!("{}", to_json(&rows)?);
    } else {
        out!("{}", fenicsx::render(&rows));
        outln!();
        out!("{}", operator::render_records(&operators));
    }
    Ok(exit_code(
        fenicsx::failures(&rows) == 0 && operator::failures(&operators) == 0,
    ))
}

fn exit_code(success: bool) -> ExitCode {
    if success {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn run_solve(args: SolveArgs) -> Result<ExitCode, String> {
    let mut spec = match &args.scene {
        Some(path) => SceneSpec::from_file(path).map_err(|e| e.to_string())?,
        None => SceneSpec::default(),
    };
    if let Some(kind) = args.punch {
        spec = spec.shape(kind);
    } else if args.scene.is_none() {
        return Err("give --punch {flat|flat-annulus|cone|sphere} or --scene FILE".into());
    }
    // --eps fixes the annulus of a flat punch, or prescribes the contact of a concave one.
    let kind = args.punch.or_else(|| spec_kind(&args));
    if let Some(eps) = args.eps {
        match kind {
            Some(PunchKind::Cone | PunchKind::Sphere) => {
                if args.depth.is_some() || args.force.is_some() {
                    return Err("--eps prescribes the contact of a concave punch; \
                                do not combine it with --depth or --force"
                        .into());
                }
                spec = spec.contact_ratio(eps);
            }
            Some(PunchKind::Flat) => {
                return Err("--eps does not apply to the flat circular punch; \
                            use --punch flat-annulus --eps B_OVER_A"
                    .into())
            }
            _ => spec = spec.inner_ratio(eps),
        }
    }
    if let Some(d) = args.depth {
        spec = spec.depth(d);
    }
    if let Some(f) = args.force {
        spec = spec.force(f);
    }
    if let Some(tol) = args.tol {
        spec = spec.tolerance(tol);
    }
    let scene = spec.validate().map_err(|e| e.to_string())?;
    let options = methods::MethodOptions {
        mesh: args.mesh.clone(),
        degree: args.degree.and_then(Degree::from_number),
        grid: args.grid.map(|g| g as usize),
        vtu: args.vtu.clone(),
    };
    let solution = methods::solve_with(&scene, args.method, &options).map_err(|e| e.to_string())?;
    if args.json {
        outln!("{}", to_json(&solution)?);
    } else {
        out!("{}", describe(&scene, &solution));
    }
    Ok(ExitCode::SUCCESS)
}

/// The punch kind named in the scene file, if any (to interpret `--eps`).
fn spec_kind(args: &SolveArgs) -> Option<PunchKind> {
    let path = args.scene.as_ref()?;
    SceneSpec::from_file(path)
        .ok()?
        .validate()
        .ok()
        .map(|s| s.punch.kind)
}

fn describe(scene: &ringcontact::scene::Scene, s: &Solution) -> String {
    let p = &scene.punch;
    let es = scene.material.effective_modulus;
    let mut out = String::new();
    let geometry = match p.kind {
        PunchKind::Flat => format!("a = {}", p.rim_radius),
        PunchKind::FlatAnnulus => format!("a = {}, b = {}", p.rim_radius, p.inner_radius),
        _ => format!("a = {}, h = {}", p.rim_radius, p.hole_depth),
    };
    out += &format!("punch            {} ({geometry}, E* = {es})\n", p.kind);
    out += &format!("method           {}\n", s.method);
    out += &format!("contact ratio    eps = b/a = {:.12}\n", s.eps);
    out += &format!("depth            d = {:.12}\n", s.depth);
    out += &format!("force            F = {:.12}\n", s.force);
    if let Some(g) = s.gamma {
        out += &format!("gamma            F/(2 E* d a) = {g:.15}\n");
    }
    if let (Some(g1), Some(g2)) = (s.gamma1, s.gamma2) {
        out += &format!("gamma1           d/h = {g1:.15}\n");
        out += &format!("gamma2           F/(2 E* h a) = {g2:.15}\n");
    }
    if let Some(k) = s.stress_intensity_rim {
        out += &format!("K at rim         {k:.12} (stress x sqrt(length))\n");
    }
    out += &match s.error_estimate {
        Some(e) => format!("error estimate   {e:.1e} (relative in gamma's, absolute in eps)\n"),
        None => "error estimate   none (see provenance: a fit, or a single mesh)\n".to_string(),
    };
    if let (Some(dofs), Some(mesh)) = (s.dofs, &s.mesh) {
        out += &format!(
            "model            {dofs} dofs, P{} on {mesh}\n",
            s.degree.unwrap_or(0)
        );
    }
    if let Some(r) = s.complementarity_residual {
        out += &format!(
            "contact          {} active-set iterations, complementarity residual {r:.1e}\n",
            s.iterations
        );
    }
    out += &format!("wall time        {:.3} ms\n", s.wall_s * 1e3);
    out += &format!("provenance       {}\n", s.provenance);
    if let Some(why) = &s.selection {
        out += &format!("selection        {why}\n");
    }
    out
}

fn print_references() {
    outln!(
        "{:<22} {:<14} {:<10} {:<24} source",
        "name",
        "quantity",
        "kind",
        "valid eps"
    );
    for r in reference::catalogue() {
        outln!(
            "{:<22} {:<14} {:<10} [{}, {}]{:<8} {}",
            r.name,
            format!("{:?}", r.quantity),
            format!("{:?}", r.kind),
            r.eps_range.0,
            r.eps_range.1,
            "",
            r.source
        );
    }
}
