//! The ring BEM on a prescribed band `[b, c]` (any edges, either beyond the rim radius): the
//! force and both edges' stress intensity factors for any gap profile. Checked against an exact
//! similarity of the flat annulus and against the plane-strain Hertz solution that a narrow
//! toroidal contact approaches.

use std::f64::consts::PI;

use ringcontact::methods::RingBem;

const TOL: f64 = 1e-11;

/// Similarity: a flat band `[b c, c]` at depth `d` is the flat annulus of ratio `b` scaled by
/// `c`: `F = 2 E* d c γ(b)` and `K = E* d κ / sqrt(π c)`, i.e. the annulus's intensities over
/// `sqrt(c)`. The band's discretisation (edges at `b c` and `c`, parametrised between them) is not
/// the annulus's (`[b, 1]`), so agreement to rounding checks the band's geometry, weights and
/// intensities.
#[test]
fn a_flat_band_is_the_scaled_flat_annulus() {
    let solver = RingBem::new();
    for eps in [0.3, 0.8, 0.99] {
        let annulus = solver.flat(eps, TOL).unwrap();
        for c in [0.6, 1.7, 25.0] {
            let band = solver
                .prescribed_band(|_| 0.0, eps * c, c, 1.0, TOL)
                .unwrap();
            let force = 2.0 * c * annulus.gamma.unwrap();
            assert!(
                (band.force - force).abs() < 1e-12 * force,
                "eps {eps}, c {c}: F {} vs {force}",
                band.force
            );
            let (k_out, k_in) = (
                annulus.rim_stress_intensity / c.sqrt(),
                annulus.inner_stress_intensity / c.sqrt(),
            );
            assert!((band.outer_stress_intensity - k_out).abs() < 1e-11 * k_out);
            assert!((band.inner_stress_intensity - k_in).abs() < 1e-11 * k_out);
        }
    }
}

/// The non-adhesive contact of a torus `g = (r - a)²/(2ρ)` (`a = 1`) on a band of half-width `w`
/// whose both edges are free: the centre `m` and depth `d` make both intensities zero (the
/// intensities are linear in `d`; the centre is found by a secant). As `w/a -> 0` the ring is a
/// plane-strain cylinder, whose Hertz solution carries `P = π E* w² / (4ρ)` per unit length
/// (Johnson, *Contact Mechanics*, eq. 4.43), so `F -> 2π m P`. The ring's curvature corrects it at
/// relative order `(w/a)²` up to a logarithm: measured differences 6.3e-3, 1.9e-3, 5.7e-4,
/// 1.6e-4 for `w = 0.08 ... 0.01` (`ρ = a/2`), observed orders 1.71, 1.76, 1.79 rising toward 2.
#[test]
fn a_narrow_torus_approaches_the_plane_strain_hertz_cylinder() {
    let solver = RingBem::new();
    let rho = 0.5;
    let gap = |r: f64| (r - 1.0) * (r - 1.0) / (2.0 * rho);
    let mut previous: Option<f64> = None;
    for w in [0.08, 0.04, 0.02, 0.01] {
        // Both edges free at centre m: d from the inner edge, residual at the outer one.
        let residual = |m: f64| -> (f64, f64, f64) {
            let at = |d: f64| {
                solver
                    .prescribed_band(gap, m - w, m + w, d, TOL)
                    .unwrap_or_else(|e| panic!("w {w}, m {m}: {e}"))
            };
            let (zero, unit) = (at(0.0), at(1.0));
            let slope_in = unit.inner_stress_intensity - zero.inner_stress_intensity;
            let d = -zero.inner_stress_intensity / slope_in;
            let slope_out = unit.outer_stress_intensity - zero.outer_stress_intensity;
            let force = zero.force + d * (unit.force - zero.force);
            (zero.outer_stress_intensity + d * slope_out, d, force)
        };
        let (mut m0, mut m1) = (1.0, 1.0 + 0.1 * w * w);
        let (mut r0, mut r1) = (residual(m0).0, residual(m1).0);
        for _ in 0..30 {
            if r1 == r0 || (m1 - m0).abs() < 1e-14 {
                break;
            }
            let m2 = m1 - r1 * (m1 - m0) / (r1 - r0);
            (m0, r0) = (m1, r1);
            m1 = m2;
            r1 = residual(m1).0;
        }
        let (res, d, force) = residual(m1);
        let hertz = 2.0 * PI * m1 * PI * w * w / (4.0 * rho);
        let error = (force - hertz).abs() / hertz;
        println!(
            "w {w}: centre {m1:.10}, d {d:.6e}, F {force:.10e}, Hertz {hertz:.10e}, \
             relative difference {error:.2e}, residual {res:.1e}"
        );
        assert!(
            res.abs() < 1e-12,
            "w {w}: the edges are not both free ({res:e})"
        );
        assert!(error < 1e-2, "w {w}: {error:e} from the Hertz cylinder");
        if let Some(p) = previous {
            let order = (p / error).log2();
            println!("  order {order:.2}");
            assert!(
                (1.5..=2.2).contains(&order),
                "w {w}: observed order {order:.2}, expected about 2 (w² with a logarithm)"
            );
        }
        previous = Some(error);
    }
}
