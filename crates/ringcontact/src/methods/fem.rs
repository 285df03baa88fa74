//! The axisymmetric finite-element method as a [`Solver`]: P1/P2/P3 triangles on committed or
//! gmsh-made meshes, unilateral contact by a primal-dual active set, the mesh ladder's estimate.

use std::path::PathBuf;

use super::ladder::{Ladder, LocatedEdges, Rung, StudyCase};
use super::units::base;
use super::Solver;
use crate::discretisation::far_field::FarField;
use crate::error::{Error, Result};
pub use crate::fem::solver::FemState;
use crate::fem::solver::{self as fem_solver, FemLoad, FemOptions};
use crate::heartbeat::Progress;
use crate::mesh::files::DataPaths;
use crate::mesh::provider::{self, MeshRequest};
use crate::mesh::triangulation::Degree;
use crate::scene::{Load, Scene};
use crate::solution::{FemProvenance, Solution};
use crate::sparse::Backend;

/// The FEM and its own options; the default climbs the mesh ladder to the scene's tolerance.
#[derive(Clone, Debug, Default)]
pub struct Fem {
    /// A mesh file instead of the committed family (a single mesh: no error estimate).
    pub mesh: Option<PathBuf>,
    /// Element degree (default: by tolerance, quadratic on a given mesh).
    pub degree: Option<Degree>,
    /// The condition on the far arc (default [`FarField::Boussinesq`]).
    pub far_field: Option<FarField>,
    /// Write the final displacement field as VTK (`.vtu`) here.
    pub vtu: Option<PathBuf>,
    /// The sparse Cholesky that factorises (default [`Backend::BUILT_IN`]).
    pub linear_solver: Option<Backend>,
    /// One line per model on standard error ([`FemOptions::trace`]).
    pub trace: bool,
    /// Where the meshes and gmsh are (default: the checkout found from the current directory).
    pub data: Option<DataPaths>,
    /// How often a long ladder reports on standard error.
    pub progress: Progress,
}

/// Finest adapted mesh level a FEM convergence study runs with quadratic elements (about 1.7 M
/// unknowns).
const STUDY_MAX_ADAPTED_LEVEL: usize = 5;
/// Finest adapted level with cubic elements (level 3: about 0.6 M unknowns, force error near
/// 2e-9).
const STUDY_MAX_CUBIC_LEVEL: i32 = 3;

impl Fem {
    /// The smallest tolerance the FEM takes ([`fem_solver::MIN_TOLERANCE`]).
    pub const MIN_TOLERANCE: f64 = fem_solver::MIN_TOLERANCE;

    /// The FEM's full answer at `scene` (its fields, reactions, active set, timings): what
    /// [`Solver::solve`] reports, before it becomes a [`Solution`].
    pub fn state(&self, scene: &Scene) -> Result<FemState> {
        fem_state(scene, self)
    }

    /// The options of a study's levels: this FEM's backend, trace, data and progress, elements
    /// of `degree`, `ν = 0`, Boussinesq's far field, the solve's own tolerance 1e-3 (each level
    /// is one model, its estimate unused).
    fn study_options(&self, degree: Degree) -> FemOptions {
        FemOptions {
            linear_solver: self.linear_solver.unwrap_or_default(),
            trace: self.trace,
            data: self.data.clone().unwrap_or_default(),
            progress: self.progress,
            degree,
            tolerance: 1e-3,
            mesh: None,
            poisson_ratio: 0.0,
            far_field: FarField::Boussinesq,
        }
    }

    /// The study's meshes and degree for a punch with a rim: with gmsh, the adapted family from
    /// its coarsest level (`g = 0.89`) with cubic elements (errors from about 5e-4 down to a
    /// few 1e-9 in six levels); without, the committed levels with quadratic elements.
    fn study_ladder(&self, case: &StudyCase) -> (Vec<MeshRequest>, Degree) {
        let data = self.data.clone().unwrap_or_default();
        if provider::gmsh_available(&data) {
            let start = fem_solver::contact_start(&case.punch, case.eps);
            let ladder = (provider::ADAPTED_MIN_LEVEL..=STUDY_MAX_CUBIC_LEVEL)
                .map(|level| MeshRequest::Adapted {
                    contact_start: start,
                    level,
                    free_edge: None,
                    edge_uncertainty: 0.0,
                    target: None,
                })
                .collect();
            return (ladder, Degree::Cubic);
        }
        let ladder = fem_solver::mesh_sequence(&data, case.punch.clone(), case.eps, 1e-3)
            .into_iter()
            .filter(|r| match r {
                MeshRequest::Adapted { level, .. } => *level <= STUDY_MAX_ADAPTED_LEVEL as i32,
                _ => true,
            })
            .collect();
        (ladder, Degree::Quadratic)
    }

    /// Level `k` of the study ladder of a punch with a rim, refined around `previous_edge`
    /// (concave punches).
    fn rim_level(&self, case: &StudyCase, k: usize, previous_edge: Option<f64>) -> Result<Rung> {
        let concave = case.punch.is_concave();
        let (sequence, degree) = self.study_ladder(case);
        let Some(request) = sequence.get(k).cloned() else {
            return Err(Error::OutOfRange {
                method: "fem".into(),
                reason: format!("the FEM has {} mesh levels", sequence.len()),
            });
        };
        // Concave punches: refine around the free edge of the previous level's solve.
        let request = request.with_free_edge(previous_edge, 0.0);
        let label = request.label();
        let options = self.study_options(degree);
        let provided = provider::provide(&options.data, &request, "the FEM convergence study")?;
        let load = if concave {
            FemLoad::ConcaveDepth(case.depth)
        } else {
            FemLoad::Flat
        };
        let s = fem_solver::solve_on_mesh(case.punch.clone(), case.eps, load, &provided, &options)?;
        let value = s.gamma.or(s.gamma2).unwrap_or(f64::NAN);
        Ok(Rung {
            label: format!("{label} P{}", degree as u8),
            size: 1.0 / (s.dofs as f64).sqrt(),
            unknowns: s.dofs,
            value,
            free_edge: concave.then_some(s.eps),
            outer_edge: None,
        })
    }

    /// Level `k` of the free-edges family (a free band, quadratic elements): the first level
    /// refined where the rigid profile meets the surface, each further one around both edges
    /// the level below located.
    fn band_level(&self, case: &StudyCase, k: usize, located: LocatedEdges) -> Result<Rung> {
        let levels = free_edges_study_levels();
        let Some(&level) = levels.get(k) else {
            return Err(Error::OutOfRange {
                method: "fem".into(),
                reason: format!(
                    "the FEM has {} mesh levels for the {}",
                    levels.len(),
                    case.punch
                ),
            });
        };
        let edges = match (located.inner, located.outer) {
            (Some(inner), Some(outer)) => Some([(inner, 0.0), (outer, 0.0)]),
            _ => None,
        };
        let options = self.study_options(Degree::Quadratic);
        let load = FemLoad::ConcaveDepth(case.depth);
        let s = fem_solver::solve_free_edges_on_level(
            case.punch.clone(),
            load,
            level,
            edges,
            &options,
        )?;
        Ok(Rung {
            label: format!("free-edges-L{level} P2"),
            size: 1.0 / (s.dofs as f64).sqrt(),
            unknowns: s.dofs,
            value: s.gamma2.unwrap_or(f64::NAN),
            free_edge: Some(s.eps),
            outer_edge: s.outer_edge,
        })
    }
}

/// The study's mesh levels for a punch with two free edges (a free band): the free-edges family
/// from its coarsest level to [`STUDY_MAX_ADAPTED_LEVEL`], quadratic elements (gmsh needed:
/// the contact line is scaled to the load).
fn free_edges_study_levels() -> Vec<i32> {
    (provider::ADAPTED_MIN_LEVEL..=STUDY_MAX_ADAPTED_LEVEL as i32).collect()
}

/// The FEM's ladder: the committed or adapted meshes of a punch with a rim, the free-edges family
/// of a free band, each level refined around the edges the level below located.
impl Ladder for Fem {
    fn check_levels(&self, case: &StudyCase, levels: usize) -> Result<()> {
        // Levels past adapted level 5 (P2, about 1.7 M unknowns) or 3 (P3, 0.6 M) take more
        // than minutes and tens of GB; the study stops there.
        let available = if case.punch.has_rim() {
            self.study_ladder(case).0.len()
        } else {
            free_edges_study_levels().len()
        };
        if levels > available {
            return Err(Error::OutOfRange {
                method: "fem".into(),
                reason: format!(
                    "the FEM study has {available} mesh levels here (up to adapted level \
                     {STUDY_MAX_ADAPTED_LEVEL} with P2, about 1.7 M unknowns, or \
                     {STUDY_MAX_CUBIC_LEVEL} with P3, 0.6 M); asked for {levels}"
                ),
            });
        }
        Ok(())
    }

    fn level(&self, case: &StudyCase, k: usize, located: LocatedEdges) -> Result<Rung> {
        if case.punch.has_rim() {
            self.rim_level(case, k, located.inner)
        } else {
            self.band_level(case, k, located)
        }
    }

    fn refines_around_located_edges(&self, case: &StudyCase) -> bool {
        case.punch.is_concave()
    }

    fn expected_order(&self, case: &StudyCase) -> Option<f64> {
        let degree = if case.punch.has_rim() {
            self.study_ladder(case).1
        } else {
            Degree::Quadratic
        };
        Some(2.0 * degree as u8 as f64)
    }

    fn error_floor(&self) -> Option<f64> {
        Some(fem_solver::UNRESOLVED_COMPONENT)
    }
}

impl Solver for Fem {
    fn name(&self) -> &'static str {
        fem_solver::METHOD
    }

    fn compute(&self, scene: &Scene) -> Result<Solution> {
        solve_fem(scene, self)
    }
}

/// The FEM's state at `scene` with `options`.
fn fem_state(scene: &Scene, options: &Fem) -> Result<FemState> {
    let kind = scene.punch.kind.clone();
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let h = scene.punch.hole_depth;
    let load = match (kind.is_concave(), scene.load) {
        (false, _) => FemLoad::Flat,
        (_, Load::Depth(d)) => FemLoad::ConcaveDepth(d / h),
        (_, Load::Force(f)) => FemLoad::ConcaveForce(f / (2.0 * es * h * a)),
        (_, Load::ContactRatio(_)) => {
            return Err(Error::Unsupported {
                method: fem_solver::METHOD.into(),
                reason:
                    "the FEM takes a depth or a force; the contact ratio is one of its outputs \
                         (use --depth or --force, or the ring BEM for --eps)"
                        .into(),
            })
        }
    };
    let tolerance = scene.tolerance.unwrap_or(fem_solver::DEFAULT_TOLERANCE);
    let data = options.data.clone().unwrap_or_default();
    let fem_options = FemOptions {
        linear_solver: options.linear_solver.unwrap_or_default(),
        trace: options.trace,
        // A given mesh keeps the quadratic default; the ladder picks by tolerance.
        degree: options.degree.unwrap_or(if options.mesh.is_some() {
            Degree::Quadratic
        } else {
            fem_solver::default_degree(&data, tolerance)
        }),
        tolerance,
        mesh: options.mesh.clone(),
        poisson_ratio: scene.material.poisson_ratio.unwrap_or(0.0),
        far_field: options.far_field.unwrap_or(FarField::Boussinesq),
        data,
        progress: options.progress,
    };
    fem_solver::solve(kind, scene.punch.inner_ratio(), load, &fem_options)
}

/// Solve with the finite-element method.
fn solve_fem(scene: &Scene, options: &Fem) -> Result<Solution> {
    let kind = scene.punch.kind.clone();
    let a = scene.punch.rim_radius;
    let state = fem_state(scene, options)?;
    let outer_radius = state.outer_edge.map_or(a, |c| c * a);
    if let Some(path) = &options.vtu {
        crate::discretisation::vtu::write_vtu(path, &state.field.mesh, &state.field.displacement)?;
    }
    Ok(Solution {
        outer_radius,
        error_estimate: state.error_estimate,
        unknowns: state.dofs,
        iterations: state.iterations,
        fem: Some(FemProvenance {
            dofs: state.dofs,
            mesh: state.mesh.clone(),
            mesh_sha256: state.mesh_sha256.clone(),
            mesh_origin: state.mesh_origin,
            gmsh_version: state.gmsh_version.clone(),
            mesh_refinement: state.mesh_refinement.clone(),
            far_field: state.far_field,
            fem_timings: state.timings,
            degree: state.degree as u8,
            edge_conditioning: state.edge_conditioning,
        }),
        complementarity_residual: kind.is_concave().then_some(state.complementarity_residual),
        provenance: format!(
            "axisymmetric FEM, P{} triangles, {} dofs on {} ({}{}, sha256 {}){}, domain radius {:.3e} a with {} far field \
             (truncation bias {:.1e} included in the estimate){}",
            state.degree as u8,
            state.dofs,
            state.mesh,
            serde_json::to_value(state.mesh_origin)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default(),
            state
                .gmsh_version
                .as_ref()
                .map(|v| format!(" by gmsh {v}"))
                .unwrap_or_default(),
            &state.mesh_sha256[..16.min(state.mesh_sha256.len())],
            state
                .mesh_refinement
                .as_ref()
                .map(|r| format!(" {r}"))
                .unwrap_or_default(),
            state.domain_radius,
            state.far_field.describe(),
            state.truncation_bias,
            if state.error_estimate.is_some() {
                ", estimate from the previous refinement level"
            } else {
                ", single mesh: no error estimate"
            }
        ),
        ..base(
            scene,
            fem_solver::METHOD,
            state.eps,
            (state.gamma, state.gamma1, state.gamma2),
            state.wall_s,
        )?
    })
}
