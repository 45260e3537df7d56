//! `cam_cycle`: a cam–follower pair over one revolution — kinematics, loads, Hertz contact and
//! sub-surface shear, lubricant film, friction and power loss, roller slip (steady or startup),
//! flash temperature. Physics in `physics::cam`, `physics::film`, `physics::friction`,
//! `physics::roller`, `physics::thermal`.
//!
//! Only what `outputs` asks for is computed (with its dependencies): a kinematics-only request
//! runs no contact, film or slip.
//!
//! Files: `spec.rs` (the request), `result.rs` (the answer), `solve.rs` (spec → physics → result);
//! this file is the kind: example, validation, solve.

mod cost;
mod output;
mod polydyne;
mod result;
mod solve;
mod spec;
mod synthesis;
mod synthesis_spec;
mod springs;
mod lash;
mod train_spec;

pub use result::*;
pub use spec::*;
pub use synthesis::*;
pub use synthesis_spec::*;
pub use springs::*;
pub use train_spec::*;
use solve::*;
pub use cost::{cycle_cost, cycle_cost_with};

use crate::jobs::cost::Cost;
use crate::jobs::quantity as Q;
use crate::jobs::kind::{Kind, Limits, OutputInfo, Validation};
use crate::jobs::kinds::common::{cam_spec_path, AsperitySpec, EhlSpec, FilmSpec, LubricantSpec, TractionSpec};
use crate::jobs::kinds::contact::LubricatedContact;
use crate::physics::film::Fidelity;
use crate::physics::{Observer, SolveError};
use serde_json::{json, Value};

pub struct CamCycle;

/// Most rows of the 2-D `fields` table (profile angles × nx × ny): ≈ 13 MB of JSON.
pub const MAX_FIELD_ROWS: usize = 1 << 17;

impl Kind for CamCycle {
    const NAME: &'static str = "cam_cycle";
    const SOLVER_VERSION: &'static str = "cam_cycle-22";
    const DESCRIPTION: &'static str = "Cam–follower pair over one revolution: kinematics, loads, Hertz contact, \
        lubricant film, friction and power loss, roller slip (steady or startup) and flash temperature \
        (fidelity fast: closed forms; accurate: numerical line-contact EHL with squeeze at every angle; auto: \
        closed forms where their estimated error is within tolerance).";
    const TABLES: &'static [&'static str] = &["series", "run_up", "fields", "contour"];
    const KEY_FIGURES: &'static [&'static str] = &["/summary/min_film", "/summary/min_lambda", "/summary/max_hertz_pressure", "/summary/max_subsurface_shear", "/summary/max_abs_slide_roll_ratio", "/summary/mean_power_loss", "/summary/max_flash_temperature", "/summary/separation_duration", "/summary/seating_velocity", "/summary/min_spring_fatigue_safety_factor", "/summary/min_coil_clash_margin"];
    type Spec = CamCycleSpec;
    type Output = CamCycleResult;

    fn example() -> Value {
        json!({
            "cam": {
                "profile": {"type": "rise_return", "base_radius": 0.018, "lift": 0.008, "rise_start_deg": 90.0,
                            "rise_deg": 90.0, "return_deg": 90.0, "law": "cycloidal"},
                "width": 0.012
            },
            "follower": {"type": "flat_faced"},
            "operation": {"speed_rpm": 3000.0},
            "load": {"type": "valve_train", "spring_preload": 300.0, "spring_stiffness": 38000.0, "moving_mass": 0.25},
            "lubricant": {"viscosity": 0.01, "pressure_viscosity": 2.2e-8},
            "angles": 720
        })
    }

    fn bound_examples() -> Vec<Value> {
        // The profiles output, the other cam profiles (seed 004's arcs, a lift table) and loads.
        let profile = |p: Value| json!({"cam": {"profile": p}});
        let rise_return = json!({"base_radius": null, "lift": null, "rise_start_deg": null, "rise_deg": null, "return_deg": null, "law": null});
        let with = |p: Value| {
            let mut patch = rise_return.clone();
            crate::jobs::kind::merge_patch(&mut patch, p);
            crate::jobs::kind::example_with::<Self>(profile(patch))
        };
        vec![
            crate::jobs::kind::example_with::<Self>(json!({"fidelity": "auto", "outputs": ["kinematics", "loads", "contact", "film", "profiles"], "profile_angles_deg": [0.0, 143.8]})),
            with(json!({"type": "multi_arc", "arcs": [{"radius": 0.0215, "angle_deg": 116.0}, {"radius": 0.1533, "angle_deg": 62.75}, {"radius": 0.0315, "angle_deg": 1.25},
                {"radius": 0.0315, "angle_deg": 1.25}, {"radius": 0.1533, "angle_deg": 62.75}, {"radius": 0.0215, "angle_deg": 116.0}]})),
            with(json!({"type": "symmetric_arcs", "base_radius": 0.0215, "base_angle_deg": 232.0, "flanks": [{"radius": 0.1533, "angle_deg": 7.2}]})),
            with(json!({"type": "table", "base_radius": 0.018, "angle_deg": [0.0, 90.0, 180.0, 270.0], "lift": [0.0, 0.004, 0.008, 0.004]})),
            with(json!({"type": "synthesised", "base_radius": 0.018, "lift": 0.008, "duration_deg": 240.0, "ramp": {"height": 2e-4, "velocity": 8e-4},
                "law": "polydyne", "limits": {"max_acceleration": 0.05, "max_jerk": 0.5}})),
            crate::jobs::kind::example_with::<Self>(json!({"load": {"external": {"angle_deg": [0.0, 180.0], "force": [0.0, 100.0]}}})),
            // The finite-length EHL of a roller (seed 000's finite cycle, coarser).
            crate::jobs::kind::example_with::<Self>(json!({"follower": {"type": "roller", "radius": 0.0255, "length": 0.012, "pin_radius": 0.016, "pin": {"model": "hydrodynamic"}},
                "fidelity": "accurate", "angles": 8, "ehl": {"geometry": "finite", "nx": 33, "ny": 65, "grid_tolerance": 0.08, "max_iterations": 60}})),
            crate::jobs::kind::example_with::<Self>(json!({"load": {"type": "spectrum", "spring_preload": null, "spring_stiffness": null, "moving_mass": null,
                "angle_deg": [0.0, 90.0, 180.0, 270.0], "load": [500.0, 800.0, 1000.0, 800.0]}})),
        ]
    }

    fn outputs() -> &'static [OutputInfo] {
        &[
            OutputInfo { name: "kinematics", description: "lift, velocity, acceleration, jerk, pressure angle, curvature, surface velocities (always computed)" },
            OutputInfo { name: "loads", description: "axial and contact loads, follower separation" },
            OutputInfo { name: "contact", description: "Hertz pressure and half-width, sub-surface shear maximum" },
            OutputInfo { name: "film", description: "central and minimum film, lambda ratio, asperity load share" },
            OutputInfo { name: "friction", description: "traction, friction coefficient, camshaft friction torque, power loss" },
            OutputInfo { name: "slip", description: "roller speed, slide-to-roll ratio, pin torque (roller followers)" },
            OutputInfo { name: "temperature", description: "flash temperature rise (Blok/Jaeger)" },
            OutputInfo { name: "profiles", description: "pressure and film profiles at profile_angles_deg (accurate/auto; with ehl.geometry finite the 2-D fields table `fields`; not in the default list)" },
        ]
    }

    fn validate(spec: &CamCycleSpec, limits: &Limits, v: &mut Validation) {
        v.count_in_range("/angles", spec.angles, 8, usize::MAX);
        v.limit("/angles", spec.angles, limits.max_angles, "the number of cam angles");
        spec.validate_lubrication(limits, v);
        validate_models(spec, v);
        let base = validate_cam(spec, limits, v);
        validate_follower(spec, base, v);
        validate_operation(spec, limits, v);
    }

    fn cost(spec: &CamCycleSpec) -> Cost {
        cycle_cost(spec)
    }

    fn solve(spec: &CamCycleSpec, observer: &dyn Observer) -> Result<CamCycleResult, SolveError> {
        solve_spec(spec, observer).map_err(|e| e.in_spec(cam_spec_path))
    }
}

/// The cycle's lubricated contact (`wear` reaches it through its `cycle`).
impl LubricatedContact for CamCycleSpec {
    fn lubricant(&self) -> Option<&LubricantSpec> {
        self.lubricant.as_ref()
    }
    fn asperities(&self) -> &AsperitySpec {
        &self.asperities
    }
    fn traction(&self) -> &TractionSpec {
        &self.traction
    }
    fn film(&self) -> &FilmSpec {
        &self.film
    }
    fn fidelity(&self) -> Fidelity {
        self.fidelity
    }
    fn ehl(&self) -> &EhlSpec {
        &self.ehl
    }
}

/// The models the follower and outputs allow (thermal and finite need a line or point contact
/// they apply to; profiles need a numerical film), and the size of the 2-D fields table.
fn validate_models(spec: &CamCycleSpec, v: &mut Validation) {
    if spec.ehl.thermal.is_some() && spec.ehl.geometry.is_line() {
        v.check(!matches!(spec.follower, FollowerSpec::Spherical { .. }), "/ehl/thermal", "the thermal line-contact model is not for a spherical follower (ehl.geometry finite: the thermal point contact)");
    }
    if !spec.ehl.geometry.is_line() {
        v.check(!matches!(spec.follower, FollowerSpec::FlatFaced { .. }), "/ehl/geometry", "finite needs a roller (finite line contact) or a spherical follower (point contact): a flat-faced follower is a line contact across the cam width");
        if spec.outputs.contains(&CamOutput::Profiles) {
            // The 2-D fields table: one row per node and angle (bounds the result's size).
            let o = spec.ehl.grid_options(matches!(spec.follower, FollowerSpec::Spherical { .. }));
            let rows = spec.profile_angles_deg.len().saturating_mul(o.nx).saturating_mul(o.ny);
            v.check(rows <= MAX_FIELD_ROWS, "/profile_angles_deg", format!("the 2-D fields of {} angles on {}×{} nodes are {rows} rows: at most {MAX_FIELD_ROWS} (fewer angles or a coarser ehl.nx/ny)", spec.profile_angles_deg.len(), o.nx, o.ny));
        }
    }
    if spec.outputs.contains(&CamOutput::Profiles) {
        v.check(spec.fidelity != Fidelity::Fast, "/outputs", "profiles need fidelity accurate or auto (the closed forms have none)");
        v.check(!spec.profile_angles_deg.is_empty(), "/profile_angles_deg", "the profiles output needs at least one angle");
        v.check(spec.profile_angles_deg.iter().all(|a| a.is_finite()), "/profile_angles_deg", "angles must be finite");
    }
    v.items("/profile_angles_deg", spec.profile_angles_deg.len(), 0, Some(64));
}

/// The cam's profile and body; the base radius when the profile has one.
fn validate_cam(spec: &CamCycleSpec, limits: &Limits, v: &mut Validation) -> Option<f64> {
    let base = match &spec.cam.profile {
        ProfileSpec::RiseReturn { base_radius, lift, rise_start_deg, rise_deg, top_dwell_deg, return_deg, .. } => {
            v.quantity("/cam/profile/lift", *lift, Q::HEIGHT.from(1e-7));
            v.in_range("/cam/profile/rise_start_deg", *rise_start_deg, -360.0, 360.0);
            v.in_range("/cam/profile/rise_deg", *rise_deg, 1e-3, 360.0);
            v.in_range("/cam/profile/top_dwell_deg", *top_dwell_deg, 0.0, 360.0);
            v.in_range("/cam/profile/return_deg", *return_deg, 1e-3, 360.0);
            v.check(
                rise_deg + top_dwell_deg + return_deg <= 360.0 + 1e-9,
                "/cam/profile/return_deg",
                "rise + top dwell + return must fit in 360°",
            );
            Some(*base_radius)
        }
        ProfileSpec::MultiArc { arcs } => {
            v.items("/cam/profile/arcs", arcs.len(), 2, Some(1000));
            for (i, a) in arcs.iter().enumerate() {
                v.quantity(&format!("/cam/profile/arcs/{i}/radius"), a.radius, Q::RADIUS);
                v.in_range(&format!("/cam/profile/arcs/{i}/angle_deg"), a.angle_deg, 1e-9, 360.0);
            }
            arcs.first().map(|a| a.radius)
        }
        ProfileSpec::SymmetricArcs { base_radius, base_angle_deg, flanks } => {
            v.in_range("/cam/profile/base_angle_deg", *base_angle_deg, 1e-9, 360.0);
            v.items("/cam/profile/flanks", flanks.len(), 0, Some(1000));
            for (i, a) in flanks.iter().enumerate() {
                v.quantity(&format!("/cam/profile/flanks/{i}/radius"), a.radius, Q::RADIUS);
                v.in_range(&format!("/cam/profile/flanks/{i}/angle_deg"), a.angle_deg, 1e-9, 360.0);
            }
            Some(*base_radius)
        }
        p @ ProfileSpec::Synthesised { base_radius, dynamic_correction, .. } => {
            synthesised(p).inspect(|s| s.validate(v));
            if let Some(c) = dynamic_correction {
                let dynamic = matches!(spec.load, Some(LoadSpec::Dynamic(_)));
                for (field, given, unit) in [("mass", c.mass, "kg"), ("stiffness", c.stiffness, "N/m")] {
                    v.check(given.is_some() || dynamic, &format!("/cam/profile/dynamic_correction/{field}"), format!("is required ({unit}) without a dynamic load to take it from"));
                }
            }
            Some(*base_radius)
        }
        ProfileSpec::Table { base_radius, angle_deg, lift } => {
            v.check(angle_deg.len() == lift.len(), "/cam/profile/lift", "must have as many entries as angle_deg");
            v.items("/cam/profile/angle_deg", angle_deg.len(), 4, None);
            v.limit("/cam/profile/angle_deg", angle_deg.len(), limits.max_angles, "the number of table points");
            v.check(
                angle_deg.windows(2).all(|w| w[1] > w[0]) && angle_deg.last().zip(angle_deg.first()).is_none_or(|(l, f)| l - f < 360.0),
                "/cam/profile/angle_deg",
                "angles must increase strictly and span less than 360°",
            );
            v.check(lift.iter().all(|x| x.is_finite()), "/cam/profile/lift", "must be finite numbers");
            Some(*base_radius)
        }
    };
    if let Some(b) = base {
        v.in_range("/cam/profile/base_radius", b, 1e-4, 10.0);
    }
    if let Some(w) = spec.cam.width {
        v.quantity("/cam/width", w, Q::LENGTH);
    }
    spec.cam.material.validate("/cam/material", v);
    v.in_range("/cam/roughness_rq", spec.cam.roughness_rq, 0.0, 1e-4);
    base
}

/// The follower of each type, its material and roughness.
fn validate_follower(spec: &CamCycleSpec, base: Option<f64>, v: &mut Validation) {
    let (material, rq) = match &spec.follower {
        FollowerSpec::FlatFaced { offset, face_radius, material, roughness_rq } => {
            v.in_range("/follower/offset", *offset, -1.0, 1.0);
            if let Some(r) = face_radius {
                v.quantity("/follower/face_radius", *r, Q::RADIUS);
            }
            v.check(spec.cam.width.is_some(), "/cam/width", "is required with a flat-faced follower (it is the contact length)");
            (*material, *roughness_rq)
        }
        FollowerSpec::Roller { radius, length, pin_radius, clearance, inertia, density, pin, crown, offset, material, roughness_rq } => {
            v.in_range("/follower/radius", *radius, 1e-4, 1.0);
            v.quantity("/follower/length", *length, Q::LENGTH);
            v.check(*pin_radius > 0.0 && pin_radius < radius, "/follower/pin_radius", "must be > 0 and smaller than the roller radius");
            v.in_range("/follower/clearance", *clearance, 1e-8, 1e-3);
            if let Some(i) = inertia {
                v.quantity("/follower/inertia", *i, Q::INERTIA);
            }
            v.quantity("/follower/density", *density, Q::DENSITY);
            match pin {
                PinSpec::Coefficient { coefficient } => {
                    v.in_range("/follower/pin/coefficient", *coefficient, 0.0, 1.0);
                }
                PinSpec::Hydrodynamic { length: l } => {
                    if let Some(l) = l {
                        v.quantity("/follower/pin/length", *l, Q::LENGTH);
                    }
                    v.check(spec.lubricant.is_some(), "/lubricant", "is required by a hydrodynamic pin");
                }
                PinSpec::Finite { length: l, thermal, oil_specific_heat, convection_coefficient } => {
                    if let Some(l) = l {
                        v.quantity("/follower/pin/length", *l, Q::LENGTH);
                    }
                    let l = l.unwrap_or(*length);
                    if l.is_finite() && l > 0.0 && *pin_radius > 0.0 {
                        let ld = l / (2.0 * pin_radius);
                        v.check(
                            (0.05..=4.0).contains(&ld),
                            "/follower/pin/length",
                            format!("L/D = length/(2 pin_radius) = {ld:.3} must be in [0.05, 4] (length defaults to the roller length)"),
                        );
                    }
                    if *thermal {
                        v.in_range("/follower/pin/oil_specific_heat", *oil_specific_heat, 100.0, 1e4);
                        v.in_range("/follower/pin/convection_coefficient", *convection_coefficient, 1e-3, 1e6);
                    }
                    v.check(spec.lubricant.is_some(), "/lubricant", "is required by a hydrodynamic pin");
                }
            }
            if let Some(c) = crown {
                v.check(c.middle_length > 0.0 && c.middle_length <= *length, "/follower/crown/middle_length", "must be in (0, length]");
                v.in_range("/follower/crown/crown_height", c.crown_height, 0.0, 1e-3);
                v.quantity("/follower/crown/end_radius", c.end_radius, Q::RADIUS);
            }
            v.in_range("/follower/offset", *offset, -1.0, 1.0);
            if let Some(b) = base {
                v.check(offset.abs() < b + radius, "/follower/offset", "must be smaller than base radius + roller radius");
            }
            (*material, *roughness_rq)
        }
        FollowerSpec::Spherical { radius, offset, material, roughness_rq } => {
            v.in_range("/follower/radius", *radius, 1e-4, 10.0);
            v.in_range("/follower/offset", *offset, -1.0, 1.0);
            if let Some(b) = base {
                v.check(offset.abs() < b + radius, "/follower/offset", "must be smaller than base radius + face radius");
            }
            (*material, *roughness_rq)
        }
    };
    material.validate("/follower/material", v);
    v.in_range("/follower/roughness_rq", rq, 0.0, 1e-4);
}

/// Speed, startup, the load model and what the outputs need, the slip march and the bodies'
/// heat properties.
fn validate_operation(spec: &CamCycleSpec, limits: &Limits, v: &mut Validation) {
    v.in_range("/operation/speed_rpm", spec.operation.speed_rpm, 1e-3, 1e5);
    if let Some(s) = spec.operation.startup {
        v.in_range("/operation/startup/rated_angle_deg", s.rated_angle_deg, 1.0, 360.0);
    }
    // Needs.
    let needs = spec.needs();
    if needs.loads {
        v.check(spec.load.is_some(), "/load", "is required unless only kinematics are requested");
    }
    if needs.film {
        v.check(spec.lubricant.is_some(), "/lubricant", "is required for film, friction, slip or temperature outputs");
    }
    match &spec.load {
        Some(LoadSpec::ValveTrain { spring_preload, spring_stiffness, moving_mass, external }) => {
            v.in_range("/load/spring_preload", *spring_preload, -1e7, 1e7);
            v.in_range("/load/spring_stiffness", *spring_stiffness, 0.0, 1e10);
            v.in_range("/load/moving_mass", *moving_mass, 0.0, 1e4);
            if let Some(t) = external {
                check_table(v, "/load/external", &t.angle_deg, &t.force, "force", limits);
            }
        }
        Some(LoadSpec::Spectrum { angle_deg, load, offset }) => {
            check_table(v, "/load", angle_deg, load, "load", limits);
            v.in_range("/load/offset", *offset, -1e7, 1e7);
        }
        Some(LoadSpec::Dynamic(d)) => validate_dynamic(spec, d, limits, v),
        None => {}
    }
    v.in_range("/slip/tolerance", spec.slip.tolerance, 1e-14, 1e-1);
    v.count_in_range("/slip/max_cycles", spec.slip.max_cycles, 1, 10_000);
    for (name, t) in [("cam", spec.thermal.cam), ("follower", spec.thermal.follower)] {
        v.quantity(&format!("/thermal/{name}/conductivity"), t.conductivity, Q::CONDUCTIVITY);
        v.quantity(&format!("/thermal/{name}/density"), t.density, Q::DENSITY);
        v.quantity(&format!("/thermal/{name}/specific_heat"), t.specific_heat, Q::SPECIFIC_HEAT);
    }
}

fn validate_dynamic(spec: &CamCycleSpec, d: &DynamicLoadSpec, limits: &Limits, v: &mut Validation) {
    v.check(
        matches!(spec.follower, FollowerSpec::FlatFaced { .. } | FollowerSpec::Roller { .. }),
        "/follower",
        "a dynamic load models a flat or roller follower (seed 003; on a rocker or finger: its pad or roller)",
    );
    v.check(spec.operation.startup.is_none(), "/operation/startup", "a dynamic load needs steady running");
    springs::validate_coils(v, "/load/spring", &d.spring);
    springs::validate_springs(d, v);
    lash::validate_lash(d, v);
    let lever = match d.arrangement {
        None | Some(ArrangementSpec::Direct) => None,
        Some(ArrangementSpec::Rocker { cam_arm, valve_arm, inertia, pushrod }) => {
            if let Some(p) = pushrod {
                v.in_range("/load/arrangement/pushrod/mass", p.mass, 0.0, 1e3);
                v.in_range("/load/arrangement/pushrod/stiffness", p.stiffness, 1.0, 1e13);
                v.in_range("/load/arrangement/pushrod/damping_ratio", p.damping_ratio, 0.0, 10.0);
                // Both ends of the pushrod are lumped bodies.
                v.check(d.follower_mass + 0.5 * p.mass > 0.0, "/load/follower_mass", "the tappet under a pushrod needs mass (follower_mass or the pushrod's)");
            }
            Some((cam_arm, valve_arm, inertia))
        }
        Some(ArrangementSpec::Finger { cam_arm, valve_arm, inertia }) => {
            v.check(cam_arm < valve_arm, "/load/arrangement/cam_arm", "a finger follower's cam contact lies between its pivot and the valve pad (cam_arm < valve_arm)");
            Some((cam_arm, valve_arm, inertia))
        }
    };
    if let Some((cam_arm, valve_arm, inertia)) = lever {
        v.in_range("/load/arrangement/cam_arm", cam_arm, 1e-4, 1.0);
        v.in_range("/load/arrangement/valve_arm", valve_arm, 1e-4, 1.0);
        v.in_range("/load/arrangement/inertia", inertia, 0.0, 1.0);
        v.in_range("/load/follower_mass", d.follower_mass, 0.0, 1e3);
        v.check(d.follower_mass > 0.0 || inertia > 0.0, "/load/arrangement/inertia", "the cam-side body needs mass: follower_mass or the lever's inertia");
    } else {
        v.in_range("/load/follower_mass", d.follower_mass, 1e-6, 1e3);
    }
    v.in_range("/load/valve_mass", d.valve_mass, 0.0, 1e3);
    if let Some(k) = d.train_stiffness {
        v.in_range("/load/train_stiffness", k, 1.0, 1e13);
        v.check(d.valve_mass > 0.0, "/load/valve_mass", "must be > 0 with an elastic train (train_stiffness)");
    }
    v.in_range("/load/train_damping_ratio", d.train_damping_ratio, 0.0, 10.0);
    if let Some(k) = d.contact_stiffness {
        v.in_range("/load/contact_stiffness", k, 1.0, 1e13);
    }
    v.in_range("/load/contact_damping_ratio", d.contact_damping_ratio, 0.0, 10.0);
    if let Some(st) = &d.seat {
        v.in_range("/load/seat/stiffness", st.stiffness, 1.0, 1e13);
        v.in_range("/load/seat/damping_ratio", st.damping_ratio, 0.0, 10.0);
        v.in_range("/load/seat/gap", st.gap, 0.0, 1e-3);
    }
    v.in_range("/load/tolerance", d.tolerance, 1e-12, 1e-2);
    v.in_range("/load/periodic_tolerance", d.periodic_tolerance, 1e-12, 1e-1);
    v.count_in_range("/load/max_revolutions", d.max_revolutions, 1, 10_000);
    if let Some(r) = &d.run_up {
        v.in_range("/load/run_up/from_rpm", r.from_rpm, 1.0, 1e5);
        v.count_in_range("/load/run_up/revolutions", r.revolutions, 1, 10_000);
        v.count_in_range("/load/run_up/samples_per_revolution", r.samples_per_revolution, 1, 7200);
        v.limit("/load/run_up/samples_per_revolution", r.revolutions.saturating_mul(r.samples_per_revolution), limits.max_angles, "the run-up table's rows");
    }
}

fn check_table(v: &mut Validation, path: &str, angles: &[f64], values: &[f64], name: &str, limits: &Limits) {
    v.items(&format!("{path}/angle_deg"), angles.len(), 1, None);
    v.items(&format!("{path}/{name}"), values.len(), 1, None);
    v.check(angles.len() == values.len(), &format!("{path}/{name}"), "must be as long as angle_deg");
    v.limit(&format!("{path}/angle_deg"), angles.len(), limits.max_angles, "the number of table points");
    v.check(angles.iter().chain(values).all(|x| x.is_finite()), &format!("{path}/angle_deg"), "entries must be finite numbers");
    let mut wrapped: Vec<f64> = angles.iter().map(|a| a.rem_euclid(360.0)).collect();
    wrapped.sort_by(|a, b| a.total_cmp(b));
    v.check(wrapped.windows(2).all(|w| w[1] > w[0]), &format!("{path}/angle_deg"), "angles must be distinct within one revolution");
}
