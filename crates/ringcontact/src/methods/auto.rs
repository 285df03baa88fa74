//! `auto`: the cheapest method whose own error estimate meets the tolerance.

use std::path::PathBuf;

use super::{Fem, Method, Reference, RingBem, Solver};
use crate::error::{Error, Result};
use crate::heartbeat::Progress;
use crate::mesh::files::DataPaths;
use crate::scene::Scene;
use crate::solution::Solution;
use crate::sparse::Backend;

/// The cheapest method whose own error estimate meets the scene's tolerance (default 1e-6).
#[derive(Clone, Debug, Default)]
pub struct Auto {
    /// Where the FEM, if chosen, writes its displacement field; the other methods then decline.
    pub vtu: Option<PathBuf>,
    /// The FEM's sparse Cholesky, if it is chosen (default [`Backend::BUILT_IN`]).
    pub linear_solver: Option<Backend>,
    /// The FEM's trace, if it is chosen.
    pub trace: bool,
    /// Where the FEM's meshes and gmsh are, if it is chosen ([`Fem::data`]).
    pub data: Option<DataPaths>,
    /// How often the FEM, if chosen, reports on standard error.
    pub progress: Progress,
}

impl Solver for Auto {
    fn name(&self) -> &'static str {
        "auto"
    }

    fn compute(&self, scene: &Scene) -> Result<Solution> {
        solve_auto(scene, self)
    }
}

impl Auto {
    /// The solver `auto` tries for `method`; only the FEM writes a displacement field.
    fn candidate(&self, method: Method) -> Result<Box<dyn Solver>> {
        match method {
            Method::Fem => Ok(Box::new(Fem {
                vtu: self.vtu.clone(),
                linear_solver: self.linear_solver,
                trace: self.trace,
                data: self.data.clone(),
                progress: self.progress,
                ..Fem::default()
            })),
            _ if self.vtu.is_some() => Err(Error::Unsupported {
                method: method.name().into(),
                reason: super::VTU_ONLY_FOR_THE_FEM.into(),
            }),
            Method::RingBem => Ok(Box::new(RingBem::new())),
            Method::Reference => Ok(Box::new(Reference)),
            // Not in `auto`'s order: the grid BEM never certifies a tolerance first.
            Method::GridBem | Method::Auto => Err(Error::Unsupported {
                method: method.name().into(),
                reason: "not one of auto's candidates".into(),
            }),
        }
    }
}

/// The order `auto` tries methods in: the axisymmetric ones by cost (ring BEM ~1 ms,
/// FEM 0.1-5 s; the grid BEM, first order, is never the cheapest to certify a tolerance),
/// then, as the last resort where both decline, the analytic references with an error bound
/// (the fixed annulus beyond the ring BEM's `b/a = 0.9999`, whose rim the FEM cannot refine
/// enough for a tight tolerance, is the narrow-ring asymptote's, bound `δ² ln(16/δ)`): the
/// independent discretisations first wherever they apply.
const AUTO_ORDER: [Method; 3] = [Method::RingBem, Method::Fem, Method::Reference];

/// Pick the cheapest method whose own error estimate meets the scene's tolerance (default 1e-6).
fn solve_auto(scene: &Scene, auto: &Auto) -> Result<Solution> {
    let tolerance = scene.tolerance.unwrap_or(1e-6);
    let scene = Scene {
        tolerance: Some(tolerance),
        ..scene.clone()
    };
    let mut tried = Vec::new();
    for method in AUTO_ORDER {
        match auto
            .candidate(method)
            .and_then(|solver| solver.solve(&scene))
        {
            Ok(mut s) if s.error_estimate.is_some_and(|e| e <= tolerance) => {
                s.selection = Some(format!(
                    "auto: {} is the cheapest method whose error estimate ({:.1e}) meets the tolerance {tolerance:.1e}{}",
                    method.name(),
                    s.error_estimate.unwrap_or(f64::NAN),
                    if tried.is_empty() { String::new() } else { format!(" (declined: {})", tried.join("; ")) }
                ));
                return Ok(s);
            }
            Ok(s) => tried.push(match s.error_estimate {
                Some(e) => format!("{} estimate {e:.1e}", method.name()),
                None => format!("{}: no error estimate", method.name()),
            }),
            Err(e) => tried.push(format!("{}: {e}", method.name())),
        }
    }
    Err(Error::NoConvergence {
        method: "auto".into(),
        reason: format!(
            "no method meets the tolerance {tolerance:.1e}: {}",
            tried.join("; ")
        ),
    })
}
