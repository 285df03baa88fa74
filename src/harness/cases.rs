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

/// The flat punch of hole `b/a = eps`: the disk at 0, else the fixed annulus.
pub(crate) fn flat_punch(eps: f64) -> PunchKind {
    if eps == 0.0 {
        PunchKind::FLAT
    } else {
        PunchKind::FLAT_ANNULUS
    }
}

/// The state `(punch, d/h)` whose contact pressure the report draws by three methods.
pub(crate) const PRESSURE_PROFILE: (PunchKind, f64) = (PunchKind::SPHERE, 1.5);

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

/// The punches whose full-contact limit `γ1 - γ2 -> 1 - κ_n/(n + 1)` the comparison checks:
/// the paper's two recessed punches and a power law between them.
pub(crate) fn full_contact_limit_punches() -> Vec<PunchKind> {
    let [first, second] = paper_recessed_punches();
    vec![first, second, power(1.5)]
}

/// A problem of the speed-accuracy study: its name in report.json, its slug (job ids, file
/// names) and chart title, the punch and state (`b/a`; `d/h` of a recessed punch, `None` for
/// a flat one), the committed mesh family of its contact line, how the ring BEM's points are
/// made, and about how long its base points take (s).
pub(crate) struct SpeedProblem {
    pub(crate) name: &'static str,
    pub(crate) slug: &'static str,
    pub(crate) title: &'static str,
    pub(crate) kind: PunchKind,
    pub(crate) eps: f64,
    pub(crate) depth: Option<f64>,
    pub(crate) family: Option<&'static str>,
    pub(crate) ring_points: RingPoints,
    pub(crate) expected_s: f64,
}

/// How the speed-accuracy study makes a problem's ring-BEM points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RingPoints {
    /// The bare ring system at a few node counts (it converges geometrically).
    NodeCounts,
    /// The solver at tolerances 1e-2 to 1e-9, each point with the solver's estimate.
    EstimatedTolerances,
    /// The solver at tolerances 1e-2 to 1e-9.
    Tolerances,
}

/// The speed-accuracy study's problems, in the report's order: the flat annulus at two holes,
/// the sphere and the cone under depth control (the last two problems, the FEM's full solve
/// against FEniCSx on the meshes the FEM makes).
pub(crate) fn speed_problems() -> Vec<SpeedProblem> {
    vec![
        SpeedProblem {
            name: "FlatHalf",
            slug: "flat-annulus-0.5",
            title: "flat annulus b/a = 0.5, gamma",
            kind: PunchKind::FLAT_ANNULUS,
            eps: 0.5,
            depth: None,
            family: Some("annulus-0.5"),
            ring_points: RingPoints::NodeCounts,
            expected_s: 0.9,
        },
        SpeedProblem {
            name: "Sphere",
            slug: "sphere-1.5",
            title: "sphere d/h = 1.5, gamma2",
            kind: PunchKind::SPHERE,
            eps: 0.0,
            depth: Some(1.5),
            family: Some("disk"),
            ring_points: RingPoints::EstimatedTolerances,
            expected_s: 1.9,
        },
        SpeedProblem {
            name: "Cone",
            slug: "cone-2",
            title: "cone d/h = 2, gamma2",
            kind: PunchKind::CONE,
            eps: 0.0,
            depth: Some(2.0),
            family: None,
            ring_points: RingPoints::Tolerances,
            expected_s: 1.6,
        },
        SpeedProblem {
            name: "FlatThick",
            slug: "flat-annulus-0.3",
            title: "flat annulus b/a = 0.3, gamma",
            kind: PunchKind::FLAT_ANNULUS,
            eps: 0.3,
            depth: None,
            family: None,
            ring_points: RingPoints::Tolerances,
            expected_s: 0.9,
        },
    ]
}

/// The punches and states the stability study drives toward their limits.
pub(crate) struct StabilityPunches {
    /// The punch whose contact is the disk.
    pub(crate) disk: PunchKind,
    /// The punch whose contact is a fixed annulus.
    pub(crate) annulus: PunchKind,
    /// A recessed punch whose hole never closes, and depths `d/h` from the first touch to deep
    /// (its hole shrinks exponentially).
    pub(crate) open_hole: (PunchKind, Vec<f64>),
    /// A recessed punch whose hole closes (at `d = 3h`), and depths about its closure.
    pub(crate) closing_hole: (PunchKind, Vec<f64>),
    /// The FEM's recessed states `(punch, d/h)`.
    pub(crate) fem_states: Vec<(PunchKind, f64)>,
    /// The grid BEM's recessed states `(punch, d/h, cells per side)`.
    pub(crate) grid_states: Vec<(PunchKind, f64, usize)>,
}

/// The stability study's punches and states.
pub(crate) fn stability_punches() -> StabilityPunches {
    let (cone, sphere) = (PunchKind::CONE, PunchKind::SPHERE);
    StabilityPunches {
        disk: PunchKind::FLAT,
        annulus: PunchKind::FLAT_ANNULUS,
        open_hole: (cone.clone(), vec![1e-3, 0.01, 5.0, 10.0, 14.0, 40.0]),
        closing_hole: (sphere.clone(), vec![2.99, 2.999999, 3.0, 3.5]),
        fem_states: vec![
            (cone.clone(), 0.2),
            (cone.clone(), 8.0),
            (sphere.clone(), 2.95),
        ],
        grid_states: vec![
            (cone.clone(), 0.05, 64),
            (cone, 0.05, 512),
            (sphere, 2.999, 64),
        ],
    }
}
