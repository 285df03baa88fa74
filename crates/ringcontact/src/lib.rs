//! # ringcontact
//!
//! Cross-verification harness for rigid axisymmetric punches whose contact with an elastic
//! half-space is a ring: a flat face with a fixed hole, and concave punches whose linear or
//! parabolic gap opens a hole that the load sets (with the full disk as a check case, and any
//! axisymmetric profile of your own).
//!
//! **Conventions** (see `docs/conventions.md`): `E* = E/(1 - nu²)` of the half-space (rigid
//! punch); `a` the rim radius, `b` the inner contact radius, `eps = b/a`; `d` the indentation
//! depth of the rim, positive into the solid; `h` the depth of the concave hole; `F` the normal
//! force, positive in compression. Any consistent units; the dimensionless functions are
//! `F = 2 E* d a γ(eps)` (fixed annulus) and `d = h γ1(eps)`, `F = 2 E* h a γ2(eps)` (concave).
//!
//! A [`scene::Scene`] goes in, a [`solution::Solution`] comes out; every solver is a
//! [`methods::Method`] behind that one interface.
//!
//! ```
//! use ringcontact::methods::{self, Method};
//! use ringcontact::punch::PunchKind;
//! use ringcontact::scene::SceneSpec;
//!
//! // The built-in punch `flat` (a = E* = 1) pressed to d = 0.1: Boussinesq's F = 2 E* a d.
//! let flat = PunchKind::from_label("flat").expect("a built-in punch");
//! let scene = SceneSpec::default().shape(flat).depth(0.1).validate()?;
//! let solution = methods::solve(&scene, Method::RingBem)?;
//! assert!((solution.force - 0.2).abs() < 1e-9);
//! # Ok::<(), ringcontact::Error>(())
//! ```
//!
//! A punch of your own implements [`punch::Profile`]; `examples/` holds three short programs to
//! start from (`every_method`, `convergence_ladder`, `own_profile`).

pub mod adhesion;
pub mod bem;
pub mod choice;
pub mod cohesive;
pub mod discretisation;
pub mod dugdale;
pub mod error;
pub mod fem;
pub mod finite_guard;
pub mod fit;
pub mod heartbeat;
pub mod mesh;
pub mod methods;
pub mod numerics;
pub mod provenance;
pub mod punch;
pub mod reference;
pub mod scene;
pub mod solution;
pub mod sparse;

pub use error::{Error, Result};
