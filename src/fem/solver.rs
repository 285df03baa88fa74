//! The finite-element method behind the common interface: picks a mesh, solves, estimates the
//! error, and returns a dimensionless state (`a = 1`, `E* = 1`, `d = 1` or `h = 1`).
//!
//! **Meshes.** Committed gmsh meshes in `meshes/` (see `meshes/half_space.geo`), families
//! `disk` (flat punch, cone, sphere) and `annulus-<b/a>` (flat annulus), refinement levels
//! `L0, L1, ...` of one size function. `--mesh PATH` uses one given file instead.
//!
//! **Error estimate and model choice.** Levels are climbed from `L1` until the change of the
//! result from the previous level meets the tolerance: the smallest model that meets it. The
//! estimate of the finer result is that change (conservative under convergence) plus the domain
//! truncation bias `1.2 a/R` (the meshes use `R = 1e5 a`; the bias is measured in the tests).
//!
//! **Material.** The frictionless rigid-punch response depends on `E*` only; the solid is given
//! `E = E* (1 - nu²)` with the scene's `nu` (default 0).

use std::path::{Path, PathBuf};
use std::time::Instant;

use super::assembly::assemble_stiffness;
use super::contact::{ContactModel, ContactSolution};
use super::element::Lame;
use super::linear_solver::ConstrainedCholesky;
use super::mesh::{tags, Degree, Mesh};
use super::msh::read_msh;
use super::quadrature::TriangleRule;
use crate::error::{Error, Result};
use crate::punch::PunchKind;

/// Name of the method.
pub const METHOD: &str = "fem";
/// Default relative tolerance of the FEM.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;
/// Radius of the committed meshes' domain, in units of `a`.
pub const DOMAIN_RADIUS: f64 = 1e5;
/// Truncation bias of the force, relative: about `1.2 a / R` (PEERS.md; measured in tests).
pub const TRUNCATION_BIAS: f64 = 1.2 / DOMAIN_RADIUS;

/// Bound on the error of the located inner radius, as a fraction of the contact-node spacing
/// there. The force is stationary in `b` (Barber), so the discrete free edge converges more slowly
/// than the force: against the ring BEM the committed meshes show errors up to 0.12 of the node
/// spacing (P2, 12 states, levels 1-3); the bound takes 0.2.
pub const INNER_RADIUS_BOUND: f64 = 0.2;

/// Highest committed level of each family.
pub const MAX_LEVEL: usize = 3;

/// What to solve.
#[derive(Clone, Copy, Debug)]
pub enum FemLoad {
    /// Flat or flat-annular punch at unit depth.
    Flat,
    /// Concave punch at `d/h`.
    ConcaveDepth(f64),
    /// Concave punch at `F/(2 E* h a)`.
    ConcaveForce(f64),
}

/// Options of the FEM.
#[derive(Clone, Debug)]
pub struct FemOptions {
    pub degree: Degree,
    pub tolerance: f64,
    /// A single mesh to use instead of the committed family.
    pub mesh: Option<PathBuf>,
    /// Poisson's ratio of the solid.
    pub poisson_ratio: f64,
}

/// A solved FEM state.
#[derive(Clone, Debug)]
pub struct FemState {
    pub eps: f64,
    pub gamma: Option<f64>,
    pub gamma1: Option<f64>,
    pub gamma2: Option<f64>,
    pub error_estimate: Option<f64>,
    pub dofs: usize,
    pub iterations: usize,
    pub complementarity_residual: f64,
    /// Mesh path relative to the repository root where possible.
    pub mesh: String,
    pub degree: Degree,
    pub wall_s: f64,
    /// `(r/a, nodal reaction)` along the contact line.
    pub reactions: Vec<(f64, f64)>,
    /// Radii of the contact-line nodes in contact, ascending (the active set).
    pub active_radii: Vec<f64>,
    /// The final model's mesh and nodal displacement (for VTK output).
    pub field: FemField,
    /// Domain radius `R/a` of the final model's mesh.
    pub domain_radius: f64,
    /// Wall time of the phases of the finest solve: assembly, first factorisation, contact loop.
    pub timings: FemTimings,
}

/// Mesh and displacement `(u_r, u_z)` per node of a solved model.
#[derive(Clone, Debug)]
pub struct FemField {
    pub mesh: Mesh,
    pub displacement: Vec<f64>,
}

/// Where the time of one solve went (seconds).
#[derive(Clone, Copy, Debug, Default)]
pub struct FemTimings {
    pub read: f64,
    pub assembly: f64,
    pub symbolic: f64,
    pub solve: f64,
    pub factorisations: usize,
}

fn fem_error(reason: String) -> Error {
    Error::NoConvergence {
        method: METHOD.into(),
        reason,
    }
}

/// Directory of the committed meshes.
pub fn mesh_directory() -> PathBuf {
    std::env::var_os("RINGCONTACT_MESHES")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes"))
}

/// Name of the mesh family for a punch (and `b/a` for the flat annulus).
pub fn family(kind: PunchKind, eps: f64) -> Result<String> {
    match kind {
        PunchKind::FlatAnnulus if eps > 0.0 => {
            let name = format!("annulus-{eps}");
            if mesh_directory().join(format!("{name}-L0.msh")).exists() {
                Ok(name)
            } else {
                Err(Error::Unsupported {
                    method: METHOD.into(),
                    reason: format!(
                        "no committed mesh family for b/a = {eps} (families: b/a = 0.5, 0.9); \
                         generate one with scripts/make_meshes.sh --b {eps} or pass --mesh PATH"
                    ),
                })
            }
        }
        _ => Ok("disk".into()),
    }
}

fn display_path(path: &Path) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    path.strip_prefix(root)
        .unwrap_or(path)
        .display()
        .to_string()
}

/// One mesh loaded, assembled and symbolically factorised.
struct PreparedModel {
    mesh: Mesh,
    path: String,
    /// Domain radius `R/a`: the largest distance of a far-boundary node from the origin.
    domain_radius: f64,
    stiffness: nalgebra_sparse::CscMatrix<f64>,
    timings: FemTimings,
}

fn prepare(path: &Path, degree: Degree, poisson_ratio: f64) -> Result<PreparedModel> {
    let start = Instant::now();
    let raw = read_msh(path)?;
    let mesh = raw.with_degree(degree);
    mesh.validate(&[
        (tags::CONTACT, "contact"),
        (tags::FAR, "far"),
        (tags::AXIS, "axis"),
    ])?;
    let read = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let material = Lame::from_young_poisson(1.0 - poisson_ratio * poisson_ratio, poisson_ratio);
    let rule = stiffness_rule(degree);
    let stiffness = assemble_stiffness(&mesh, &material, &rule)?;
    let assembly = start.elapsed().as_secs_f64();
    let domain_radius = mesh
        .boundary_nodes(tags::FAR)
        .iter()
        .map(|&n| mesh.nodes[n][0].hypot(mesh.nodes[n][1]))
        .fold(0.0, f64::max);
    Ok(PreparedModel {
        mesh,
        domain_radius,
        path: display_path(path),
        stiffness,
        timings: FemTimings {
            read,
            assembly,
            ..Default::default()
        },
    })
}

/// The quadrature rule of the stiffness: degree 2 (3 points) for linear, degree 4 (6 points)
/// for quadratic elements.
pub fn stiffness_rule(degree: Degree) -> TriangleRule {
    match degree {
        Degree::Linear => TriangleRule::degree2(),
        Degree::Quadratic => TriangleRule::degree4(),
    }
}

/// Solve one prepared model.
fn solve_model(
    model: &mut PreparedModel,
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    inner_radius_guess: Option<f64>,
    depth_guess: Option<f64>,
    tolerance: f64,
) -> Result<(ContactSolution, f64, f64)> {
    let start = Instant::now();
    let mut solver = ConstrainedCholesky::new(&model.stiffness)?;
    model.timings.symbolic = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let contact = ContactModel::new(&model.mesh)?;
    if kind == PunchKind::FlatAnnulus || kind == PunchKind::Flat {
        let start_line = contact.contact_line_start();
        if (start_line - eps).abs() > 1e-9 {
            return Err(Error::InvalidMesh {
                path: model.path.clone(),
                message: format!(
                    "its contact line starts at r/a = {start_line}, the scene needs b/a = {eps}"
                ),
            });
        }
    }
    let result = match load {
        FemLoad::Flat => {
            let s = contact.flat(&mut solver, 1.0)?;
            let gamma = 0.5 * s.force;
            (s, gamma, f64::NAN)
        }
        FemLoad::ConcaveDepth(depth) => {
            let warm = inner_radius_guess.map(|b| contact.active_set_for_radius(b));
            let (s, _) = contact.concave(&mut solver, kind, depth, warm)?;
            let g2 = 0.5 * s.force;
            (s, depth, g2)
        }
        FemLoad::ConcaveForce(target) => {
            let warm = inner_radius_guess.map(|b| contact.active_set_for_radius(b));
            // F = 2 E* h a γ2 with h = a = E* = 1.
            let (s, depth) = contact.concave_at_force(
                &mut solver,
                kind,
                2.0 * target,
                depth_guess.unwrap_or(target),
                warm,
                tolerance,
            )?;
            let g2 = 0.5 * s.force;
            (s, depth, g2)
        }
    };
    model.timings.solve = start.elapsed().as_secs_f64();
    model.timings.factorisations = solver.factorisations;
    Ok(result)
}

/// Relative stiffening of the force by truncating the half-space at radius `R` (units of `a`),
/// about `1.2 a/R` (PEERS.md; the committed meshes' finest results sit at this bias).
pub fn truncation_bias(domain_radius: f64) -> f64 {
    1.2 / domain_radius
}

/// A domain too small for the tolerance is a detectable failure: decline it.
fn check_domain(model: &PreparedModel, tolerance: f64) -> Result<()> {
    let bias = truncation_bias(model.domain_radius);
    if bias > tolerance {
        return Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "mesh {} ends at R = {:.3} a: truncating the half-space there stiffens the force by about \
                 1.2 a/R = {bias:.1e}, above the tolerance {tolerance:.1e} (use a mesh with R >= {:.0} a)",
                model.path,
                model.domain_radius,
                1.2 / tolerance
            ),
        });
    }
    Ok(())
}

/// `(eps, γ, γ1, γ2)` of a solved state.
type StateValues = (f64, Option<f64>, Option<f64>, Option<f64>);

/// Package a solved model as a state.
fn finish(
    model: &PreparedModel,
    solution: ContactSolution,
    (eps, gamma, gamma1, gamma2): StateValues,
    error_estimate: Option<f64>,
    iterations: usize,
    degree: Degree,
    start: Instant,
) -> FemState {
    FemState {
        eps,
        gamma,
        gamma1,
        gamma2,
        error_estimate,
        dofs: 2 * model.mesh.nodes.len(),
        iterations,
        complementarity_residual: solution.complementarity_residual,
        mesh: model.path.clone(),
        degree,
        wall_s: start.elapsed().as_secs_f64(),
        reactions: solution.reactions,
        active_radii: solution.active_radii,
        field: FemField {
            mesh: model.mesh.clone(),
            displacement: solution.displacement,
        },
        domain_radius: model.domain_radius,
        timings: model.timings,
    }
}

/// Solve a punch problem with the FEM.
pub fn solve(kind: PunchKind, eps: f64, load: FemLoad, options: &FemOptions) -> Result<FemState> {
    let start = Instant::now();
    if options.tolerance < 1e-6 {
        return Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "tolerance {:e} is below what the committed meshes reach (the truncation bias alone \
                 is {TRUNCATION_BIAS:.1e}); use >= 1e-5, or the ring BEM",
                options.tolerance
            ),
        });
    }
    let state_of =
        |s: &ContactSolution, x: f64, y: f64| -> (f64, Option<f64>, Option<f64>, Option<f64>) {
            match load {
                FemLoad::Flat => (eps, Some(x), None, None),
                _ => (s.inner_radius, None, Some(x), Some(y)),
            }
        };
    if let Some(path) = &options.mesh {
        let mut model = prepare(path, options.degree, options.poisson_ratio)?;
        check_domain(&model, options.tolerance)?;
        let (s, x, y) = solve_model(&mut model, kind, eps, load, None, None, options.tolerance)?;
        let state = state_of(&s, x, y);
        let iterations = s.iterations;
        return Ok(finish(
            &model,
            s,
            state,
            None,
            iterations,
            options.degree,
            start,
        ));
    }
    let family = family(kind, eps)?;
    let path_of = |level: usize| mesh_directory().join(format!("{family}-L{level}.msh"));
    let mut previous: Option<(f64, f64, f64)> = None;
    let mut previous_spacing = 0.0;
    let mut last_estimate = f64::INFINITY;
    let mut iterations = 0;
    for level in 0..=MAX_LEVEL {
        let path = path_of(level);
        if !path.exists() {
            break;
        }
        let mut model = prepare(&path, options.degree, options.poisson_ratio)?;
        check_domain(&model, options.tolerance)?;
        // The previous level's contact radius (and depth) start the iterations.
        let guess = previous.map(|p: (f64, f64, f64)| p.2);
        let depth_guess = previous.map(|p: (f64, f64, f64)| p.0);
        let (s, x, y) = solve_model(
            &mut model,
            kind,
            eps,
            load,
            guess,
            depth_guess,
            options.tolerance,
        )?;
        iterations += s.iterations;
        let (eps_out, gamma, gamma1, gamma2) = state_of(&s, x, y);
        let values = (
            gamma.or(gamma1).unwrap_or(f64::NAN),
            gamma2.unwrap_or(f64::NAN),
            eps_out,
        );
        if let Some(prev) = previous {
            let relative = |a: f64, b: f64| {
                if a.is_nan() {
                    0.0
                } else {
                    (a - b).abs() / a.abs()
                }
            };
            // The located inner radius converges to first order in the node spacing there, which
            // shrinks by q between levels: the finer level's error is about |Δeps| / (q - 1)
            // (Richardson), never taken below the element-size bound.
            let ratio = previous_spacing / s.inner_node_spacing;
            let eps_change = (values.2 - prev.2).abs();
            let eps_estimate = if s.inner_node_spacing > 0.0 && ratio > 1.5 {
                (eps_change / (ratio - 1.0)).max(INNER_RADIUS_BOUND * s.inner_node_spacing)
            } else {
                eps_change.max(INNER_RADIUS_BOUND * s.inner_node_spacing)
            };
            let estimate = relative(values.0, prev.0)
                .max(relative(values.1, prev.1))
                .max(eps_estimate)
                + truncation_bias(model.domain_radius);
            if estimate <= options.tolerance {
                let state = (eps_out, gamma, gamma1, gamma2);
                return Ok(finish(
                    &model,
                    s,
                    state,
                    Some(estimate),
                    iterations,
                    options.degree,
                    start,
                ));
            }
            last_estimate = estimate;
        }
        previous = Some(values);
        previous_spacing = s.inner_node_spacing;
    }
    Err(fem_error(format!(
        "the finest committed mesh of family `{family}` reaches an estimated error of {last_estimate:.1e}, \
         above the tolerance {:.1e}; refine with scripts/make_meshes.sh --levels N or loosen --tol",
        options.tolerance
    )))
}
