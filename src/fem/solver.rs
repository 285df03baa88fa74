//! The finite-element method behind the common interface: picks a mesh, solves, estimates the
//! error, and returns a dimensionless state (`a = 1`, `E* = 1`, `d = 1` or `h = 1`).
//!
//! **Meshes.** A sequence of models for the scene and tolerance ([`mesh_sequence`]): the committed
//! families in `meshes/` (`disk`, `annulus-0.5`, `annulus-0.9`, levels L0-L2), continued by the
//! adapted family made by gmsh at run time ([`super::mesh_provider`]); `--mesh PATH` uses one
//! given file instead.
//!
//! **Error estimate and model choice.** Levels are climbed until the change of the result from
//! the previous level meets the tolerance: the smallest model that meets it. The estimate of the
//! finer result is that change (conservative under convergence) plus the far-field truncation
//! bias ([`FarField::truncation_bias`]) and the [`unresolved_component`].
//!
//! **Material.** The frictionless rigid-punch response depends on `E*` only; the solid is given
//! `E = E* (1 - nu²)` with the scene's `nu` (default 0).

use std::path::{Path, PathBuf};
use std::time::Instant;

use super::assembly::assemble_stiffness;
use super::contact::{ContactModel, ContactSolution};
use super::element::Lame;
use super::far_field::{FarField, FarFieldCondition};
use super::linear_solver::ConstrainedCholesky;
use super::mesh::{tags, Degree, Mesh};
use super::mesh_provider::{self, MeshOrigin, MeshRequest, ProvidedMesh};
use super::msh::read_msh;
use super::quadrature::TriangleRule;
use crate::error::{Error, Result};
use crate::punch::PunchKind;

/// Name of the method.
pub const METHOD: &str = "fem";
/// Default relative tolerance of the FEM.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;
/// Smallest tolerance the FEM accepts: below it, the unresolved component
/// ([`unresolved_component`]) is not known well enough to bound.
pub const MIN_TOLERANCE: f64 = 1e-8;

/// An error component that level-to-level changes do not capture, added to every estimate:
/// `8.6e-8 g^0.77` for a model of grading `g` (the mesh's far-arc edge over `R`).
///
/// Measured on the flat annulus `b/a = 0.3` with cubic elements against the ring BEM: the error
/// is 8.1e-9 at `g = 0.115` and 3.7e-9 at `g = 0.041`, while consecutive levels differ by only
/// 1.7e-9; it grows by about 7e-10 per decade of the domain radius, and it is neither the
/// quadrature (a 10 x 10 collapsed Gauss rule changes it by 2e-14) nor the linear solve
/// (iterative refinement changes it by 2e-11). The bound is twice the fit `4.3e-8 g^0.77`; at the
/// tolerances of the committed meshes (1e-3, 1e-4) it is negligible. Its cause is open.
pub fn unresolved_component(grading: f64) -> f64 {
    8.6e-8 * grading.powf(0.77)
}
/// Below this tolerance the committed family is skipped and the adapted family starts directly.
pub const COMMITTED_TOLERANCE_FLOOR: f64 = 1e-4;

/// Bound on the error of the located inner radius, as a fraction of the contact-node spacing
/// there. The force is stationary in `b` (Barber), so the discrete free edge converges more slowly
/// than the force: against the ring BEM the committed meshes show errors up to 0.12 of the node
/// spacing (P2, 12 states, levels 1-3); the bound takes 0.2.
pub const INNER_RADIUS_BOUND: f64 = 0.2;

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
    /// Treatment of the far arc (default: Boussinesq's point-force field, bias `O((a/R)²)`).
    pub far_field: FarField,
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
    /// Relative force bias left by truncating the half-space there (in the estimate).
    pub truncation_bias: f64,
    /// Far-field treatment of the final model.
    pub far_field: FarField,
    /// SHA-256 of the final model's mesh file.
    pub mesh_sha256: String,
    /// Where that mesh came from (committed, cache, gmsh, user).
    pub mesh_origin: MeshOrigin,
    /// Version of the gmsh that made it (generated meshes).
    pub gmsh_version: Option<String>,
    /// Wall time of the phases of the finest solve: assembly, first factorisation, contact loop.
    pub timings: FemTimings,
}

/// Mesh and displacement `(u_r, u_z)` per node of a solved model.
#[derive(Clone, Debug)]
pub struct FemField {
    pub mesh: Mesh,
    pub displacement: Vec<f64>,
}

/// Where the time of the finest model's solve went (seconds; JSON key `fem_timings`).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct FemTimings {
    /// Reading the mesh and raising its degree.
    #[serde(rename = "read_s")]
    pub read: f64,
    /// Assembling the stiffness (and the far-field condition).
    #[serde(rename = "assembly_s")]
    pub assembly: f64,
    /// Symbolic Cholesky analysis (ordering, elimination tree).
    #[serde(rename = "symbolic_s")]
    pub symbolic: f64,
    /// The contact solve: factorisations, band responses, iterations.
    #[serde(rename = "contact_s")]
    pub solve: f64,
    /// Numeric factorisations done by the contact solve.
    pub factorisations: usize,
    /// Part of `contact_s` spent in them.
    #[serde(rename = "factorisation_s")]
    pub factorisation: f64,
    /// Unit responses of band nodes computed by the banded contact solve.
    pub band_responses: usize,
}

fn fem_error(reason: String) -> Error {
    Error::NoConvergence {
        method: METHOD.into(),
        reason,
    }
}

/// Directory of the committed meshes (see [`mesh_provider::mesh_directory`]).
pub fn mesh_directory() -> PathBuf {
    mesh_provider::mesh_directory()
}

/// Where the contact line of the punch's mesh starts: `b/a` for the flat annulus, else 0.
pub fn contact_start(kind: PunchKind, eps: f64) -> f64 {
    match kind {
        PunchKind::FlatAnnulus => eps,
        _ => 0.0,
    }
}

/// The sequence of meshes climbed for a scene and tolerance: the committed family (when one
/// exists for this contact line and the tolerance is at least [`COMMITTED_TOLERANCE_FLOOR`]),
/// continued by the adapted family made by gmsh; otherwise the adapted family alone, from the
/// level whose predicted error (about `3.5e-4 · 0.13^k` for P2) is within 100 x the tolerance.
pub fn mesh_sequence(kind: PunchKind, eps: f64, tolerance: f64) -> Vec<MeshRequest> {
    let start_line = contact_start(kind, eps);
    let mut sequence = Vec::new();
    let mut first_adapted = 0;
    if tolerance >= COMMITTED_TOLERANCE_FLOOR {
        if let Some(family) = mesh_provider::committed_family(start_line) {
            for level in 0..=mesh_provider::COMMITTED_MAX_LEVEL {
                sequence.push(MeshRequest::Committed {
                    family: family.clone(),
                    level,
                });
            }
            first_adapted = 3;
        }
    }
    if sequence.is_empty() {
        while first_adapted < 3 && 3.5e-4 * 0.13f64.powi(first_adapted as i32) > 100.0 * tolerance {
            first_adapted += 1;
        }
    }
    for level in first_adapted..=mesh_provider::ADAPTED_MAX_LEVEL {
        sequence.push(MeshRequest::Adapted {
            contact_start: start_line,
            level,
            free_edge: None,
            edge_uncertainty: 0.0,
        });
    }
    sequence
}

fn display_path(path: &Path) -> String {
    let root = mesh_provider::project_root();
    path.strip_prefix(&root)
        .unwrap_or(path)
        .display()
        .to_string()
}

/// One mesh loaded, assembled and symbolically factorised.
struct PreparedModel {
    mesh: Mesh,
    path: String,
    provided: ProvidedMesh,
    /// Domain radius `R/a`: the largest distance of a far-boundary node from the origin.
    domain_radius: f64,
    /// Largest far-arc edge over `R`: the grading of the far field.
    arc_grading: f64,
    stiffness: nalgebra_sparse::CscMatrix<f64>,
    /// The far-field condition, when the arc is slaved to Boussinesq's field.
    far_field: Option<FarFieldCondition>,
    timings: FemTimings,
}

fn prepare(
    provided: &ProvidedMesh,
    degree: Degree,
    poisson_ratio: f64,
    far_field: FarField,
    contact_start: f64,
) -> Result<PreparedModel> {
    let start = Instant::now();
    let path = provided.path.as_path();
    let raw = read_msh(path)?;
    let required = [
        (tags::CONTACT, "contact"),
        (tags::FAR, "far"),
        (tags::AXIS, "axis"),
    ];
    // The file's mesh first (its messages quote the file's tags), then the degree-raised one.
    raw.validate(&required)?;
    raw.validate_geometry(contact_start)?;
    let mesh = raw.with_degree(degree);
    mesh.validate(&required)?;
    let read = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let material = Lame::from_young_poisson(1.0 - poisson_ratio * poisson_ratio, poisson_ratio);
    let rule = stiffness_rule(degree);
    let stiffness = assemble_stiffness(&mesh, &material, &rule)?;
    let domain_radius = mesh
        .boundary_nodes(tags::FAR)
        .iter()
        .map(|&n| mesh.nodes[n][0].hypot(mesh.nodes[n][1]))
        .fold(0.0, f64::max);
    let arc_grading = mesh
        .boundary
        .iter()
        .filter(|e| e.tag == tags::FAR)
        .map(|e| {
            let (p, q) = (mesh.nodes[e.nodes[0]], mesh.nodes[e.nodes[1]]);
            (p[0] - q[0]).hypot(p[1] - q[1]) / domain_radius
        })
        .fold(0.0, f64::max);
    let (stiffness, far_field) = match far_field {
        FarField::Fixed => (stiffness, None),
        FarField::Boussinesq => {
            let condition = FarFieldCondition::new(&mesh, &material, domain_radius);
            (condition.extend(&stiffness)?, Some(condition))
        }
    };
    let assembly = start.elapsed().as_secs_f64();
    Ok(PreparedModel {
        mesh,
        domain_radius,
        arc_grading,
        far_field,
        path: display_path(path),
        provided: provided.clone(),
        stiffness,
        timings: FemTimings {
            read,
            assembly,
            ..Default::default()
        },
    })
}

/// The quadrature rule of the stiffness: degree 2 (3 points) for linear, degree 4 (6 points)
/// for quadratic, degree 6 (12 points) for cubic elements (degree `2p`: exact for the
/// polynomial part `∇N·∇N r` of the integrand up to one degree of the `r` factor).
pub fn stiffness_rule(degree: Degree) -> TriangleRule {
    match degree {
        Degree::Linear => TriangleRule::degree2(),
        Degree::Quadratic => TriangleRule::degree4(),
        Degree::Cubic => TriangleRule::degree6(),
    }
}

/// What a coarser model tells the next one about a concave punch's free edge.
#[derive(Clone, Copy, Debug)]
pub struct WarmStart {
    /// Inner contact radius located on the coarser model.
    pub inner_radius: f64,
    /// Half-width of the band around it where the finer model's edge is expected: twice the
    /// coarser model's estimated error of the inner radius.
    pub band: f64,
}

/// Core of the banded contact solve: the contact nodes above the band are held in the
/// factorisation (none without a warm start).
fn core_radius(warm: Option<WarmStart>) -> f64 {
    warm.map_or(f64::INFINITY, |w| w.inner_radius + w.band)
}

/// Solve one prepared model.
fn solve_model(
    model: &mut PreparedModel,
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    warm: Option<WarmStart>,
    depth_guess: Option<f64>,
    tolerance: f64,
) -> Result<(ContactSolution, f64, f64)> {
    let start = Instant::now();
    let mut solver = ConstrainedCholesky::new(&model.stiffness)?;
    model.timings.symbolic = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let contact = ContactModel::new(&model.mesh, model.stiffness.nrows())?;
    if kind == PunchKind::FlatAnnulus || kind == PunchKind::Flat {
        let start_line = contact.contact_line_start();
        if (start_line - eps).abs() > 1e-9 {
            return Err(Error::InvalidMesh {
                path: model.path.clone(),
                message: format!(
                    "its contact line starts at r/a = {}, the scene needs b/a = {}",
                    crate::error::show(start_line),
                    crate::error::show(eps)
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
            let initial = warm.map(|w| contact.active_set_for_radius(w.inner_radius));
            let mut system = contact.banded_system(&mut solver, kind, core_radius(warm));
            let (s, _, _) = contact.concave_with(&mut system, kind, depth, initial)?;
            model.timings.band_responses = system.responses_computed();
            let g2 = 0.5 * s.force;
            (s, depth, g2)
        }
        FemLoad::ConcaveForce(target) => {
            let initial = warm.map(|w| contact.active_set_for_radius(w.inner_radius));
            let mut system = contact.banded_system(&mut solver, kind, core_radius(warm));
            // F = 2 E* h a γ2 with h = a = E* = 1.
            let (s, depth) = contact.concave_at_force(
                &mut system,
                kind,
                2.0 * target,
                depth_guess.unwrap_or(target),
                initial,
                tolerance,
            )?;
            model.timings.band_responses = system.responses_computed();
            let g2 = 0.5 * s.force;
            (s, depth, g2)
        }
    };
    model.timings.solve = start.elapsed().as_secs_f64();
    model.timings.factorisations = solver.factorisations;
    model.timings.factorisation = solver.factorisation_seconds;
    Ok(result)
}

impl PreparedModel {
    /// Relative force bias of truncating the half-space at this model's `R` with its far-field
    /// treatment ([`FarField::truncation_bias`]).
    fn truncation_bias(&self) -> f64 {
        self.far_field_kind()
            .truncation_bias(self.domain_radius, self.arc_grading)
    }

    fn far_field_kind(&self) -> FarField {
        if self.far_field.is_some() {
            FarField::Boussinesq
        } else {
            FarField::Fixed
        }
    }
}

/// [`prepare`] with the options' degree, material and far field, then [`check_domain`].
fn prepare_checked(
    provided: &ProvidedMesh,
    options: &FemOptions,
    contact_start: f64,
) -> Result<PreparedModel> {
    let model = prepare(
        provided,
        options.degree,
        options.poisson_ratio,
        options.far_field,
        contact_start,
    )?;
    check_domain(&model, options.tolerance)?;
    Ok(model)
}

/// A domain too small for the tolerance is a detectable failure: decline it.
fn check_domain(model: &PreparedModel, tolerance: f64) -> Result<()> {
    let bias = model.truncation_bias();
    if bias > tolerance {
        return Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "mesh {} ends at R = {:.3} a: truncating the half-space there biases the force by about \
                 {bias:.1e}, above the tolerance {tolerance:.1e} (use a larger domain)",
                model.path,
                model.domain_radius
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
            displacement: match &model.far_field {
                Some(condition) => condition.expand(&solution.displacement),
                None => solution.displacement,
            },
        },
        domain_radius: model.domain_radius,
        truncation_bias: model.truncation_bias(),
        far_field: model.far_field_kind(),
        mesh_sha256: model.provided.sha256.clone(),
        mesh_origin: model.provided.origin,
        gmsh_version: model.provided.gmsh_version.clone(),
        timings: model.timings,
    }
}

/// One line per model on standard error (`RINGCONTACT_TRACE=1`): size, phase times, contact cost.
fn trace_level(model: &PreparedModel, solution: &ContactSolution) {
    let t = &model.timings;
    eprintln!(
        "fem: {} ({} unknowns): read {:.3} s, assembly {:.3} s, symbolic {:.3} s, contact {:.3} s \
         ({} factorisations {:.3} s, {} band responses, {} iterations), b/a = {:.10}, force {:.12}",
        model.path,
        model.stiffness.nrows(),
        t.read,
        t.assembly,
        t.symbolic,
        t.solve,
        t.factorisations,
        t.factorisation,
        t.band_responses,
        solution.iterations,
        solution.inner_radius,
        solution.force
    );
}

/// Solve a punch problem with the FEM.
pub fn solve(kind: PunchKind, eps: f64, load: FemLoad, options: &FemOptions) -> Result<FemState> {
    let start = Instant::now();
    if options.tolerance.is_nan() || options.tolerance < MIN_TOLERANCE {
        return Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "tolerance {:e} is below the FEM's floor {MIN_TOLERANCE:e} (an error component of a \
                 few 1e-9 that refinement reduces slowly); use the ring BEM for tighter tolerances",
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
        let provided = ProvidedMesh {
            sha256: mesh_provider::sha256_file(path)?,
            path: path.clone(),
            origin: MeshOrigin::User,
            gmsh_version: None,
        };
        let mut model = prepare_checked(&provided, options, contact_start(kind, eps))?;
        let (s, x, y) = solve_model(&mut model, kind, eps, load, None, None, options.tolerance)?;
        if std::env::var_os("RINGCONTACT_TRACE").is_some() {
            trace_level(&model, &s);
        }
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
    // The mesh families live in the project's data directory: say so if it cannot be found.
    mesh_provider::find_project_root()?;
    let why = format!(
        "the FEM for the {kind} at tolerance {:e}",
        options.tolerance
    );
    let mut previous: Option<(f64, f64, f64)> = None;
    let mut previous_spacing = 0.0;
    let mut previous_eps_error = 0.0;
    let mut last_estimate = f64::INFINITY;
    let mut iterations = 0;
    let mut last_mesh = String::new();
    for request in mesh_sequence(kind, eps, options.tolerance) {
        // The adapted family refines around the free edge located on the previous (coarser) solve.
        let request = if kind.is_concave() {
            request.with_free_edge(previous.map(|p| p.2), previous_eps_error)
        } else {
            request
        };
        let provided = mesh_provider::provide(&request, &why)?;
        let mut model = prepare_checked(&provided, options, contact_start(kind, eps))?;
        last_mesh = model.path.clone();
        // The previous level's contact radius (and depth) start the iterations.
        let guess = previous.map(|p: (f64, f64, f64)| WarmStart {
            inner_radius: p.2,
            band: previous_eps_error,
        });
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
        if std::env::var_os("RINGCONTACT_TRACE").is_some() {
            trace_level(&model, &s);
        }
        let mut eps_error = INNER_RADIUS_BOUND * s.inner_node_spacing;
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
            eps_error = eps_estimate;
            let estimate = relative(values.0, prev.0)
                .max(relative(values.1, prev.1))
                .max(eps_estimate)
                + model.truncation_bias()
                + unresolved_component(model.arc_grading);
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
        previous_eps_error = eps_error;
    }
    Err(fem_error(format!(
        "the finest model ({last_mesh}) reaches an estimated error of {last_estimate:.1e}, above the \
         tolerance {:.1e}; loosen --tol or use the ring BEM",
        options.tolerance
    )))
}
