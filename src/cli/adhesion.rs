//! `verify adhesion`: the Maugis-Dugdale pull-off of one punch at one Tabor parameter, or the
//! sweep over the Tabor parameter.

use serde::Serialize;

use super::{message, refuse_non_finite, to_json, Reply};
use crate::cli::args::AdhesionArgs;
use crate::harness::progress::Progress;
use crate::harness::studies::dugdale_sweep;
use ringcontact::adhesion;
use ringcontact::dugdale::{self, law, Control, DugdaleLaw, DugdalePulloff, DugdaleSolver};
use ringcontact::methods::RingBem;
use ringcontact::punch::{Contact, PunchKind};
use ringcontact::reference::dugdale_flat;

/// The answer of `verify adhesion --json`: the pull-off and what to read it against.
#[derive(Serialize)]
struct Answer {
    #[serde(flatten)]
    pulloff: DugdalePulloff,
    /// `b/a` of a fixed annulus.
    #[serde(skip_serializing_if = "Option::is_none")]
    eps: Option<f64>,
    /// The range `δc/d0 = sqrt(2)/(π λ)`.
    range_over_d0: f64,
    /// The cohesive zone's length at a crack tip in the JKR limit, `ℓ/a = 1/λ²`.
    zone_length_over_a: f64,
    /// The JKR limit's pull-off `F/F0` (`verify jkr`: Kendall's -1 for the whole face, the
    /// governing edge's for a fixed annulus).
    jkr_pulloff_force: f64,
    /// The flat face's closed form (`reference::dugdale_flat`), where it applies.
    closed_form_force: Option<f64>,
    units: &'static str,
}

const UNITS: &str = "forces in F0 = sqrt(8 pi E* dw a^3) (negative: tensile), depths in \
                     d0 = sqrt(2 pi a dw / E*), radii in a";

/// `verify adhesion`.
pub fn adhesion(args: AdhesionArgs) -> Result<Reply, String> {
    let punch = super::punch_kind_or_free_band(args.punch, args.exponent, args.profile.as_deref())?;
    let control = match args.control.as_str() {
        "grips" => Control::Grips,
        _ => Control::Load,
    };
    dugdale::check_face(&punch, args.eps).map_err(message)?;
    let jkr_force = jkr_limit(&punch, args.eps)?;
    let solver = DugdaleSolver::new();
    if args.sweep {
        if args.tabor.is_some() {
            return Err("--sweep runs its own Tabor parameters (0.05 to 100); drop --tabor".into());
        }
        let out = crate::cli::output_directory(args.out.as_deref(), "reports/adhesion");
        let mut bar = Progress::new("sweep", 40);
        let sweep =
            dugdale_sweep::sweep(&solver, &punch, args.eps, args.tol, jkr_force, &out, |s| {
                bar.tick(s)
            })
            .map_err(message)?;
        if args.json {
            return Ok(Reply::ok(to_json(&sweep.rows)?));
        }
        let files: Vec<String> = sweep
            .files
            .iter()
            .map(|f| f.display().to_string())
            .collect();
        return Ok(Reply::ok(
            sweep.table.to_terminal() + &format!("  wrote {}\n", files.join(", ")),
        ));
    }
    let tabor = args
        .tabor
        .ok_or("give --tabor LAMBDA (the Tabor parameter, > 0) or --sweep")?;
    let law = DugdaleLaw::new(tabor).map_err(message)?;
    let pulloff = solver
        .pulloff(&punch, args.eps, law, control, args.tol)
        .map_err(message)?;
    let answer = Answer {
        range_over_d0: law::WORK / law.tension(),
        zone_length_over_a: law.zone_length(),
        jkr_pulloff_force: jkr_force,
        closed_form_force: (punch.contact() == Contact::Disk)
            .then(|| dugdale_flat::pulloff(tabor).map(|p| p.force))
            .flatten(),
        units: UNITS,
        eps: args.eps,
        pulloff,
    };
    refuse_non_finite(&format!("adhesion {punch} --tabor {tabor}"), &answer)?;
    Ok(Reply::ok(if args.json {
        to_json(&answer)?
    } else {
        text(&answer)
    }))
}

/// The JKR limit's pull-off force `F/F0` of `punch` (checked by [`dugdale::check_face`]),
/// which the Dugdale pull-off tends to: Kendall's for the whole face, the governing edge's
/// critical force for a fixed annulus (`verify jkr`).
fn jkr_limit(punch: &PunchKind, eps: Option<f64>) -> Result<f64, String> {
    match (punch.contact(), eps) {
        (Contact::FixedAnnulus, Some(eps)) => {
            let jkr = adhesion::fixed_annulus(&RingBem::new(), eps).map_err(message)?;
            Ok(if jkr.governing_edge == "inner" {
                jkr.fc_inner
            } else {
                jkr.fc_outer
            })
        }
        _ => Ok(-1.0),
    }
}

fn text(answer: &Answer) -> String {
    let p = &answer.pulloff;
    let [inner, outer] = p.contact;
    let contact = if outer <= inner {
        "none (the whole face in tension)".to_string()
    } else if inner == 0.0 {
        format!("r/a <= {outer:.6}")
    } else {
        format!("{inner:.6} <= r/a <= {outer:.6}")
    };
    let mut out =
        format!(
        "{} punch{}, Dugdale law, Tabor parameter {} (range dc/d0 = {:.6}, zone length a/lambda^2 \
         = {:.3e} a), fixed {}\n",
        p.punch,
        answer.eps.map(|e| format!(" b/a = {e}")).unwrap_or_default(),
        p.tabor,
        answer.range_over_d0,
        answer.zone_length_over_a,
        p.control.name()
    );
    out += &format!(
        "  pull-off force  F/F0 = {:.10} (error bound {:.1e})\n",
        p.pulloff_force, p.pulloff_force_error
    );
    out += &format!(
        "  pull-off depth  d/d0 = {:.10} (error bound {:.1e})\n",
        p.pulloff_depth, p.pulloff_depth_error
    );
    out += &format!(
        "  detaching edge  {}; contact at pull-off {contact}; loaded (contact and zones) to \
         r/a = {:.6}\n",
        p.detaching_edge.name(),
        p.loaded_region[1]
    );
    out += &format!(
        "  JKR limit       F/F0 = {:.6} (verify jkr)\n",
        answer.jkr_pulloff_force
    );
    if let Some(closed) = answer.closed_form_force {
        out += &format!(
            "  closed form     F/F0 = {closed:.10} (a flat face, Sneddon's representation; \
             difference {:.1e})\n",
            p.pulloff_force - closed
        );
    }
    out += &format!(
        "  path            {} states, N = {} ring nodes (--json: path_depth, path_force)\n",
        p.path_depth.len(),
        p.nodes
    );
    out + &format!("  units: {UNITS}\n")
}
