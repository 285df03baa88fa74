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
    /// Punch shape: the key `punch` (its name), and `exponent` where the shape takes one.
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
    /// Tube radius `ρ` of a free band (length units; its depth scale is `h = a²/(2ρ)`).
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
    /// The grid BEM's grid (grid BEM only), written as keys of the solution itself (`grid`,
    /// `grid_extent`).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub grid_bem: Option<GridBemPart>,
    /// Why this method was chosen (`--method auto`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub selection: Option<String>,
    /// Pressure profile, ascending in `r` (empty for references without one).
    pub pressure: Vec<PressureSample>,
    /// How the numbers were obtained, in one line.
    pub provenance: String,
}

/// The grid BEM's part of a [`Solution`]: its grid. Its keys are the solution's own in JSON.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct GridBemPart {
    /// Cells per side of the square grid.
    #[serde(rename = "grid")]
    pub cells: usize,
    /// Half-size `L` of the grid's square `[-L, L]²`, in the scene's length unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid_extent: Option<f64>,
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
    /// Conditioning of the located free edge, `κ = |db/dd| d` (concave punches): the edge moves
    /// κ times a relative change of the depth; above about 1 its error is set by the
    /// displacement field's, not by the mesh at the edge.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_conditioning: Option<f64>,
}

impl Solution {
    /// Refuse a state that cannot exist before anyone sees it: every number finite, `0 <= eps < 1`,
    /// depth and force positive (the punch presses), the dimensionless functions positive, a
    /// non-negative error estimate, full contact (`eps = 0`) only where the punch can reach it
    /// (docs/conventions.md facts 4-5), finite pressures.
    pub fn check_plausible(&self) -> crate::error::Result<()> {
        self.check_finite()
            .and_then(|()| self.check_contact_ratio())
            .and_then(|()| self.check_pressing())
            .and_then(|()| self.check_signs())
            .and_then(|()| self.check_full_contact())
            .and_then(|()| self.check_pressures())
            .map_err(|reason| crate::error::Error::Implausible {
                method: self.method.clone(),
                state: format!(
                    "{} at eps = {:.6e}, d = {:.6e}, F = {:.6e}",
                    self.punch, self.eps, self.depth, self.force
                ),
                reason,
            })
    }

    /// Every number of the state finite.
    fn check_finite(&self) -> Result<(), String> {
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
        match named
            .into_iter()
            .find_map(|(name, value)| value.filter(|v| !v.is_finite()).map(|v| (name, v)))
        {
            Some((name, v)) => Err(format!("{name} is {v} (overflow or a failed solve)")),
            None => Ok(()),
        }
    }

    /// `0 <= b/a < 1`.
    fn check_contact_ratio(&self) -> Result<(), String> {
        if (0.0..1.0).contains(&self.eps) {
            return Ok(());
        }
        Err(format!(
            "the contact ratio b/a = {} is outside [0, 1)",
            crate::error::show(self.eps)
        ))
    }

    /// Depth and force positive: the punch presses (a zero is an underflow of the units).
    fn check_pressing(&self) -> Result<(), String> {
        if self.depth > 0.0 && self.force > 0.0 {
            return Ok(());
        }
        const UNDERFLOW: &str =
            "underflows f64, so choose units in which a, h, E* and the load are nearer 1";
        Err(format!(
            "a pressing punch needs depth > 0 and force > 0 (got d = {}, F = {}){}",
            crate::error::show(self.depth),
            crate::error::show(self.force),
            match (self.depth > 0.0, self.force > 0.0) {
                (true, false) if self.force == 0.0 => format!(": the force {UNDERFLOW}"),
                (false, true) if self.depth == 0.0 => format!(": the depth {UNDERFLOW}"),
                _ => String::new(),
            }
        ))
    }

    /// The dimensionless functions positive, the error estimate non-negative.
    fn check_signs(&self) -> Result<(), String> {
        for (name, value) in [
            ("gamma", self.gamma),
            ("gamma1", self.gamma1),
            ("gamma2", self.gamma2),
        ] {
            if let Some(v) = value.filter(|v| *v <= 0.0) {
                return Err(format!(
                    "{name} = {} must be positive",
                    crate::error::show(v)
                ));
            }
        }
        match self.error_estimate {
            Some(e) if e < 0.0 => Err(format!("negative error estimate {e}")),
            _ => Ok(()),
        }
    }

    /// Full contact (`b/a = 0`) only where the punch's contact can reach the axis: the full
    /// disk; a concave punch at or beyond its closure, or, whose hole never closes, within an
    /// error estimate at least as wide as its hole ([`crate::punch::Profile::hole_lower_bound`]).
    fn check_full_contact(&self) -> Result<(), String> {
        if self.eps != 0.0 {
            return Ok(());
        }
        match self.punch.contact() {
            Contact::Disk => Ok(()),
            Contact::FixedAnnulus => Err(format!(
                "the {} has a hole: b/a = 0 is the {}",
                self.punch.name(),
                crate::punch::PunchName::names(Some(Contact::Disk), ", ")
            )),
            Contact::FreeBand => Err(format!(
                "full contact: the {}'s contact never reaches the axis (its gap has a kink \
                 there, a dimple tensile at the apex in full contact)",
                self.punch.name()
            )),
            Contact::RimAndFreeInner => {
                let depth_over_hole = self.gamma1.unwrap_or(f64::NAN);
                match self.punch.profile().hole_lower_bound(depth_over_hole) {
                    Some(hole) => self.check_hole_within_estimate(depth_over_hole, hole),
                    None => self.check_closure(depth_over_hole),
                }
            }
        }
    }

    /// A hole that never closes but shrinks fast with depth (the linear gap's) may be resolved as
    /// closed when the estimate of `eps` is at least the hole there (`eps = 0` within the
    /// estimate then holds the true hole); a closed contact whose estimate is smaller is wrong.
    fn check_hole_within_estimate(&self, depth_over_hole: f64, hole: f64) -> Result<(), String> {
        let within_estimate = self.error_estimate.is_some_and(|e| e >= hole);
        if !depth_over_hole.is_nan() && within_estimate {
            return Ok(());
        }
        let punch = self.punch.label();
        Err(match self.error_estimate {
            None => format!(
                "full contact at d/h = {} without an error estimate: the {punch} never closes",
                crate::error::show(depth_over_hole)
            ),
            Some(estimate) => format!(
                "full contact at d/h = {}: the {punch} never closes, and its hole there is at \
                 least {} a (ring BEM), more than the error estimate {estimate:.1e}",
                crate::error::show(depth_over_hole),
                crate::error::show(hole)
            ),
        })
    }

    /// A concave punch's full contact only at or beyond its closure
    /// ([`crate::punch::Profile::closure`], less the method's own error in the depth); a hole that
    /// never closes may be resolved as closed only with an error estimate to say how wide it is.
    fn check_closure(&self, depth_over_hole: f64) -> Result<(), String> {
        let slack = 3.0 * self.error_estimate.unwrap_or(0.0).max(1e-9);
        match self.punch.closure().map(|(depth, _)| depth) {
            Some(closure) if depth_over_hole >= closure * (1.0 - slack) => Ok(()),
            None if self.error_estimate.is_some() => Ok(()),
            closure => Err(format!(
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

    /// Every pressure sample finite.
    fn check_pressures(&self) -> Result<(), String> {
        let Some(p) = self
            .pressure
            .iter()
            .find(|p| !p.r.is_finite() || !p.p.is_finite())
        else {
            return Ok(());
        };
        Err(format!(
            "pressure sample p({}) = {}{}",
            crate::error::show(p.r),
            crate::error::show(p.p),
            if p.r.is_finite() {
                " (beyond f64's range: choose units in which a, h, E* and the load are nearer 1)"
            } else {
                ""
            }
        ))
    }
}
