//! What every method returns for a scene: the physical state, the dimensionless functions of the
//! paper, the pressure profile, and what the answer cost and how accurate it is believed to be.

use serde::Serialize;

use crate::punch::{Contact, PunchKind};

/// One sample of the contact pressure.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct PressureSample {
    /// Radius `r` (length units of the scene).
    pub r: f64,
    /// Pressure `p(r)` (stress units of the scene), compression positive.
    pub p: f64,
}

/// The solution of a scene by one method.
///
/// Dimensionless functions (paper eqs. 1 and 5): flat punches `F = 2 E* d a γ(eps)`; concave
/// punches `d = h γ1(eps)`, `F = 2 E* h a γ2(eps)`.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Solution {
    /// Punch shape: the key `punch` (its name), and `exponent` for the power law.
    #[serde(flatten)]
    pub punch: PunchKind,
    /// Method that produced the numbers (`ring-bem`, `reference:<name>`, ...).
    pub method: String,
    /// Contact ratio `b/a` (0 for full contact).
    pub eps: f64,
    /// Indentation depth `d` of the rim (length units).
    pub depth: f64,
    /// Normal force `F` (force units), compression positive.
    pub force: f64,
    /// Inner contact radius `b` (length units).
    pub inner_radius: f64,
    /// Rim radius `a` (length units).
    pub rim_radius: f64,
    /// Outer contact radius `c` (length units): the contact is the annulus
    /// `inner_radius <= r <= outer_radius`. At the rim (`c = a`) for every punch with one.
    pub outer_radius: f64,
    /// Tube radius `ρ` of the torus (length units; its depth scale is `h = a²/(2ρ)`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tube_radius: Option<f64>,
    /// `γ = F / (2 E* d a)` (flat punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// `γ1 = d / h` (concave punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma1: Option<f64>,
    /// `γ2 = F / (2 E* h a)` (concave punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma2: Option<f64>,
    /// Mode-I stress intensity factor at the rim, `K = lim sqrt(2π(a - r)) p(r)` (stress·√length).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_intensity_rim: Option<f64>,
    /// Stress intensity factor at the inner edge `r = b` (0 at a free inner edge).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_intensity_inner: Option<f64>,
    /// Estimated error of the dimensionless results: the largest of the relative errors of
    /// `γ`/`γ1`/`γ2` and the absolute error of `eps`. `None` where the method has no estimate.
    pub error_estimate: Option<f64>,
    /// Wall time of the solve (seconds), including the error estimate.
    pub wall_s: f64,
    /// Number of unknowns of the finest discretisation used (0 for closed forms).
    pub unknowns: usize,
    /// Factorisations (ring BEM) or active-set iterations (FEM) spent.
    pub iterations: usize,
    /// Where the FEM's numbers come from (FEM only): its model, mesh and times, written as keys
    /// of the solution itself (`dofs`, `mesh`, `mesh_sha256`, ...).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub fem: Option<FemProvenance>,
    /// Complementarity residual of the contact solution (FEM concave punches, grid BEM).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub complementarity_residual: Option<f64>,
    /// Conditioning of the located free edge, `κ = |db/dd| d` (FEM concave punches): the edge
    /// moves κ times a relative change of the depth; above about 1 its error is set by the
    /// displacement field's, not by the mesh at the edge.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_conditioning: Option<f64>,
    /// Cells per side of the square grid (grid BEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<usize>,
    /// Grid BEM: half-size `L` of the grid's square `[-L, L]²`, in the scene's length unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid_extent: Option<f64>,
    /// Why this method was chosen (`--method auto`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub selection: Option<String>,
    /// Pressure profile, ascending in `r` (empty for references without one).
    pub pressure: Vec<PressureSample>,
    /// How the numbers were obtained, in one line.
    pub provenance: String,
}

/// The FEM's part of a [`Solution`]: the finest model's size, its mesh with where it came from,
/// the far field and where the time went. Its keys are the solution's own in JSON.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct FemProvenance {
    /// Degrees of freedom of the finest finite-element model used.
    pub dofs: usize,
    /// Mesh used, relative to the repository root.
    pub mesh: String,
    /// SHA-256 of that mesh file.
    pub mesh_sha256: String,
    /// Where the mesh came from: `committed`, `cache`, `gmsh` (made for this run) or `user`.
    pub mesh_origin: crate::mesh::provider::MeshOrigin,
    /// Version of the gmsh that made the mesh (generated meshes only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gmsh_version: Option<String>,
    /// Refinement applied to that file's mesh when it was read (corner halvings around the
    /// singular edges below the element sizes gmsh makes well; FEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh_refinement: Option<String>,
    /// Far-field treatment of the FEM domain: `fixed` or `boussinesq`.
    pub far_field: crate::discretisation::far_field::FarField,
    /// Where the finest FEM model's time went.
    pub fem_timings: crate::fem::solver::FemTimings,
    /// Element degree, 1, 2 or 3.
    pub degree: u8,
}

/// The conical punch's hole `b/a` at depth `d/h` (`γ1(b/a) = d/h`), ascending in depth: the ring
/// BEM (`verify solve --punch cone --eps B --method ring-bem`, its error estimates 1e-13 to
/// 1e-9). They follow `d/h ≈ (π/2) ln(a/b) + 1` (docs/conventions.md fact 5).
const CONE_HOLE_BY_DEPTH: [(f64, f64); 16] = [
    (1.789611, 0.5),
    (2.761971, 0.3),
    (3.462597, 0.2),
    (4.596961, 0.1),
    (5.699800, 0.05),
    (6.505729, 0.03),
    (7.143858, 0.02),
    (8.233465, 0.01),
    (9.322488, 5e-3),
    (10.124946, 3e-3),
    (10.761867, 2e-3),
    (11.850672, 1e-3),
    (12.939468, 5e-4),
    (13.741872, 3e-4),
    (14.378776, 2e-4),
    (15.467569, 1e-4),
];

/// Share of the interpolated hole that [`cone_hole_lower_bound`] keeps: `ln(a/b)` is nearly
/// linear in `d/h` (slope `2/π`), and interpolating it between the rows of
/// [`CONE_HOLE_BY_DEPTH`] gave 0.991-1.000 of the ring BEM's hole at 15 depths between them
/// (2 to 15 h).
const CONE_HOLE_BOUND_SHARE: f64 = 0.9;

/// The cone's hole deeper than [`CONE_HOLE_BY_DEPTH`] (where the ring BEM stops at `b/a =
/// 1e-4`): docs/conventions.md fact 5, `d/h = (π/2) ln(a/b) + c`, with `c = 1`. The table's `c` rises
/// toward it from below and has settled at 0.9998-1.0002 from `b/a = 1e-2` down, so
/// `b/a = exp(-2 (d/h - 1)/π)` is within 0.02 % of the hole at the table's end.
fn cone_hole_asymptote(depth: f64) -> f64 {
    (-2.0 * (depth - 1.0) / std::f64::consts::PI).exp()
}

/// A lower bound of the conical punch's hole `b/a` at depth `d/h`: `ln(b/a)` interpolated
/// linearly in `d/h` between the rows of [`CONE_HOLE_BY_DEPTH`], times
/// [`CONE_HOLE_BOUND_SHARE`]. Shallower than the first row, that row's hole times the share (the
/// hole shrinks as the punch presses deeper, so it is wider there); deeper than the last, the
/// asymptote ([`cone_hole_asymptote`]) times the share.
pub fn cone_hole_lower_bound(depth: f64) -> f64 {
    let rows = &CONE_HOLE_BY_DEPTH;
    if depth.is_nan() || depth <= rows[0].0 {
        // Shallower than the first row (or not a number): at least its hole.
        return CONE_HOLE_BOUND_SHARE * rows[0].1;
    }
    rows.windows(2).find(|pair| depth <= pair[1].0).map_or(
        CONE_HOLE_BOUND_SHARE * cone_hole_asymptote(depth),
        |pair| {
            let ((d0, b0), (d1, b1)) = (pair[0], pair[1]);
            let t = (depth - d0) / (d1 - d0);
            CONE_HOLE_BOUND_SHARE * (b0.ln() + t * (b1.ln() - b0.ln())).exp()
        },
    )
}

impl Solution {
    /// A concave punch's full contact only at or beyond its closure ([`crate::punch::Profile::closure`],
    /// less the method's own error in the depth); a hole that never closes may be resolved as
    /// closed only with an error estimate to say how wide it is.
    fn check_closure(
        &self,
        fail: impl Fn(String) -> crate::error::Result<()>,
    ) -> crate::error::Result<()> {
        let depth_over_hole = self.gamma1.unwrap_or(f64::NAN);
        let slack = 3.0 * self.error_estimate.unwrap_or(0.0).max(1e-9);
        match self.punch.closure().map(|(depth, _)| depth) {
            Some(closure) if depth_over_hole >= closure * (1.0 - slack) => Ok(()),
            None if self.error_estimate.is_some() => Ok(()),
            closure => fail(format!(
                "full contact at d/h = {}: the {} reaches it only at d/h >= {}",
                crate::error::show(depth_over_hole),
                self.punch,
                closure.map_or(
                    "infinity (its hole never closes)".into(),
                    crate::error::show
                )
            )),
        }
    }

    /// Refuse a state that cannot exist before anyone sees it: every number finite, `0 <= eps < 1`,
    /// depth and force positive (the punch presses), the dimensionless functions positive and
    /// consistent with the scene's `eps`, full contact (`eps = 0`) only for the flat punch and the
    /// spherical punch at `d >= 3h` (docs/conventions.md facts 4-5: the cone never reaches it), a
    /// non-negative error estimate, finite pressures.
    pub fn check_plausible(&self) -> crate::error::Result<()> {
        let fail = |reason: String| {
            Err(crate::error::Error::Implausible {
                method: self.method.clone(),
                state: format!(
                    "{} at eps = {:.6e}, d = {:.6e}, F = {:.6e}",
                    self.punch, self.eps, self.depth, self.force
                ),
                reason,
            })
        };
        let named = [
            ("eps", Some(self.eps)),
            ("depth", Some(self.depth)),
            ("force", Some(self.force)),
            ("inner radius", Some(self.inner_radius)),
            ("gamma", self.gamma),
            ("gamma1", self.gamma1),
            ("gamma2", self.gamma2),
            ("rim stress intensity", self.stress_intensity_rim),
            ("inner stress intensity", self.stress_intensity_inner),
            ("error estimate", self.error_estimate),
        ];
        for (name, value) in named {
            if let Some(v) = value {
                if !v.is_finite() {
                    return fail(format!("{name} is {v} (overflow or a failed solve)"));
                }
            }
        }
        if !(0.0..1.0).contains(&self.eps) {
            return fail(format!(
                "the contact ratio b/a = {} is outside [0, 1)",
                crate::error::show(self.eps)
            ));
        }
        if self.depth <= 0.0 || self.force <= 0.0 {
            return fail(format!(
                "a pressing punch needs depth > 0 and force > 0 (got d = {}, F = {}){}",
                crate::error::show(self.depth),
                crate::error::show(self.force),
                match (self.depth > 0.0, self.force > 0.0) {
                    (true, false) if self.force == 0.0 => {
                        ": the force underflows f64, so choose units in which a, h, E* and the \
                         load are nearer 1"
                    }
                    (false, true) if self.depth == 0.0 => {
                        ": the depth underflows f64, so choose units in which a, h, E* and the \
                         load are nearer 1"
                    }
                    _ => "",
                }
            ));
        }
        for (name, value) in [
            ("gamma", self.gamma),
            ("gamma1", self.gamma1),
            ("gamma2", self.gamma2),
        ] {
            if let Some(v) = value {
                if v <= 0.0 {
                    return fail(format!(
                        "{name} = {} must be positive",
                        crate::error::show(v)
                    ));
                }
            }
        }
        if let Some(e) = self.error_estimate {
            if e < 0.0 {
                return fail(format!("negative error estimate {e}"));
            }
        }
        if self.eps == 0.0 {
            match self.punch.contact() {
                Contact::Disk => {}
                Contact::FixedAnnulus => {
                    return fail("the flat annulus has a hole: b/a = 0 is the flat punch".into())
                }
                Contact::FreeBand => {
                    return fail(format!(
                        "full contact: the {}'s contact never reaches the axis (its gap is a \
                         conical dimple there, tensile at the apex in full contact)",
                        self.punch.name()
                    ))
                }
                // The cone by its gap (the power shape with n = 1 is checked by its closure).
                Contact::RimAndFreeInner
                    if self.punch.power_law_exponent() == Some(1.0)
                        && self.punch.exponent_parameter().is_none() =>
                {
                    // The cone never closes, but its hole shrinks fast with depth: a
                    // discretisation may resolve it as closed when its estimate of `eps` is at
                    // least the hole there (`eps = 0` within the estimate then holds the true
                    // hole). A closed contact whose estimate is smaller than the hole is wrong.
                    let depth_over_hole = self.gamma1.unwrap_or(f64::NAN);
                    let hole = cone_hole_lower_bound(depth_over_hole);
                    let within_estimate = self.error_estimate.is_some_and(|e| e >= hole);
                    if depth_over_hole.is_nan() || !within_estimate {
                        return fail(match self.error_estimate {
                            None => format!(
                                "full contact at d/h = {} without an error estimate: the \
                                 conical punch never closes",
                                crate::error::show(depth_over_hole)
                            ),
                            Some(estimate) => format!(
                                "full contact at d/h = {}: the conical punch never closes, and \
                                 its hole there is at least {} a (ring BEM), more than the error \
                                 estimate {estimate:.1e}",
                                crate::error::show(depth_over_hole),
                                crate::error::show(hole)
                            ),
                        });
                    }
                }
                Contact::RimAndFreeInner => self.check_closure(fail)?,
            }
        }
        if let Some(p) = self
            .pressure
            .iter()
            .find(|p| !p.r.is_finite() || !p.p.is_finite())
        {
            return fail(format!(
                "pressure sample p({}) = {}{}",
                crate::error::show(p.r),
                crate::error::show(p.p),
                if p.r.is_finite() {
                    " (beyond f64's range: choose units in which a, h, E* and the load are \
                     nearer 1)"
                } else {
                    ""
                }
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FEM's part is written as the solution's own keys (the JSON of `verify solve --json`
    /// before it had a part of its own), absent for other methods, and read back as it was.
    #[test]
    fn fem_provenance_keys_are_the_solutions_own() {
        let other = state(PunchKind::SPHERE, 0.2, 1.5, 2.0);
        let json = serde_json::to_value(&other).unwrap();
        assert!(json.get("dofs").is_none() && json.get("fem").is_none());
        let back: Solution = serde_json::from_value(json).unwrap();
        assert!(back.fem.is_none());
        let fem = Solution {
            fem: Some(FemProvenance {
                dofs: 1234,
                mesh: "meshes/disk-L2.msh".into(),
                mesh_sha256: "ab".repeat(32),
                mesh_origin: crate::mesh::provider::MeshOrigin::Committed,
                gmsh_version: None,
                mesh_refinement: None,
                far_field: crate::discretisation::far_field::FarField::Boussinesq,
                fem_timings: Default::default(),
                degree: 2,
            }),
            ..other
        };
        let json = serde_json::to_value(&fem).unwrap();
        assert_eq!(json["dofs"], 1234);
        assert_eq!(json["mesh"], "meshes/disk-L2.msh");
        assert_eq!(json["far_field"], "boussinesq");
        assert_eq!(json["degree"], 2);
        assert!(json.get("fem").is_none() && json.get("gmsh_version").is_none());
        let back: Solution = serde_json::from_value(json).unwrap();
        let part = back.fem.expect("the FEM's keys read back into its part");
        assert_eq!((part.dofs, part.degree), (1234, 2));
    }

    fn state(punch: PunchKind, eps: f64, depth: f64, force: f64) -> Solution {
        Solution {
            punch,
            method: "test".into(),
            eps,
            depth,
            force,
            inner_radius: eps,
            rim_radius: 1.0,
            outer_radius: 1.0,
            tube_radius: None,
            gamma: None,
            gamma1: Some(depth),
            gamma2: Some(0.5 * force),
            stress_intensity_rim: None,
            stress_intensity_inner: None,
            error_estimate: Some(1e-4),
            wall_s: 0.0,
            unknowns: 0,
            iterations: 0,
            fem: None,
            complementarity_residual: None,
            edge_conditioning: None,
            grid: None,
            grid_extent: None,
            selection: None,
            pressure: Vec::new(),
            provenance: String::new(),
        }
    }

    #[test]
    fn the_cone_hole_table_follows_the_asymptote_and_bounds_from_below() {
        // docs/conventions.md fact 5: γ1 grows like (π/2) ln(1/eps); with the constant 1 it holds to
        // 0.03 from eps = 0.1 down (independent of the ring BEM that made the table).
        for &(depth, hole) in &CONE_HOLE_BY_DEPTH {
            let asymptote = std::f64::consts::FRAC_PI_2 * (1.0 / hole).ln() + 1.0;
            if hole <= 0.1 {
                assert!(
                    (depth - asymptote).abs() < 0.03,
                    "{hole}: {depth} against {asymptote}"
                );
            }
        }
        for pair in CONE_HOLE_BY_DEPTH.windows(2) {
            assert!(pair[1].0 > pair[0].0 && pair[1].1 < pair[0].1);
        }
        // Between the rows the bound stays below the ring BEM's hole and within 20 % of it
        // (depths not in the table); before the table it is the first row's, beyond it none.
        // (At 1e-9: the ring BEM's values scatter by about 1e-10 of themselves at the holes of
        // 1e-4 a near d/h = 15, so 1e-10 is met or refused by rounding.)
        let bem = crate::bem::ring_contact::RingBemSolver::new();
        for depth in [2.0, 3.0, 4.0, 6.0, 8.0, 10.5, 12.0, 13.0, 14.0, 15.0] {
            let hole = bem
                .concave_at_depth(&PunchKind::CONE, depth, 1e-9)
                .unwrap()
                .eps;
            let bound = cone_hole_lower_bound(depth);
            assert!(
                bound <= hole && bound >= 0.8 * hole,
                "d/h = {depth}: bound {bound:e}, hole {hole:e}"
            );
        }
        assert_eq!(cone_hole_lower_bound(1.0), 0.9 * 0.5);
        assert_eq!(cone_hole_lower_bound(f64::NAN), 0.9 * 0.5);
        // Beyond it, the asymptote (c = 1): at the table's end within 0.02 % of the ring BEM's
        // hole, then 0.9 of it, falling by e^{-2/π} per h.
        let last = CONE_HOLE_BY_DEPTH[CONE_HOLE_BY_DEPTH.len() - 1];
        assert!((cone_hole_asymptote(last.0) / last.1 - 1.0).abs() < 2e-4);
        for depth in [16.0, 20.0, 60.0] {
            let bound = cone_hole_lower_bound(depth);
            assert_eq!(bound, 0.9 * cone_hole_asymptote(depth));
            assert!(bound > 0.0 && bound < last.1);
        }
    }

    #[test]
    fn an_underflowed_force_is_refused_with_short_numbers_and_the_cause() {
        let mut tiny = state(PunchKind::CONE, 0.45, 2e-301, 0.0);
        tiny.gamma2 = Some(1.8);
        let message = tiny.check_plausible().unwrap_err().to_string();
        assert!(message.contains("force underflows"), "{message}");
        assert!(message.contains("2.000000e-301"), "{message}");
        assert!(message.len() < 400, "{message}");
    }

    #[test]
    fn impossible_states_are_refused() {
        assert!(state(PunchKind::CONE, 0.45, 2.0, 3.6)
            .check_plausible()
            .is_ok());
        // A coarse mesh that lost its whole contact: eps = 1 with a positive force.
        assert!(state(PunchKind::CONE, 1.0, 2.0, 3.6)
            .check_plausible()
            .is_err());
        // Overflow.
        assert!(state(PunchKind::SPHERE, 0.3, 1.0, f64::INFINITY)
            .check_plausible()
            .is_err());
        // Force and depth of opposite signs.
        assert!(state(PunchKind::CONE, 0.45, 2.0, -3.6)
            .check_plausible()
            .is_err());
        // Full contact where it cannot exist: the cone with an estimate smaller than its hole
        // there (or without an estimate), and the sphere below d = 3h.
        assert!(state(PunchKind::CONE, 0.0, 5.0, 10.0)
            .check_plausible()
            .is_err());
        assert!(state(PunchKind::CONE, 0.0, 50.0, 100.0)
            .check_plausible()
            .is_ok());
        let mut without_estimate = state(PunchKind::CONE, 0.0, 50.0, 100.0);
        without_estimate.error_estimate = None;
        assert!(without_estimate.check_plausible().is_err());
        // At 13h the hole is 4.8e-4 a (ring BEM): closed within 8.2e-4 holds it (the FEM's P2
        // answer at --tol 1e-3), closed within 1e-4 does not; nor, at 5h (a hole of 7.8e-2 a),
        // closed within 5e-2.
        let mut closed_at_13 = state(PunchKind::CONE, 0.0, 13.0, 25.6);
        closed_at_13.error_estimate = Some(8.2e-4);
        assert!(closed_at_13.check_plausible().is_ok());
        closed_at_13.error_estimate = Some(1e-4);
        assert!(closed_at_13.check_plausible().is_err());
        let mut closed_at_5 = state(PunchKind::CONE, 0.0, 5.0, 10.0);
        closed_at_5.error_estimate = Some(5e-2);
        assert!(closed_at_5.check_plausible().is_err());
        // Deeper than the ring BEM's table: at 20h the hole is about 5.6e-6 a (asymptote).
        let mut closed_at_20 = state(PunchKind::CONE, 0.0, 20.0, 40.0);
        closed_at_20.error_estimate = Some(1e-5);
        assert!(closed_at_20.check_plausible().is_ok());
        closed_at_20.error_estimate = Some(1e-6);
        assert!(closed_at_20.check_plausible().is_err());
        assert!(state(PunchKind::SPHERE, 0.0, 2.5, 5.0)
            .check_plausible()
            .is_err());
        assert!(state(PunchKind::SPHERE, 0.0, 3.5, 6.3)
            .check_plausible()
            .is_ok());
    }
}
