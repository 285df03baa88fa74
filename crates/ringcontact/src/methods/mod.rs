//! Every solver behind one interface: a scene goes in, a solution comes out.
//!
//! Each method is a type with its own typed options implementing [`Solver`], in its own file:
//! [`RingBem`], [`Fem`], [`GridBem`], [`Reference`] and [`Auto`]. [`Method`] is the list the
//! command line names them by, and [`MethodOptions`] the command line's flags, which
//! [`Method::solver`] turns into one method's options (refusing a flag that method does not take).
//! Each method turns the dimensionless state it computes into physical units with
//! `F = 2 E* d a γ` (flat punches) and `d = h γ1`, `F = 2 E* h a γ2` (concave punches).

use std::path::PathBuf;

use serde::Serialize;

use crate::bem::ring_contact;
use crate::error::{Error, Result};
use crate::fem::solver as fem_solver;
use crate::scene::Scene;
use crate::solution::Solution;

mod auto;
mod fem;
mod grid_bem;
pub mod ladder;
mod reference;
mod ring_bem;
mod units;

// The FEM's option types, with the method that takes them.
pub use crate::discretisation::far_field::FarField;
pub use crate::mesh::triangulation::Degree;
pub use auto::Auto;
pub use fem::{Fem, FemState};
pub use grid_bem::{GridBem, GridState, DEFAULT_GRID};
pub use reference::Reference;
pub use ring_bem::{BandState, RingBem, RingState};

/// A method: solves a scene into a [`Solution`] with its own error estimate.
pub trait Solver {
    /// The method's name on the command line and in [`Solution::method`].
    fn name(&self) -> &'static str;

    /// The solution of `scene`, before the plausibility check of [`Solver::solve`].
    fn compute(&self, scene: &Scene) -> Result<Solution>;

    /// The solution of `scene`, checked before anyone sees it (never a number that cannot exist).
    fn solve(&self, scene: &Scene) -> Result<Solution> {
        let solution = self.compute(scene)?;
        solution.check_plausible()?;
        Ok(solution)
    }
}

/// The methods `verify solve --method` accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Axisymmetric ring-element BEM, exact elliptic kernel, Gauss-Chebyshev collocation.
    RingBem,
    /// The most trusted analytic reference valid at the state (exact, series, asymptote, fit).
    Reference,
    /// Axisymmetric finite elements (P1/P2/P3 triangles) on committed meshes, then meshes gmsh makes for the scene.
    Fem,
    /// The paper's 3-D FFT BEM on a square grid (Polonsky-Keer), `--grid N`.
    GridBem,
    /// The cheapest method whose own error estimate meets the tolerance (`--tol`): the ring BEM,
    /// then the FEM, then an analytic reference with an error bound.
    Auto,
}

impl crate::choice::Choice for Method {
    const ALL: &'static [Method] = &[
        Method::RingBem,
        Method::Reference,
        Method::Fem,
        Method::GridBem,
        Method::Auto,
    ];

    fn name(self) -> &'static str {
        Method::name(self)
    }

    fn description(self) -> &'static str {
        match self {
            Method::RingBem => {
                "Axisymmetric ring-element BEM, exact elliptic kernel, Gauss-Chebyshev collocation"
            }
            Method::Reference => {
                "The most trusted analytic reference valid at the state (exact, series, \
                 asymptote, fit)"
            }
            Method::Fem => {
                "Axisymmetric finite elements (P1/P2/P3 triangles) on committed meshes, then \
                 meshes gmsh makes for the scene"
            }
            Method::GridBem => {
                "The paper's 3-D FFT BEM on a square grid (Polonsky-Keer), `--grid N`"
            }
            Method::Auto => {
                "The cheapest method whose own error estimate meets the tolerance (`--tol`): the \
                 ring BEM, then the FEM, then an analytic reference with an error bound"
            }
        }
    }
}

impl Method {
    /// Name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::RingBem => ring_contact::METHOD,
            Method::Reference => "reference",
            Method::Fem => fem_solver::METHOD,
            Method::GridBem => crate::bem::grid::METHOD,
            Method::Auto => "auto",
        }
    }

    /// The solver this method names, with the options `options` holds for it; an error naming
    /// any option that belongs to another method.
    pub fn solver(self, options: &MethodOptions) -> Result<Box<dyn Solver>> {
        options.check_for(self)?;
        Ok(match self {
            Method::RingBem => Box::new(RingBem::new()),
            Method::Reference => Box::new(Reference),
            Method::Fem => Box::new(Fem {
                mesh: options.mesh.clone(),
                degree: options.degree,
                far_field: options.far_field,
                vtu: options.vtu.clone(),
                linear_solver: options.linear_solver,
                trace: options.trace,
                data: options.data.clone(),
                progress: options.progress,
            }),
            Method::GridBem => Box::new(GridBem {
                cells: options.grid.unwrap_or(DEFAULT_GRID),
                extent: options.grid_extent,
                with_estimate: !options.grid_without_estimate,
                max_iterations: None,
            }),
            Method::Auto => Box::new(Auto {
                vtu: options.vtu.clone(),
                linear_solver: options.linear_solver,
                trace: options.trace,
                data: options.data.clone(),
                progress: options.progress,
            }),
        })
    }

    /// This method's refinement ladder ([`ladder::Ladder`]) for convergence studies, with the
    /// FEM's backend, trace, data and progress from `options`; an error for a method that does
    /// not refine (`reference`, `auto`).
    pub fn ladder(self, options: &MethodOptions) -> Result<Box<dyn ladder::Ladder>> {
        match self {
            Method::RingBem => Ok(Box::new(RingBem::new())),
            Method::GridBem => Ok(Box::new(GridBem::default())),
            Method::Fem => Ok(Box::new(Fem {
                linear_solver: options.linear_solver,
                trace: options.trace,
                data: options.data.clone(),
                progress: options.progress,
                ..Fem::default()
            })),
            Method::Reference | Method::Auto => Err(Error::Unsupported {
                method: self.name().into(),
                reason: "convergence studies refine one method: choose ring-bem, fem or grid-bem"
                    .into(),
            }),
        }
    }
}

/// Why `--vtu` is refused by a method other than the FEM.
const VTU_ONLY_FOR_THE_FEM: &str = "--vtu writes the FEM's displacement field: use --method fem";

/// The command line's method flags, each used by one method ([`Method::solver`] sorts them).
#[derive(Clone, Debug, Default)]
pub struct MethodOptions {
    /// FEM: a mesh file instead of the committed family.
    pub mesh: Option<PathBuf>,
    /// FEM: element degree (default quadratic).
    pub degree: Option<Degree>,
    /// Grid BEM: cells per side (default 256).
    pub grid: Option<usize>,
    /// Grid BEM, free bands only: half-size `L` of the square `[-L, L]²` in units of `a` (default:
    /// sized from a coarse solve; the other punches' grid is their own `[-a, a]²`).
    pub grid_extent: Option<f64>,
    /// Grid BEM: solve the requested grid alone, without the coarser levels of its error
    /// estimate (the paper's method as the peer codes run it; for timing it against them).
    pub grid_without_estimate: bool,
    /// FEM: write the final displacement field as VTK (`.vtu`) here.
    pub vtu: Option<PathBuf>,
    /// FEM: the condition on the far arc (default [`FarField::Boussinesq`]).
    pub far_field: Option<FarField>,
    /// FEM (and `auto` where it picks the FEM): the sparse Cholesky (`--linear-solver`; default
    /// [`crate::sparse::Backend::BUILT_IN`]). Every method takes it: the other methods have
    /// no sparse factorisation to choose.
    pub linear_solver: Option<crate::sparse::Backend>,
    /// FEM (and `auto` where it picks the FEM): one line per model on standard error
    /// (`RINGCONTACT_TRACE=1`).
    pub trace: bool,
    /// FEM (and `auto`): where the meshes and gmsh are (`--data-dir`; default: the checkout
    /// found from the current directory). Every method takes it.
    pub data: Option<crate::mesh::files::DataPaths>,
    /// FEM (and `auto`): how often a long ladder reports on standard error.
    pub progress: crate::heartbeat::Progress,
}

impl MethodOptions {
    /// An error naming the first option that `method` does not take.
    fn check_for(&self, method: Method) -> Result<()> {
        let refuse = |reason: &str| {
            Err(Error::Unsupported {
                method: method.name().into(),
                reason: reason.into(),
            })
        };
        let fem = method == Method::Fem;
        let grid = method == Method::GridBem;
        if !fem && (self.mesh.is_some() || self.degree.is_some()) {
            return refuse("--mesh and --degree apply to --method fem only");
        }
        if !fem && method != Method::Auto && self.vtu.is_some() {
            return refuse(VTU_ONLY_FOR_THE_FEM);
        }
        if !fem && self.far_field.is_some() {
            return refuse("--far-field sets the FEM's truncated domain: use --method fem");
        }
        if !grid && self.grid.is_some() {
            return refuse("--grid applies to --method grid-bem only");
        }
        if !grid && self.grid_without_estimate {
            return refuse("--no-grid-estimate applies to --method grid-bem only");
        }
        if !grid && self.grid_extent.is_some() {
            return refuse(grid_bem::EXTENT_ONLY_FOR_A_BAND);
        }
        Ok(())
    }
}

/// Solve `scene` with `method`.
pub fn solve(scene: &Scene, method: Method) -> Result<Solution> {
    solve_with(scene, method, &MethodOptions::default())
}

/// Solve `scene` with `method` and the command line's method options.
pub fn solve_with(scene: &Scene, method: Method, options: &MethodOptions) -> Result<Solution> {
    method.solver(options)?.solve(scene)
}
