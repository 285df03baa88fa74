//! Helpers shared by the integration tests.

/// Whether gmsh is there; when it is not, the tests that need generated meshes are skipped with
/// a message, unless `RINGCONTACT_REQUIRE_GMSH=1` (set by `.ci/run` after it installs gmsh).
pub fn gmsh_available(test: &str) -> bool {
    let root = ringcontact::mesh::provider::project_root();
    if ringcontact::mesh::gmsh::Gmsh::find(&root).is_some() {
        return true;
    }
    assert!(
        std::env::var("RINGCONTACT_REQUIRE_GMSH").as_deref() != Ok("1"),
        "{test}: RINGCONTACT_REQUIRE_GMSH=1 but gmsh was not found"
    );
    eprintln!("{test}: skipped, gmsh not found (bash scripts/install_gmsh.sh)");
    false
}
