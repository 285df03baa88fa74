//! The axisymmetric finite-element method as a [`Solver`]: P1/P2/P3 triangles on committed or
//! gmsh-made meshes, unilateral contact by a primal-dual active set, the mesh ladder's estimate.

use std::path::PathBuf;

use super::units::base;
use super::Solver;
use crate::discretisation::far_field::FarField;
use crate::error::{Error, Result};
use crate::fem::solver::{self as fem_solver, FemLoad, FemOptions};
use crate::heartbeat::Progress;
use crate::mesh::files::DataPaths;
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

impl Solver for Fem {
    fn name(&self) -> &'static str {
        fem_solver::METHOD
    }

    fn compute(&self, scene: &Scene) -> Result<Solution> {
        solve_fem(scene, self)
    }
}

/// Solve with the finite-element method.
fn solve_fem(scene: &Scene, options: &Fem) -> Result<Solution> {
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
    let state = fem_solver::solve(kind.clone(), scene.punch.inner_ratio(), load, &fem_options)?;
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
        }),
        complementarity_residual: kind.is_concave().then_some(state.complementarity_residual),
        edge_conditioning: state.edge_conditioning,
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
