//! A user's own profile whose contact is a free band (both edges free) runs in every method that
//! solves free bands, with nothing in the crate naming it.
//!
//! References: the built-in ring of parabolic section (an independent implementation of the same
//! gap, solved by the same methods) and, for a ring no built-in punch has, the agreement of two
//! independent discretisations (ring BEM and grid BEM) within the sum of their own estimates.

use ringcontact::adhesion;
use ringcontact::methods::RingBem;
use ringcontact::methods::{self, Method};
use ringcontact::punch::{Contact, Profile, PunchKind, PunchName};
use ringcontact::scene::SceneSpec;
use ringcontact::solution::Solution;

/// The ring of parabolic section written by a user: `ĝ(ρ) = (1 - ρ)²`, nothing but its gap.
#[derive(Debug)]
struct MyRing;

impl Profile for MyRing {
    fn name(&self) -> &str {
        "my-ring"
    }
    fn contact(&self) -> Contact {
        Contact::FreeBand
    }
    fn gap(&self, rho: f64) -> f64 {
        (1.0 - rho) * (1.0 - rho)
    }
    fn slope(&self, rho: f64) -> f64 {
        -2.0 * (1.0 - rho)
    }
    fn smooth_at_axis(&self) -> bool {
        false
    }
}

/// A ring no built-in punch has: lowest at `r0 = 0.8 a`, `ĝ(ρ) = ((ρ - 0.8)/0.8)²`.
#[derive(Debug)]
struct InnerRing;

impl Profile for InnerRing {
    fn name(&self) -> &str {
        "inner-ring"
    }
    fn contact(&self) -> Contact {
        Contact::FreeBand
    }
    fn gap(&self, rho: f64) -> f64 {
        ((rho - 0.8) / 0.8).powi(2)
    }
    fn slope(&self, rho: f64) -> f64 {
        2.0 * (rho - 0.8) / 0.64
    }
    fn smooth_at_axis(&self) -> bool {
        false
    }
    fn first_touch(&self) -> Option<(f64, f64)> {
        Some((0.8, 2.0 / 0.64))
    }
}

/// The unit ring (`a = E* = 1`, tube radius `a/2`, so `h = 1`) at `d/h = depth`.
fn solve(kind: PunchKind, depth: f64, method: Method) -> Solution {
    let scene = SceneSpec::default()
        .shape(kind)
        .rim_radius(1.0)
        .tube_radius(0.5)
        .depth(depth)
        .validate()
        .unwrap();
    methods::solve(&scene, method).unwrap()
}

fn torus() -> PunchKind {
    PunchName::Torus.with_exponent(None).unwrap()
}

#[test]
fn own_parabolic_ring_equals_the_built_in_one_on_the_ring_bem() {
    for depth in [0.05, 0.5, 3.0] {
        let own = solve(PunchKind::new(MyRing), depth, Method::RingBem);
        let built_in = solve(torus(), depth, Method::RingBem);
        let bound = own.error_estimate.unwrap() + built_in.error_estimate.unwrap();
        let difference = (own.force - built_in.force).abs() / built_in.force;
        assert!(
            difference <= bound,
            "d/h = {depth}: force {} against {} (relative {difference:.1e}, bound {bound:.1e})",
            own.force,
            built_in.force
        );
        assert!((own.eps - built_in.eps).abs() <= bound.max(1e-9));
        assert_eq!(own.punch.name(), "my-ring");
    }
}

#[test]
fn own_parabolic_ring_equals_the_built_in_one_on_the_grid_bem() {
    let own = solve(PunchKind::new(MyRing), 0.5, Method::GridBem);
    let built_in = solve(torus(), 0.5, Method::GridBem);
    // The same gap on the same cells: the same linear algebra, to rounding.
    assert!((own.force - built_in.force).abs() <= 1e-12 * built_in.force);
}

#[test]
fn own_parabolic_ring_has_the_built_in_ones_jkr_pulloff() {
    let solver = RingBem::new();
    let own = adhesion::band_jkr(&solver, &PunchKind::new(MyRing), 0.1).unwrap();
    let built_in = adhesion::band_jkr(&solver, &torus(), 0.1).unwrap();
    let (own_load, built_in_load) = (own.fixed_load.unwrap(), built_in.fixed_load.unwrap());
    assert!(
        (own_load.force - built_in_load.force).abs()
            <= own_load.error_bound + built_in_load.error_bound,
        "{} against {}",
        own_load.force,
        built_in_load.force
    );
    // Without `first_touch` the profile gives no narrow limit; the built-in ring gives it.
    assert!(own.plane_strain_fixed_load.is_none());
    assert!(built_in.plane_strain_fixed_load.is_some());
}

#[test]
fn a_ring_no_built_in_punch_has_agrees_between_ring_bem_and_grid_bem() {
    let ring = solve(PunchKind::new(InnerRing), 0.3, Method::RingBem);
    let grid = solve(PunchKind::new(InnerRing), 0.3, Method::GridBem);
    let bound = ring.error_estimate.unwrap() + grid.error_estimate.unwrap();
    let difference = (grid.force - ring.force).abs() / ring.force;
    eprintln!("grid BEM against ring BEM: {difference:.1e} (bound {bound:.1e})");
    assert!(
        difference <= bound,
        "force: ring BEM {} grid BEM {} (relative {difference:.1e}, bound {bound:.1e})",
        ring.force,
        grid.force
    );
    // The band lies around the ring's lowest circle, r0 = 0.8 a.
    assert!(ring.eps < 0.8 && ring.outer_radius > 0.8, "{ring:?}");
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn a_ring_no_built_in_punch_has_agrees_between_ring_bem_and_fem() {
    let ring = solve(PunchKind::new(InnerRing), 0.3, Method::RingBem);
    let fem = solve(PunchKind::new(InnerRing), 0.3, Method::Fem);
    let bound = ring.error_estimate.unwrap() + fem.error_estimate.unwrap();
    let difference = (fem.force - ring.force).abs() / ring.force;
    eprintln!("FEM against ring BEM: {difference:.1e} (bound {bound:.1e})");
    assert!(
        difference <= bound,
        "force: ring BEM {} FEM {} (relative {difference:.1e}, bound {bound:.1e})",
        ring.force,
        fem.force
    );
}
