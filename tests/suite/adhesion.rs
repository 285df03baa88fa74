//! JKR adhesion from the ring BEM: the formula route against known limits and against a direct
//! BEM solve of the adhesive contact.

use std::f64::consts::PI;

use ringcontact::adhesion::{self, full_contact_constants};
use ringcontact::bem::ring::{ContactRegion, RingSystem};
use ringcontact::methods::RingBem;
use ringcontact::numerics::tanh_sinh::TanhSinhRule;
use ringcontact::punch::PunchKind;

#[test]
fn a_small_hole_detaches_like_kendalls_flat_punch() {
    // eps -> 0: outer-edge detachment at d_c = -d0, F_c = -F0 (Kendall 1971).
    let r = adhesion::fixed_annulus(&RingBem::new(), 0.01).unwrap();
    assert!(
        (r.dc_outer + 1.0).abs() < 1e-6 && (r.fc_outer + 1.0).abs() < 1e-6,
        "{r:?}"
    );
    assert_eq!(r.governing_edge, "outer");
}

#[test]
fn flat_annulus_agrees_with_collins_and_approaches_argatov() {
    let solver = RingBem::new();
    // Collins' series in (16)-(17): truncation error O(eps^7) in gamma.
    let r = adhesion::fixed_annulus(&solver, 0.1).unwrap();
    let c = r.collins.unwrap();
    assert!(
        (r.dc_outer - c.depth).abs() < 1e-6 && (r.fc_outer - c.force).abs() < 1e-6,
        "{r:?}"
    );
    // Argatov's narrow-ring asymptote (22) is leading order: the difference shrinks toward eps = 1.
    let diff = |eps: f64| {
        let r = adhesion::fixed_annulus(&solver, eps).unwrap();
        let a = r.argatov.unwrap();
        ((r.fc_outer - a.force) / a.force).abs()
    };
    let (d1, d2, d3) = (diff(0.9), diff(0.99), diff(0.999));
    assert!(d2 < d1 && d3 < d2, "{d1} {d2} {d3}");
}

#[test]
fn a_small_holes_inner_edge_follows_collins_down_to_the_range_end() {
    // Collins' series (paper 21): γ' = -4 eps²/π² - 8 eps⁴/(3π²) - 32 eps⁵/(9π⁴), so
    // κ_in = sqrt(-γ'/eps) and d_c = -1/κ_in at the inner edge. The differenced γ' loses digits
    // here (γ' ~ 1e-9 against γ ~ 1): it once gave a d_c 24 % off at eps = 1e-4.
    let solver = RingBem::new();
    for eps in [1e-4, 3e-4, 1e-3, 1e-2] {
        let r = adhesion::fixed_annulus(&solver, eps).unwrap();
        let gp = -4.0 * eps * eps / (PI * PI)
            - 8.0 * eps.powi(4) / (3.0 * PI * PI)
            - 32.0 * eps.powi(5) / (9.0 * PI.powi(4));
        let collins = -1.0 / (-gp / eps).sqrt();
        assert!(
            ((r.dc_inner - collins) / collins).abs() < 1e-5,
            "eps = {eps}: d_c = {} against Collins' {collins}",
            r.dc_inner
        );
    }
    // The validated range's other end: the derivative's stencil stays inside it.
    assert!(adhesion::fixed_annulus(&solver, 0.9999).is_ok());
}

#[test]
fn the_outer_edge_governs_and_edge_intensities_are_consistent() {
    // Paper: "the annular flat punch will always start to detach at the outer boundary".
    let solver = RingBem::new();
    for eps in [0.05, 0.2, 0.4, 0.6, 0.8, 0.95, 0.99] {
        let r = adhesion::fixed_annulus(&solver, eps).unwrap();
        assert_eq!(r.governing_edge, "outer", "eps = {eps}");
        assert!(r.dc_outer.abs() < r.dc_inner.abs());
        // κ read off the pressure field vs κ from the force derivative (docs/conventions.md fact 7).
        assert!(
            r.kappa_consistency < 1e-7,
            "eps = {eps}: {}",
            r.kappa_consistency
        );
    }
}

#[test]
fn concave_critical_state_satisfies_griffith_in_a_direct_solve() {
    // Formula route (superposition, κ_in of the flat annulus) against a fresh BEM solve of the
    // adhesive contact at the critical state: G_inner = Δw and the same rim intensity.
    for kind in [PunchKind::CONE, PunchKind::SPHERE] {
        let r = adhesion::concave(&RingBem::new(), kind.clone(), 1.0).unwrap();
        let ratio = r.direct_inner_energy_ratio.unwrap();
        assert!((ratio - 1.0).abs() < 1e-8, "{kind}: G/dw = {ratio}");
        assert!(r.direct_rim_difference.unwrap().abs() < 1e-8);
        // Under fixed load and fixed grips the pull-off forces are close (paper: "almost
        // independent of the regime").
        let (load, grips) = (r.fixed_load.unwrap(), r.fixed_grips.unwrap());
        assert!(
            load.force < grips.force && (load.force - grips.force).abs() < 0.1 * load.force.abs()
        );
    }
}

#[test]
fn full_contact_constants_match_the_disk_bem_for_the_sphere() {
    // MDR: sphere F = 2E*a(d - h/3) and rim intensity d + h; the disk BEM must agree.
    let rule = TanhSinhRule::new(1.0 / 16.0);
    let system = RingSystem::assemble(ContactRegion::Disk, 32, &rule);
    let profile: Vec<f64> = system
        .radii()
        .iter()
        .map(|&r| -PunchKind::SPHERE.gap_shape(r))
        .collect();
    let field = system.solve(&profile).unwrap();
    let (c_f, kappa_h) = full_contact_constants(&PunchKind::SPHERE).unwrap();
    assert!((-0.5 * field.force - c_f).abs() < 1e-12);
    assert!((system.rim_stress_intensity(&field) * PI.sqrt() - kappa_h).abs() < 1e-10);
}

#[test]
fn strong_adhesion_leaves_no_stable_annular_state() {
    // Finding: for d0/h = 10 F(eps) has no stationary point on 0.004..0.9999: the annular
    // contact is unstable under fixed load, and pull-off needs the full-contact branch, whose rim
    // holds up to F/F0 = -1 - (c_F + κ_h)/(d0/h).
    let r = adhesion::concave(&RingBem::new(), PunchKind::SPHERE, 10.0).unwrap();
    assert!(r.fixed_load.is_none() && r.fixed_load_note.is_some());
    let expected = -1.0 - (1.0 / 3.0 + 1.0) / 10.0;
    assert!((r.full_contact.pulloff.force - expected).abs() < 1e-12);
}

/// The critical states' error bounds (propagated from the ring BEM's estimates) bound the
/// actual error where an independent reference is accurate far beyond them: Collins' series at
/// small holes (truncation `O(eps^7)`: below 1e-13 at `eps <= 0.02`) for the outer edge's
/// critical depth and force.
#[test]
fn the_flat_annulus_error_bounds_bound_the_error_against_collins() {
    let solver = RingBem::new();
    for eps in [0.01, 0.015, 0.02] {
        let r = adhesion::fixed_annulus(&solver, eps).unwrap();
        let c = r.collins.unwrap();
        let bounds = r.error_bounds.expect("bounds");
        let truncation = 10.0 * eps.powi(7);
        assert!(
            (r.dc_outer - c.depth).abs() <= bounds.dc_outer + truncation,
            "eps {eps}: d_c off by {:e}, bound {:e}",
            (r.dc_outer - c.depth).abs(),
            bounds.dc_outer
        );
        assert!(
            (r.fc_outer - c.force).abs() <= bounds.fc_outer + truncation,
            "eps {eps}: F_c off by {:e}, bound {:e}",
            (r.fc_outer - c.force).abs(),
            bounds.fc_outer
        );
        assert!(
            bounds.fc_outer > 0.0 && bounds.fc_outer < 1e-6,
            "{bounds:?}"
        );
    }
}

/// No bound is zero: a zero bound claims an exact number. (The inner edge's bound, the change
/// between two tolerances, was exactly 0 where both ladders stopped at the same discretisation,
/// as at `eps = 1e-3`.)
#[test]
fn no_flat_annulus_bound_is_zero() {
    let solver = RingBem::new();
    for eps in [1e-3, 0.1, 0.5, 0.9] {
        let b = adhesion::fixed_annulus(&solver, eps)
            .unwrap()
            .error_bounds
            .expect("bounds");
        for (name, bound) in [
            ("dc_outer", b.dc_outer),
            ("fc_outer", b.fc_outer),
            ("dc_inner", b.dc_inner),
            ("fc_inner", b.fc_inner),
        ] {
            assert!(bound > 0.0, "eps {eps}: {name} bound {bound:e}");
        }
    }
}

/// A concave punch's critical states carry bounds; full contact's closed forms are exact.
#[test]
fn the_concave_critical_states_carry_error_bounds() {
    let r = adhesion::concave(&RingBem::new(), PunchKind::SPHERE, 1.0).unwrap();
    for c in [&r.fixed_load, &r.fixed_grips].into_iter().flatten() {
        let bound = c.error_bound.expect("a bound");
        assert!(bound > 0.0 && bound < 1e-6, "{c:?}");
        assert!(
            c.depth_error_bound.is_some_and(|b| b > 0.0 && b < 1e-6),
            "{c:?}"
        );
    }
    assert_eq!(r.full_contact.pulloff.error_bound, Some(0.0));
}

/// Least clearance `w(r) - (d - g(r))` of the surface over the punch's floor in the hole of the
/// ring `[eps, 1]` pressed to `d/h = depth` (any edge intensities: the displacement on the ring
/// fixes the pressure), from a collocation system assembled here (96 nodes) and probed at 64
/// radii (the analysis probes 8).
fn least_hole_clearance(kind: PunchKind, eps: f64, depth: f64) -> f64 {
    hole_clearances(kind, eps, depth)
        .into_iter()
        .fold(f64::INFINITY, f64::min)
}

/// The clearances `w(r) - (d - g(r))` behind [`least_hole_clearance`], at its 64 radii.
fn hole_clearances(kind: PunchKind, eps: f64, depth: f64) -> Vec<f64> {
    let rule = TanhSinhRule::new(1.0 / 32.0);
    let region = ContactRegion::Annulus { eps };
    let system = RingSystem::assemble(region, 96, &rule);
    let target: Vec<f64> = system
        .radii()
        .iter()
        .map(|&r| depth - kind.gap_shape(r))
        .collect();
    let field = system.solve(&target).expect("a regular system");
    (0..64)
        .map(|k| {
            let r = eps * k as f64 / 64.0;
            let w = system.deflection_in_hole(&field, r, &rule).unwrap();
            w - (depth - kind.gap_shape(r))
        })
        .collect()
}

/// A profile flatter than the sphere at the axis (the power law `n = 20`) grows its adhesive
/// ring from the rim until the surface in the hole meets the punch's floor, short of closing
/// the hole. The analysis ends the annular branch there and unloads from there; it once took
/// the branch on through rings whose floor cuts into the surface (the fixed-load branch started
/// at eps = 0.92, 0.1 h into it) and said the hole closed at d/h = 1.82. Checked by states
/// assembled here from the analysis's depths, 2e-3 either side of the reported touch.
#[test]
fn a_steep_power_laws_adhesive_branch_ends_where_its_hole_meets_the_floor() {
    let solver = RingBem::new();
    let kind = PunchKind::power(ringcontact::punch::Exponent::new(20.0).unwrap());
    let s = 0.5;
    let r = adhesion::concave(&solver, kind.clone(), s).unwrap();
    let touch = r.floor_contact.clone().expect("the branch meets the floor");
    assert!(r.full_contact.closing_depth.is_none());
    for (eps, clear) in [(touch.eps + 2e-3, true), (touch.eps - 2e-3, false)] {
        let depth = adhesion::branch_point(&solver, kind.clone(), eps)
            .unwrap()
            .depth(s);
        let least = least_hole_clearance(kind.clone(), eps, depth);
        assert_eq!(least >= 0.0, clear, "eps = {eps}: clearance {least:.3e} h");
    }
    let (start, _) = r.stable_branch_fixed_load.expect("a fixed-load branch");
    assert!(start >= touch.eps - 1e-9, "unloading starts at {start}");
    // The critical state itself lies on the branch and satisfies Griffith in a direct solve.
    let load = r.fixed_load.as_ref().expect("a fixed-load pull-off");
    assert!(load.eps > touch.eps);
    assert!((r.direct_inner_energy_ratio.unwrap() - 1.0).abs() < 1e-8);
    // The sphere's hole closes before its floor is met: no touch, a closing depth.
    let sphere = adhesion::concave(&solver, PunchKind::SPHERE, s).unwrap();
    assert!(sphere.floor_contact.is_none() && sphere.full_contact.closing_depth.is_some());
}

/// The power law `n = 50`: its widest scan rings need 128 nodes and settle only to about 1e-9
/// (rounding at the inner edge), where the analysis once stopped at 80 nodes and 1e-10. It runs
/// now, and its fixed-load critical state satisfies Griffith in a direct solve.
#[test]
fn a_power_law_with_a_wall_as_steep_as_n_50_has_a_jkr_analysis() {
    let solver = RingBem::new();
    let kind = PunchKind::power(ringcontact::punch::Exponent::new(50.0).unwrap());
    let r = adhesion::concave(&solver, kind, 5.0).unwrap();
    let load = r.fixed_load.as_ref().expect("a fixed-load pull-off");
    assert!(load.force < 0.0 && load.error_bound.is_some_and(|b| b < 1e-8));
    assert!((r.direct_inner_energy_ratio.unwrap() - 1.0).abs() < 1e-8);
    assert!(r.direct_rim_difference.unwrap().abs() < 1e-8);
}

/// The JKR analysis probes the hole's floor only for profiles that can meet it
/// (`PunchKind::may_meet_hole_floor`: the power law with `n > 2`, tables). The claim behind
/// skipping the others, checked on systems assembled here (96 nodes, 64 radii): for `n <= 2`
/// the non-adhesive ring with a free inner edge clears the floor at every ratio from 1e-4 to
/// 0.999, and the flat annulus's surface in its hole sinks less than the punch (`w <= 1`), so
/// the adhesive states, the first plus the second pulled by `s/kappa_in > 0`, clear it too.
/// The fields are converged to 1e-9: at `b/a = 1e-4` the free-edge depth's rounding floor is
/// 1e-10 (its values at 32-128 nodes scatter by 5e-10 relative, whichever quadrature assembles
/// the rows), so 1e-10 there is refused or met by chance.
#[test]
fn profiles_no_flatter_than_the_sphere_clear_their_holes_floor_at_every_ratio() {
    let solver = RingBem::new();
    let ratios = [1e-4, 1e-3, 0.01, 0.05, 0.2, 0.4, 0.6, 0.8, 0.95, 0.999];
    let power = |n| PunchKind::power(ringcontact::punch::Exponent::new(n).unwrap());
    for kind in [power(0.25), PunchKind::CONE, power(1.5), PunchKind::SPHERE] {
        assert!(!kind.may_meet_hole_floor());
        for eps in ratios {
            let depth = solver
                .engine()
                .free_inner_edge_field(&kind, eps, 1e-9)
                .unwrap()
                .gamma1
                .unwrap();
            // Clear means not below the rounding of `w` and `d - g`, both of order `d`.
            let least = least_hole_clearance(kind.clone(), eps, depth);
            assert!(
                least >= -1e-14 * depth.max(1.0),
                "{kind} at eps = {eps}: clearance {least:.3e} h"
            );
        }
    }
    for eps in ratios {
        let rise = hole_clearances(PunchKind::FLAT_ANNULUS, eps, 1.0)
            .into_iter()
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            rise <= 0.0,
            "flat annulus at eps = {eps}: w - 1 = {rise:.3e}"
        );
    }
    assert!(power(2.5).may_meet_hole_floor());
}

/// `adhesion::jkr` picks the analysis by the punch's contact: a small-holed annulus lets go as
/// Kendall's flat punch (`d_c = -d0`, `F_c = -F0`, Kendall 1971); the torus's narrow band as the
/// plane-strain JKR cylinder it tends to (within 1e-3 at `d0/h = 1e-3`, as
/// `tests/suite/torus_jkr.rs` checks against the closed form); and a
/// value of the other family, or a missing one, is an error naming it.
#[test]
fn one_entry_routes_every_punch_and_names_a_missing_value() {
    let solver = RingBem::new();
    let flat = PunchKind::FLAT_ANNULUS;
    match adhesion::jkr(&solver, &flat, Some(0.01), None).unwrap() {
        adhesion::Jkr::FixedAnnulus(r) => {
            assert!((r.dc_outer + 1.0).abs() < 1e-6 && (r.fc_outer + 1.0).abs() < 1e-6)
        }
        other => panic!("the flat annulus routed to {other:?}"),
    }
    match adhesion::jkr(&solver, &PunchKind::TORUS, None, Some(1e-3)).unwrap() {
        adhesion::Jkr::Band(r) => {
            let asymptote = r
                .plane_strain_fixed_load
                .expect("the narrow band's asymptote");
            let force = r.fixed_load.expect("a fixed-load pull-off").force;
            assert!(
                (force / asymptote - 1.0).abs() < 1e-3,
                "{force} vs {asymptote}"
            );
        }
        other => panic!("the torus routed to {other:?}"),
    }
    assert!(matches!(
        adhesion::jkr(&solver, &PunchKind::CONE, None, Some(0.5)).unwrap(),
        adhesion::Jkr::Concave(_)
    ));
    for (kind, eps, d0h, named) in [
        (PunchKind::CONE, None, None, "`d0h` is needed"),
        (
            PunchKind::CONE,
            Some(0.5),
            Some(1.0),
            "`eps` fixes the hole of a fixed annulus",
        ),
        (flat.clone(), None, None, "`eps` is needed"),
        (
            flat.clone(),
            Some(0.5),
            Some(1.0),
            "`d0h` is a concave punch's",
        ),
        (PunchKind::FLAT, None, Some(1.0), "Kendall's"),
    ] {
        let message = adhesion::jkr(&solver, &kind, eps, d0h)
            .unwrap_err()
            .to_string();
        assert!(message.contains(named), "{kind}: {message}");
    }
}
