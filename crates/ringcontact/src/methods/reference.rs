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
                "no analytic reference for {quantity:?} is valid at eps = {}",
                crate::error::show(eps)
            ),
        })
}

/// Solve with the analytic references (exact results, series, asymptotes, the paper's fits).
fn solve_reference(scene: &Scene) -> Result<Solution> {
    let start = Instant::now();
    // Every field below is set from the reference that applies.
    let solution = base(scene, "reference", 0.0, (None, None, None), 0.0)?;
    let mut solution = match reference_family(&scene.punch.kind)? {
        ReferenceFamily::Flat => flat_reference(scene, solution)?,
        ReferenceFamily::Cone => concave_reference(scene, solution, false)?,
        ReferenceFamily::Sphere => concave_reference(scene, solution, true)?,
        ReferenceFamily::Power(n) => power_full_contact(scene, solution, n)?,
    };
    solution.wall_s = start.elapsed().as_secs_f64();
    Ok(solution)
}

/// The flat annulus's `γ(b/a)` from the most trusted reference valid at `b/a`.
fn flat_reference(scene: &Scene, mut solution: Solution) -> Result<Solution> {
    let a = scene.punch.rim_radius;
    let eps = scene.punch.inner_ratio();
    let (value, name, source) = best_reference(Quantity::FlatGamma, eps)?;
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

/// The cone's or the sphere's `γ1`, `γ2` at the scene's load: the sphere's full contact in
/// closed form (the MDR), else the contact ratio whose references meet the load.
fn concave_reference(scene: &Scene, solution: Solution, sphere: bool) -> Result<Solution> {
    let (a, es, h) = (
        scene.punch.rim_radius,
        scene.material.effective_modulus,
        scene.punch.hole_depth,
    );
    let (q1, q2) = if !sphere {
        (Quantity::ConeGamma1, Quantity::ConeGamma2)
    } else {
        (Quantity::SphereGamma1, Quantity::SphereGamma2)
    };
    let full_contact = match scene.load {
        Load::Depth(d) if sphere => {
            reference::sphere_full_contact_gamma2(d / h).map(|g2| (d / h, g2))
        }
        Load::Force(f) if sphere => {
            let g2 = f / (2.0 * es * h * a);
            (g2 >= 8.0 / 3.0).then_some((g2 + 1.0 / 3.0, g2))
        }
        _ => None,
    };
    let (eps, g1, g2, name, source, bound) = if let Some((g1, g2)) = full_contact {
        (
            0.0,
            g1,
            g2,
            "sphere-full-contact",
            "MDR: F = 2 E* a (d - h/3) for d >= 3h",
            Some(0.0),
        )
    } else {
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
        (eps, v1.value, v2.value, name, source, bound)
    };
    Ok(concave_solution(
        solution,
        scene,
        (eps, g1, g2),
        bound,
        (&format!("reference:{name}"), source),
    ))
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

/// The power law's full contact by the MDR; its annular contact has no closed form.
fn power_full_contact(scene: &Scene, solution: Solution, n: f64) -> Result<Solution> {
    let (a, es, h) = (
        scene.punch.rim_radius,
        scene.material.effective_modulus,
        scene.punch.hole_depth,
    );
    let full_contact = match scene.load {
        Load::Depth(d) => power_law::full_contact_gamma2(n, d / h).map(|g2| (d / h, g2)),
        Load::Force(f) => {
            let g2 = f / (2.0 * es * h * a);
            power_law::full_contact_gamma1(n, g2).map(|g1| (g1, g2))
        }
        Load::ContactRatio(_) => None,
    };
    let Some((g1, g2)) = full_contact else {
        return Err(Error::OutOfRange {
            method: "reference".into(),
            reason: format!(
                "the power-law punch has a closed form only in full contact (n > 1 and \
                 d >= h (1 + κ_n/(n - 1)){}); its annular contact is the ring BEM's \
                 (--method ring-bem)",
                power_law::closure_depth(n)
                    .map(|d| format!(", here d >= {} h", crate::error::show(d)))
                    .unwrap_or_default()
            ),
        });
    };
    Ok(concave_solution(
        solution,
        scene,
        (0.0, g1, g2),
        Some(0.0),
        (
            "reference:power-full-contact",
            "MDR: F = 2 E* a ((d - h) + κ_n h/(n + 1)) for d >= h (1 + κ_n/(n - 1)), \
             κ_n = (n √π/2) Γ(n/2)/Γ((n+1)/2)",
        ),
    ))
}

/// The closed-form references that hold for a punch, asked of its profile.
enum ReferenceFamily {
    /// The flat circular and annular punch's `γ(b/a)`.
    Flat,
    /// The cone's `γ1`, `γ2` (series and asymptotes).
    Cone,
    /// The sphere's `γ1`, `γ2` and its full contact.
    Sphere,
    /// The power law's full contact (the MDR).
    Power(f64),
}

/// Which [`ReferenceFamily`] holds for `kind`; an error saying why where none does.
fn reference_family(kind: &PunchKind) -> Result<ReferenceFamily> {
    let none = |reason: String| Error::OutOfRange {
        method: "reference".into(),
        reason,
    };
    if !kind.is_concave() {
        return Ok(ReferenceFamily::Flat);
    }
    if kind.piecewise().is_some() {
        return Err(none(format!(
            "the {} punch has no closed form (its full contact is a quadrature of the \
             interpolated profile); it is the ring BEM's (--method ring-bem)",
            kind.name()
        )));
    }
    if kind.is_free_band() {
        return Err(none(format!(
            "the {} has no closed form (its narrow limit, the plane-strain Hertz cylinder, is an \
             asymptote without an error bound); it is the ring BEM's (--method ring-bem)",
            kind.name()
        )));
    }
    match (kind.exponent_parameter(), kind.power_law_exponent()) {
        (Some(n), _) => Ok(ReferenceFamily::Power(n)),
        (None, Some(1.0)) => Ok(ReferenceFamily::Cone),
        (None, Some(2.0)) => Ok(ReferenceFamily::Sphere),
        (None, Some(n)) => Ok(ReferenceFamily::Power(n)),
        (None, None) => Err(none(format!(
            "the {kind} has no closed form here; it is the ring BEM's (--method ring-bem)"
        ))),
    }
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
            "cannot invert {quantity:?} = {} with the references: {e:?}",
            crate::error::show(target)
        ),
    })
}
