//! The physical state of a solution from a method's dimensionless results:
//! `F = 2 E* d a γ` (flat punches), `d = h γ1`, `F = 2 E* h a γ2` (concave punches).

use crate::error::{Error, Result};
use crate::scene::{Load, Scene};
use crate::solution::Solution;

/// A solution of `scene` by `method` with the physical state filled in from the dimensionless
/// results and every method-specific field empty (to be overridden with struct-update syntax).
pub(super) fn base(
    scene: &Scene,
    method: &str,
    eps: f64,
    (gamma, gamma1, gamma2): (Option<f64>, Option<f64>, Option<f64>),
    wall_s: f64,
) -> Result<Solution> {
    let (depth, force) = depth_force(scene, gamma, gamma1, gamma2)?;
    let a = scene.punch.rim_radius;
    Ok(Solution {
        punch: scene.punch.kind.clone(),
        method: method.to_string(),
        eps,
        depth,
        force,
        inner_radius: eps * a,
        rim_radius: a,
        outer_radius: a,
        tube_radius: scene.punch.tube_radius(),
        gamma,
        gamma1,
        gamma2,
        stress_intensity_rim: None,
        stress_intensity_inner: None,
        error_estimate: None,
        wall_s,
        unknowns: 0,
        iterations: 0,
        fem: None,
        complementarity_residual: None,
        grid_bem: None,
        selection: None,
        pressure: Vec::new(),
        provenance: String::new(),
    })
}

/// Physical depth and force from the dimensionless results: flat punches by
/// [`flat_depth_force`], concave punches by `d = h γ1`, `F = 2 E* h a γ2`.
fn depth_force(
    scene: &Scene,
    gamma: Option<f64>,
    gamma1: Option<f64>,
    gamma2: Option<f64>,
) -> Result<(f64, f64)> {
    match gamma {
        Some(gamma) => flat_depth_force(scene, gamma),
        None => {
            let (h, a, es) = (
                scene.punch.hole_depth,
                scene.punch.rim_radius,
                scene.material.effective_modulus,
            );
            Ok((
                h * gamma1.unwrap_or(f64::NAN),
                2.0 * es * h * a * gamma2.unwrap_or(f64::NAN),
            ))
        }
    }
}

/// Physical depth and force of a flat-faced punch with `F = 2 E* d a γ`, under the scene's load.
pub(super) fn flat_depth_force(scene: &Scene, gamma: f64) -> Result<(f64, f64)> {
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    match scene.load {
        Load::Depth(d) => Ok((d, 2.0 * es * d * a * gamma)),
        Load::Force(f) => Ok((f / (2.0 * es * a * gamma), f)),
        Load::ContactRatio(_) => Err(Error::invalid(
            "load.contact_ratio",
            "applies only to a punch whose contact edge is found (a free edge)",
        )),
    }
}
