//! The analytic references as a [`Solver`]: the most trusted closed form, series, asymptote or
//! fit valid at the state, with its error bound where it has one.

use std::time::Instant;

use super::units::{base, flat_depth_force};
use super::Solver;
use crate::error::{Error, Result};
use crate::numerics::roots::find_root;
use crate::punch::PunchKind;
use crate::reference::{self, power_law, Quantity, ReferenceValue};
use crate::scene::{Load, Scene};
use crate::solution::Solution;

/// The analytic references (`Solution::method` names the one used, `reference:NAME`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Reference;

impl Solver for Reference {
    fn name(&self) -> &'static str {
        "reference"
    }

    fn compute(&self, scene: &Scene) -> Result<Solution> {
        solve_reference(scene)
    }
}

/// The most trusted reference for `quantity` at `eps`, or an out-of-range error.
fn best_reference(
    quantity: Quantity,
    eps: f64,
) -> Result<(ReferenceValue, &'static str, &'static str)> {
    reference::valid_references(quantity, eps)
        .first()
        .map(|r| {
            (
                r.evaluate(eps).expect("valid range checked"),
                r.name,
                r.source,
            )
        })
        .ok_or_else(|| Error::OutOfRange {
            method: "reference".into(),
            reason: format!(
                "no analytic reference for {} is valid at eps = {}",
                quantity.label(),
                crate::error::show(eps)
            ),
        })
}

/// Solve with the analytic references (exact results, series, asymptotes, the paper's fits)
/// that the punch's profile declares, and the full contact past its declared closure.
fn solve_reference(scene: &Scene) -> Result<Solution> {
    let start = Instant::now();
    // Every field below is set from the reference that applies.
    let solution = base(scene, "reference", 0.0, (None, None, None), 0.0)?;
    let mut solution = if scene.punch.kind.is_concave() {
        concave_reference(scene, solution)?
    } else {
        flat_reference(scene, solution)?
    };
    solution.wall_s = start.elapsed().as_secs_f64();
    Ok(solution)
}

/// The error of a punch without a closed form at this state.
fn no_closed_form(reason: String) -> Error {
    Error::OutOfRange {
        method: "reference".into(),
        reason,
    }
}

/// A flat-faced punch's `γ(b/a)` from the most trusted reference valid at `b/a`.
fn flat_reference(scene: &Scene, mut solution: Solution) -> Result<Solution> {
    let kind = &scene.punch.kind;
    let a = scene.punch.rim_radius;
    let eps = scene.punch.inner_ratio();
    let quantity = reference::quantity_of(kind, 0).ok_or_else(|| {
        no_closed_form(format!(
            "the {kind} declares no closed form; it is the ring BEM's (--method ring-bem)"
        ))
    })?;
    let (value, name, source) = best_reference(quantity, eps)?;
    let (d, f) = flat_depth_force(scene, value.value)?;
    solution.eps = eps;
    solution.inner_radius = eps * a;
    solution.gamma = Some(value.value);
    solution.depth = d;
    solution.force = f;
    solution.error_estimate = value.error_bound.map(|b| b / value.value);
    solution.method = format!("reference:{name}");
    solution.provenance = source.to_string();
    Ok(solution)
}

/// A concave punch's `γ1`, `γ2` at the scene's load: past the closure its profile declares, the
/// full contact in closed form; else the contact ratio where the profile's references meet the
/// load.
fn concave_reference(scene: &Scene, solution: Solution) -> Result<Solution> {
    let kind = &scene.punch.kind;
    refuse_without_closed_form(kind)?;
    if let Some(full) = full_contact(scene, &solution) {
        return Ok(full);
    }
    let (h, a, es) = (
        scene.punch.hole_depth,
        scene.punch.rim_radius,
        scene.material.effective_modulus,
    );
    let (Some(q1), Some(q2)) = (
        reference::quantity_of(kind, 1),
        reference::quantity_of(kind, 2),
    ) else {
        return Err(no_closed_form(without_references(kind)));
    };
    let eps = match scene.load {
        Load::ContactRatio(eps) => eps,
        Load::Depth(d) => invert_reference(q1, d / h)?,
        Load::Force(f) => invert_reference(q2, f / (2.0 * es * h * a))?,
    };
    let (v1, name, source) = best_reference(q1, eps)?;
    let (v2, _, _) = best_reference(q2, eps)?;
    let bound = match (v1.error_bound, v2.error_bound) {
        (Some(b1), Some(b2)) => Some((b1 / v1.value).max(b2 / v2.value)),
        _ => None,
    };
    Ok(concave_solution(
        solution,
        scene,
        (eps, v1.value, v2.value),
        bound,
        (&format!("reference:{name}"), source),
    ))
}

/// Refuse the profiles whose references are never closed forms: a piecewise (interpolated)
/// gap and a free band.
fn refuse_without_closed_form(kind: &PunchKind) -> Result<()> {
    if kind.piecewise().is_some() {
        return Err(no_closed_form(format!(
            "the {} punch has no closed form (its full contact is a quadrature of the \
             interpolated profile); it is the ring BEM's (--method ring-bem)",
            kind.name()
        )));
    }
    if kind.is_free_band() {
        return Err(no_closed_form(format!(
            "the {} has no closed form (its narrow limit, the plane-strain Hertz cylinder, is an \
             asymptote without an error bound); it is the ring BEM's (--method ring-bem)",
            kind.name()
        )));
    }
    Ok(())
}

/// Why a concave punch without references of its annular contact has no answer here.
fn without_references(kind: &PunchKind) -> String {
    match kind.power_law_exponent() {
        Some(n) => format!(
            "the gap h (1 - (r/a)^n) has a closed form only in full contact (n > 1 and \
             d >= h (1 + κ_n/(n - 1)){}); its annular contact is the ring BEM's \
             (--method ring-bem)",
            power_law::closure_depth(n)
                .map(|d| format!(", here d >= {} h", crate::error::show(d)))
                .unwrap_or_default()
        ),
        None => {
            format!("the {kind} has no closed form here; it is the ring BEM's (--method ring-bem)")
        }
    }
}

/// `solution` at the concave state `(b/a, γ1 = d/h, γ2 = F/(2 E* h a))` of `scene`, with its
/// relative error bound and its method's name and provenance.
fn concave_solution(
    mut solution: Solution,
    scene: &Scene,
    (eps, g1, g2): (f64, f64, f64),
    bound: Option<f64>,
    (method, provenance): (&str, &str),
) -> Solution {
    let (a, es, h) = (
        scene.punch.rim_radius,
        scene.material.effective_modulus,
        scene.punch.hole_depth,
    );
    solution.eps = eps;
    solution.inner_radius = eps * a;
    solution.gamma1 = Some(g1);
    solution.gamma2 = Some(g2);
    solution.depth = h * g1;
    solution.force = 2.0 * es * h * a * g2;
    solution.error_estimate = bound;
    solution.method = method.to_string();
    solution.provenance = provenance.to_string();
    solution
}

/// The full contact past the closure `(d_c/h, γ2_c)` the profile declares: the contact is the
/// disk there and a rigid shift adds the flat-faced punch's stiffness, `γ2 = γ2_c + (γ1 - d_c/h)`.
fn full_contact(scene: &Scene, solution: &Solution) -> Option<Solution> {
    let kind = &scene.punch.kind;
    let (closure_depth, closure_force) = kind.closure()?;
    let (a, es, h) = (
        scene.punch.rim_radius,
        scene.material.effective_modulus,
        scene.punch.hole_depth,
    );
    let (g1, g2) = match scene.load {
        Load::Depth(d) => {
            let g1 = d / h;
            (g1 >= closure_depth).then_some((g1, closure_force + (g1 - closure_depth)))
        }
        Load::Force(f) => {
            let g2 = f / (2.0 * es * h * a);
            (g2 >= closure_force).then_some((closure_depth + (g2 - closure_force), g2))
        }
        Load::ContactRatio(_) => None,
    }?;
    let provenance = format!(
        "MDR: full contact from d = {} h at F = {} E* h a; beyond, F = 2 E* a (d - {} h)",
        crate::error::show(closure_depth),
        crate::error::show(2.0 * closure_force),
        crate::error::show(closure_depth - closure_force)
    );
    Some(concave_solution(
        solution.clone(),
        scene,
        (0.0, g1, g2),
        Some(0.0),
        (
            &format!("reference:{}-full-contact", kind.name()),
            &provenance,
        ),
    ))
}

/// `eps` where the most trusted reference for `quantity` equals `target` (references decrease
/// monotonically in `eps`).
fn invert_reference(quantity: Quantity, target: f64) -> Result<f64> {
    let (lo, hi) = (1e-12, 1.0 - 1e-12);
    find_root(
        |eps| {
            best_reference(quantity, eps)
                .map(|(v, _, _)| v.value - target)
                .map_err(|e| e.to_string())
        },
        lo,
        hi,
        0.5,
        1e-15,
        200,
    )
    .map(|r| r.x)
    .map_err(|e| Error::OutOfRange {
        method: "reference".into(),
        reason: format!(
            "cannot invert {} = {} with the references: {e:?}",
            quantity.label(),
            crate::error::show(target)
        ),
    })
}
