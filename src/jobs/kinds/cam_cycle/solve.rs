//! Solving a `cam_cycle` spec: the spec turned into the physics input (`CycleSpec`), the cycle run,
//! and its output mapped to the result fields.

use super::output::{events_of, fields_of, film_model_counts, profiles_of, series_of, single_film_model};
use super::result::*;
use super::spec::*;
use crate::jobs::kinds::common::{composite_sigma, LubricantSpec};
use crate::physics::cam::contour::undercut_margin;
use crate::physics::cam::summary::{check_contact_on_face, summarise, CycleSummary, FlatFace};
use crate::physics::cam::cycle::{run_cycle, CycleSpec, FollowerKind, Needs, SlipMode};
use crate::physics::cam::{CamProfile, FollowerGeometry, FollowerShape, LiftProgram, LoadModel, MultiArc, PeriodicSpline, PeriodicTable, SpeedSchedule};
use crate::physics::contact::{contact_modulus, Elastic};
use crate::jobs::kinds::contact::LubricatedContact;
use crate::physics::roller::pin_finite::roller_cooled_area;
use crate::physics::geometry::Crown;
use crate::physics::roller::{FinitePin, PinFriction, PinTable, PinThermal, RollerParams};
use crate::physics::valvetrain::{
    damping_from_ratio, line_contact_stiffness, periodic_response, run_up, Drive, DynamicsOptions, Lash, Lever, Link,
    NestedSpring, PeriodicResponse, Pushrod, RunUpResponse, Seat, ValveTrain,
};
use crate::physics::{Observer, SolveError};
use crate::jobs::kinds::accuracy::LineFamily;
use crate::physics::film::Fidelity;
use std::f64::consts::PI;

fn deg(x: f64) -> f64 {
    x * PI / 180.0
}

impl CamCycleSpec {
    /// What the spec's `outputs` ask the cycle to compute (dependencies included).
    pub fn needs(&self) -> Needs {
        let has = |o| self.outputs.contains(&o);
        Needs {
            loads: has(CamOutput::Loads),
            contact: has(CamOutput::Contact),
            film: has(CamOutput::Film) || has(CamOutput::Profiles),
            friction: has(CamOutput::Friction),
            slip: has(CamOutput::Slip),
            temperature: has(CamOutput::Temperature),
        }
        .closed(self.is_roller())
    }

    /// The line contact whose measured accuracy ladder chooses the grid (`kinds::accuracy`).
    pub fn line_family(&self) -> LineFamily {
        match self.follower {
            FollowerSpec::FlatFaced { .. } => LineFamily::FlatFaced,
            FollowerSpec::Roller { .. } | FollowerSpec::Spherical { .. } => LineFamily::Roller,
        }
    }

    fn is_roller(&self) -> bool {
        matches!(self.follower, FollowerSpec::Roller { .. })
    }

    fn follower_elastic(&self) -> (Elastic, f64) {
        let (e, nu, rq) = match self.follower {
            FollowerSpec::FlatFaced { material, roughness_rq, .. }
            | FollowerSpec::Roller { material, roughness_rq, .. }
            | FollowerSpec::Spherical { material, roughness_rq, .. } => (material.youngs_modulus, material.poisson_ratio, roughness_rq),
        };
        (Elastic { youngs_modulus: e, poisson_ratio: nu }, rq)
    }

    fn profile(&self) -> Result<CamProfile, SolveError> {
        Ok(match &self.cam.profile {
            ProfileSpec::RiseReturn { base_radius, lift, rise_start_deg, rise_deg, top_dwell_deg, return_deg, law, return_law } => {
                CamProfile::Program {
                    base_radius: *base_radius,
                    program: LiftProgram {
                        lift: *lift,
                        rise_start: deg(*rise_start_deg),
                        rise: deg(*rise_deg),
                        top_dwell: deg(*top_dwell_deg),
                        fall: deg(*return_deg),
                        rise_law: *law,
                        return_law: return_law.unwrap_or(*law),
                    },
                }
            }
            ProfileSpec::MultiArc { arcs } => {
                let a: Vec<(f64, f64)> = arcs.iter().map(|a| (a.radius, deg(a.angle_deg))).collect();
                CamProfile::MultiArc(MultiArc::new(&a)?)
            }
            ProfileSpec::SymmetricArcs { base_radius, base_angle_deg, flanks } => {
                let f: Vec<(f64, f64)> = flanks.iter().map(|a| (a.radius, deg(a.angle_deg))).collect();
                CamProfile::MultiArc(MultiArc::symmetric(*base_radius, deg(*base_angle_deg), &f)?)
            }
            p @ ProfileSpec::Synthesised { base_radius, .. } => match super::synthesis::synthesised(p) {
                Some(s) => CamProfile::Synthesised { base_radius: *base_radius, law: s.law()? },
                None => unreachable!("a synthesised profile"),
            },
            ProfileSpec::Table { base_radius, angle_deg, lift } => {
                let x: Vec<f64> = angle_deg.iter().map(|a| deg(*a)).collect();
                let spline = PeriodicSpline::new(&x, lift).map_err(|e| match e {
                    SolveError::InvalidInput { message, .. } => SolveError::invalid("/cam/profile", message),
                    other => other,
                })?;
                CamProfile::Tabulated { base_radius: *base_radius, spline }
            }
        })
    }

    /// The physics description of this spec (a `dynamic` load is refused: it needs
    /// [`solve_spec`]'s dynamics run).
    pub fn cycle_spec(&self) -> Result<CycleSpec, SolveError> {
        self.cycle_spec_inner(false)
    }

    /// The cam's signed margin against undercut, m ([`undercut_margin`]: the smallest convex
    /// radius of curvature of the surface, zero or negative where the cam undercuts), from the
    /// profile alone — what `cam_optimisation` reports for a design the cycle refuses with
    /// `cam_undercut`. `None` when the spec does not describe a cam.
    pub fn undercut_margin(&self) -> Option<f64> {
        let c = self.cycle_spec_inner(true).ok()?;
        let shape = match c.geometry.shape {
            FollowerShape::Curved { radius, offset } if c.geometry.clockwise => FollowerShape::Curved { radius, offset: -offset },
            s => s,
        };
        Some(undercut_margin(&c.profile, shape, self.angles.max(720)))
    }

    fn cycle_spec_inner(&self, dynamic_allowed: bool) -> Result<CycleSpec, SolveError> {
        let profile = self.profile()?;
        let (follower_elastic, follower_rq) = self.follower_elastic();
        let cam_elastic = self.cam.material.elastic();
        let es = contact_modulus(cam_elastic, follower_elastic);
        let lub = self.lubricant.clone().unwrap_or(LubricantSpec {
            viscosity: 0.01,
            pressure_viscosity: 2e-8,
            temperature_viscosity: 0.0,
            reference_temperature: 313.0,
            temperature: None,
            density: 870.0,
            viscosity_model: Default::default(),
            density_model: Default::default(),
        });
        let lubricant = lub.to_physics();
        let temperature = lub.inlet_temperature();
        let (shape, follower) = match &self.follower {
            FollowerSpec::FlatFaced { .. } => (FollowerShape::Flat, FollowerKind::Flat { contact_length: self.cam.width.unwrap_or(0.0) }),
            FollowerSpec::Roller { radius, length, pin_radius, clearance, inertia, density, pin, crown, offset, .. } => {
                let inertia = inertia.unwrap_or_else(|| crate::physics::roller::ring_inertia(*density, *radius, *pin_radius, *length));
                let pin = match pin {
                    PinSpec::Coefficient { coefficient } => PinFriction::Coefficient { coefficient: *coefficient, pin_radius: *pin_radius },
                    PinSpec::Hydrodynamic { length: l } => PinFriction::ShortBearing {
                        pin_radius: *pin_radius,
                        clearance: *clearance,
                        length: l.unwrap_or(*length),
                        viscosity: lubricant.viscosity_at(0.0, temperature),
                    },
                    PinSpec::Finite { length: l, thermal, oil_specific_heat, convection_coefficient } => {
                        let l = l.unwrap_or(*length);
                        // The dimensionless table (one run of the journal solver per node) is
                        // built once per run.
                        let table = PinTable::build(l / (2.0 * pin_radius), &crate::physics::Silent)?;
                        PinFriction::FiniteBearing(FinitePin {
                            pin_radius: *pin_radius,
                            clearance: *clearance,
                            length: l,
                            lubricant,
                            ambient_temperature: temperature,
                            thermal: thermal.then(|| PinThermal {
                                oil_specific_heat: *oil_specific_heat,
                                oil_density: lubricant.density,
                                convection_coefficient: *convection_coefficient,
                                cooled_area: roller_cooled_area(*radius, *pin_radius, *length),
                            }),
                            table: std::sync::Arc::new(table),
                        })
                    }
                };
                let contact_length = self.cam.width.map_or(*length, |w| w.min(*length));
                (
                    FollowerShape::Curved { radius: *radius, offset: *offset },
                    FollowerKind::Roller {
                        roller: RollerParams { radius: *radius, inertia, pin },
                        contact_length,
                        crown: crown.map(|c| Crown { length: *length, middle_length: c.middle_length, crown_height: c.crown_height, end_radius: c.end_radius, profile: c.profile.into() }),
                    },
                )
            }
            FollowerSpec::Spherical { radius, offset, .. } => {
                (FollowerShape::Curved { radius: *radius, offset: *offset }, FollowerKind::Spherical { face_radius: *radius })
            }
        };
        let omega = crate::physics::units::rpm_to_rad_per_s(self.operation.speed_rpm);
        let schedule = match self.operation.startup {
            None => SpeedSchedule::Steady { omega },
            Some(s) => SpeedSchedule::Startup { omega, rated_angle: deg(s.rated_angle_deg) },
        };
        let load = match &self.load {
            None => LoadModel::ValveTrain { preload: 0.0, stiffness: 0.0, mass: 0.0, external: None },
            Some(LoadSpec::ValveTrain { spring_preload, spring_stiffness, moving_mass, external }) => LoadModel::ValveTrain {
                preload: *spring_preload,
                stiffness: *spring_stiffness,
                mass: *moving_mass,
                external: match external {
                    Some(t) => Some(table(&t.angle_deg, &t.force, "/load/external")?),
                    None => None,
                },
            },
            Some(LoadSpec::Spectrum { angle_deg, load, offset }) => LoadModel::Spectrum { table: table(angle_deg, load, "/load")?, offset: *offset },
            // Replaced by the dynamics' force in `solve_spec` (only the cam_cycle kind solves it).
            Some(LoadSpec::Dynamic(_)) if dynamic_allowed => LoadModel::ValveTrain { preload: 0.0, stiffness: 0.0, mass: 0.0, external: None },
            Some(LoadSpec::Dynamic(_)) => return Err(SolveError::invalid("/load", "a dynamic load is solved by the cam_cycle kind only")),
        };
        let mut cycle = CycleSpec {
            profile,
            geometry: FollowerGeometry { shape, clockwise: self.operation.direction == Direction::Cw },
            follower,
            schedule,
            angles: self.angles,
            load,
            contact_modulus: es,
            poisson_ratio: self.cam.material.poisson_ratio,
            lubricant,
            temperature,
            roughness: self.asperities.roughness(composite_sigma(self.cam.roughness_rq, follower_rq)),
            traction_law: self.traction.to_physics(),
            asperity_friction: self.asperities.friction(),
            cam_thermal: self.thermal.cam.to_physics(),
            follower_thermal: self.thermal.follower.to_physics(),
            slip: match self.slip.mode {
                SlipModeSpec::PureRolling => SlipMode::PureRolling,
                SlipModeSpec::TorqueBalance => SlipMode::TorqueBalance { tolerance: self.slip.tolerance, max_cycles: self.slip.max_cycles },
            },
            profile_angles: if self.outputs.contains(&CamOutput::Profiles) {
                let n = self.angles;
                let mut v: Vec<usize> = self
                    .profile_angles_deg
                    .iter()
                    .map(|a| ((a.rem_euclid(360.0) / 360.0 * n as f64).round() as usize) % n)
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            } else {
                Vec::new()
            },
        };
        // The polydyne's dynamic correction of a synthesised cam (its train from the dynamic
        // load's when not given).
        let from_load = match &self.load {
            Some(LoadSpec::Dynamic(d)) => Some(valve_train(d, &cycle).polydyne_train()),
            _ => None,
        };
        super::polydyne::apply(self, &mut cycle, from_load)?;
        Ok(cycle)
    }
}

fn table(angles_deg: &[f64], values: &[f64], path: &str) -> Result<PeriodicTable, SolveError> {
    let a: Vec<f64> = angles_deg.iter().map(|x| deg(*x)).collect();
    PeriodicTable::new(&a, values).map_err(|e| match e {
        SolveError::InvalidInput { message, .. } => SolveError::invalid(path, message),
        other => other,
    })
}

/// The physics valve train of a `dynamic` load for `cycle` (SI; damping ratios turned into
/// coefficients, the contact stiffness defaulted from seed 003 eq. 6 at the preload on the base
/// circle).
pub fn valve_train(d: &DynamicLoadSpec, cycle: &CycleSpec) -> ValveTrain {
    let preload = d.preload();
    // The contact on the base circle: a flat face against the base radius, a roller against it
    // with the reduced radius of the two cylinders.
    let base = cycle.profile.base_radius();
    let (length, radius) = match &cycle.follower {
        FollowerKind::Flat { contact_length } => (*contact_length, base),
        FollowerKind::Roller { contact_length, roller, .. } => (*contact_length, base * roller.radius / (base + roller.radius)),
        FollowerKind::Spherical { .. } => (0.0, base),
    };
    let lever = match d.arrangement {
        None | Some(ArrangementSpec::Direct) => None,
        Some(ArrangementSpec::Rocker { cam_arm, valve_arm, inertia, pushrod }) => Some((cam_arm, valve_arm, inertia, pushrod)),
        Some(ArrangementSpec::Finger { cam_arm, valve_arm, inertia }) => Some((cam_arm, valve_arm, inertia, None)),
    };
    let ratio = lever.map_or(1.0, |(lc, lv, _, _)| lv / lc);
    let kc = d.contact_stiffness.unwrap_or_else(|| {
        line_contact_stiffness(ratio * preload, length, radius, cycle.contact_modulus)
    });
    let rigid = d.train_stiffness.is_none();
    let reduced = |a: f64, b: f64| if a + b > 0.0 { a * b / (a + b) } else { 0.0 };
    // Each spring its own chain; a nested inner spring with its installed force.
    let spring = super::springs::chain_of(&d.spring);
    let inner_spring = d.inner_spring.as_ref().map(|s| NestedSpring { spring: super::springs::chain_of(s), preload: super::springs::installed_force(s).unwrap_or(0.0) });
    let Some((cam_arm, valve_arm, inertia, pushrod)) = lever else {
        // Direct-acting.
        let follower_side = if rigid { d.follower_mass + d.valve_mass } else { d.follower_mass };
        return ValveTrain {
            lash: d.lash.map(|l| Lash::Mechanical(l.clearance)).or_else(|| d.hydraulic_lash_adjuster.map(|h| Lash::Hydraulic(super::lash::adjuster(&h, d.valve_mass)))),
            follower_mass: d.follower_mass,
            valve_mass: d.valve_mass,
            train: d.train_stiffness.map(|k| Link { stiffness: k, damping: damping_from_ratio(d.train_damping_ratio, k, reduced(d.follower_mass, d.valve_mass)) }),
            spring,
            inner_spring,
            preload,
            contact: Link { stiffness: kc, damping: damping_from_ratio(d.contact_damping_ratio, kc, follower_side) },
            seat: d.seat.map(|st| Seat {
                link: Link { stiffness: st.stiffness, damping: damping_from_ratio(st.damping_ratio, st.stiffness, d.valve_mass.max(follower_side)) },
                gap: st.gap,
            }),
            lever: None,
        };
    };
    // A lever: masses reduced to the cam side (valve side × r², the lever I/l_c²; module docs of
    // `physics::valvetrain::model`). Each damping ratio acts on the mass its link carries.
    let r2 = ratio * ratio;
    let lever_mass = inertia / (cam_arm * cam_arm);
    let valve_cam_side = if rigid { r2 * d.valve_mass } else { 0.0 };
    // The lever's body (cam side) and the tappet under a pushrod.
    let (tappet, lever_body) = match pushrod {
        Some(p) => (d.follower_mass + 0.5 * p.mass, lever_mass + 0.5 * p.mass),
        None => (0.0, d.follower_mass + lever_mass),
    };
    let contact_mass = match pushrod {
        Some(_) => tappet,
        None => lever_body + valve_cam_side,
    };
    ValveTrain {
        lash: d.lash.map(|l| Lash::Mechanical(l.clearance / ratio)),
        follower_mass: d.follower_mass,
        valve_mass: d.valve_mass,
        // Valve side: the lever's body reduced to the valve side against the valve.
        train: d.train_stiffness.map(|k| Link { stiffness: k, damping: damping_from_ratio(d.train_damping_ratio, k, reduced(lever_body / r2, d.valve_mass)) }),
        spring,
        inner_spring,
        preload,
        contact: Link { stiffness: kc, damping: damping_from_ratio(d.contact_damping_ratio, kc, contact_mass) },
        seat: d.seat.map(|st| Seat {
            link: Link {
                stiffness: st.stiffness,
                damping: damping_from_ratio(st.damping_ratio, st.stiffness, if rigid { d.valve_mass + lever_body / r2 } else { d.valve_mass }),
            },
            gap: st.gap,
        }),
        lever: Some(Lever {
            cam_arm,
            valve_arm,
            inertia,
            pushrod: pushrod.map(|p| Pushrod {
                mass: p.mass,
                link: Link { stiffness: p.stiffness, damping: damping_from_ratio(p.damping_ratio, p.stiffness, reduced(tappet, lever_body + valve_cam_side)) },
            }),
        }),
    }
}

/// Run the valve-train dynamics of a `dynamic` load over the cycle's angles.
#[allow(clippy::type_complexity)]
fn dynamic_response(
    d: &DynamicLoadSpec,
    cycle: &CycleSpec,
    observer: &dyn Observer,
) -> Result<(ValveTrain, PeriodicResponse, Option<RunUpResponse>), SolveError> {
    let SpeedSchedule::Steady { omega } = cycle.schedule else {
        return Err(SolveError::invalid("/operation/startup", "a dynamic load needs steady running"));
    };
    let train = valve_train(d, cycle);
    let shape = cycle.geometry.shape;
    let profile = &cycle.profile;
    let lift = move |theta: f64| {
        let j = profile.lift(theta, shape);
        (j.v, j.d1)
    };
    let max_lift = (0..720).map(|k| lift(std::f64::consts::TAU * k as f64 / 720.0).0).fold(0.0, f64::max);
    let drive = Drive { lift: &lift, omega, max_lift };
    let options = DynamicsOptions {
        tolerance: d.tolerance,
        periodic_tolerance: d.periodic_tolerance,
        max_revolutions: d.max_revolutions,
        ..Default::default()
    };
    let response = periodic_response(&train, drive, cycle.angles, &options, observer)?;
    let ramp = match &d.run_up {
        Some(r) => {
            let from = Drive { omega: crate::physics::units::rpm_to_rad_per_s(r.from_rpm), ..drive };
            Some(run_up(&train, from, omega, r.revolutions, r.samples_per_revolution, &options, observer).map_err(|e| match e {
                SolveError::InvalidInput { message, .. } => SolveError::invalid("/load/run_up", message),
                other => other,
            })?)
        }
        None => None,
    };
    Ok((train, response, ramp))
}

/// A `cam_undercut` refusal with the fields it concerns and the cam's signed undercut margin
/// over the whole cycle ([`CamCycleSpec::undercut_margin`]); other errors unchanged.
fn undercut_named(spec: &CamCycleSpec, e: SolveError) -> SolveError {
    let SolveError::Physical { code: crate::physics::PhysicalFailure::CamUndercut, message } = e else { return e };
    let margin = spec.undercut_margin().map_or(String::new(), |m| format!("{:.4} mm", m * 1e3));
    let rule = match &spec.follower {
        FollowerSpec::Roller { radius, .. } | FollowerSpec::Spherical { radius, .. } => format!(
            "fields /cam/profile/base_radius and /follower/radius ({:.3} mm): the pitch curve's smallest convex radius of \
             curvature minus the follower radius is {margin} over the cycle (must be > 0 mm)",
            radius * 1e3
        ),
        _ => format!("field /cam/profile/base_radius: the smallest r_b + s + s'' over the cycle is {margin} (must be > 0 mm)"),
    };
    SolveError::physical(crate::physics::PhysicalFailure::CamUndercut, format!("{message}; {rule}"))
}

pub(super) fn solve_spec(spec: &CamCycleSpec, observer: &dyn Observer) -> Result<CamCycleResult, SolveError> {
    let mut cycle = spec.cycle_spec_inner(true)?;
    let needs = spec.needs();
    // Dynamic load: the train's periodic response gives the axial force at the cycle's angles.
    let dynamics = match &spec.load {
        Some(LoadSpec::Dynamic(d)) if needs.loads => {
            let (train, mut r, ramp) = dynamic_response(d, &cycle, observer)?;
            let shape = cycle.geometry.shape;
            let jump = train.rigid_jump_speed((0..3600).map(|k| {
                let j = cycle.profile.lift(std::f64::consts::TAU * k as f64 / 3600.0, shape);
                (j.v, j.d2)
            }));
            r.rigid_jump_speed = jump;
            let angles: Vec<f64> = (0..cycle.angles).map(|k| std::f64::consts::TAU * k as f64 / cycle.angles as f64).collect();
            cycle.load = LoadModel::Dynamic { axial: PeriodicTable::new(&angles, &r.contact_force)? };
            Some((train, r, ramp))
        }
        _ => None,
    };
    let mut settings = spec.ehl.to_physics(spec.line_family());
    settings.thermal = spec.ehl.thermal_settings(spec.thermal.cam.to_physics(), spec.thermal.follower.to_physics());
    if let Some(f) = settings.finite.as_mut() {
        // The roller's crown (the whole roller: the cam's width does not cut a crowned contact,
        // as in the slice model), or a point contact's grid.
        match &spec.follower {
            FollowerSpec::Roller { length, crown: Some(c), .. } => {
                f.crown = Some(Crown { length: *length, middle_length: c.middle_length, crown_height: c.crown_height, end_radius: c.end_radius, profile: c.profile.into() });
            }
            FollowerSpec::Spherical { .. } => f.options = spec.ehl.grid_options(true),
            _ => {}
        }
    }
    let model = needs.film.then(|| spec.film_model(settings));
    let fast = crate::physics::film::ClosedForm { formula: spec.film.formula, squeeze: spec.film.squeeze };
    let out = run_cycle(&cycle, needs, model.as_deref().unwrap_or(&fast), observer).map_err(|e| undercut_named(spec, e))?;
    let figures = summarise(&out, spec.operation.startup.is_none());
    // Contact must stay on a flat face of finite radius (centred on the follower axis).
    if let FollowerSpec::FlatFaced { face_radius: Some(radius), offset, .. } = spec.follower {
        check_contact_on_face(&out.series, FlatFace { centre: offset, radius })?;
    }
    let es = cycle.contact_modulus;
    let mut result = CamCycleResult {
        fidelity_used: spec.fidelity,
        film_model: single_film_model(&out.series),
        ehl_settings: (needs.film && spec.fidelity != Fidelity::Fast && spec.ehl.geometry.is_line()).then(|| spec.ehl.settings_used(spec.line_family())),
        contact_modulus: es,
        effective_modulus: 2.0 * es,
        angles: spec.angles,
        duration: out.duration,
        summary: summary_of(&figures),
        profiles: None,
        fields: None,
        events: events_of(&out.events),
        series: CamSeries::default(),
        convergence: out.convergence.clone(),
        dynamics_convergence: None,
        run_up: None,
        synthesis: None,
        contour: None,
        spring_checks: None,
    };
    let from_load = match &spec.load {
        Some(LoadSpec::Dynamic(d)) => Some(valve_train(d, &cycle).polydyne_train()),
        _ => None,
    };
    let correction = super::polydyne::train_of(spec, from_load)?;
    if let Some((synthesis, contour)) = super::synthesis::synthesis_of(spec, &cycle.profile, cycle.geometry.shape, correction) {
        result.synthesis = Some(synthesis);
        result.contour = Some(contour);
    }
    result.summary.fidelity_used = film_model_counts(&out.series);
    if spec.outputs.contains(&CamOutput::Profiles) {
        result.profiles = Some(profiles_of(&out));
        result.fields = (!out.fields.is_empty()).then(|| fields_of(&out));
    }
    result.series = series_of(out.series);
    if let Some((train, r, ramp)) = dynamics {
        add_dynamics(&mut result, &train, r);
        if let Some(u) = ramp {
            add_run_up(&mut result, u);
        }
    }
    if let Some(LoadSpec::Dynamic(d)) = &spec.load {
        let shape = cycle.geometry.shape;
        let max_lift = (0..3600).map(|k| cycle.profile.lift(std::f64::consts::TAU * k as f64 / 3600.0, shape).v).fold(0.0, f64::max);
        super::springs::add_spring_checks(&mut result, d, max_lift, spec.operation.speed_rpm)?;
    }
    Ok(result)
}

/// The valve-train response in the result: series (angles as the cycle's) and summary figures.
fn add_dynamics(result: &mut CamCycleResult, train: &ValveTrain, r: PeriodicResponse) {
    let series = &mut result.series;
    series.valve_lift = Some(r.valve_lift);
    series.valve_velocity = Some(r.valve_velocity);
    series.valve_acceleration = Some(r.valve_acceleration);
    series.follower_displacement = Some(r.follower_displacement);
    series.spring_force_retainer = Some(r.spring_force_moving);
    series.spring_force_fixed_end = Some(r.spring_force_fixed);
    if train.seat.is_some() {
        series.seat_force = Some(r.seat_force);
    }
    let summary = &mut result.summary;
    summary.separation = Some(r.separation.iter().map(|(a, b)| [a.to_degrees(), b.to_degrees()]).collect());
    summary.separation_duration = Some(r.separation_time);
    summary.seating_velocity = r.seating_velocity;
    summary.seating_angle_deg = r.seating_angle.map(f64::to_degrees);
    summary.bounces = r.bounces;
    summary.max_bounce_height = r.max_bounce_height;
    let inner = train.inner_spring.as_ref().map_or((0.0, 0.0), |n| (n.spring.rate, n.spring.mass));
    let (rate, mass) = (train.spring.rate + inner.0, train.spring.mass + inner.1);
    summary.spring_rate = Some(rate);
    summary.spring_mass = Some(mass);
    summary.spring_surge_frequency = Some(0.5 * (rate / mass).sqrt()).filter(|f| f.is_finite());
    summary.contact_stiffness = Some(train.contact.stiffness);
    summary.rigid_jump_speed_rpm = r.rigid_jump_speed.map(|w| w * 30.0 / std::f64::consts::PI).filter(|w| w.is_finite());
    summary.equivalent_mass = Some(train.quasi_static_equivalent().2);
    summary.lever_ratio = train.lever.map(|l| l.ratio());
    if train.lash.is_some() {
        // Valve side (the model's cam-side velocity times the lever ratio).
        summary.opening_impact_velocity = r.opening_impact_velocity.map(|v| v * train.ratio());
        summary.lift_loss = Some(r.lift_loss);
    }
    result.dynamics_convergence = Some(r.convergence);
}


/// The run-up table and its summary figure.
fn add_run_up(result: &mut CamCycleResult, u: RunUpResponse) {
    let rpm = crate::physics::units::rad_per_s_to_rpm;
    let first = u.first_separation_speed.map(rpm);
    result.summary.run_up_first_separation_rpm = first;
    result.summary.run_up_steps = Some(u.stats.accepted);
    // The table holds the per-sample columns only (servable as CSV); the irregular list of
    // intervals goes to the events.
    result.events.run_up_separation_deg = Some(u.separation.iter().map(|(a, b)| [a.to_degrees(), b.to_degrees()]).collect());
    result.run_up = Some(RunUpTable {
        angle_deg: u.angle.iter().map(|a| a.to_degrees()).collect(),
        speed_rpm: u.speed.iter().map(|&w| rpm(w)).collect(),
        contact_load: u.contact_force,
        valve_lift: u.valve_lift,
        valve_velocity: u.valve_velocity,
        spring_force_fixed_end: u.spring_force_fixed,
    });
}

/// The physics summary in the result's terms (angles in degrees).
fn summary_of(p: &CycleSummary) -> CamSummary {
    let value = |x: Option<(f64, f64)>| x.map(|(v, _)| v);
    let angle = |x: Option<(f64, f64)>| x.map(|(_, a)| a.to_degrees());
    CamSummary {
        max_lift: p.max_lift,
        max_velocity: p.max_velocity,
        max_acceleration: p.max_acceleration,
        min_acceleration: p.min_acceleration,
        max_abs_jerk: p.max_abs_jerk,
        max_abs_pressure_angle_deg: p.max_abs_pressure_angle.to_degrees(),
        min_cam_radius_of_curvature: p.min_cam_radius_of_curvature,
        min_reduced_radius: p.min_reduced_radius,
        zero_entrainment_count: p.zero_entrainment_count,
        max_contact_load: p.max_contact_load,
        min_axial_load: p.min_axial_load,
        max_hertz_pressure: value(p.max_hertz_pressure),
        max_hertz_pressure_angle_deg: angle(p.max_hertz_pressure),
        max_subsurface_shear: p.max_subsurface_shear,
        min_film: value(p.min_film),
        min_film_angle_deg: angle(p.min_film),
        min_central_film: p.min_central_film,
        fidelity_used: None,
        min_exit_film: p.min_exit_film,
        max_pressure_spike: value(p.max_pressure_spike),
        max_pressure_spike_angle_deg: angle(p.max_pressure_spike),
        newton_steps: p.newton_steps,
        min_lambda: value(p.min_lambda),
        min_lambda_angle_deg: angle(p.min_lambda),
        max_asperity_load_fraction: p.max_asperity_load_fraction,
        max_friction_coefficient: p.max_friction_coefficient,
        mean_friction_coefficient: p.mean_friction_coefficient,
        mean_friction_torque: p.mean_friction_torque,
        mean_power_loss: p.mean_power_loss,
        energy_loss: p.energy_loss,
        max_abs_slide_roll_ratio: value(p.max_abs_slide_roll_ratio),
        max_abs_slide_roll_ratio_angle_deg: angle(p.max_abs_slide_roll_ratio),
        mean_slide_roll_ratio: p.mean_slide_roll_ratio,
        max_flash_temperature: value(p.max_flash_temperature),
        max_flash_temperature_angle_deg: angle(p.max_flash_temperature),
        ..Default::default()
    }
}
