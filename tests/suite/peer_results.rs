//! Tamaas and ContactMechanics (stored by scripts/peers/run_peers.sh) against our grid BEM on the
//! same grids and profiles: forces within 1e-6 relative.

use ringcontact_verify::harness::records::peers::{self, PEER_AGREEMENT};

#[test]
fn stored_peer_results_agree_with_our_grid_bem() {
    let rows = peers::run(256).unwrap();
    assert!(
        rows.len() >= 16,
        "expected the stored peer suite, found {}",
        rows.len()
    );
    for package in ["tamaas", "contactmechanics"] {
        assert!(
            rows.iter().any(|r| r.stored.package == package),
            "no {package} results"
        );
    }
    for r in &rows {
        assert!(
            r.relative_difference.abs() <= PEER_AGREEMENT,
            "{}: {:e}",
            r.file,
            r.relative_difference
        );
    }
}
