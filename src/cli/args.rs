//! The command line's arguments (clap derive): what `verify --help` and each subcommand's
//! `--help` teach. The binary parses them and hands them to [`crate::cli::dispatch`].

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use super::choice;
use crate::harness::report::document;
use ringcontact::methods::{GridBem, Method};
use ringcontact::punch::PunchName;
use ringcontact::scene::DEFAULT_TOLERANCE;

/// The cells per side `--grid` takes: the grid BEM's own range.
const GRID_RANGE: std::ops::RangeInclusive<u64> =
    (GridBem::MIN_CELLS as u64)..=(GridBem::MAX_CELLS as u64);

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
  verify table --punch cone --eps 0.1:0.9:0.1   one row per state (CSV; --json)
  verify grade --results mine.csv          another code's results against the references
  verify fenicsx                           stored FEniCSx results against our FEM
  verify plan --nightly --out n.plan       the suite as independent jobs: `verify run --shard I/N`,
                                           `verify merge` (on Slurm: scripts/slurm/submit.sh)

Environment:
  RINGCONTACT_DATA_DIR=DIR    the project's data directory (as --data-dir)
  RINGCONTACT_TRACE=1         one line per finite-element model on stderr (phase times, sizes)
  RINGCONTACT_LINEAR_SOLVER=faer|native   the FEM's sparse Cholesky (as --linear-solver)
  RAYON_NUM_THREADS=N         worker threads of the solvers (default: one per core)")]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The project's data directory (holding meshes/ and verify/) [default: found upward from the
    /// current directory; RINGCONTACT_DATA_DIR also sets it].
    #[arg(long, global = true, value_name = "DIR")]
    pub data_dir: Option<PathBuf>,
    /// The FEM's sparse Cholesky factorisation: `native` (this crate's, split over two cores
    /// where the model admits a separator; 1.3-2.2x faster on the FEM's targets) or `faer`
    /// (faer's public sparse Cholesky, one thread). The same answers (forces within 1e-10)
    /// [default: native; RINGCONTACT_LINEAR_SOLVER also sets it].
    #[arg(long, global = true, value_name = "NAME", value_parser = ["native", "faer"])]
    pub linear_solver: Option<String>,
}

#[derive(Subcommand)]
pub enum Command {
    /// Solve one scene with one method and print the state (or JSON).
    #[command(after_help = "\
Defaults: a = 1, E* = 1, h = 1, so the outputs are the paper's dimensionless functions
(flat punches: F = 2 E* d a gamma; concave: d = h gamma1, F = 2 E* h a gamma2).

Examples:
  verify solve --punch flat-annulus --eps 0.5            gamma(0.5) at unit depth
  verify solve --punch cone --depth 2 --json             eps and gamma2 at d = 2h
  verify solve --punch sphere --eps 0.3                  gamma1(0.3), gamma2(0.3)
  verify solve --punch sphere --force 3                  F/(2E*ha) = 1.5: eps and depth
  verify solve --punch power --exponent 1.5 --depth 2    gap h (1 - (r/a)^1.5)
  verify solve --punch torus --tube-radius 0.25 --force 0.1   both edges of the ring found
  verify solve --punch table --profile verify/profiles/sphere-21.csv --depth 1   a measured profile
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
    /// Solve one punch at many states (a list or range of b/a, depths or forces) in one process
    /// and write one row per state: every quantity and its error estimate (CSV, or JSON).
    #[command(after_help = "\
LIST: numbers and inclusive ranges START:STOP:STEP, comma-separated (0.01:0.99:0.01 is 99
states, 0.5,1,2 three). Exactly one of --eps, --depth, --force.

Columns (CSV header = JSON keys, the keys of `verify solve --json`): given_eps, given_depth or
given_force (the state as listed), punch, exponent (power), tube_radius (torus), method, eps,
inner_radius, outer_radius, rim_radius, depth, force, gamma (flat punches), gamma1, gamma2
(concave punches), stress_intensity_rim, stress_intensity_inner, error_estimate, unknowns,
iterations, wall_s; a column without a value in any row is left out. Units: the scene's (a = h =
E* = 1 without --scene, so depth = d/h, force = F/(E* h a) = 2 gamma2).

All states are checked before the first is solved; a state the method fails on stops the table
with the state named (exit status 1). Progress on standard error for long tables.

Examples:
  verify table --punch flat-annulus --eps 0.01:0.99:0.01 > gamma.csv
  verify table --punch sphere --depth 0.5,1,2,3,4 --json
  verify table --punch cone --eps 0.1:0.9:0.1 --tol 1e-12
  verify table --punch torus --tube-radius 0.25 --force 0.01,0.1,1
  verify table --scene verify/scenes/flat-annulus-half.toml --depth 0.01:0.05:0.01
  verify table --punch sphere --depth 1,2 --method fem --tol 1e-6 --out sphere-fem.csv")]
    Table(TableArgs),
    /// Grade another code's results (CSV or JSON) against the converged references at the same
    /// states: each value's relative error, the reference's own bound, within --tol or not.
    #[command(after_help = "\
Input: CSV with a header row (or JSON: an array of objects, or an object whose `rows` is one, as
`verify table --json` writes). Columns (case-sensitive; others are kept and ignored):
  punch          flat, flat-annulus, cone, sphere, power, torus, table (required)
  depth, force, eps   the state: the column named by `state` (depth, force or eps), else the
                 first of depth, force, eps given; the others are graded (the flat annulus's
                 eps is its hole b/a)
  gamma          F/(2 E* d a), flat punches
  gamma1, gamma2 d/h and F/(2 E* h a), concave punches and the torus
  exponent, tube_radius, profile   the power law's n, the torus's rho, the table's file
  E_star, a, h   the row's units (default 1: the dimensionless functions). Dimensional data:
                 give E_star, a and h, and depth and force in those units (F = 2 E* h a gamma2).

The reference: the ring BEM at 1e-12 (where it declines: --method auto at T/100). Each value:
relative_error = |value - reference| / |reference|, within = relative_error <= T. A value closer
to the reference than 100 times the reference's error bound is said to be so (`resolved`: false).
Exit status 1 if any value is beyond T.

Examples:
  verify grade --results verify/grade/paper-fits.csv --tol 0.03   the paper's fits (exit 1: 25 %)
  verify grade --results mine.csv --json > graded.json
  verify grade --results mine.csv --svg errors.svg")]
    Grade(GradeArgs),
    /// Write the converged reference values (non-adhesive functions, stress intensity factors,
    /// JKR critical states and pull-off forces, fitted formulas), each with its error bound, as
    /// CSV and JSON tables described by a datapackage.json.
    #[command(after_help = "\
Tables (NAME.csv with one header row, NAME.json with the same rows, fields and provenance):
  functions-flat-annulus   gamma(eps), K at both edges, 1e-4 <= eps <= 0.9999
  functions-cone, functions-sphere, functions-power-n1.5   gamma1(eps), gamma2(eps), K at the
                           rim, up to eps = 1e-4
  functions-torus          gamma1(eps), gamma2(eps) and c/a of the band (both edges free),
                           0.01 <= eps <= 0.9999; one family in units of h = a²/(2 rho)
  jkr-flat-annulus         critical depth and force at either edge against b/a, with bounds
  jkr-cone, jkr-sphere, jkr-power-n1.5   pull-off against d0/h: fixed load, fixed grips,
                           full contact
  jkr-torus                pull-off against d0/h (1e-3 to 1): fixed load, fixed grips (both
                           edges free), beside the plane-strain JKR cylinder's
  fits                     the paper's formulas, refitted, and the best forms, largest errors
datapackage.json (Frictionless Data) gives each column's type, unit and meaning, the
interpolation and its measured error, and the provenance (version, commit, command). pandas:
pd.read_csv('DIR/functions-cone.csv'); R: read.csv(...); frictionless: Package('DIR/datapackage.json').

The function tables are uniform in s = ln(eps/(1 - eps)); exp of the cubic in s through
ln(value) at the four nearest rows interpolates them to the error stated (measured at every
interval's midpoint). The full dataset takes seconds; --small (the copy in verify/dataset/)
about one.

Examples:
  verify dataset                       into reports/dataset/
  verify dataset --out /tmp/rc --small")]
    Dataset(DatasetArgs),
    /// Compare the methods with the analytic references on all punches (the default job).
    #[command(after_help = "Example:\n  verify compare --tol 1e-10 --json > comparison.json")]
    Compare(CompareArgs),
    /// Compare every stored FEniCSx result (verify/fenicsx/) with our FEM on the identical problem.
    #[command(after_help = "\
Each result is re-solved with FEniCSx's model (same mesh, degree, quadrature, supports): the force
must agree within 1e-8 and the active contact set must be the same. Results whose mesh changed
since they were stored are reported as stale and not used.

Each stored result carries `reproduce` (this solve, as a command) and `peer_reproduce` (FEniCSx's).
Refresh the stored results (FEniCSx installed by bash scripts/fenicsx/setup.sh; review the
difference and commit it):
  python3 scripts/fenicsx/run_all.py --out verify/fenicsx [--large]
How fast each code is, measured interleaved: benches/records/fenicsx-speed.md
(python3 scripts/fenicsx/speed.py).

Example:
  verify fenicsx --json
  verify fenicsx --large              add the stored results on the largest meshes (about a minute
                                      with the meshes cached; gmsh remakes them when they are not)
  verify fenicsx --operators --json   the stored operator comparisons (python3
                                      scripts/fenicsx/operators.py --out verify/fenicsx/operators
                                      remakes them)")]
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
  verify mesh --parameters a=1,b=0.3,R=1e5        any parameters of meshes/half_space.geo
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
Levels: grid-bem 64, 128, 256, ... cells per side; fem with gmsh the adapted levels it makes
(graded toward the edges, each refined at the free edge the level below located; P3), without
gmsh the committed levels L0-L2 (P2); the torus's fem the free-edges levels
(refined at both edges; P2, gmsh needed); ring-bem 6, 8, 10, ... collocation nodes (flat
punches).

Examples:
  verify convergence --punch flat --method grid-bem --levels 5          64 .. 1024
  verify convergence --punch sphere --depth 1.5 --method fem --levels 4
  verify convergence --punch torus --depth 1 --method fem --levels 4
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
    /// Pull-off by direct simulation: an adhesion law on the FE model's contact line, pressed
    /// and pulled under displacement control, at decreasing ranges (growing Tabor parameter),
    /// extrapolated to the JKR limit and set beside `verify jkr`.
    #[command(after_help = "\
The law: exponential adhesion, tension (dw/rho) exp(-s/rho) at separation s, work of adhesion dw,
with non-penetration, on the contact line of the P2 FE model (condensed: the half-space's
response there is exactly the FE model's). The punch is pressed to 0.5 d0 (flat punches) or 3h
(cone, sphere; deeper, in steps of 3h up to 24h, until the hole closes: small d0/h), then pulled
under displacement control; the preload's branch is followed until it ends (a jump, which is what
fixed grips see); the pull-off is its most tensile force while the crack front, running in from
the rim, lies in the refined rim band (below). A range at which a concave punch's hole stays
open, or reopens on the way out (the apex's unresolved pinhole is a flaw of the law's range), is
on the annular branch, whose moving inner edge the mesh does not resolve: it is left out with
that reason and a range half the smallest replaces it (down to rho/d0 = 0.001), until three
ranges are on the closed hole's branch (--branch closed, the default).

--branch annular (cone, sphere): touched (the rim plane at the surface; adhesion pulls the rim
into contact, the hole stays open), then pulled: the inner edge moves outward until the annulus
lets go; the JKR limit is the annular contact's fixed-load pull-off (the paper's route). The
contact line is meshed uniformly at a third of the zone length, one gmsh mesh per range (ranges
rho/d0 >= 0.032: at most 600 line elements); node hops of the inner edge (force steps under
0.01 F0) continue the branch. Where the hole closes first (no stable annular contact, as at
d0/h >= 3) the range is left out; where it does at every range, the case is declined.

--punch torus (two free edges; d0/h <= 1, h = a²/(2 rho)): touched at its lowest circle (d = 0),
then pulled, both edges moving until the band lets go; the JKR limit is the two-edge JKR
solution's fixed-load pull-off (`verify jkr --punch torus`). Its contact line [0, 1.5 a] is
meshed uniformly at a third of the zone length, one gmsh mesh per range (ranges rho/d0 >= 0.039),
as the annular branch's; --branch does not apply (the torus has no hole to close).

Units: d0 = sqrt(2 pi a dw / E*) (= a for the flat punches; h = 1 for the concave ones, so
d0 = d0/h); forces are tensile-positive multiples of Kendall's F0 = sqrt(8 pi E* dw a^3). The
Tabor-like parameter is sqrt(a/l), l = pi E* dw / (4 sigma0^2) the cohesive zone's length. Beside
the result: the JKR route (`verify jkr`: fixed-load pull-off; from full contact for concave
punches) and the paper's route on its fitted formulas.

Mesh (closed branch): one gmsh mesh per range, level 1 of the adapted family with the band
[a - 20 l, a] at the rim meshed uniformly at l/6 (l the zone length): the front runs 3-13 l in
before the tension peaks, and node hops of the front inside the band (force steps under 1e-3 F0)
continue the branch; a front that leaves the band while the tension still rises is an error
(not resolved). The mesh check: the smallest range at l/3 on level 0. Without gmsh: the
committed meshes of the ratio (b/a = 0, 0.5, 0.9; level 2, level 1 for the check), no band, the
pull-off the first end of the branch (about 2 % low at Tabor 36), and the ranges 0.05, 0.025,
0.0125 by default. --mesh: that mesh for every range, no band, no check.

Examples:
  verify pulloff --punch flat                          Kendall: the sequence tends to 1
  verify pulloff --punch flat-annulus --eps 0.5 --json
  verify pulloff --punch sphere --d0h 3
  verify pulloff --punch cone --d0h 1 --branch annular   about 3 min: the paper's route's branch
  verify pulloff --punch torus --d0h 1                    about 5 min: two free edges
  verify pulloff --punch flat --ranges 0.1,0.05,0.025")]
    Pulloff(PulloffArgs),
    /// Adhesion at any Tabor parameter: the Maugis-Dugdale law on the ring BEM, from the
    /// rigid limit (uniform tension over the contact) to JKR; the pull-off and its path.
    #[command(after_help = "\
The law (--law dugdale): a tension sigma0 wherever the gap between punch and surface is below
delta_c = dw/sigma0 (dw the work of adhesion), none beyond; contact where the gap closes. The
Tabor parameter lambda = 2 sigma0 sqrt(a/(pi E* dw)) sets the range: the cohesive zone at a crack
tip is about a/lambda^2 long; lambda -> infinity is JKR (`verify jkr`), small lambda the rigid
limit. Each cohesive zone's tension is laid on in closed form and the contact's pressure is
solved by the ring BEM with bounded stress at its free edges; the pull-off is the first
extremum of the force (--control load) or the depth (--control grips) met as the punch is
pulled, refined on a ladder of node counts until its last two changes are within --tol (the
larger is the error bound reported).

Punches: flat (its closed form, derived in the library's reference::dugdale_flat, is printed
beside); flat-annulus --eps B_OVER_A (the contact held at a face edge while that edge's stress
is compressive, else both edges free, a cohesive zone from each free edge toward the face's
edge; detaching_edge names the face edge whose gap reaches the range first); the concave cone,
sphere, power and table --d0h D0_OVER_H (pressed until the hole is about to close, then pulled:
the contact holds the rim while the rim's stress is compressive, a cohesive zone runs from the
free inner edge into the recess; where the narrowing ring vanishes the surface is held by its
zone alone, shrinking to the rim: under grips the punch may come away gradually, force about 0
at depth -delta_c; detaching_edge is outer when the rim's gap reaches the range, else inner;
the JKR limit is `verify jkr`'s annular pull-off). The torus is declined.

Units: forces in F0 = sqrt(8 pi E* dw a^3) (Kendall's flat punch; negative = tensile), depths in
d0 = sqrt(2 pi a dw / E*), radii in a: the JKR limit reads against `verify jkr` directly.

--sweep: the pull-off against lambda from 0.05 to 100 under both controls, with the JKR value,
written as dugdale-PUNCH.csv and .svg into --out (default reports/adhesion), the lambdas solved
in parallel. Time on a 2-core machine: flat about 15 s; flat-annulus and the concave punches
6-10 min (lambdas above 20 take the longest). A lambda whose node ladder does not meet --tol
(about 10-40 and above at 1e-6), or whose path has no pull-off on its route, is listed as
declined with the reason.

Examples:
  verify adhesion --punch flat --tabor 2
  verify adhesion --punch flat --tabor 5 --control grips --json
  verify adhesion --punch flat-annulus --eps 0.5 --tabor 3
  verify adhesion --punch cone --d0h 1 --tabor 5
  verify adhesion --punch flat --sweep")]
    Adhesion(AdhesionArgs),
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
    /// Write the suite as a plan of independent jobs (one line each: id, expected seconds,
    /// output file, the exact `verify` command), for `verify run --shard` and `verify merge`.
    #[command(after_help = "\
Plans (the same arguments give the same plan, byte for byte):
  verify plan                  the default report (`verify compare --report`), 30 jobs
  verify plan --nightly        the nightly suite: the report with the FEM down to 1e-8, the
                               pull-off simulations (verify/pulloff/) and the stability probes
  verify plan --convergence --punch sphere --depth 1.5 --method fem --levels 4
                               one job per level of a convergence study

Run on one machine, in three shards, and merge:
  verify plan --nightly --out nightly.plan
  for i in 1 2 3; do verify run --plan nightly.plan --shard $i/3 --results results; done
  verify merge --plan nightly.plan --results results --report reports/nightly

On a Slurm cluster (a job array, the merge a dependent job): scripts/slurm/submit.sh")]
    Plan(PlanArgs),
    /// Run one shard of a plan: each of its jobs in its own process, one result file per job
    /// (an error record when a job fails); exit status 1 when any job failed.
    #[command(after_help = "\
Shard I of N gets the jobs a deterministic split gives it: longest expected time first, each to
the shard with the least expected time so far. Every shard of the same plan and N gets the same
jobs on every machine, so N independent tasks (a Slurm array) cover the plan exactly once.

Example:
  verify run --plan nightly.plan --shard 2/3 --results results")]
    Run(RunArgs),
    /// Build the report from a plan's result files (the same report as the single-process run);
    /// fails, naming them, if any job's result is missing or an error.
    #[command(after_help = "\
A report plan writes the report directory as `verify compare --report DIR` does (index.html,
report.md, report.json, CSV tables, SVG charts; with --nightly plans also stability.json and
the pull-off simulations of this run) and prints the same summary; a convergence plan writes
each study's CSV and chart. Exit status 1 when a check fails, as `verify compare`.

Example:
  verify merge --plan nightly.plan --results results --report reports/nightly")]
    Merge(MergeArgs),
    /// Run one job of a plan and print its record (JSON); what `verify run` calls for each job.
    #[command(after_help = "\
The id names the job and all its parameters (`verify plan` lists them), e.g.
  verify part comparison:tol=1e-6
  verify part speed:cone-2:fem-tol=1e-8
  verify part convergence:sphere:fem:eps=0:depth=1.5:level=2:of=3
  verify part pulloff:cone:d0h=10")]
    Part(PartArgs),
    /// List the analytic references and the range of eps where each is valid.
    #[command(after_help = "Examples:\n  verify references\n  verify references --json")]
    References(JsonArgs),
}

// The arguments of `verify history`.
#[derive(Args)]
pub struct HistoryArgs {
    /// Report directory written by `verify compare --report DIR` (and `stability.json` in it).
    #[arg(long)]
    pub report: PathBuf,
    /// JSON-lines history file.
    #[arg(long, default_value = "reports/history.jsonl")]
    pub history: PathBuf,
    /// Whether the FEniCSx results were refreshed (`fresh`) or read from the repository (`stored`).
    #[arg(long, default_value = "stored")]
    pub fenicsx: String,
    /// The same for the Tamaas/ContactMechanics results.
    #[arg(long, default_value = "stored")]
    pub peers: String,
    /// Date label of this run [default: the report directory's name].
    #[arg(long)]
    pub date: Option<String>,
}

// The arguments of `verify pulloff`.
#[derive(Args)]
pub struct PulloffArgs {
    /// Punch shape (cone and sphere: from full contact, pressed until the hole closes).
    #[arg(long, value_parser = choice::parser::<PunchName>())]
    pub punch: PunchName,
    /// Exponent n of the power-law punch (`--punch power`): gap h (1 - (r/a)^n), any n > 0
    /// (n = 1 is the cone, n = 2 the sphere).
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Profile table of `--punch table` (CSV of `r/a, g/h` points, as for `verify solve`).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// b/a of the flat annulus.
    #[arg(long, allow_negative_numbers = true)]
    pub eps: Option<f64>,
    /// d0/h of a concave punch.
    #[arg(long, allow_negative_numbers = true)]
    pub d0h: Option<f64>,
    /// Ranges rho/d0 of the law, decreasing, comma-separated (the last three are extrapolated)
    /// [default: 0.05,0.025,0.0125,0.005 (Tabor 9 to 90); without gmsh 0.05,0.025,0.0125; with
    /// --branch annular 0.1,0.07,0.05].
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub ranges: Option<Vec<f64>>,
    /// Concave punches: the branch to follow. `closed`: pressed until the hole closes, then
    /// pulled (JKR limit: the pull-off from full contact). `annular`: touched with the hole open,
    /// then pulled, the inner edge moving outward (JKR limit: the annular contact's fixed-load
    /// pull-off, the paper's route); its contact line is meshed uniformly at a third of the
    /// zone per range (gmsh needed).
    #[arg(long, value_parser = choice::parser::<ringcontact::cohesive::study::Branch>(), default_value = "closed")]
    pub branch: ringcontact::cohesive::study::Branch,
    /// A gmsh .msh file (units of a; physical groups as in meshes/half_space.geo) instead of the
    /// default mesh.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify adhesion`.
#[derive(Args)]
pub struct AdhesionArgs {
    /// Punch shape: flat, flat-annulus or a concave one (cone, sphere, power, table).
    #[arg(long, value_parser = choice::parser::<PunchName>())]
    pub punch: PunchName,
    /// Exponent n of the power-law punch (`--punch power`).
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Profile table of `--punch table` (CSV of `r/a, g/h` points).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// b/a of the flat annulus.
    #[arg(long, allow_negative_numbers = true)]
    pub eps: Option<f64>,
    /// d0/h of a concave punch (its recess's depth h in units of d0 = sqrt(2 pi a dw / E*)).
    #[arg(long, allow_negative_numbers = true)]
    pub d0h: Option<f64>,
    /// The adhesion law: dugdale (constant tension sigma0 up to the gap dw/sigma0).
    #[arg(long, default_value = "dugdale", value_parser = ["dugdale"])]
    pub law: String,
    /// Tabor parameter lambda = 2 sigma0 sqrt(a/(pi E* dw)), > 0 (needed unless --sweep).
    #[arg(long, allow_negative_numbers = true)]
    pub tabor: Option<f64>,
    /// What the machine holds while pulling: the force (load) or the depth (grips).
    #[arg(long, default_value = "load", value_parser = ["load", "grips"])]
    pub control: String,
    /// Bound on the pull-off's error, in units of F0 and d0.
    #[arg(long, default_value_t = 1e-6, allow_negative_numbers = true)]
    pub tol: f64,
    /// Sweep lambda from 0.05 to 100 under both controls, writing CSV and SVG into --out.
    #[arg(long)]
    pub sweep: bool,
    /// Directory for the sweep's CSV and SVG [default: reports/adhesion in the project's
    /// directory].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify jkr`.
#[derive(Args)]
pub struct JkrArgs {
    /// Punch shape: flat-annulus, a concave one (cone, sphere, power, table) or torus.
    #[arg(long, value_parser = choice::parser::<PunchName>())]
    pub punch: PunchName,
    /// Exponent n of the power-law punch (`--punch power`): gap h (1 - (r/a)^n), any n > 0
    /// (n = 1 is the cone, n = 2 the sphere).
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Profile table of `--punch table` (CSV of `r/a, g/h` points, as for `verify solve`).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// b/a of the flat annulus.
    #[arg(long)]
    pub eps: Option<f64>,
    /// Dimensionless work of adhesion d0/h of a concave punch.
    #[arg(long)]
    pub d0h: Option<f64>,
    /// Concave punches: sweep d0/h from 0.1 to 100 (the paper's Fig. 10), writing CSV and SVG
    /// into --out.
    #[arg(long)]
    pub sweep: bool,
    /// Directory for the sweep's CSV and SVG [default: reports/jkr in the project's directory].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify convergence`.
#[derive(Args)]
pub struct ConvergenceArgs {
    /// Punch shape.
    #[arg(long, value_parser = choice::parser::<PunchName>())]
    pub punch: PunchName,
    /// Exponent n of the power-law punch (`--punch power`): gap h (1 - (r/a)^n), any n > 0
    /// (n = 1 is the cone, n = 2 the sphere).
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Profile table of `--punch table` (CSV of `r/a, g/h` points, as for `verify solve`).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Method to refine.
    #[arg(long, value_parser = choice::parser::<Method>())]
    pub method: Method,
    /// Number of refinement levels.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u64).range(2..=8))]
    pub levels: u64,
    /// b/a of the flat annulus.
    #[arg(long, default_value_t = 0.5)]
    pub eps: f64,
    /// d/h of a concave punch (the torus: h = a²/(2 rho), its gap at the axis).
    #[arg(long, default_value_t = 1.5)]
    pub depth: f64,
    /// Directory for the CSV and SVG files [default: reports/convergence in the project's
    /// directory].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify mesh`.
#[derive(Args)]
pub struct MeshArgs {
    /// Start of the contact line `b/a` (the flat annulus' inner radius; 0 for the disk).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub eps: f64,
    /// Level of the adapted family (-2 to 7; grading g = 0.32 * 0.6^level).
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub level: i32,
    /// Refine around this inner contact radius `b/a` (concave punches).
    #[arg(long, allow_negative_numbers = true)]
    pub free_edge: Option<f64>,
    /// How well that radius is known (the coarser solve's error estimate): the element size at
    /// the free edge puts about 24 contact nodes between it and that distance.
    #[arg(long, default_value_t = 0.0)]
    pub edge_uncertainty: f64,
    /// Make the mesh for a solve at this relative tolerance (rim and edge sizes follow it), as
    /// `verify solve --method fem --tol X` does.
    #[arg(long)]
    pub tol: Option<f64>,
    /// Element degree of that solve (with --tol).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub degree: u8,
    /// Make the mesh from these meshes/half_space.geo parameters instead (NAME=VALUE,...: the
    /// `mesh_parameters` this command prints and stored results carry).
    #[arg(long, value_name = "NAME=VALUE,...", conflicts_with_all = ["eps", "level", "free_edge", "edge_uncertainty", "tol"])]
    pub parameters: Option<String>,
}

// The arguments of `verify export`.
#[derive(Args)]
pub struct ExportArgs {
    /// gmsh .msh file (physical groups as in meshes/half_space.geo).
    #[arg(long, required_unless_present = "mesh_parameters")]
    pub mesh: Option<PathBuf>,
    /// A mesh made by gmsh from meshes/half_space.geo with these parameters (NAME=VALUE,...,
    /// as `verify mesh` prints them) instead of --mesh.
    #[arg(long, value_name = "NAME=VALUE,...", conflicts_with = "mesh")]
    pub mesh_parameters: Option<String>,
    /// Element degree: 1, 2 or 3.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub degree: u8,
    /// Directory to write stiffness.mtx, load.mtx and dofs.csv into (created if missing)
    /// [default with --compare: a temporary directory, removed afterwards].
    #[arg(long, required_unless_present = "compare")]
    pub out: Option<PathBuf>,
    /// FEniCSx's export of the same mesh and degree (scripts/fenicsx/export.py --out DIR):
    /// compare the two operators and print the differences (JSON with --json).
    #[arg(long, value_name = "DIR")]
    pub compare: Option<PathBuf>,
    /// With --compare: print the comparison as JSON.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify fenicsx`.
#[derive(Args)]
pub struct FenicsxArgs {
    /// Print JSON instead of the table (the force comparisons; with --operators, the operator
    /// comparisons).
    #[arg(long)]
    pub json: bool,
    /// Show only the stored comparisons of the assembled operator (stiffness matrix and load
    /// vector, entry by entry, dofs matched by position) with FEniCSx's.
    #[arg(long)]
    pub operators: bool,
    /// Also compare the stored results on the largest meshes (verify/fenicsx/large/: 6e5 to
    /// 1.4e6 unknowns, the top of the README's cost table). Takes about a minute with the meshes
    /// cached, plus gmsh's time to remake them when they are not (needs gmsh then).
    #[arg(long, conflicts_with = "operators")]
    pub large: bool,
}

// The arguments of the subcommands whose only flag is `--json`.
#[derive(Args)]
pub struct JsonArgs {
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify solve`.
#[derive(Args, Clone)]
pub struct SolveArgs {
    /// Punch shape.
    #[arg(long, value_parser = choice::parser::<PunchName>())]
    pub punch: Option<PunchName>,
    /// Exponent n of the power-law punch (`--punch power`): gap h (1 - (r/a)^n), any n > 0
    /// (n = 1 is the cone, n = 2 the sphere).
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Tube radius rho of the torus (`--punch torus`), in the length unit of a (1 unless a scene
    /// file says otherwise): gap (r - a)²/(2 rho), depth scale h = a²/(2 rho).
    #[arg(long, allow_negative_numbers = true)]
    pub tube_radius: Option<f64>,
    /// Profile table of `--punch table`: a CSV file of `r/a, g/h` points (an optional header
    /// row; `#` comments), sorted by radius from the axis (`0, 1`) to the rim (`1, 0`), the gap
    /// never rising outward. Interpolated by monotone cubics (PCHIP); rim at r = a, inner edge
    /// free. Every method solves it (the ring BEM by default); `verify jkr` gives its pull-off.
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Contact ratio b/a: fixes the flat annulus; for a concave punch or the torus it prescribes
    /// the inner contact edge (depth, force and the torus's outer edge are then computed).
    #[arg(long, allow_negative_numbers = true)]
    pub eps: Option<f64>,
    /// Indentation depth d of the rim (for concave punches with h = 1 this is d/h).
    #[arg(long, conflicts_with = "force", allow_negative_numbers = true)]
    pub depth: Option<f64>,
    /// Normal force F, compression positive.
    #[arg(long, allow_negative_numbers = true)]
    pub force: Option<f64>,
    /// Method.
    #[arg(long, value_parser = choice::parser::<Method>(), default_value = "ring-bem")]
    pub method: Method,
    /// Scene file (TOML, see verify/scenes/); flags given as well override its values.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Relative tolerance wanted in the dimensionless results [default: the scene's, else the
    /// method's: 1e-9 ring-bem, 1e-3 fem]. The FEM climbs meshes gmsh makes for the scene and
    /// tolerance (found at run time: `bash scripts/install_gmsh.sh` installs it; without it, the
    /// committed meshes serve tolerances down to 1e-4) until its error estimate meets it.
    #[arg(long)]
    pub tol: Option<f64>,
    /// FEM only: a gmsh .msh file (units of a; physical groups as in meshes/half_space.geo)
    /// instead of the committed mesh family. No error estimate is made on a single mesh.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// FEM only: a single mesh made by gmsh from meshes/half_space.geo with these parameters
    /// (NAME=VALUE,...: what `verify mesh` prints and stored results carry), cached in
    /// .mesh-cache/; like --mesh otherwise.
    #[arg(long, value_name = "NAME=VALUE,...", conflicts_with = "mesh")]
    pub mesh_parameters: Option<String>,
    /// FEM only: the condition on the far arc of the truncated domain. `boussinesq` (the
    /// default): the arc follows the point-force field, bias O((a/R)^2); `fixed`: u = 0 there,
    /// the classical truncation (too stiff by about 1.2 a/R), the model of the stored FEniCSx
    /// results.
    #[arg(long, value_parser = choice::parser::<ringcontact::methods::FarField>())]
    pub far_field: Option<ringcontact::methods::FarField>,
    /// FEM only: element degree, 1 (linear), 2 (quadratic) or 3 (cubic) [default: 3 on meshes
    /// made by gmsh, 2 on the committed meshes and with --mesh].
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub degree: Option<u8>,
    /// FEM only: write the displacement field of the finest model as VTK (.vtu) for ParaView.
    #[arg(long)]
    pub vtu: Option<PathBuf>,
    /// Grid BEM only: cells per side of the square grid on [-a, a]^2 [default: 256].
    #[arg(long, value_parser = clap::value_parser!(u64).range(GRID_RANGE))]
    pub grid: Option<u64>,
    /// Grid BEM with --punch torus only: the grid covers [-L, L]^2 with L = this times a
    /// (1 < L <= 10) [default: the band's outer edge plus a quarter of its width, from a
    /// coarse solve]. A peer's grid is reproduced with it.
    #[arg(long, value_name = "L")]
    pub grid_extent: Option<f64>,
    /// Grid BEM only: solve the requested grid alone, without the two coarser grids (N/2, N/4)
    /// that make its error estimate (about a fifth of the time); the answer then has no
    /// estimate. For timing the paper's method against codes that run one grid.
    #[arg(long)]
    pub no_grid_estimate: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Solve many scenes in one process: FILE (`-` for standard input) holds one JSON object
    /// per line, with the keys of a scene file (`{"punch": {"shape": "cone"}, "load":
    /// {"depth": 2}}`; dimensional ones too) and optionally `"method"`. Prints one JSON line per
    /// scene, in order: the solution (as `--json`, compact) with `"line"`, or `{"line": N,
    /// "error": "..."}` for a scene that fails, without stopping the rest. --method and --tol
    /// apply to lines that do not say. Exit status 1 if any line failed.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["punch", "exponent", "tube_radius", "profile", "eps", "depth", "force", "scene", "mesh", "mesh_parameters", "vtu"])]
    pub batch: Option<PathBuf>,
}

// The arguments of `verify table`.
#[derive(Args)]
#[command(group(clap::ArgGroup::new("state").required(true).args(["eps", "depth", "force"])))]
pub struct TableArgs {
    /// Punch shape.
    #[arg(long, value_parser = choice::parser::<PunchName>())]
    pub punch: Option<PunchName>,
    /// Exponent n of the power-law punch (`--punch power`).
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Tube radius rho of the torus (`--punch torus`).
    #[arg(long, allow_negative_numbers = true)]
    pub tube_radius: Option<f64>,
    /// Profile table of `--punch table` (CSV of `r/a, g/h` points).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Scene file (TOML) giving the punch, the material and the units; its load is replaced by
    /// each state of the list.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// States by contact ratio b/a: numbers and ranges START:STOP:STEP (inclusive),
    /// comma-separated. Fixes the flat annulus; prescribes a concave punch's (or the torus's)
    /// inner contact edge.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub eps: Option<String>,
    /// States by indentation depth d (d/h for concave punches with h = 1), as a LIST.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub depth: Option<String>,
    /// States by normal force F (compression positive), as a LIST.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub force: Option<String>,
    /// Method.
    #[arg(long, value_parser = choice::parser::<Method>(), default_value = "ring-bem")]
    pub method: Method,
    /// Relative tolerance wanted [default: the scene's, else the method's].
    #[arg(long)]
    pub tol: Option<f64>,
    /// FEM only: the condition on the far arc (as `verify solve`).
    #[arg(long, value_parser = choice::parser::<ringcontact::methods::FarField>())]
    pub far_field: Option<ringcontact::methods::FarField>,
    /// FEM only: element degree 1, 2 or 3 (as `verify solve`).
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub degree: Option<u8>,
    /// Grid BEM only: cells per side (as `verify solve`).
    #[arg(long, value_parser = clap::value_parser!(u64).range(GRID_RANGE))]
    pub grid: Option<u64>,
    /// Grid BEM only: solve each state on the requested grid alone, without the two coarser
    /// grids that make its error estimate (as `verify solve --no-grid-estimate`).
    #[arg(long)]
    pub no_grid_estimate: bool,
    /// Print one JSON object (provenance and `rows`) instead of CSV.
    #[arg(long)]
    pub json: bool,
    /// Write the table to this file instead of standard output.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

// The arguments of `verify grade`.
#[derive(Args)]
pub struct GradeArgs {
    /// The results to grade (CSV with a header row, or JSON).
    #[arg(long, value_name = "FILE")]
    pub results: PathBuf,
    /// Relative error a value may have and pass.
    #[arg(long, default_value_t = 1e-3, value_name = "T")]
    pub tol: f64,
    /// Print one JSON object (`rows`, `summary`, `max_relative_error`, `tolerance`, the
    /// provenance) instead of the tables.
    #[arg(long)]
    pub json: bool,
    /// Write the chart of the relative error against the state to this SVG file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

// The arguments of `verify dataset`.
#[derive(Args)]
pub struct DatasetArgs {
    /// Directory to write into (created if absent) [default: reports/dataset in the project's
    /// directory].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// The small copy (coarser grids, five values of d0/h): what verify/dataset/ holds.
    #[arg(long)]
    pub small: bool,
    /// Print a JSON summary (files, rows, interpolation errors) instead of the table.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify compare`.
#[derive(Args)]
pub struct CompareArgs {
    /// Relative tolerance of the ring BEM.
    #[arg(long, default_value_t = DEFAULT_TOLERANCE)]
    pub tol: f64,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Report directory (Markdown, JSON, SVG charts) [default: reports/latest in the project's
    /// directory, wherever the command runs].
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Skip the report directory (tables only).
    #[arg(long)]
    pub no_report: bool,
    /// Tolerances of the FEM's full solve in the report's speed-against-accuracy charts (meshes
    /// made by gmsh; left out without it), comma-separated. The nightly run adds 1e-8.
    #[arg(long, value_delimiter = ',', default_values_t = document::DEFAULT_FEM_TOLERANCES)]
    pub fem_tolerances: Vec<f64>,
    /// A directory of fresh peer and pull-off results laid out as verify/ (fenicsx/, peers/,
    /// pulloff/; what scripts/nightly.sh writes into REPORT/fresh): each is compared with its
    /// committed baseline, a difference beyond tolerance a failed check.
    #[arg(long, value_name = "DIR")]
    pub fresh: Option<PathBuf>,
}

// The arguments of `verify plan`.
#[derive(Args)]
pub struct PlanArgs {
    /// The nightly suite (the report with the FEM down to 1e-8, the pull-off simulations, the
    /// stability probes) instead of the default report.
    #[arg(long, conflicts_with = "convergence")]
    pub nightly: bool,
    /// A convergence study, one job per level (with --punch, --method, --levels, --eps, --depth).
    #[arg(long, requires_all = ["punch", "method"])]
    pub convergence: bool,
    /// Relative tolerance of the ring BEM in the comparison job.
    #[arg(long, default_value_t = DEFAULT_TOLERANCE)]
    pub tol: f64,
    /// Tolerances of the FEM's full solve in the speed-accuracy jobs [default: 1e-3,1e-4,1e-6;
    /// with --nightly also 1e-8].
    #[arg(long, value_delimiter = ',')]
    pub fem_tolerances: Option<Vec<f64>>,
    /// Convergence plan: punch shape.
    #[arg(long, value_parser = choice::parser::<PunchName>(), requires = "convergence")]
    pub punch: Option<PunchName>,
    /// Convergence plan: the power law's exponent n (`--punch power`).
    #[arg(long, requires = "convergence")]
    pub exponent: Option<f64>,
    /// Convergence plan: the method to refine.
    #[arg(long, value_parser = choice::parser::<Method>(), requires = "convergence")]
    pub method: Option<Method>,
    /// Convergence plan: number of levels.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u64).range(2..=8))]
    pub levels: u64,
    /// Convergence plan: b/a of the flat annulus.
    #[arg(long, default_value_t = 0.5)]
    pub eps: f64,
    /// Convergence plan: d/h of a concave punch.
    #[arg(long, default_value_t = 1.5)]
    pub depth: f64,
    /// Write the plan to this file instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

// The arguments of `verify run`.
#[derive(Args)]
pub struct RunArgs {
    /// The plan file (`verify plan --out FILE`).
    #[arg(long)]
    pub plan: PathBuf,
    /// Which shard to run, I/N (1 <= I <= N) [default: 1/1, the whole plan].
    #[arg(long, default_value = "1/1", value_parser = crate::harness::plan::parse_shard)]
    pub shard: (usize, usize),
    /// Directory for the jobs' result files (created if absent).
    #[arg(long)]
    pub results: PathBuf,
}

// The arguments of `verify merge`.
#[derive(Args)]
pub struct MergeArgs {
    /// The plan file the results were computed from.
    #[arg(long)]
    pub plan: PathBuf,
    /// Directory of the jobs' result files.
    #[arg(long)]
    pub results: PathBuf,
    /// Report directory to write.
    #[arg(long)]
    pub report: PathBuf,
    /// Print JSON instead of the tables.
    #[arg(long)]
    pub json: bool,
}

// The arguments of `verify part`.
#[derive(Args)]
pub struct PartArgs {
    /// The job's id (a line of `verify plan`).
    pub id: String,
}
