//! The integration tests in one binary (each test binary links the whole library): one module
//! per theme, each with its own doc. `cargo test --release --test suite -- MODULE::` runs one.
//! Kept apart: `library_side_effects` (it checks the process's own state), `fuzz_inputs` and
//! `reproduce` (the nightly run gives them their long settings).

#[path = "../common/mod.rs"]
mod common;

mod adhesion;
mod cli;
mod code_shape;
mod dataset;
mod docs_commands;
mod dugdale;
mod examples;
mod fem_contact_band;
mod fem_far_field;
mod fem_manufactured;
mod fem_vs_ring_bem;
mod fenicsx_operator;
mod fenicsx_results;
mod fit;
mod grade;
mod grid_bem;
mod grid_estimate;
mod harness;
mod harness_integrity;
mod layering;
mod library_cases;
mod linear_solver_contract;
mod mesh_roles;
mod msh_reader;
mod own_band;
mod peer_results;
mod plan;
mod power_law_punch;
mod prescribed_band;
mod pulloff;
mod report_browser;
mod ring_bem_references;
mod scripts;
mod table_and_batch;
mod table_punch;
mod torus_fem;
mod torus_jkr;
mod torus_pulloff;
mod torus_punch;
