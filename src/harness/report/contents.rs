//! What a report holds beyond its comparison tables, as data: the pull-off points, the paper's
//! claims with their verdicts, the headline count of checks and the names of the chart files
//! the tables refer to. Written by [`crate::harness::report::document`], shown by
//! [`crate::harness::report::tables`].

use serde::Serialize;

use crate::harness::studies::convergence;
use crate::harness::studies::speed_accuracy::SpeedAccuracy;

/// Pull-off force `-F/F0` of a concave punch (or a free band) at one `d0/h` by each route.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct PulloffPoint {
    pub punch: String,
    pub d0_over_h: f64,
    /// Converged solutions, annular branch, fixed load (absent: no stable annular state).
    pub fixed_load: Option<f64>,
    /// The paper's route on the paper's fitted formulas.
    pub paper_fits: Option<f64>,
    /// From full contact (rim criterion; absent for a free band, which has no rim).
    pub full_contact: Option<f64>,
    /// A free band: fixed grips (both edges Griffith, the minimum of the depth).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed_grips: Option<f64>,
    /// A free band: the plane-strain JKR cylinder's fixed-load pull-off over the ring, the
    /// narrow-band asymptote.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plane_strain: Option<f64>,
}

/// Everything the report holds beyond the comparison tables.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct ReportExtras {
    pub speed_accuracy: Vec<SpeedAccuracy>,
    pub convergence: Vec<convergence::Study>,
    pub pulloff: Vec<PulloffPoint>,
    /// The paper's claims checked by this run.
    pub verdicts: Vec<Verdict>,
    /// The stored pull-off simulations (`verify/pulloff/`).
    pub pulloff_simulations: Vec<crate::harness::records::pulloff::PulloffRecord>,
    /// This run's single pull-off simulation (linear gap, `d0/h = 10`, the smallest default range),
    /// or why it failed.
    pub pulloff_live: std::result::Result<ringcontact::cohesive::study::LiveSimulation, String>,
    /// Tamaas's pull-off (stored, `verify/peers/adhesion/`) against this run's simulations.
    #[serde(default)]
    pub adhesion_peers: Vec<crate::harness::records::adhesion_peers::AdhesionPeerComparison>,
    /// Fresh peer and pull-off results against the committed baselines (`--fresh DIR`).
    #[serde(default)]
    pub baselines: Vec<crate::harness::records::baselines::BaselineCheck>,
    /// The stored peer results graded against the converged references by `verify grade`'s
    /// code path ([`crate::harness::grade`]); none without stored results.
    #[serde(default)]
    pub peer_grading: Option<crate::harness::grade::Grading>,
    /// The checks counted, failed and not run (the report's first line).
    #[serde(default)]
    pub headline: Headline,
    pub wall_s: f64,
}

/// One claim of the paper, the numbers of this run, and the verdict.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Verdict {
    pub claim: String,
    pub numbers: String,
    pub verdict: String,
}

/// Check the paper's claims with this run's converged solutions.
/// File of the live simulation's force-displacement chart.
pub const PULLOFF_CURVE_CHART: &str = "pulloff-curve.svg";
/// File of the chart of a stored study's curves, the ranges that left the branch among them.
pub const PULLOFF_BRANCHES_CHART: &str = "pulloff-branches.svg";

/// File of the chart of the annular branch: simulated pulls against the JKR route's branch.
pub const PULLOFF_ANNULAR_CHART: &str = "pulloff-annular.svg";

/// File of the chart of our pull-off curves against Tamaas's.
pub const ADHESION_PEER_CHART: &str = "pulloff-tamaas.svg";

/// What a report checked: how many checks, how many failed, and what was not run and why.
#[derive(Clone, Debug, Default, Serialize, serde::Deserialize)]
pub struct Headline {
    pub checks: usize,
    pub failed: usize,
    /// `(count, reason)` of the checks left out (a stored result whose mesh needs gmsh, ...).
    pub not_run: Vec<(usize, String)>,
    /// `(group, checks in it)`, in the report's order.
    pub groups: Vec<(String, usize)>,
}

impl Headline {
    /// `**80 checks, 0 failed, 10 not run: need gmsh (...).** ring BEM against ...: 28; ...`
    pub(crate) fn sentence(&self) -> String {
        let not_run: usize = self.not_run.iter().map(|(n, _)| n).sum();
        let mut first = format!("{} checks, {} failed", self.checks, self.failed);
        match self.not_run.as_slice() {
            [] => {}
            [(_, why)] => first += &format!(", {not_run} not run: {why}"),
            reasons => {
                let reasons: Vec<String> = reasons
                    .iter()
                    .map(|(n, why)| format!("{n} {why}"))
                    .collect();
                first += &format!(", {not_run} not run: {}", reasons.join("; "));
            }
        }
        let groups: Vec<String> = self
            .groups
            .iter()
            .map(|(name, n)| format!("{name}: {n}"))
            .collect();
        format!("**{first}.** {}.", groups.join("; "))
    }
}
