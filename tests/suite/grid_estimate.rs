//! The grid BEM's error estimate on a single grid (`bem/grid_estimate.rs` of the library) bounds
//! its actual error against the ring BEM at 1e-12 (the yardstick, independent: spectral collocation
//! on rings, no grid), for each output: the `γ`s relative, the free edges absolute. A sample of the
//! 192 states it was measured on, every punch, depth and force control, 64² and 128² cells, and the
//! hardest: the sphere's small hole near full contact (`d = 2.95 h`) on 256² cells.

use ringcontact::methods::{self, Method, MethodOptions};
use ringcontact::scene::SceneSpec;
use ringcontact::solution::Solution;

/// The scene of `keywords` (the Python package's flat scene keys) solved by `method`; the ring
/// BEM at 1e-12.
fn solve(keywords: &str, method: Method, grid: Option<usize>) -> Solution {
    let serde_json::Value::Object(mut object) = serde_json::from_str(keywords).unwrap() else {
        panic!("{keywords} is not an object");
    };
    if grid.is_none() {
        object.insert("tolerance".into(), serde_json::json!(1e-12));
    }
    let scene = SceneSpec::from_keywords(object, "test", None)
        .and_then(SceneSpec::validate)
        .unwrap();
    let options = MethodOptions {
        grid,
        ..MethodOptions::default()
    };
    methods::solve_with(&scene, method, &options).unwrap()
}

#[test]
fn the_estimate_bounds_every_outputs_actual_error() {
    let states = [
        r#"{"punch": "flat"}"#,
        r#"{"punch": "flat-annulus", "inner_radius": 0.5}"#,
        r#"{"punch": "cone", "depth": 1.0}"#,
        r#"{"punch": "cone", "force": 1.5}"#,
        r#"{"punch": "sphere", "depth": 2.0}"#,
        r#"{"punch": "sphere", "force": 1.0}"#,
        r#"{"punch": "power", "exponent": 1.5, "depth": 1.25}"#,
        r#"{"punch": "torus", "tube_radius": 0.5, "force": 0.3}"#,
        r#"{"punch": "torus", "tube_radius": 0.5, "depth": 1.0}"#,
        r#"{"punch": "sphere", "depth": 2.95}"#,
    ];
    let mut checked = 0;
    for state in states {
        let reference = solve(state, Method::RingBem, None);
        let grids: &[usize] = if state.contains("2.95") {
            &[64, 128, 256]
        } else {
            &[64, 128]
        };
        for &n in grids {
            let grid = solve(state, Method::GridBem, Some(n));
            let Some(estimate) = grid.error_estimate else {
                // Only a ring too narrow for the coarser levels has none, and says so.
                assert!(grid.provenance.contains("no error estimate"), "{state}");
                continue;
            };
            let relative = |a: Option<f64>, b: Option<f64>| match (a, b) {
                (Some(a), Some(b)) => (a - b).abs() / b.abs(),
                _ => 0.0,
            };
            let a = reference.rim_radius;
            let errors = [
                ("gamma", relative(grid.gamma, reference.gamma)),
                ("gamma1", relative(grid.gamma1, reference.gamma1)),
                ("gamma2", relative(grid.gamma2, reference.gamma2)),
                ("eps", (grid.eps - reference.eps).abs()),
                (
                    "outer edge",
                    (grid.outer_radius - reference.outer_radius).abs() / a,
                ),
            ];
            for (name, error) in errors {
                assert!(
                    error <= estimate,
                    "{state} on {n}²: {name} off by {error:.2e}, estimate {estimate:.2e}"
                );
            }
            // The estimate is a bound of the right size, not a blanket: within 30x of the
            // largest actual error (measured: 1.5x to 20x).
            let largest = errors.iter().map(|e| e.1).fold(0.0, f64::max);
            assert!(
                estimate < 30.0 * largest,
                "{state} on {n}²: estimate {estimate:.2e}, largest error {largest:.2e}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 17, "only {checked} estimates checked");
}
