//! `wear`: how a cam profile wears over running hours.
//!
//! * `model: "archard"` (default): Archard wear `dh/dt = k p v_s` per cam-surface point over the
//!   steady cam cycle of `cam_cycle` (same pair, same physics: kinematics, loads, Hertz contact,
//!   film and Greenwood–Tripp load share, roller slip), with worn-profile evolution every update
//!   interval until the running time or the wear limit. Physics: `physics::wear::{archard,
//!   deposit, evolution}`.
//!   Fidelity `accurate` (and the numerical angles of `auto`): the numerical line-contact EHL film
//!   at every angle of every cycle, whose pressure (spike and exit constriction included) and
//!   local Greenwood–Tripp asperity pressure replace the Hertz band (`physics::wear::archard`);
//!   the cost is bounded by a budget of numerical work (see `validate`).
//! * `model: "irgashev"`: seed 004's method (Tables 1–5, eq. 1–15) on the paper's multi-arc cam and
//!   spherical tappet, reproduced as printed; its inconsistencies are documented in
//!   `physics::wear::irgashev`. Physics: `physics::wear::irgashev`.

use super::cam_cycle::{CamCycle, CamCycleSpec, CamOutput, FollowerSpec, LoadSpec, ProfileSpec, ThermalPair};
use super::common::{cam_spec_path, composite_sigma};
use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::cam::summary::FlatFace;
use crate::physics::contact::contact_modulus;
use crate::physics::film::{FilmFormula, FilmModelId, Fidelity};
use super::contact::LubricatedContact;
use crate::physics::wear::irgashev::{self, ArcRole, IrgashevSi};
use crate::physics::wear::{evolve, ArchardParams, LoadShare, Stop, WearRun};
use crate::physics::{ensure_finite, Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use utoipa::ToSchema;

mod spec;
mod result;
mod solve;
pub use spec::*;
pub use result::*;
use solve::*;

pub struct Wear;

/// Most profile updates of one run at fidelity `fast`, including the ones added for stability
/// (each is one cam cycle).
pub const MAX_UPDATES: usize = 5_000;

/// At fidelity `accurate`/`auto` a run takes at most this many times its planned updates
/// (`ceil(hours / update_interval_hours)`): the stability cut may shorten intervals, but the
/// numerical work stays within the validated budget.
pub const NUMERICAL_UPDATE_FACTOR: usize = 2;

/// The unit of numerical work of the budget: one cam cycle of 720 angles on 192-node EHL grids
/// (`cam_cycle`'s default accurate cycle, ≈ 1–2.5 s in release on the seed cases).
pub const STANDARD_CYCLE_WORK: usize = 720 * 192;

// ---------------------------------------------------------------- spec

// ---------------------------------------------------------------- result

// ---------------------------------------------------------------- conversion

impl Kind for Wear {
    const NAME: &'static str = "wear";
    const SOLVER_VERSION: &'static str = "wear-10";
    const DESCRIPTION: &'static str = "Cam wear over running hours: Archard wear over the cam cycle (asperity load share in \
        mixed lubrication, roller slip) with worn-profile evolution, or seed 004's method (model irgashev).";
    const TABLES: &'static [&'static str] = &["series", "rows", "history", "follower_face"];
    const KEY_FIGURES: &'static [&'static str] = &["/summary/max_wear_depth", "/summary/max_wear_angle_deg", "/summary/valve_lift_loss", "/summary/valve_lift_loss_lash_adjusted", "/summary/hours_to_limit", "/summary/final_min_film", "/summary/final_max_pressure"];
    type Spec = WearSpec;
    type Output = WearResult;

    fn example() -> Value {
        json!({
            "cycle": {
                "cam": {
                    "profile": {"type": "rise_return", "base_radius": 0.018, "lift": 0.008, "rise_start_deg": 90.0,
                                "rise_deg": 90.0, "return_deg": 90.0, "law": "cycloidal"},
                    "width": 0.012,
                    "roughness_rq": 2e-7
                },
                "follower": {"type": "flat_faced", "roughness_rq": 1e-7},
                "operation": {"speed_rpm": 3000.0},
                "load": {"type": "valve_train", "spring_preload": 450.0, "spring_stiffness": 38000.0, "moving_mass": 0.25},
                "lubricant": {"viscosity": 0.01, "pressure_viscosity": 2.2e-8},
                "angles": 720
            },
            "hours": 1000.0,
            "update_interval_hours": 100.0,
            "wear_coefficient": {"dimensionless": 1e-7, "hardness": 7e9}
        })
    }

    fn validate(spec: &WearSpec, limits: &Limits, v: &mut Validation) {
        // The pair, as cam_cycle validates it.
        v.under("/cycle", |v| {
            CamCycle::validate(&spec.cycle_spec(), limits, v);
            v.check(
                spec.cycle.outputs == super::cam_cycle::default_outputs(),
                "/outputs",
                "the wear model chooses what its cycles compute: leave `outputs` out",
            );
            v.check(spec.cycle.profile_angles_deg.is_empty(), "/profile_angles_deg", "wear keeps no pressure profiles: leave it out");
            v.check(spec.cycle.ehl.thermal.is_none(), "/ehl/thermal", "the wear model does not run the thermal EHL model yet");
            v.check(spec.cycle.ehl.geometry.is_line(), "/ehl/geometry", "the wear model reads line-contact pressure profiles: geometry finite is not supported");
            v.check(spec.cycle.thermal == ThermalPair::default(), "/thermal", "wear computes no temperatures: leave `thermal` out");
        });
        if spec.cycle.fidelity != Fidelity::Fast {
            match spec.model {
                WearModel::Irgashev => {
                    v.error("/cycle/fidelity", "model irgashev is an empirical method without a film model: use fidelity fast");
                }
                WearModel::Archard => {
                    v.check(
                        spec.cycle.lubricant.is_some(),
                        "/cycle/fidelity",
                        "accurate and auto solve the lubricant film: give a lubricant (without one the contact is dry: use fast)",
                    );
                    // Budget of numerical work: every angle of every cycle may run the EHL solver.
                    let cycles = spec.max_updates().saturating_add(1);
                    let work = (spec.cycle.angles as f64) * (cycles as f64) * (spec.cycle.ehl.nodes(spec.cycle.line_family()) as f64);
                    let units = (work / STANDARD_CYCLE_WORK as f64).ceil().min(1e15) as usize;
                    v.limit(
                        "/cycle/ehl/nodes",
                        units,
                        limits.max_evaluations,
                        &format!(
                            "the numerical EHL work of this run — {} angles × {cycles} cycles (at most {NUMERICAL_UPDATE_FACTOR} × the planned \
                             updates, plus the unworn cycle) × {} nodes, counted in cycles of 720 angles × 192 nodes (fewer nodes, \
                             angles or updates reduce it)",
                            spec.cycle.angles, spec.cycle.ehl.nodes(spec.cycle.line_family())
                        ),
                    );
                }
            }
        }
        v.check(spec.cycle.operation.startup.is_none(), "/cycle/operation/startup", "wear needs steady running (no startup)");
        match (spec.hours, spec.cycles) {
            (Some(h), None) => {
                v.in_range("/hours", h, 1e-6, 1e6);
            }
            (None, Some(c)) => {
                v.in_range("/cycles", c, 1.0, 1e12);
            }
            _ => {
                v.error("/hours", "give the running time as `hours` or as `cycles` (one of them)");
            }
        }
        if let Some(l) = spec.wear_limit {
            v.in_range("/wear_limit", l, 1e-9, 0.01);
        }
        v.count_in_range("/snapshots", spec.snapshots, 0, 100);
        let sigma = spec.composite_sigma();
        match spec.model {
            WearModel::Archard => {
                match &spec.wear_coefficient {
                    Some(c) => c.validate("/wear_coefficient", v),
                    None => {
                        v.error("/wear_coefficient", "is required by the archard model");
                    }
                }
                if let Some(c) = &spec.follower_wear_coefficient {
                    c.validate("/follower_wear_coefficient", v);
                }
                v.check(spec.irgashev.is_none(), "/irgashev", "belongs to model irgashev");
                if spec.load_share == LoadShareSpec::Asperity {
                    v.check(
                        spec.cycle.lubricant.is_some(),
                        "/load_share",
                        "the asperity share needs a lubricant (without one the contact is dry: use `full`)",
                    );
                    v.check(
                        spec.cycle.lubricant.is_none() || sigma > 0.0,
                        "/load_share",
                        "smooth surfaces carry no asperity load: give roughness_rq of cam or follower, or use `full`",
                    );
                }
                if spec.is_roller() {
                    v.check(spec.cycle.lubricant.is_some(), "/cycle/lubricant", "is required with a roller follower (its slip)");
                }
                if let Some(u) = spec.update_interval_hours {
                    v.check(u.is_finite() && u > 0.0, "/update_interval_hours", "must be a finite number > 0");
                }
                let updates = spec.planned_updates();
                if updates > 0 {
                    v.limit("/update_interval_hours", updates, limits.max_evaluations, "the number of profile updates");
                }
                if let FollowerSpec::Spherical { .. } = spec.cycle.follower {
                    // fine: point contact, no follower-face table
                }
            }
            WearModel::Irgashev => {
                v.check(spec.update_interval_hours.is_none(), "/update_interval_hours", "belongs to model archard");
                if let Some(c) = &spec.wear_coefficient {
                    c.validate("/wear_coefficient", v);
                }
                match &spec.irgashev {
                    None => {
                        v.error("/irgashev", "is required by model irgashev");
                    }
                    Some(ir) => {
                        v.positive("/irgashev/nose_lift", ir.nose_lift);
                        v.count_in_range("/irgashev/flank_steps", ir.flank_steps, 1, 1000);
                        v.positive("/irgashev/elasticity_constant", ir.elasticity_constant);
                        v.positive("/irgashev/yield_strength", ir.yield_strength);
                        v.positive("/irgashev/deformation_coefficient", ir.deformation_coefficient);
                        v.positive("/irgashev/cycles_to_failure", ir.cycles_to_failure);
                        for (i, s) in ir.slip.iter().enumerate() {
                            v.in_range(&format!("/irgashev/slip/{i}"), *s, 0.0, 10.0);
                        }
                        if let ProfileSpec::MultiArc { arcs } = &spec.cycle.cam.profile {
                            v.check(ir.slip.len() == arcs.len(), "/irgashev/slip", "needs one value per arc");
                        }
                    }
                }
                match &spec.cycle.cam.profile {
                    ProfileSpec::MultiArc { arcs } => {
                        v.check(arcs.len() >= 6 && arcs.len() % 2 == 0, "/cycle/cam/profile/arcs", "the seed 004 method needs an even number (≥ 6) of arcs: base, flank(s), nose, nose, flank(s), base");
                        let total: f64 = arcs.iter().map(|a| a.angle_deg).sum();
                        v.check((total - 360.0).abs() < 1e-6, "/cycle/cam/profile/arcs", format!("the arc angles must add up to 360° (they add up to {total}°)"));
                    }
                    _ => {
                        v.error("/cycle/cam/profile", "model irgashev needs a multi_arc profile (seed 004 Tables 1–2)");
                    }
                }
                v.check(matches!(spec.cycle.follower, FollowerSpec::Spherical { .. }), "/cycle/follower", "model irgashev needs a spherical follower (the tappet sphere)");
                match spec.cycle.load {
                    Some(LoadSpec::ValveTrain { spring_stiffness, .. }) => {
                        v.check(spring_stiffness > 0.0, "/cycle/load/spring_stiffness", "must be > 0 for model irgashev");
                    }
                    _ => {
                        v.error("/cycle/load", "model irgashev needs a valve_train load (spring preload and rate)");
                    }
                }
            }
        }
    }

    fn cost(spec: &WearSpec) -> Cost {
        // The unworn cycle and one cycle per profile update (the stability rule may add updates,
        // up to `max_updates`: the estimate counts the planned ones); seed 004's method runs
        // one cycle. Memory: one cycle at a time, plus the wear depth and history per angle.
        let cycle = super::cam_cycle::cycle_cost_with(&spec.cycle_spec(), crate::jobs::cost::WEAR_ANGLE_S);
        let cycles = match spec.model {
            WearModel::Archard => spec.planned_updates().max(1) as f64 + 1.0,
            // Seed 004's method: closed forms over the profile's angles, no film.
            WearModel::Irgashev => {
                let seconds = crate::jobs::cost::JOB_OVERHEAD_S + spec.cycle.angles as f64 * crate::jobs::cost::WEAR_ANGLE_S;
                return Cost::new(seconds, crate::jobs::cost::CAM_BASE_BYTES).work_at("/cycle/angles", format!("{} angles", spec.cycle.angles));
            }
        };
        let what = format!("{cycles:.0} cam cycles ({})", cycle.work_what);
        // The cycle's fixed cost is paid once.
        let once = crate::jobs::cost::CYCLE_BASE_S;
        cycle.plus_seconds(-once).repeated(cycles).plus_seconds(once).under("/cycle").work_at("/update_interval_hours", what)
    }

    fn solve(spec: &WearSpec, observer: &dyn Observer) -> Result<WearResult, SolveError> {
        let solved = match spec.model {
            WearModel::Archard => solve_archard(spec, observer),
            WearModel::Irgashev => solve_irgashev(spec, observer),
        };
        solved.map_err(|e| in_cycle(e.in_spec(wear_spec_path)))
    }
}
