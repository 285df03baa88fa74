//! The states the studies solve, punch by punch: the comparison, the report's charts and jobs,
//! the claims and the dataset take their cases from here and ask each profile for everything
//! else (its contact, its edges, its references); a punch with a free band is found by its
//! contact. The stability and speed-accuracy studies still keep their own lists.

use ringcontact::methods::ladder::StudyCase;
use ringcontact::punch::{Contact, Exponent, PunchKind};

/// A state a study solves: the punch, its contact ratio `b/a` (the fixed annulus's hole, 0
/// otherwise) and the depth `d/h` of a punch whose contact edges are found (`None`: a flat
/// punch, pressed to a depth of its own scale).
pub(crate) type State = (PunchKind, f64, Option<f64>);

/// The built-in punches whose contact is a band with two free edges and no rim.
pub(crate) fn free_bands() -> Vec<PunchKind> {
    PunchKind::built_in(Contact::FreeBand)
}

/// The power-law punch `h (1 - (r/a)^n)`.
pub(crate) fn power(n: f64) -> PunchKind {
    PunchKind::power(Exponent::new(n).expect("a positive finite exponent"))
}

/// The FEM against the ring BEM on the committed meshes: every flat and recessed shape at
/// states that span its contact (the free bands' states, [`BAND_FEM_DEPTHS`], need gmsh).
pub(crate) fn fem_cross_check_states() -> Vec<State> {
    vec![
        (PunchKind::FLAT, 0.0, None),
        (PunchKind::FLAT_ANNULUS, 0.5, None),
        (PunchKind::FLAT_ANNULUS, 0.9, None),
        (PunchKind::CONE, 0.0, Some(0.5)),
        (PunchKind::CONE, 0.0, Some(2.0)),
        (PunchKind::SPHERE, 0.0, Some(1.5)),
        (PunchKind::SPHERE, 0.0, Some(3.5)),
        (power(1.5), 0.0, Some(2.0)),
        (power(3.0), 0.0, Some(2.0)),
    ]
}

/// Depths `d/h` at which the FEM is checked against the ring BEM on each free band (meshes
/// made by gmsh for the scene).
pub(crate) const BAND_FEM_DEPTHS: [f64; 2] = [0.1, 2.0];

/// The incremental stiffness identity `γ2'(b) = c γ(b/c) γ1'(b)`: each punch whose inner edge
/// is found, at contact ratios `b/a` where its contact is one annulus (the power law with
/// `n = 3` is one annulus only down to `b ≈ 0.55 a`, docs/conventions.md fact 8).
pub(crate) fn stiffness_identity_ratios() -> Vec<(PunchKind, &'static [f64])> {
    let mut cases: Vec<(PunchKind, &'static [f64])> = vec![
        (PunchKind::CONE, &[0.1, 0.5, 0.9]),
        (PunchKind::SPHERE, &[0.1, 0.5, 0.9]),
        (power(1.5), &[0.1, 0.5, 0.9]),
        (power(3.0), &[0.6, 0.9]),
    ];
    cases.extend(
        free_bands()
            .into_iter()
            .map(|band| (band, &[0.1, 0.5, 0.9][..])),
    );
    cases
}

/// Contact ratios `b/a` at which each free band's two edges are checked for `K = 0` by the
/// prescribed-band solve.
pub(crate) const BAND_EDGE_RATIOS: [f64; 2] = [0.3, 0.8];

/// The dataset's tables of the non-adhesive functions (`functions-*`): the fixed annulus, the
/// recessed shapes and the free bands.
pub(crate) fn dataset_function_punches() -> Vec<PunchKind> {
    let mut punches = vec![PunchKind::FLAT_ANNULUS];
    punches.extend(dataset_recessed_jkr_punches());
    punches.extend(free_bands());
    punches
}

/// The recessed punches whose JKR pull-off against `d0/h` the dataset tabulates (`jkr-*`).
pub(crate) fn dataset_recessed_jkr_punches() -> Vec<PunchKind> {
    vec![PunchKind::CONE, PunchKind::SPHERE, power(1.5)]
}

/// The concave punches whose functions the report charts: the paper's cone and sphere, two
/// power laws, `n = 1.5` (closes by a shrinking hole) and `n = 3` (closes from a disk and an
/// annulus), and the table punch of [`REPORT_TABLE_FILE`] (where the checkout has it).
pub(crate) fn report_concave_punches() -> Vec<PunchKind> {
    [
        Some(PunchKind::CONE),
        Some(PunchKind::SPHERE),
        Some(power(1.5)),
        Some(power(3.0)),
        report_table_punch(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// The report's table punch: the sphere's profile `g/h = 1 - (r/a)²` sampled at 21 points and
/// interpolated (PCHIP), charted beside the sphere it samples ([`REPORT_TABLE_SAMPLES`]).
pub(crate) const REPORT_TABLE_FILE: &str = "verify/profiles/sphere-21.csv";
/// The punch whose profile [`REPORT_TABLE_FILE`] samples.
pub(crate) const REPORT_TABLE_SAMPLES: PunchKind = PunchKind::SPHERE;

/// The table punch of [`REPORT_TABLE_FILE`], relative to the current directory when it is the
/// project's root, else under the project's root; `None` where no checkout holds the file (the
/// report then has no table chart). A job id names it by its label (`table-<sha256 prefix>`).
pub(crate) fn report_table_punch() -> Option<PunchKind> {
    let relative = std::path::Path::new(REPORT_TABLE_FILE);
    let path = if relative.is_file() {
        relative.to_path_buf()
    } else {
        crate::harness::settings::project_root().join(relative)
    };
    ringcontact::punch::TableProfile::load(&path)
        .ok()
        .map(PunchKind::new)
}

/// The punches whose functions the report charts: [`report_concave_punches`] and the free
/// bands.
pub(crate) fn report_profile_punches() -> Vec<PunchKind> {
    let mut punches = report_concave_punches();
    punches.extend(free_bands());
    punches
}

/// The convergence study the report shows: the sphere at `d = 1.5 h`.
pub(crate) const REPORT_STUDY: StudyCase = StudyCase {
    punch: PunchKind::SPHERE,
    eps: 0.0,
    depth: 1.5,
};

/// The pull-off simulations of the nightly run (`scripts/pulloff/run_all.py`'s cases):
/// `(punch, b/a, d0/h)`, the flat punch and annuli, and the paper's recessed punches at four
/// works of adhesion.
pub(crate) fn pulloff_simulations() -> Vec<(PunchKind, f64, f64)> {
    let mut cases = vec![
        (PunchKind::FLAT, 0.0, 0.0),
        (PunchKind::FLAT_ANNULUS, 0.5, 0.0),
        (PunchKind::FLAT_ANNULUS, 0.9, 0.0),
    ];
    for d0_over_h in [0.3, 1.0, 3.0, 10.0] {
        for punch in paper_recessed_punches() {
            cases.push((punch, 0.0, d0_over_h));
        }
    }
    cases
}

/// The recessed punches of the study the tool verifies, whose claims the report checks.
pub(crate) fn paper_recessed_punches() -> [PunchKind; 2] {
    [PunchKind::CONE, PunchKind::SPHERE]
}

/// The pull-off the report simulates live: `(punch, d0/h)`, the cone with its hole closed.
pub(crate) fn live_pulloff() -> (PunchKind, f64) {
    (PunchKind::CONE, 10.0)
}
