//! The finite-element method behind the common interface: picks a mesh, solves, estimates the
//! error, and returns a dimensionless state (`a = 1`, `E* = 1`, `d = 1` or `h = 1`).
//!
//! **Meshes.** A sequence of models for the scene and tolerance ([`mesh_sequence`]): the committed
//! families in `meshes/` (`disk`, `annulus-0.5`, `annulus-0.9`, levels L0-L2), continued by the
//! adapted family made by gmsh at run time ([`crate::mesh::provider`]); `--mesh PATH` uses one
//! given file instead.
//!
//! **Error estimate and model choice.** Levels are climbed until the change of the result from
//! the previous level meets the tolerance: the smallest model that meets it. The estimate of the
//! finer result is that change (conservative under convergence) plus the far-field truncation
//! bias ([`FarField::truncation_bias`]) and the [`UNRESOLVED_COMPONENT`]. A concave punch's
//! located edge is bounded by its level change, by a share of the node spacing there and, where
//! the edge is ill-conditioned (a nearly closed hole), by [`EDGE_FIELD_FRACTION`] of its
//! conditioning times the force estimate (under a prescribed force and where the force converged
//! more slowly than its order says: [`EDGE_FIELD_FRACTION_WHOLE`] of it, added to the edge's
//! own error).
//!
//! **Material.** The frictionless rigid-punch response depends on `E*` only; the solid is given
//! `E = E* (1 - nu²)` with the scene's `nu` (default 0).

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;

use crate::discretisation::assembly::{BubbleRecovery, StiffnessPattern};
use crate::discretisation::element::Lame;
use crate::discretisation::far_field::{FarField, FarFieldCondition};
use crate::discretisation::node_ordering::node_ordering_of_raised;
use crate::discretisation::quadrature::stiffness_rule;
use crate::error::{Error, Result};
use crate::fem::contact::{ContactModel, ContactSolution};
use crate::heartbeat::{Heartbeat, Progress};
use crate::mesh::files::DataPaths;
use crate::mesh::msh::{read_msh_hashed, PendingHash};
use crate::mesh::provider::{self, MeshOrigin, MeshRequest, ProvidedMesh, SizeTarget};
use crate::mesh::triangulation::{tags, Degree, Mesh};
use crate::punch::PunchKind;
use crate::sparse::constrained::ConstrainedCholesky;
use crate::sparse::{analyse_beside, Analysis, Pattern};

mod free_edges;
mod ladder;

/// Name of the method.
pub const METHOD: &str = "fem";
/// Default relative tolerance of the FEM.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;
/// Smallest tolerance the FEM accepts; below it the estimates have not been checked
/// (docs/decisions.md, "Where the constants come from").
pub const MIN_TOLERANCE: f64 = 1e-8;

/// An error component that level-to-level changes do not capture, added to every relative
/// estimate: `2e-9`, whatever the contact ratio (docs/decisions.md, "Where the constants come
/// from").
pub const UNRESOLVED_COMPONENT: f64 = 2e-9;

/// Coefficient `c` of the singular edges' force error `c h / w` ([`PreparedModel`]'s edge
/// component: `h` the element size at the edges, `w` the ring's width): three times the largest
/// found for cubic elements, zero for the linear and quadratic ladders, verified without it
/// (docs/decisions.md, "Where the constants come from").
fn edge_error_coefficient(degree: Degree) -> f64 {
    match degree {
        Degree::Linear | Degree::Quadratic => 0.0,
        Degree::Cubic => 0.05,
    }
}

/// Below this tolerance the committed family is skipped and the adapted family starts directly.
const COMMITTED_TOLERANCE_FLOOR: f64 = 1e-4;

/// Fewest free contact nodes in a concave punch's hole for the located edge to be bounded by
/// [`INNER_RADIUS_BOUND`] of the spacing: the edge is extrapolated from the three free nodes
/// before the last (P3) or the last three (P1, P2); with fewer the bound is two spacings (the
/// linear gap at `d = 12 h`, hole `9.1e-4 a` inside 1-2 nodes, was located 5.9e-4 off).
const MIN_FREE_NODES: usize = 5;

/// Bound on the error of the located inner radius, as a fraction of the contact-node spacing
/// there. The force is stationary in `b` (Barber), so the discrete free edge converges more slowly
/// than the force: against the ring BEM, P2 on the committed meshes showed errors up to 0.12 of
/// the spacing (12 states, levels 1-3), and P3 on the adapted meshes up to 0.20 (the parabolic gap
/// at `d = 2.8 h`, `--tol 1e-6`; 0.04-0.14 elsewhere); the bound takes 0.3.
const INNER_RADIUS_BOUND: f64 = 0.3;

/// What to solve.
#[derive(Clone, Copy, Debug)]
pub enum FemLoad {
    /// Flat or fixed-annulus punch at unit depth.
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
    /// The sparse Cholesky backend that factorises the stiffness ([`crate::sparse::Backend`]).
    pub linear_solver: crate::sparse::Backend,
    /// One line per model on standard error: size, phase times, contact cost (a program's
    /// `RINGCONTACT_TRACE=1`).
    pub trace: bool,
    /// Where the committed meshes, the mesh cache and gmsh are.
    pub data: DataPaths,
    /// How often a long ladder reports on standard error.
    pub progress: Progress,
}

impl Default for FemOptions {
    /// Quadratic elements to [`DEFAULT_TOLERANCE`], `ν = 0`, Boussinesq's far field, the
    /// built-in backend, the checkout's data found from the current directory.
    fn default() -> Self {
        FemOptions {
            degree: Degree::Quadratic,
            tolerance: DEFAULT_TOLERANCE,
            mesh: None,
            poisson_ratio: 0.0,
            far_field: FarField::Boussinesq,
            linear_solver: crate::sparse::Backend::default(),
            trace: false,
            data: DataPaths::default(),
            progress: Progress::default(),
        }
    }
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
    /// Refinement applied to that file's mesh when it was read, described.
    pub mesh_refinement: Option<String>,
    /// Wall time of the phases of the finest solve: assembly, first factorisation, contact loop.
    pub timings: FemTimings,
    /// Concave punches: the located edge's conditioning `κ = |db/dd| d` on the final model
    /// ([`crate::fem::contact::ContactModel::edge_depth_sensitivity`]).
    pub edge_conditioning: Option<f64>,
    /// The sparse Cholesky backend that factorised the final model.
    pub linear_solver: crate::sparse::Backend,
    /// A contact with two free edges (a free band): the located outer edge `c/a`; `None` where
    /// the contact ends at the rim.
    pub outer_edge: Option<f64>,
}

impl FemState {
    /// Nodal contact pressures `(r, p)` along the contact line, ascending in `r`
    /// ([`crate::fem::contact::nodal_pressure`]: the reactions over the nodes' weights).
    pub fn contact_pressure(&self) -> Vec<(f64, f64)> {
        crate::fem::contact::nodal_pressure(&self.field.mesh, &self.reactions)
    }
}

/// Mesh and displacement `(u_r, u_z)` per node of a solved model.
#[derive(Clone, Debug)]
pub struct FemField {
    pub mesh: Mesh,
    pub displacement: Vec<f64>,
}

/// Where the time of the finest model's solve went (seconds; JSON key `fem_timings`).
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct FemTimings {
    /// Reading the mesh: the parse, the checks, any corner refinement and the end of the file's
    /// hash (raising its degree is part of `assembly_s`).
    #[serde(rename = "read_s")]
    pub read: f64,
    /// Assembling the stiffness (and the far-field condition), wall time: the symbolic analysis
    /// runs alongside, within it.
    #[serde(rename = "assembly_s")]
    pub assembly: f64,
    /// Symbolic Cholesky analysis (the ordering beside the pattern, then the elimination tree
    /// and supernodes, which share the two cores with the values' assembly): the wall time of
    /// those two phases, part of `assembly_s`, not added to it.
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
    /// The linear model on the same mesh that located a concave punch's free edge for a cold
    /// start (all its phases; 0 when a coarser model or a flat-faced punch needed none).
    #[serde(rename = "edge_presolve_s")]
    pub edge_presolve: f64,
}

fn fem_error(reason: String) -> Error {
    Error::NoConvergence {
        method: METHOD.into(),
        reason,
    }
}

/// Directory of the committed meshes of the checkout found from the current directory
/// ([`DataPaths::default`]).
pub fn mesh_directory() -> PathBuf {
    DataPaths::default().meshes
}

/// Where the contact line of the punch's mesh starts: `b/a` for the fixed annulus, else 0.
pub fn contact_start(kind: &PunchKind, eps: f64) -> f64 {
    if kind.has_fixed_hole() {
        eps
    } else {
        0.0
    }
}

/// The sequence of meshes climbed for a scene and tolerance: the committed family (when one
/// exists for this contact line and the tolerance is at least [`COMMITTED_TOLERANCE_FLOOR`]),
/// continued by the adapted family made by gmsh; otherwise the adapted family alone, from the
/// level whose predicted error (about `3.5e-4 · 0.13^k` for P2) is within 100 x the tolerance.
pub fn mesh_sequence(
    data: &DataPaths,
    kind: PunchKind,
    eps: f64,
    tolerance: f64,
) -> Vec<MeshRequest> {
    let start_line = contact_start(&kind, eps);
    let mut sequence = Vec::new();
    let mut first_adapted: i32 = 0;
    if tolerance >= COMMITTED_TOLERANCE_FLOOR {
        if let Some(family) = provider::committed_family(data, start_line) {
            for level in 0..=provider::COMMITTED_MAX_LEVEL {
                sequence.push(MeshRequest::Committed {
                    family: family.clone(),
                    level,
                });
            }
            first_adapted = 3;
        }
    }
    if sequence.is_empty() {
        while first_adapted < 3 && 3.5e-4 * 0.13f64.powi(first_adapted) > 100.0 * tolerance {
            first_adapted += 1;
        }
    }
    for level in first_adapted..=provider::ADAPTED_MAX_LEVEL {
        sequence.push(MeshRequest::Adapted {
            contact_start: start_line,
            level,
            free_edge: None,
            edge_uncertainty: 0.0,
            target: None,
        });
    }
    sequence
}

/// One mesh loaded, assembled and symbolically factorised.
struct PreparedModel {
    mesh: Mesh,
    /// SHA-256 of the file's bytes as read and parsed ([`read_msh_hashed`]).
    mesh_sha256: String,
    /// The file's mesh (after any corner refinement), validated, before its degree was raised:
    /// what the linear edge locator assembles without reading the file again.
    vertex_mesh: Mesh,
    path: String,
    provided: ProvidedMesh,
    /// What the model was assembled as (the linear edge locator reuses it at degree 1).
    spec: ModelSpec,
    /// Domain radius `R/a`: the largest distance of a far-boundary node from the origin.
    domain_radius: f64,
    /// Largest far-arc edge over `R`: the grading of the far field.
    arc_grading: f64,
    /// The stiffness, cubic cells' bubbles condensed
    /// ([`StiffnessPattern::with_condensed_bubbles`]).
    stiffness: nalgebra_sparse::CscMatrix<f64>,
    /// Where each column's diagonal entry is among `stiffness`'s entries (from the assembly).
    diagonal: Vec<usize>,
    /// What recovers the condensed bubbles' displacements (cubic models).
    bubbles: Option<BubbleRecovery>,
    /// The symbolic Cholesky analysis of `stiffness`'s pattern (done during the assembly).
    symbolic: Analysis,
    /// The far-field condition, when the arc is slaved to Boussinesq's field.
    far_field: Option<FarFieldCondition>,
    timings: FemTimings,
}

/// What a model is besides its mesh.
#[derive(Clone, Copy, Debug)]
struct ModelSpec {
    degree: Degree,
    /// Poisson's ratio of the material (`E* = 1` whatever it is).
    poisson_ratio: f64,
    far_field: FarField,
    /// Where the scene's contact line starts, `b/a` (0 for a closed one).
    contact_start: f64,
    linear_solver: crate::sparse::Backend,
    /// [`FemOptions::trace`].
    trace: bool,
    /// The mesh's length unit in units of `a`: 1, except for a contact with two free edges,
    /// whose mesh's contact line `[0, 1]` is `[0, frame a]` ([`ContactModel::with_free_edges`]).
    frame: f64,
}

/// Physical groups every model needs.
const REQUIRED_TAGS: [(i32, &str); 3] = [
    (tags::CONTACT, "contact"),
    (tags::FAR, "far"),
    (tags::AXIS, "axis"),
];

/// Read and validate the mesh file (its messages quote the file's tags), then apply its corner
/// refinement, validated again: the vertex mesh every degree of the model is raised from. Raising
/// the degree keeps a valid mesh valid (its added nodes lie at the fractions `k/p` of straight
/// edges; `raising_the_degree_keeps_a_mesh_valid` tests it), so the raised mesh is not checked
/// again.
fn read_vertex_mesh(provided: &ProvidedMesh, contact_start: f64) -> Result<(Mesh, PendingHash)> {
    let (raw, sha256) = read_msh_hashed(provided.path.as_path()).map_err(|e| {
        match (e, provided.origin) {
            // gmsh's files enter the cache whole (written under another name, then renamed), so
            // an unreadable one was damaged afterwards: say how to have it made again.
            (Error::InvalidMesh { path, message }, MeshOrigin::Cache) => Error::InvalidMesh {
                path,
                message: format!(
                    "{message}; this file is in the mesh cache, damaged since gmsh made it: \
                     delete it and the next run makes it again"
                ),
            },
            (e, _) => e,
        }
    })?;
    raw.validate(&REQUIRED_TAGS)?;
    raw.validate_geometry(contact_start)?;
    match &provided.corner_refinement {
        Some(refinement) => {
            let refined = refinement.apply(&raw)?;
            refined.validate(&REQUIRED_TAGS)?;
            Ok((refined, sha256))
        }
        None => Ok((raw, sha256)),
    }
}

/// Read the mesh of `provided` and assemble its model ([`assemble_model`]).
fn prepare(provided: &ProvidedMesh, spec: ModelSpec) -> Result<PreparedModel> {
    let start = Instant::now();
    let (vertex_mesh, hashing) = read_vertex_mesh(provided, spec.contact_start)?;
    // The file's hash ran beside the parse's last steps, the checks and any corner refinement;
    // the assembly has work for both cores, so it starts when the hash is done.
    let mesh_sha256 = hashing.finish();
    let read = start.elapsed().as_secs_f64();
    let mut model = assemble_model(vertex_mesh, mesh_sha256, provided, spec)?;
    model.timings.read += read;
    Ok(model)
}

/// What the raised mesh gives before any value is assembled: its domain radius `R` (the far
/// arc's largest `|x|`), the far arc's grading (largest edge over `R`), the far-field condition
/// ([`FarField::Boussinesq`]) and the stiffness pattern with it.
struct ModelPattern {
    domain_radius: f64,
    arc_grading: f64,
    far_field: Option<FarFieldCondition>,
    pattern: StiffnessPattern,
}

/// The raised mesh's [`ModelPattern`] under `far_field`.
fn model_pattern(mesh: &Mesh, far_field: FarField, material: &Lame) -> Result<ModelPattern> {
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
    let far_field = match far_field {
        FarField::Fixed => None,
        FarField::Boussinesq => Some(FarFieldCondition::new(mesh, material, domain_radius)),
    };
    let pattern = StiffnessPattern::of_model(mesh, far_field.as_ref())?;
    Ok(ModelPattern {
        domain_radius,
        arc_grading,
        far_field,
        pattern,
    })
}

/// Raise `vertex_mesh` to the spec's degree, assemble its stiffness `K = Σ_e K_e` and, with
/// [`FarField::Boussinesq`], slave the far arc to the point-force field.
fn assemble_model(
    vertex_mesh: Mesh,
    mesh_sha256: String,
    provided: &ProvidedMesh,
    spec: ModelSpec,
) -> Result<PreparedModel> {
    let ModelSpec {
        degree,
        poisson_ratio,
        far_field,
        linear_solver,
        ..
    } = spec;
    let start = Instant::now();
    let material = Lame::from_young_poisson(1.0 - poisson_ratio * poisson_ratio, poisson_ratio);
    let rule = stiffness_rule(degree);
    // On one core the degree is raised and the pattern built; on the other, beside them, the
    // node order, whose vertex graph and minimum-degree order need only the vertex mesh (it then
    // waits for the raised mesh, set before the pattern's work begins, so it never waits on work
    // queued behind it). A panic while raising is an error, and the order beside does not wait.
    let raised: OnceLock<Option<Mesh>> = OnceLock::new();
    let raise = || {
        raised.get_or_init(|| {
            std::panic::catch_unwind(AssertUnwindSafe(|| vertex_mesh.with_degree(degree))).ok()
        })
    };
    let raise_and_build_pattern = || -> Result<ModelPattern> {
        let mesh = raise()
            .as_ref()
            .ok_or_else(|| unraisable_mesh_error(provided, degree))?;
        model_pattern(mesh, far_field, &material)
    };
    let order_nodes = || {
        let start = Instant::now();
        let ordering = node_ordering_of_raised(&vertex_mesh, linear_solver, || {
            raised.wait().as_ref().unwrap_or(&vertex_mesh)
        });
        (ordering, start.elapsed().as_secs_f64())
    };
    let (built, (ordering, ordering_seconds)) = rayon::join(raise_and_build_pattern, order_nodes);
    let ModelPattern {
        domain_radius,
        arc_grading,
        far_field,
        pattern,
    } = built?;
    let mesh = raised
        .into_inner()
        .flatten()
        .ok_or_else(|| unraisable_mesh_error(provided, degree))?;
    // The symbolic analysis needs only the pattern: the values are assembled beside it.
    let analysis_start = Instant::now();
    let (symbolic, values) = analyse_beside(
        Pattern::new(pattern.col_offsets(), pattern.row_indices()),
        &ordering,
        linear_solver,
        || pattern.condensed_values(&mesh, &material, &rule),
    );
    let symbolic_seconds = ordering_seconds + analysis_start.elapsed().as_secs_f64();
    let (symbolic, (mut values, bubbles)) = (symbolic?, values?);
    if let Some(condition) = &far_field {
        condition.fill_extension(pattern.col_offsets(), pattern.row_indices(), &mut values);
    }
    let (stiffness, diagonal) = pattern.into_matrix_and_diagonal(values)?;
    let assembly = start.elapsed().as_secs_f64();
    Ok(PreparedModel {
        mesh,
        mesh_sha256,
        vertex_mesh,
        domain_radius,
        arc_grading,
        far_field,
        path: display_path(&provided.path),
        provided: provided.clone(),
        spec,
        stiffness,
        diagonal,
        bubbles,
        symbolic,
        timings: FemTimings {
            assembly,
            symbolic: symbolic_seconds,
            ..Default::default()
        },
    })
}

/// `path` relative to the data directory it lies in (`meshes/disk-L1.msh`), else whole.
fn display_path(path: &Path) -> String {
    match path.parent().map(DataPaths::find_from) {
        Some(Ok(data)) => data.display(path),
        _ => path.display().to_string(),
    }
}

/// The error of a mesh whose degree could not be raised (a panic while raising: not expected).
fn unraisable_mesh_error(provided: &ProvidedMesh, degree: Degree) -> Error {
    Error::InvalidMesh {
        path: display_path(&provided.path),
        message: format!(
            "internal: its degree could not be raised to {}",
            degree as usize
        ),
    }
}

/// What a coarser model tells the next one about a concave punch's free edge.
#[derive(Clone, Copy, Debug)]
struct WarmStart {
    /// Inner contact radius located on the coarser model.
    pub inner_radius: f64,
    /// Half-width of the band around it where the finer model's edge is expected: twice the
    /// coarser model's estimated error of the inner radius.
    pub band: f64,
    /// Outer contact radius located on the coarser model: a free edge (a free band), else
    /// infinite (the rim).
    pub outer_radius: f64,
}

/// Core of the banded contact solve: the contact nodes above the band are held in the
/// factorisation (none without a warm start).
fn core_radius(warm: Option<WarmStart>) -> f64 {
    warm.map_or(f64::INFINITY, |w| w.inner_radius + w.band)
}

/// Below this tolerance, solves take a step of iterative refinement
/// ([`ConstrainedCholesky::refine_solutions`]). Without it the force's rounding error was
/// 1e-14 to 2.4e-12 relative on the FEniCSx comparison's models (3e3 to 1.4e6 unknowns, the
/// force's change when the step is taken; both within 7e-11 of FEniCSx's LU), and at most
/// 4e-9 on the most graded 10^6-unknown models (against the ring BEM, earlier builds): 250 times
/// below this tolerance. The step costs a residual and a second triangular solve, 8-12 % of a
/// single-mesh flat solve at 6e4-9e4 unknowns.
const REFINE_BELOW_TOLERANCE: f64 = 1e-6;

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
    let (warm, depth_guess) = match warm {
        None if kind.is_concave() && kind.has_rim() && model.mesh.degree != Degree::Linear => {
            let start = Instant::now();
            let located =
                linear_edge_locator(model, kind.clone(), eps, load, depth_guess, tolerance);
            model.timings.edge_presolve = start.elapsed().as_secs_f64();
            match located {
                Some((warm, depth)) => (Some(warm), depth_guess.or(Some(depth))),
                None => (None, depth_guess),
            }
        }
        _ => (warm, depth_guess),
    };
    let mut solver = ConstrainedCholesky::with_symbolic_and_diagonal(
        &model.stiffness,
        model.symbolic.clone(),
        &model.diagonal,
    )?;
    solver.refine_solutions(tolerance < REFINE_BELOW_TOLERANCE);
    let start = Instant::now();
    let mut contact = ContactModel::new(&model.mesh, model.stiffness.nrows())?;
    if !kind.has_rim() {
        let frame = model.spec.frame;
        contact = contact.with_free_edges(frame);
        let initial = warm.map(|w| contact.active_set_between(w.inner_radius, w.outer_radius));
        let result = solve_free_edges_model(
            &contact,
            &mut solver,
            (kind, load),
            initial,
            depth_guess,
            frame,
            tolerance,
        );
        model.timings.solve = start.elapsed().as_secs_f64();
        model.timings.factorisations = solver.factorisations;
        model.timings.factorisation = solver.factorisation_seconds;
        return result;
    }
    if !kind.is_concave() {
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
            let mut system = contact.banded_system(&mut solver, kind.clone(), core_radius(warm));
            let s = contact.concave_with_sensitivity(&mut system, kind, depth, initial)?;
            model.timings.band_responses = system.responses_computed();
            let g2 = 0.5 * s.force;
            (s, depth, g2)
        }
        FemLoad::ConcaveForce(target) => {
            let initial = warm.map(|w| contact.active_set_for_radius(w.inner_radius));
            let mut system = contact.banded_system(&mut solver, kind.clone(), core_radius(warm));
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

/// A contact with two free edges on a model whose length unit is `frame a`
/// ([`ContactModel::with_free_edges`]): the depth `d/h` and the force `F/(2 E* h a)` of the
/// scene go in as `d / frame` and `F / frame²`, and the solution, depth and force come back in
/// units of `a` (`(s, γ1, γ2)` as [`solve_model`] returns them).
fn solve_free_edges_model(
    contact: &ContactModel,
    solver: &mut ConstrainedCholesky,
    (kind, load): (PunchKind, FemLoad),
    initial: Option<Vec<bool>>,
    depth_guess: Option<f64>,
    frame: f64,
    tolerance: f64,
) -> Result<(ContactSolution, f64, f64)> {
    let mut system = contact.banded_system(solver, kind.clone(), f64::INFINITY);
    let (s, depth) = match load {
        FemLoad::ConcaveDepth(depth) => {
            let s = contact.concave_with_sensitivity(&mut system, kind, depth / frame, initial)?;
            (s, depth)
        }
        FemLoad::ConcaveForce(target) => {
            let (s, depth) = contact.concave_at_force(
                &mut system,
                kind,
                2.0 * target / (frame * frame),
                depth_guess.unwrap_or(target) / frame,
                initial,
                tolerance,
            )?;
            (s, depth * frame)
        }
        FemLoad::Flat => {
            return Err(fem_error(
                "a flat-faced punch has a rim: it is not solved as a contact with two free edges"
                    .into(),
            ))
        }
    };
    let s = s.in_units_of_a(frame);
    let gamma2 = 0.5 * s.force;
    Ok((s, depth, gamma2))
}

/// Half-width of the band around the edge the linear locator found, in contact-node spacings
/// of the linear model there; a miss only costs the banded solve a factorisation per move
/// (docs/decisions.md, "Where the constants come from").
const LINEAR_LOCATOR_BAND_SPACINGS: f64 = 4.0;

/// Locate a concave punch's free edge on the linear model of the same mesh (its vertices only,
/// about a quarter of the quadratic model's unknowns and an eighth of its factorisation time),
/// for a cold start of a quadratic or cubic model: the FEM's own coarser solve, so the model
/// then needs about one factorisation instead of one per active-set change (3-13 of them cold).
/// Returns the warm start and the linear model's depth, or `None` when the linear model
/// cannot be solved (the model is then solved cold, as before).
fn linear_edge_locator(
    model: &PreparedModel,
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    depth_guess: Option<f64>,
    tolerance: f64,
) -> Option<(WarmStart, f64)> {
    let spec = ModelSpec {
        degree: Degree::Linear,
        ..model.spec
    };
    let vertex_mesh = model.vertex_mesh.clone();
    let mut linear = assemble_model(
        vertex_mesh,
        model.mesh_sha256.clone(),
        &model.provided,
        spec,
    )
    .ok()?;
    let (s, depth, _) =
        solve_model(&mut linear, kind, eps, load, None, depth_guess, tolerance).ok()?;
    if linear.spec.trace {
        trace_level(&linear, &s);
    }
    let spacing = full_contact_spacing(&s).unwrap_or(s.inner_node_spacing);
    let warm = WarmStart {
        inner_radius: s.inner_radius,
        band: LINEAR_LOCATOR_BAND_SPACINGS * spacing,
        outer_radius: f64::INFINITY,
    };
    Some((warm, depth))
}

impl PreparedModel {
    /// The displacement `(u_r, u_z)` of every node from the solution of the model's system: the
    /// far-field arc restored ([`FarFieldCondition::expand`]), then the condensed bubbles
    /// ([`BubbleRecovery::recover`]).
    fn nodal_field(&self, solution: Vec<f64>) -> Vec<f64> {
        let mut u = match &self.far_field {
            Some(condition) => condition.expand(&solution),
            None => solution,
        };
        if let Some(bubbles) = &self.bubbles {
            bubbles.recover(&self.mesh, &mut u);
        }
        u
    }

    /// Relative force bias of truncating the half-space at this model's `R` with its far-field
    /// treatment ([`FarField::truncation_bias`]).
    fn truncation_bias(&self) -> f64 {
        self.spec
            .far_field
            .truncation_bias(self.domain_radius, self.arc_grading)
    }

    /// Largest contact-line element at a singular edge: at the rim `r = a`, and for the fixed
    /// annulus also at `r = b` (units of `a`; from the vertex mesh, so the element's length).
    fn edge_element_size(&self) -> f64 {
        let start = self.spec.contact_start;
        let touches =
            |r: f64| (r - 1.0).abs() < 1e-12 || (start > 0.0 && (r - start).abs() < 1e-12);
        self.vertex_mesh
            .boundary
            .iter()
            .filter(|e| e.tag == tags::CONTACT)
            .filter_map(|e| {
                let (p, q) = (
                    self.vertex_mesh.nodes[e.nodes[0]],
                    self.vertex_mesh.nodes[e.nodes[1]],
                );
                (touches(p[0]) || touches(q[0])).then(|| (p[0] - q[0]).hypot(p[1] - q[1]))
            })
            .fold(0.0, f64::max)
    }

    /// Relative force error the elements at the singular edges leave, which the ladder's level
    /// changes do not see while the levels share their edge size:
    /// [`edge_error_coefficient`]` · h / w`, `h` the [`Self::edge_element_size`] and `w = 1 - b/a`
    /// the contact ring's width (both edges' singular fields scale with it).
    fn edge_component(&self, contact_ratio: f64) -> f64 {
        let width = (1.0 - contact_ratio).max(f64::MIN_POSITIVE);
        edge_error_coefficient(self.spec.degree) * self.edge_element_size() / width
    }
}

/// [`prepare`] with the options' degree, material and far field, then [`check_domain`].
/// The domain is checked against `domain_tolerance` (the options' tolerance for a model whose
/// result is returned; the edge locator's result never is).
fn prepare_checked(
    provided: &ProvidedMesh,
    options: &FemOptions,
    contact_start: f64,
    domain_tolerance: f64,
) -> Result<PreparedModel> {
    let spec = ModelSpec {
        degree: options.degree,
        poisson_ratio: options.poisson_ratio,
        far_field: options.far_field,
        contact_start,
        linear_solver: options.linear_solver,
        trace: options.trace,
        frame: 1.0,
    };
    let model = prepare(provided, spec)?;
    check_domain(&model, domain_tolerance)?;
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
    let edge_conditioning = gamma1
        .filter(|_| solution.conditioning.edge_depth_sensitivity != 0.0)
        .map(|depth| solution.conditioning.edge_depth_sensitivity.abs() * depth.abs());
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
            displacement: model.nodal_field(solution.displacement),
        },
        domain_radius: model.domain_radius,
        truncation_bias: model.truncation_bias(),
        far_field: model.spec.far_field,
        mesh_sha256: model.mesh_sha256.clone(),
        mesh_origin: model.provided.origin,
        gmsh_version: model.provided.gmsh_version.clone(),
        mesh_refinement: model
            .provided
            .corner_refinement
            .as_ref()
            .map(|r| r.describe()),
        timings: model.timings,
        edge_conditioning,
        linear_solver: model.spec.linear_solver,
        outer_edge: None,
    }
}

/// One line per model on standard error ([`FemOptions::trace`]): size, phase times, contact cost.
fn trace_level(model: &PreparedModel, solution: &ContactSolution) {
    let t = &model.timings;
    eprintln!(
        "fem: {} ({} unknowns, factorised {}): read {:.3} s, assembly {:.3} s (symbolic {:.3} s of it, alongside), contact {:.3} s \
         ({} factorisations {:.3} s, {} band responses, {} iterations), b/a = {:.10} (node spacing \
         there {:.2e}, db/dd {:.3e}, opening margin {:.2e}, at the axis above {:.2e}), force {:.12}",
        model.path,
        model.stiffness.nrows(),
        model.symbolic.describe(),
        t.read,
        t.assembly,
        t.symbolic,
        t.solve,
        t.factorisations,
        t.factorisation,
        t.band_responses,
        solution.iterations,
        solution.inner_radius,
        solution.inner_node_spacing,
        solution.conditioning.edge_depth_sensitivity,
        solution.conditioning.opening_margin,
        solution.conditioning.closure_margin,
        solution.force
    );
}

/// Below this tolerance, cubic elements are the default (`--degree` not given): on the adapted
/// family their force error falls like `g⁶` against `g⁴` for quadratic ones.
const CUBIC_BELOW_TOLERANCE: f64 = 1e-4;

/// Element degree when none is asked for: cubic on meshes made for the scene (gmsh found, or a
/// tolerance below [`CUBIC_BELOW_TOLERANCE`]); quadratic on the committed ladder, whose levels
/// were made for it.
pub fn default_degree(data: &DataPaths, tolerance: f64) -> Degree {
    if tolerance < CUBIC_BELOW_TOLERANCE || provider::gmsh_available(data) {
        Degree::Cubic
    } else {
        Degree::Quadratic
    }
}

/// Share of the edge's conditioning times the model's force error that bounds the located
/// edge's error from the displacement field (`EDGE_FIELD_FRACTION · κ · ε`, `κ = |db/dd| d`
/// from [`ContactModel::edge_depth_sensitivity`], `ε` the force estimate with its floor): in depth
/// control the contact ring's displacements are exact, so a field error moves the edge by less
/// than the `κ ε` of a depth error (docs/decisions.md, "Where the constants come from").
const EDGE_FIELD_FRACTION: f64 = 0.5;

/// The whole shift `κ ε` of a field error that acted as a depth error, with a margin for `κ`'s
/// own error, taken instead of [`EDGE_FIELD_FRACTION`] under a prescribed force and outside the
/// asymptotic range ([`below_known_order`]) (docs/decisions.md, "Where the constants come from").
const EDGE_FIELD_FRACTION_WHOLE: f64 = 1.5;

/// Safety factor on the Richardson estimate between two grading levels (Roache's `F_s = 3` for
/// two grids).
const RICHARDSON_SAFETY: f64 = 3.0;

/// Largest model after which the ladder still climbs: the next level has about 2.7 times as many
/// unknowns, so no model beyond about 2 M unknowns is made (P3 at 4e6 needs about 10 GB and half
/// a minute per factorisation here).
const MAX_LADDER_UNKNOWNS: usize = 750_000;

/// Most refinements of one adapted level around the free edge before the next level.
const MAX_EDGE_REPEATS: usize = 2;

/// Force error of the finer of two consecutive adapted levels per unit change between them:
/// the force converges like `g^{2p}` asymptotically, but the coarse levels converge more slowly,
/// so the order taken is `2p - 1`: the finer error is `|ΔF| / (0.6^{1-2p} - 1)`, times
/// [`RICHARDSON_SAFETY`] (docs/decisions.md, "Where the constants come from").
fn richardson_factor(degree: Degree) -> f64 {
    RICHARDSON_SAFETY / (known_order_ratio(degree) - 1.0)
}

/// Smallest ratio of consecutive grading steps' force changes that [`grading_step_estimate`]
/// divides by: a ratio nearer 1 (changes that do not shrink) is taken as this one, an estimate
/// of twice the change times [`RICHARDSON_SAFETY`].
const MIN_OBSERVED_RATIO: f64 = 1.5;

/// Force error of the finer model of a grading step whose force changed by `change`, the step
/// before having changed it by `previous_change`: Richardson with the known order
/// ([`richardson_factor`], a ratio of `0.6^{1-2p}` per level), or with the observed ratio
/// `previous_change / change` where that is smaller (docs/methods.md: a result outside the
/// asymptotic range converges more slowly than its order says).
fn grading_step_estimate(degree: Degree, change: f64, previous_change: Option<f64>) -> f64 {
    let assumed = known_order_ratio(degree);
    let ratio = observed_ratio(change, previous_change).map_or(assumed, |r| r.min(assumed));
    RICHARDSON_SAFETY * change / (ratio.max(MIN_OBSERVED_RATIO) - 1.0)
}

/// The ratio of consecutive grading steps' force changes that the known order gives,
/// `0.6^{1-2p}` ([`richardson_factor`]).
fn known_order_ratio(degree: Degree) -> f64 {
    0.6f64.powi(1 - 2 * degree as i32)
}

/// `previous_change / change`, where both changes are known and positive.
fn observed_ratio(change: f64, previous_change: Option<f64>) -> Option<f64> {
    previous_change
        .filter(|&previous| previous > 0.0 && change > 0.0)
        .map(|previous| previous / change)
}

/// Whether a grading step whose force changed by `change`, after a step that changed it by
/// `previous_change`, converged more slowly than the known order says (the observed ratio is the
/// one [`grading_step_estimate`] used): the model is outside the asymptotic range.
fn below_known_order(degree: Degree, change: f64, previous_change: Option<f64>) -> bool {
    observed_ratio(change, previous_change).is_some_and(|r| r < known_order_ratio(degree))
}

/// Predicted relative force error of adapted level `k` at degree `p`: `C_p 0.6^{2pk}` with
/// `C_1 = 1e-2`, `C_2 = 3.3e-4`, `C_3 = 3.3e-6` (fitted on the fixed annulus 0.3 and the linear gap
/// at `d = 2h`, level 0).
fn predicted_force_error(degree: Degree, level: i32) -> f64 {
    let base = match degree {
        Degree::Linear => 1e-2,
        Degree::Quadratic => 3.3e-4,
        Degree::Cubic => 3.3e-6,
    };
    base * 0.6f64.powi(2 * degree as i32 * level)
}

/// First adapted level climbed without committed meshes: the lowest `k` whose step to `k + 1` is
/// predicted to meet the tolerance (`richardson_factor · error(k) <= tol`).
fn first_adapted_level(degree: Degree, tolerance: f64) -> i32 {
    (provider::ADAPTED_MIN_LEVEL..provider::ADAPTED_MAX_LEVEL)
        .find(|&k| richardson_factor(degree) * predicted_force_error(degree, k) <= tolerance)
        .unwrap_or(provider::ADAPTED_MAX_LEVEL - 1)
}

/// The committed levels climbed first: L0-L2 of the family for this contact line, when there is
/// one, the tolerance is at least [`COMMITTED_TOLERANCE_FLOOR`] and gmsh is not there to make
/// meshes for the scene (which are smaller for the same accuracy); else none.
fn committed_ladder(
    data: &DataPaths,
    kind: PunchKind,
    eps: f64,
    tolerance: f64,
) -> Vec<MeshRequest> {
    if tolerance < COMMITTED_TOLERANCE_FLOOR || provider::gmsh_available(data) {
        return Vec::new();
    }
    let Some(family) = provider::committed_family(data, contact_start(&kind, eps)) else {
        return Vec::new();
    };
    (0..=provider::COMMITTED_MAX_LEVEL)
        .map(|level| MeshRequest::Committed {
            family: family.clone(),
            level,
        })
        .collect()
}

/// A concave punch's first model when no committed ladder is climbed: the committed level 0
/// of its contact line (a few thousand unknowns), which locates the free edge for the first
/// adapted mesh to refine around. Its force, whose error is dominated by the unrefined edge, does
/// not enter a Richardson estimate.
fn edge_locator(data: &DataPaths, kind: PunchKind, eps: f64) -> Vec<MeshRequest> {
    provider::committed_family(data, contact_start(&kind, eps))
        .map(|family| MeshRequest::Committed { family, level: 0 })
        .into_iter()
        .collect()
}

/// The outputs one model gives: the force-like output (`γ` for a flat-faced punch, `γ1` for a
/// concave one), `γ2` (concave punches; NaN otherwise) and the located `eps`.
#[derive(Clone, Copy, Debug)]
struct LevelValues {
    primary: f64,
    gamma2: f64,
    eps: f64,
}

/// What a concave punch's model found at the axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AxisContact {
    /// A hole (or a flat-faced punch): the edge is where the contact line's nodes say.
    Open,
    /// Full contact: the located edge `0` is known only to within the first contact node off
    /// the axis (`spacing`), the whole of which bounds its error.
    Full,
    /// Full contact of a profile with a kink at the axis (the linear gap, whose hole never closes)
    /// that its margins do not show closed beyond the model's error: a hole hides inside the
    /// first node off the axis (`spacing`), or just beyond it; the next mesh refines inside it.
    HoleInsideFirstNode,
}

/// What one model of the ladder found, for the next one's estimate and mesh.
struct LevelResult {
    values: LevelValues,
    /// Contact-node spacing at the located free edge.
    spacing: f64,
    /// Estimated error of the located free edge.
    eps_error: f64,
    /// Adapted level, `None` for a committed mesh.
    level: Option<i32>,
    /// Only locates the free edge for the next mesh ([`edge_locator`]): no estimate against it.
    locator: bool,
    axis: AxisContact,
    /// Bound on the located edge's error as a multiple of `spacing` ([`INNER_RADIUS_BOUND`], or
    /// more when the hole holds too few nodes to extrapolate from).
    edge_bound: f64,
}

impl LevelResult {
    /// Full contact weighed against the model's error taken as a relative depth error
    /// (`depth_error`), with the margin by which the contact would still close
    /// (`closure_margin`).
    fn settle_axis(&mut self, kind: PunchKind, closure_margin: f64, depth_error: f64) {
        // Full contact, its margins against the model's error taken as a relative depth error:
        // a profile smooth at the axis whose contact would open only beyond that error is closed
        // (`eps = 0` exactly, no hole to bound by the first node's radius); full contact that the
        // error could open (the innermost node off the axis releases within it) leaves whether a
        // hole is open, and how wide, below this model: only finer levels tell.
        if self.axis == AxisContact::Full
            && kind.profile_smooth_at_axis()
            && closure_margin > depth_error
        {
            self.axis = AxisContact::Open;
            self.eps_error = 0.0;
        }
        // A profile with a kink at the axis never closes: its full contact, unless its margin
        // extrapolated to the axis stays beyond the model's error, hides a hole at its first
        // node, and the model's error at the apex can hide one a little wider (the linear gap at 12
        // h: a hole of 9e-4 a under first nodes at 7.5e-4 a, whose margins fell toward the axis):
        // two first-node radii bound it, and the next mesh refines inside.
        if self.axis == AxisContact::Full
            && !kind.profile_smooth_at_axis()
            && closure_margin <= depth_error
        {
            self.axis = AxisContact::HoleInsideFirstNode;
            self.eps_error = self.eps_error.max(2.0 * self.spacing);
        }
    }

    /// Largest relative change of the force-like outputs from `previous`.
    fn force_change(&self, previous: &LevelResult) -> f64 {
        let relative = |a: f64, b: f64| {
            if a.is_nan() {
                0.0
            } else {
                (a - b).abs() / a.abs()
            }
        };
        relative(self.values.primary, previous.values.primary)
            .max(relative(self.values.gamma2, previous.values.gamma2))
    }

    /// Error of the located inner radius: first order in the node spacing there, which shrank by
    /// `q` from `previous`, so about `|Δeps| / (q - 1)` (Richardson), never below
    /// [`INNER_RADIUS_BOUND`] of the spacing.
    fn eps_estimate(&self, previous: &LevelResult) -> f64 {
        let eps_change = self.values.eps - previous.values.eps;
        free_edges::edge_error(eps_change, previous.spacing, self.spacing)
            .max(self.edge_bound * self.spacing)
    }
}

/// The state `(eps, γ, γ1, γ2)` of a solved model: the flat punches' `γ = x` at their fixed
/// `eps`; the concave punches' located inner radius with `γ1 = x`, `γ2 = y`.
fn state_of(
    load: FemLoad,
    eps: f64,
    s: &ContactSolution,
    x: f64,
    y: f64,
) -> (f64, Option<f64>, Option<f64>, Option<f64>) {
    match load {
        FemLoad::Flat => (eps, Some(x), None, None),
        _ => (s.inner_radius, None, Some(x), Some(y)),
    }
}

/// Every contact node off the axis in contact, the axis node in contact or not: a hole, if any,
/// lies inside the first node off the axis, whose radius is returned (the located edge's
/// uncertainty); else `None`. A free axis node alone bounds the hole by that radius too (its
/// own spacing to the axis is no bound: P2 returned `eps = 0` with an estimate of 2.3e-4 for
/// holes 6e-3 and 1.9e-2 a wide, the parabolic gap at `d = 2.9999h` and `2.999h`).
fn full_contact_spacing(s: &ContactSolution) -> Option<f64> {
    let on_axis = |&(r, _): &(f64, f64)| r == 0.0;
    let axis_free_alone =
        s.reactions.first().is_some_and(on_axis) && s.active_radii.len() + 1 == s.reactions.len();
    let first_off_axis = s.active_radii.iter().copied().find(|&r| r > 0.0);
    (s.active_radii.first() == Some(&0.0) || axis_free_alone).then(|| first_off_axis.unwrap_or(1.0))
}

/// A concave punch whose contact ring holds no contact node but the rim's: the ring is narrower
/// than the model's last contact-node spacing, so the located edge (`b/a = 1`) and the force are
/// not resolved, however small the change between models. Declined with the spacing, instead of
/// returning the rim as the edge.
fn rim_resolves_the_ring(
    model: &PreparedModel,
    kind: PunchKind,
    s: &ContactSolution,
) -> Result<()> {
    if !kind.is_concave() || s.active_radii.len() > 1 {
        return Ok(());
    }
    // The spacing between the rim and the last free node.
    let spacing = s.inner_node_spacing;
    Err(Error::OutOfRange {
        method: METHOD.into(),
        reason: format!(
            "only the rim node of {} is in contact: the contact ring is narrower than the \
             contact-node spacing at the rim ({} a), below what the model resolves (the ring BEM \
             declines rings narrower than 1e-4 a); press deeper or use a mesh refined at r = a",
            model.path,
            crate::error::show(spacing)
        ),
    })
}

/// Solve on one provided mesh (`--mesh`, or a level the convergence study picked), with no
/// error estimate: the mesh's corner refinement, if any, is applied as in the ladder.
pub fn solve_on_mesh(
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    provided: &ProvidedMesh,
    options: &FemOptions,
) -> Result<FemState> {
    let start = Instant::now();
    let mut model = prepare_checked(
        provided,
        options,
        contact_start(&kind, eps),
        options.tolerance,
    )?;
    let (s, x, y) = solve_model(
        &mut model,
        kind.clone(),
        eps,
        load,
        None,
        None,
        options.tolerance,
    )?;
    if model.spec.trace {
        trace_level(&model, &s);
    }
    rim_resolves_the_ring(&model, kind, &s)?;
    let state = state_of(load, eps, &s, x, y);
    let iterations = s.iterations;
    Ok(finish(
        &model,
        s,
        state,
        None,
        iterations,
        options.degree,
        start,
    ))
}

/// One model of the ladder of a punch with two free edges (a free band) on its own, for a
/// mesh-convergence study: level `level` of the free-edges mesh family, refined around `edges`
/// (`(radius, uncertainty)` in units of `a`; `None`: where the rigid profile meets the
/// surface). The state has no error estimate; its outer edge is in `outer_edge`.
pub fn solve_free_edges_on_level(
    kind: PunchKind,
    load: FemLoad,
    level: i32,
    edges: Option<[(f64, f64); 2]>,
    options: &FemOptions,
) -> Result<FemState> {
    check_tolerance(options.tolerance)?;
    if kind.has_rim() {
        return Err(fem_error(format!(
            "the {kind} has a rim: its levels are the adapted family's (`solve_on_mesh`)"
        )));
    }
    free_edges::solve_on_level(kind, load, level, edges, options)
}

/// Solve a punch problem with the FEM: a free band on its own ladder, a given mesh once, else
/// the mesh ladder (`ladder::climb`) until a model's estimate meets the tolerance.
pub fn solve(kind: PunchKind, eps: f64, load: FemLoad, options: &FemOptions) -> Result<FemState> {
    let start = Instant::now();
    check_tolerance(options.tolerance)?;
    if !kind.has_rim() {
        return free_edges::solve(kind, load, options);
    }
    if let Some(path) = &options.mesh {
        // The solution's hash is that of the bytes the solve reads (`PreparedModel::mesh_sha256`),
        // computed beside the parse; a user's mesh is not hashed beforehand.
        let provided = ProvidedMesh {
            path: path.clone(),
            origin: MeshOrigin::User,
            gmsh_version: None,
            corner_refinement: None,
        };
        return solve_on_mesh(kind, eps, load, &provided, options);
    }
    // The mesh families live in the project's data directory: say so if it cannot be found.
    options.data.check()?;
    ladder::climb(ladder::Problem { kind, eps, load }, options, start)
}

/// The FEM's tolerance must be at least [`MIN_TOLERANCE`].
fn check_tolerance(tolerance: f64) -> Result<()> {
    if tolerance.is_nan() || tolerance < MIN_TOLERANCE {
        return Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "tolerance {tolerance:e} is below the FEM's floor {MIN_TOLERANCE:e} (the smallest \
                 at which its error estimate was shown to bound its error); use the ring BEM for \
                 tighter tolerances"
            ),
        });
    }
    Ok(())
}

/// The FE model of `provided` (degree, far field and Poisson's ratio of `options`) condensed onto
/// its contact line, which starts at `contact_start = b/a` (see
/// [`crate::fem::surface_response::condense`]); with the mesh's display path.
pub fn surface_response_on_mesh(
    provided: &ProvidedMesh,
    options: &FemOptions,
    contact_start: f64,
) -> Result<(crate::fem::surface_response::SurfaceResponse, String)> {
    let model = prepare_checked(provided, options, contact_start, options.tolerance)?;
    let mut solver = ConstrainedCholesky::with_symbolic_and_diagonal(
        &model.stiffness,
        model.symbolic.clone(),
        &model.diagonal,
    )?;
    let contact = ContactModel::new(&model.mesh, model.stiffness.nrows())?;
    let start_line = contact.contact_line_start();
    if (start_line - contact_start).abs() > 1e-9 {
        return Err(Error::InvalidMesh {
            path: model.path.clone(),
            message: format!(
                "its contact line starts at r/a = {}, the scene needs b/a = {}",
                crate::error::show(start_line),
                crate::error::show(contact_start)
            ),
        });
    }
    let supports = contact.supports().to_vec();
    let response = crate::fem::surface_response::condense(&contact, &mut solver, &supports)?;
    Ok((response, model.path.clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grading_step_takes_the_lower_of_the_known_and_the_observed_ratio() {
        // docs/methods.md's Richardson estimate of the finer model, F_s |ΔF| / (q^p - 1), with
        // q^p the ratio of the two steps' changes where it is below 0.6^{1-2p}.
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-13;
        let change = 1.9e-4;
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let known = richardson_factor(degree) * change;
            assert!(close(grading_step_estimate(degree, change, None), known));
            // Converging faster than the order says: the known order's (smaller ratio) estimate.
            let faster = grading_step_estimate(degree, change, Some(100.0 * change));
            assert!(close(faster, known), "{degree:?}");
        }
        // The parabolic gap at 2.9998 h, P3: changes 1.6e-3 then 1.9e-4, a ratio of 8.5 (not 12.9).
        let observed = grading_step_estimate(Degree::Cubic, change, Some(1.6e-3));
        assert!(close(
            observed,
            RICHARDSON_SAFETY * change / (1.6e-3 / change - 1.0)
        ));
        assert!(observed > 1.5 * richardson_factor(Degree::Cubic) * change);
        // Changes that do not shrink: the ratio is taken as MIN_OBSERVED_RATIO, never below.
        let stalled = grading_step_estimate(Degree::Cubic, change, Some(change));
        assert!(close(
            stalled,
            RICHARDSON_SAFETY * change / (MIN_OBSERVED_RATIO - 1.0)
        ));
        assert_eq!(grading_step_estimate(Degree::Cubic, 0.0, Some(1e-3)), 0.0);
    }

    #[test]
    fn a_step_slower_than_the_known_order_is_pre_asymptotic() {
        // The known order's ratio per level is 0.6^{1-2p}: 1.67 (P1), 4.63 (P2), 12.86 (P3).
        let change = 1.9e-4;
        for (degree, known) in [
            (Degree::Linear, 1.0 / 0.6),
            (Degree::Quadratic, 0.6f64.powi(-3)),
            (Degree::Cubic, 0.6f64.powi(-5)),
        ] {
            assert!(!below_known_order(degree, change, None), "{degree:?}");
            assert!(!below_known_order(
                degree,
                change,
                Some(1.01 * known * change)
            ));
            assert!(below_known_order(
                degree,
                change,
                Some(0.99 * known * change)
            ));
        }
        // The parabolic gap at 2.9998 h, P3: a ratio of 8.5.
        assert!(below_known_order(Degree::Cubic, change, Some(1.6e-3)));
        // No change to compare with: not judged.
        assert!(!below_known_order(Degree::Cubic, 0.0, Some(1.6e-3)));
        assert!(!below_known_order(Degree::Cubic, change, Some(0.0)));
    }
}
