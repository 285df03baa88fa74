//! `verify adhesion`: the Maugis-Dugdale pull-off of one punch at one Tabor parameter, or the
//! sweep over the Tabor parameter.

use serde::Serialize;

use super::{message, refuse_non_finite, to_json, Reply};
use crate::cli::args::AdhesionArgs;
use crate::harness::progress::Progress;
use crate::harness::studies::dugdale_sweep;
use ringcontact::adhesion;
use ringcontact::dugdale::{
    self, law, Control, DugdaleLaw, DugdalePulloff, DugdaleSolver, FaceParameters,
};
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
    /// The JKR limit's pull-off `F/F0` under this control (`verify jkr`: Kendall's -1 for the
    /// whole face, the governing edge's for a fixed annulus, the annular pull-off for a concave
    /// punch; `null` where that has none, `jkr_note` saying why).
    jkr_pulloff_force: Option<f64>,
    /// Why there is no JKR pull-off to read against.
    #[serde(skip_serializing_if = "Option::is_none")]
    jkr_note: Option<String>,
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
    let parameters = FaceParameters {
        eps: args.eps,
        d0_over_h: args.d0h,
    };
    dugdale::check_face(&punch, parameters).map_err(message)?;
    let solver = DugdaleSolver::new();
    if args.sweep {
        if args.tabor.is_some() {
            return Err("--sweep runs its own Tabor parameters (0.05 to 100); drop --tabor".into());
        }
        let out = crate::cli::output_directory(args.out.as_deref(), "reports/adhesion");
        let mut bar = Progress::new("sweep", 40);
        let jkr = jkr_limits(&punch, parameters)?.map(Result::ok);
        let sweep = dugdale_sweep::sweep(&solver, &punch, parameters, args.tol, jkr, &out, |s| {
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
    let [at_load, at_grips] = jkr_limits(&punch, parameters)?;
    let jkr = match control {
        Control::Load => at_load,
        Control::Grips => at_grips,
    };
    let pulloff = solver
        .pulloff(&punch, parameters, law, control, args.tol)
        .map_err(message)?;
    let answer = Answer {
        range_over_d0: law::WORK / law.tension(),
        zone_length_over_a: law.zone_length(),
        jkr_pulloff_force: jkr.as_ref().ok().copied(),
        jkr_note: jkr.err(),
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

/// The JKR limit's pull-off force `F/F0` of `punch` under fixed load and fixed grips (checked
/// by [`dugdale::check_face`]), which the Dugdale pull-off tends to (`verify jkr`): Kendall's for
/// the whole face, the governing edge's critical force for a fixed annulus, the annular
/// pull-off (the rim criterion included) for a concave punch; `Err(why)` where it has none.
fn jkr_limits(
    punch: &PunchKind,
    parameters: FaceParameters,
) -> Result<[Result<f64, String>; 2], String> {
    match (punch.contact(), parameters) {
        (Contact::FixedAnnulus, FaceParameters { eps: Some(eps), .. }) => {
            let jkr = adhesion::fixed_annulus(&RingBem::new(), eps).map_err(message)?;
            let force = if jkr.governing_edge == "inner" {
                jkr.fc_inner
            } else {
                jkr.fc_outer
            };
            Ok([Ok(force), Ok(force)])
        }
        (
            Contact::RimAndFreeInner,
            FaceParameters {
                d0_over_h: Some(s), ..
            },
        ) => {
            let jkr = adhesion::concave(&RingBem::new(), punch.clone(), s).map_err(message)?;
            let annular = |critical: Option<adhesion::Critical>, note: Option<String>| {
                critical.map(|c| c.force).ok_or_else(|| {
                    format!(
                        "verify jkr has no annular pull-off here: {}",
                        note.unwrap_or_default()
                    )
                })
            };
            Ok([
                annular(jkr.fixed_load, jkr.fixed_load_note),
                annular(jkr.fixed_grips, jkr.fixed_grips_note),
            ])
        }
        _ => Ok([Ok(-1.0), Ok(-1.0)]),
    }
}

fn text(answer: &Answer) -> String {
    let p = &answer.pulloff;
    let [inner, outer] = p.contact;
    let contact = if p.loaded_region[0] >= 1.0 {
        "none, no zone left (the punch came away gradually, the force falling to zero)".to_string()
    } else if outer <= inner {
        "none (the cohesive zone alone holds the surface)".to_string()
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
        answer.eps.map(|e| format!(" b/a = {e}")).unwrap_or_default()
            + &p.d0_over_h.map(|s| format!(" d0/h = {s}")).unwrap_or_default(),
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
    out += &match (answer.jkr_pulloff_force, &answer.jkr_note) {
        (Some(force), _) => format!("  JKR limit       F/F0 = {force:.6} (verify jkr)\n"),
        (None, note) => format!(
            "  JKR limit       none: {}\n",
            note.as_deref().unwrap_or("")
        ),
    };
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
