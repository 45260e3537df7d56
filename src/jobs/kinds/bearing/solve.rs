//! The adapter between the spec and `physics::journal`: spec → [`Case`] (plain SI structs),
//! [`Solution`] → [`BearingResult`]. No physics here: the operating point, the heat balance, the
//! coefficients' figures and the limit checks are `journal::operating`, `journal::heat_balance`,
//! `journal::threshold` and `journal::limits`.

use super::*;
use crate::physics::journal::case::{Case, Solution};
use crate::physics::journal::heat_balance::{HeatBalance, Lubricant, ThermalBalance, ViscosityData};
use crate::physics::journal::limits::{check_limits, LimitCheck, OperatingLimits};
use crate::physics::journal::operating::{self, LoadDemand, Size};
use crate::physics::journal::threshold::{DynamicFigures, MomentFigures};
use crate::physics::journal::{self, Analysis, Bearing, Guess, Misalignment, Operating, Profile, Settings, Supply, Workspace};
use crate::physics::units::{rad_per_s_to_rpm, rpm_to_rad_per_s};
use crate::physics::{Observer, SolveError};

impl BearingSpec {
    /// The SI scales, when size, speed and viscosity are given.
    pub fn dimensions(&self) -> Option<Dimensions> {
        let viscosity = self.operating?.viscosity?;
        Some(self.size()?.with_viscosity(viscosity))
    }

    /// The solver's bearing: L/D, misalignment, profile, supply (angles in rad).
    pub fn bearing(&self) -> Bearing {
        Bearing {
            length_to_diameter: self.length_to_diameter(),
            misalignment: self
                .misalignment
                .map_or(Misalignment::default(), |m| Misalignment { vertical: m.vertical, horizontal: m.horizontal }),
            profile: self.profile.map(|p| Profile { order: p.order, height: p.height, length_fraction: p.length_fraction }),
            supply: match self.supply {
                SupplySpec::MaxFilm => Supply::MaxFilm,
                SupplySpec::Angle { angle_deg } => Supply::Angle(angle_deg.to_radians()),
                SupplySpec::Periodic => Supply::Periodic,
                SupplySpec::TwoGrooves { angle_deg } => Supply::TwoGrooves(angle_deg.to_radians()),
            },
        }
    }

    /// The solver's grid, tolerances and caps.
    pub fn settings(&self) -> Settings {
        Settings {
            circumferential: self.grid.circumferential,
            axial: self.grid.axial,
            pressure_tolerance: self.solver.pressure_tolerance,
            load_tolerance: self.solver.load_tolerance,
            max_load_iterations: self.solver.max_load_iterations,
            max_cycles: self.solver.max_cycles,
            min_film: self.solver.min_film,
        }
    }

    /// Radius, length, clearance and speed (SI), when all are given.
    pub fn size(&self) -> Option<Size> {
        let g = &self.geometry;
        let o = self.operating?;
        Some(Size { radius: g.radius?, length: g.length?, clearance: g.radial_clearance?, omega: rpm_to_rad_per_s(o.speed_rpm) })
    }

    /// What the spec's `load` asks for.
    pub fn load_demand(&self) -> Result<LoadDemand, SolveError> {
        let l = &self.load;
        if let Some(e) = l.eccentricity_ratio {
            return Ok(match l.attitude_angle_deg {
                Some(a) => LoadDemand::Position { eccentricity: e, attitude: a.to_radians() },
                None => LoadDemand::Eccentricity(e),
            });
        }
        if let Some(e) = l.aligned_eccentricity_ratio {
            return Ok(LoadDemand::AlignedEccentricity(e));
        }
        if let Some(f) = l.force {
            return Ok(LoadDemand::Force(f));
        }
        if let Some(s) = l.sommerfeld_number {
            return Ok(LoadDemand::Sommerfeld(s));
        }
        Err(SolveError::invalid("/load", "no operating point given"))
    }

    /// The heat balance of `thermal`, if any.
    pub fn heat_balance(&self) -> Result<Option<HeatBalance>, SolveError> {
        let Some(t) = &self.thermal else { return Ok(None) };
        let lu = &t.lubricant;
        let viscosity = match (&lu.iso_vg, &lu.viscosity_curve) {
            (Some(g), _) => ViscosityData::IsoVg { grade: *g, viscosity_100c: lu.viscosity_100c },
            (None, Some(c)) if c.len() == 2 => ViscosityData::Curve([(c[0].temperature, c[0].viscosity), (c[1].temperature, c[1].viscosity)]),
            _ => return Err(SolveError::invalid("Lubricant", "an ISO VG grade or a two-point viscosity curve")),
        };
        Ok(Some(HeatBalance {
            lubricant: Lubricant { viscosity, density: lu.density, specific_heat: lu.specific_heat },
            supply_temperature: t.supply_temperature,
            carry_over: t.carry_over,
            housing: t.housing.map(|h| (h.heat_transfer, h.ambient_temperature)),
            tolerance: t.tolerance,
            max_iterations: t.max_iterations,
        }))
    }

    /// Whether the fields are asked for.
    pub fn wants_fields(&self) -> bool {
        self.outputs.iter().any(|o| matches!(o, BearingOutput::PressureField | BearingOutput::FilmField))
    }

    /// The physics case of the spec.
    pub fn case(&self) -> Result<Case, SolveError> {
        Ok(Case {
            bearing: self.bearing(),
            settings: self.settings(),
            heat: self.heat_balance()?,
            load: self.load_demand()?,
            size: self.size(),
            viscosity: self.operating.and_then(|o| o.viscosity),
            want_fields: self.wants_fields(),
            dynamic_coefficients: self.outputs.contains(&BearingOutput::DynamicCoefficients),
            moment_coefficients: self.outputs.contains(&BearingOutput::MomentCoefficients),
        })
    }
}

/// Solve a spec: its case in `physics::journal::case`, the solution as the result document.
pub(super) fn solve_bearing(spec: &BearingSpec, observer: &dyn Observer) -> Result<BearingResult, SolveError> {
    let case = spec.case()?;
    let s = journal::case::solve(&case, observer)?;
    Ok(result_of(spec, &s))
}

/// The result document of a solution.
fn result_of(spec: &BearingSpec, s: &Solution) -> BearingResult {
    let mut r = result_at(spec, s.dimensions, &s.analysis, s.target);
    r.thermal = s.thermal.as_ref().map(thermal_result);
    r.dynamic_coefficients = s.dynamic.as_ref().map(dynamic_result);
    r.moment_coefficients = s.moment.as_ref().map(moment_result);
    if let Some(lim) = &spec.limits {
        r.checks = checks(spec, &r, lim);
    }
    r
}

/// What the spec's `load` asks for, resolved to the solver's operating point (the aligned
/// reference is solved here when needed). Returns the operating point and a starting guess.
pub fn resolve_load(spec: &BearingSpec, observer: &dyn Observer) -> Result<(Operating, Option<Guess>, Option<f64>), SolveError> {
    resolve_load_in(spec, None, observer)
}

/// [`resolve_load`] with a workspace for the reference analysis (the grids are reused; the
/// result does not depend on what the workspace held).
pub fn resolve_load_in(
    spec: &BearingSpec,
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(Operating, Option<Guess>, Option<f64>), SolveError> {
    let p = operating::resolve_load(&spec.bearing(), &spec.settings(), &spec.load_demand()?, spec.dimensions().as_ref(), workspace, observer)?;
    Ok((p.operating, p.guess, p.target))
}

/// The load (W̄) an aligned, unprofiled bearing with the spec's L/D, supply and grid carries at
/// eccentricity ratio `e`, and its position.
pub fn aligned_reference(spec: &BearingSpec, e: f64, observer: &dyn Observer) -> Result<(f64, Guess), SolveError> {
    operating::aligned_reference(&spec.bearing(), &spec.settings(), e, None, observer)
}

/// Analyse one bearing spec at a resolved operating point `(operating, guess, target)`.
pub fn solve_spec(
    spec: &BearingSpec,
    load: (Operating, Option<Guess>, Option<f64>),
    workspace: Option<&mut Workspace>,
    observer: &dyn Observer,
) -> Result<(Analysis, BearingResult), SolveError> {
    let a = journal::analyse(&spec.bearing(), &load.0, &spec.settings(), workspace, load.1, spec.wants_fields(), observer)?;
    let r = to_result(spec, &a, load.2);
    Ok((a, r))
}

/// Turn an analysis into the result document.
pub fn to_result(spec: &BearingSpec, a: &Analysis, target: Option<f64>) -> BearingResult {
    result_at(spec, spec.dimensions(), a, target)
}

/// The fields asked for, downsampled by the spec's stride (every stride-th node plus the last
/// of each direction; the 360° column repeats 0°).
fn field_table(spec: &BearingSpec, a: &Analysis) -> Option<FieldTable> {
    let stride = spec.field_stride;
    let want_p = spec.outputs.contains(&BearingOutput::PressureField);
    let want_h = spec.outputs.contains(&BearingOutput::FilmField);
    a.fields.as_ref().filter(|_| want_p || want_h).map(|f| {
        let nt = f.theta.len();
        let nz = f.z.len();
        // columns 0..nt (the 360° column repeats 0°), rows 0..nz, every stride-th plus the last
        let pick = |n: usize, s: usize| {
            let mut v: Vec<usize> = (0..n).step_by(s).collect();
            if *v.last().unwrap() != n - 1 {
                v.push(n - 1);
            }
            v
        };
        let cols = pick(nt + 1, stride.circumferential);
        let rows = pick(nz, stride.axial);
        let mut t = FieldTable {
            angle_deg: Vec::new(),
            z: Vec::new(),
            pressure_dimensionless: want_p.then(Vec::new),
            film_dimensionless: want_h.then(Vec::new),
        };
        for &j in &rows {
            for &c in &cols {
                let i = c % nt;
                let ang = if c == nt { f.theta[0].to_degrees() + 360.0 } else { f.theta[i].to_degrees() };
                t.angle_deg.push(ang);
                t.z.push(f.z[j]);
                if let Some(p) = &mut t.pressure_dimensionless {
                    p.push(f.pressure[j * nt + i]);
                }
                if let Some(h) = &mut t.film_dimensionless {
                    h.push(f.film[j * nt + i]);
                }
            }
        }
        t
    })
}

/// The result document of an analysis with the SI scales `d`.
fn result_at(spec: &BearingSpec, d: Option<Dimensions>, a: &Analysis, target: Option<f64>) -> BearingResult {
    BearingResult {
        eccentricity_ratio: a.eccentricity,
        attitude_angle_deg: a.attitude.to_degrees(),
        sommerfeld_number: a.sommerfeld,
        load: LoadResult {
            dimensionless: a.load,
            along_load_dimensionless: a.force_along_load,
            across_load_dimensionless: a.force_across_load,
            force: d.map(|d| a.load * d.load_scale()),
            target_dimensionless: target,
        },
        max_pressure_dimensionless: a.max_pressure,
        max_pressure_location: Location { angle_deg: a.max_pressure_theta.to_degrees(), z: a.max_pressure_z },
        max_pressure: d.map(|d| a.max_pressure * d.pressure_scale()),
        min_film_dimensionless: a.min_film,
        min_film_location: Location { angle_deg: a.min_film_theta.to_degrees(), z: a.min_film_z },
        min_film: d.map(|d| d.film(a.min_film)),
        friction_variable: a.friction_variable,
        friction_variable_seed002: a.friction_variable_seed002,
        friction_coefficient: d.and_then(|d| a.friction_variable.map(|f| d.friction_coefficient(f))),
        flow_variable: a.flow_variable,
        side_flow_variable: a.side_flow_variable,
        side_flow_ratio: a.side_flow_ratio,
        flow: d.map(|d| d.flow(a.flow_variable)),
        side_flow: d.map(|d| d.flow(a.side_flow_variable)),
        power_loss_dimensionless: a.friction_force,
        power_loss: d.map(|d| d.power(a.friction_force)),
        convergence: a.convergence.clone(),
        pressure_convergence: PressureConvergence {
            active_set_steps: a.pressure_solve.steps,
            cycles: a.pressure_solve.cycles,
            residual: a.pressure_solve.residual,
        },
        grids: a
            .steps_per_grid
            .iter()
            .map(|&(c, z, s)| GridSteps { circumferential: c, axial: z, steps: s })
            .collect(),
        field: field_table(spec, a),
        dynamic_coefficients: None,
        moment_coefficients: None,
        thermal: None,
        checks: None,
    }
}

/// The heat balance block (field for field `journal::heat_balance::ThermalBalance`).
fn thermal_result(t: &ThermalBalance) -> BearingThermalResult {
    BearingThermalResult {
        effective_temperature: t.effective_temperature,
        viscosity: t.viscosity,
        kinematic_viscosity: t.kinematic_viscosity,
        inlet_temperature: t.inlet_temperature,
        outlet_temperature: t.outlet_temperature,
        max_temperature: t.max_temperature,
        supply_temperature: t.supply_temperature,
        power_loss: t.power_loss,
        film_inflow: t.film_inflow,
        side_flow: t.side_flow,
        supply_flow: t.supply_flow,
        convergence: t.convergence.clone(),
    }
}

/// The coefficients block: dimensionless always (at a positive load), SI with dimensions; the
/// threshold speed in rev/min.
fn dynamic_result(f: &DynamicFigures) -> DynamicCoefficientsResult {
    let k = |m: [[f64; 2]; 2]| StiffnessResult { kxx: m[0][0], kxy: m[0][1], kyx: m[1][0], kyy: m[1][1] };
    let c = |m: [[f64; 2]; 2]| DampingResult { cxx: m[0][0], cxy: m[0][1], cyx: m[1][0], cyy: m[1][1] };
    DynamicCoefficientsResult {
        stiffness: f.stiffness.map(k),
        damping: f.damping.map(c),
        stiffness_dimensionless: f.stiffness_dimensionless.map(k),
        damping_dimensionless: f.damping_dimensionless.map(c),
        whirl_ratio: f.whirl_ratio,
        critical_mass_dimensionless: f.critical_mass_dimensionless,
        critical_mass: f.critical_mass,
        threshold_speed_rpm: f.threshold_speed.map(rad_per_s_to_rpm),
        convergence: f.convergence.clone(),
    }
}

/// The force and moment coefficients block: dimensionless always (at a positive load), SI with
/// dimensions; rows and columns `(x, y, tilt_x, tilt_y)`.
fn moment_result(f: &MomentFigures) -> MomentCoefficientsResult {
    let rows = |m: [[f64; 4]; 4]| -> Vec<Vec<f64>> { m.iter().map(|r| r.to_vec()).collect() };
    MomentCoefficientsResult {
        coordinates: ["x", "y", "tilt_x", "tilt_y"].iter().map(|s| s.to_string()).collect(),
        stiffness: f.stiffness.map(rows),
        damping: f.damping.map(rows),
        stiffness_dimensionless: f.stiffness_dimensionless.map(rows),
        damping_dimensionless: f.damping_dimensionless.map(rows),
        convergence: f.convergence.clone(),
    }
}

/// The operating-limit checks of a result (needs its SI values).
fn checks(spec: &BearingSpec, r: &BearingResult, lim: &BearingLimitsSpec) -> Option<BearingChecks> {
    let g = &spec.geometry;
    let (radius, length) = (g.radius?, g.length?);
    let limits = OperatingLimits {
        journal_roughness: lim.journal_roughness,
        bearing_roughness: lim.bearing_roughness,
        film_allowance: lim.film_allowance,
        max_temperature: lim.max_temperature,
        max_specific_load: lim.max_specific_load,
    };
    let c = check_limits(r.min_film?, r.load.force?, radius, length, r.thermal.as_ref().map(|t| t.max_temperature), &limits);
    let check = |c: LimitCheck| BearingCheck { value: c.value, limit: c.limit, pass: c.pass, margin: c.margin };
    Some(BearingChecks { min_film: check(c.min_film), specific_load: check(c.specific_load), max_temperature: c.max_temperature.map(check), pass: c.pass })
}

/// The spec path of a journal-bearing solver input field (`physics::journal`).
pub fn bearing_spec_path(field: &str) -> Option<String> {
    let path = match field {
        "Bearing.length_to_diameter" => "/geometry/length_to_diameter",
        "Bearing.profile" => "/profile",
        "Settings.grid" => "/grid",
        "Settings.tolerances" => "/solver",
        "Operating.eccentricity" => "/load/eccentricity_ratio",
        "Operating.load" => "/load",
        "Operating.force" => "/load/force",
        "HeatBalance.size" => "/thermal",
        "Lubricant" | "Lubricant.viscosity_curve" => "/thermal/lubricant",
        "Lubricant.iso_vg" => "/thermal/lubricant/iso_vg",
        _ => return None,
    };
    Some(path.to_string())
}
