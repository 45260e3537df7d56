//! Valve-spring design data and checks of a `dynamic` load (issue 45 item 2): the spec sections
//! (`load.spring.design`, `load.inner_spring`, `load.spring_checks`), their validation, and the
//! result's `spring_checks` (physics in `physics::valvetrain::spring`, Shigley ch. 10).

use super::spec::{DynamicLoadSpec, ValveSpringSpec};
use crate::jobs::kind::Validation;
use crate::jobs::quantity as Q;
use crate::physics::valvetrain::spring::{check_spring, SpringCheck, SpringCriteria, SpringDesign, SpringEnds, StressFactor, WireStrength};
use crate::physics::valvetrain::progressive::{coil_constant, state_at, CoilGroup};
use crate::physics::valvetrain::{ClosingGroup, HelicalSpring, SpringChain};
use crate::physics::SolveError;
use super::train_spec::*;
use serde::Serialize;
use utoipa::ToSchema;

/// One valve spring's checks (`dynamic` load with `spring.design`; the outer spring first, then
/// `inner_spring`). The lift is the kinematic valve lift (cam lift × lever ratio).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct SpringCheckResult {
    /// `spring` or `inner_spring`.
    pub spring: String,
    /// Every check passed.
    pub pass: bool,
    /// Spring index D/d (a ratio).
    pub spring_index: f64,
    /// Rate at installed length (a progressive spring's tangent rate), N/m.
    pub rate: f64,
    /// Rate at full lift, N/m (the same as `rate` for a uniform pitch).
    pub rate_full_lift: f64,
    /// Coils open at installed length (a count).
    pub active_coils_installed: f64,
    /// Coils open at full lift (a count; fewer than installed when pitch groups have closed).
    pub active_coils_full_lift: f64,
    /// Solid length, m.
    pub solid_length: f64,
    /// Force at installed length (preload), N.
    pub installed_force: f64,
    /// Force at full lift, N.
    pub full_lift_force: f64,
    /// Wahl factor.
    pub wahl_factor: f64,
    /// Bergsträsser factor.
    pub bergstrasser_factor: f64,
    /// Shear stress at installed length, Pa.
    pub stress_installed: f64,
    /// Shear stress at full lift, Pa.
    pub stress_full_lift: f64,
    /// Shear stress at solid length, Pa.
    pub stress_solid: f64,
    /// Minimum tensile strength S_ut, Pa.
    pub tensile_strength: f64,
    /// Safety factor at solid length against the allowable static stress (a factor).
    pub solid_safety_factor: f64,
    /// Solid check passed.
    pub solid_pass: bool,
    /// Goodman fatigue safety factor (Zimmerli endurance, load line through the origin).
    pub fatigue_safety_factor: f64,
    /// Fatigue check passed.
    pub fatigue_pass: bool,
    /// Clearance to solid length at full lift (coil-clash margin), m.
    pub coil_clash_margin: f64,
    /// Fractional overrun to closure at full lift (a ratio).
    pub overrun_ratio: f64,
    /// Coil-clash check passed.
    pub clash_pass: bool,
    /// First surge frequency, both ends fixed, of the coils open at installed length (the
    /// lowest), Hz.
    pub surge_frequency: f64,
    /// First surge frequency of the coils open at full lift, Hz.
    pub surge_frequency_full_lift: f64,
    /// Surge frequency over the highest cam frequency (a ratio).
    pub surge_ratio: f64,
    /// Cam orders (harmonics of the cam frequency) that meet the surge frequency within the
    /// speed range, lowest first (at most 64).
    pub exciting_orders: Vec<u32>,
    /// Surge check passed.
    pub surge_pass: bool,
}

/// The coil groups of a progressive spring (empty: uniform pitch).
pub fn groups_of(s: &ValveSpringSpec) -> Vec<CoilGroup> {
    s.pitch_groups.iter().flatten().map(|g| CoilGroup { coils: g.coils, pitch: g.pitch }).collect()
}

/// The spring chain of the dynamics: rate and mass with every coil open, a progressive spring's
/// groups (share of the coils, closing force `K (p − d)`) from the fixed end.
pub fn chain_of(s: &ValveSpringSpec) -> SpringChain {
    let coil = coil_of(s);
    let k = coil_constant(&coil);
    let groups = groups_of(s).iter().map(|g| ClosingGroup { share: g.coils / coil.active_coils, closing_force: k * (g.pitch - coil.wire_diameter) }).collect();
    SpringChain { rate: coil.rate(), mass: coil.active_mass(), elements: s.elements, damping_ratio: s.damping_ratio, groups }
}

/// A spring's installed force, N: from its design (the progressive curve at
/// `free − installed`), if any.
pub fn installed_force(s: &ValveSpringSpec) -> Option<f64> {
    s.design.map(|d| state_at(&coil_of(s), &groups_of(s), d.free_length - d.installed_length).force)
}

fn design_of(s: &ValveSpringSpec) -> Option<SpringDesign> {
    let d = s.design?;
    let wire = match (d.tensile_strength, d.wire) {
        (Some(t), _) => WireStrength::Given(t),
        (None, SpringWireSpec::MusicWire) => WireStrength::MusicWire,
        (None, SpringWireSpec::OilTempered) => WireStrength::OilTempered,
        (None, SpringWireSpec::ChromeVanadium) => WireStrength::ChromeVanadium,
        (None, SpringWireSpec::ChromeSilicon) => WireStrength::ChromeSilicon,
    };
    let ends = match d.ends {
        SpringEndsSpec::Plain => SpringEnds::Plain,
        SpringEndsSpec::PlainGround => SpringEnds::PlainGround,
        SpringEndsSpec::Squared => SpringEnds::Squared,
        SpringEndsSpec::SquaredGround => SpringEnds::SquaredGround,
    };
    Some(SpringDesign {
        coil: coil_of(s),
        total_coils: d.total_coils,
        ends,
        free_length: d.free_length,
        installed_length: d.installed_length,
        wire,
        peened: d.shot_peened,
        groups: groups_of(s),
    })
}

/// The coils of a spring spec.
pub fn coil_of(s: &ValveSpringSpec) -> HelicalSpring {
    HelicalSpring { wire_diameter: s.wire_diameter, mean_diameter: s.mean_diameter, active_coils: s.active_coils, shear_modulus: s.shear_modulus, density: s.density }
}

impl DynamicLoadSpec {
    /// The springs: the outer one and the nested inner one if any.
    pub fn springs(&self) -> impl Iterator<Item = (&'static str, &ValveSpringSpec)> {
        std::iter::once(("spring", &self.spring)).chain(self.inner_spring.as_ref().map(|s| ("inner_spring", s)))
    }

    /// Spring force with the valve closed, N: `spring_preload`, or from the springs' designs
    /// (rate × (free − installed length), a progressive spring's curve there; summed over nested
    /// springs).
    pub fn preload(&self) -> f64 {
        self.spring_preload.unwrap_or_else(|| self.springs().filter_map(|(_, s)| installed_force(s)).sum())
    }
}

fn validate_design(v: &mut Validation, spring: &str, s: &ValveSpringSpec) {
    let Some(d) = s.design else { return };
    let path = format!("{spring}/design");
    v.quantity(&format!("{path}/free_length"), d.free_length, Q::LENGTH);
    v.quantity(&format!("{path}/installed_length"), d.installed_length, Q::LENGTH);
    v.check(d.installed_length < d.free_length, &format!("{path}/installed_length"), "must be below free_length (m): the spring is compressed when installed");
    let ends = design_of(s).map(|x| x.ends).unwrap_or_default();
    let total = d.total_coils.unwrap_or_else(|| ends.total_coils(s.active_coils));
    if let Some(t) = d.total_coils {
        v.in_range(&format!("{path}/total_coils"), t, 0.5, 1000.0);
        v.check(t >= s.active_coils, &format!("{path}/total_coils"), "must be ≥ active_coils (count of coils)");
    }
    let solid = ends.solid_length(s.wire_diameter, total);
    v.check(
        d.installed_length > solid,
        &format!("{path}/installed_length"),
        format!("must exceed the solid length {solid:.4e} m (wire diameter × coils, Shigley Table 10-1)"),
    );
    if let Some(t) = d.tensile_strength {
        v.quantity(&format!("{path}/tensile_strength"), t, Q::STRESS);
    }
    // Shigley §10-5's recommended ranges: a legal spring outside them is implausible.
    let c = s.mean_diameter / s.wire_diameter;
    v.warn(&format!("{spring}/mean_diameter"), (!(4.0..=12.0).contains(&c)).then(|| format!("spring index D/d = {c:.2} is outside Shigley's recommended 4 to 12")));
    v.warn(&format!("{spring}/active_coils"), (!(3.0..=15.0).contains(&s.active_coils)).then(|| format!("{} active coils is outside Shigley's recommended 3 to 15", s.active_coils)));
}

/// Validate the spring sections of a `dynamic` load (paths under `/load`).
pub fn validate_springs(d: &DynamicLoadSpec, v: &mut Validation) {
    let designed = d.spring.design.is_some();
    match d.spring_preload {
        Some(p) => {
            v.in_range("/load/spring_preload", p, 1e-3, 1e7);
            v.check(!designed, "/load/spring_preload", "give either spring_preload (N) or spring.design's free and installed lengths (m), not both");
        }
        None => {
            v.check(designed, "/load/spring_preload", "is required (N) unless spring.design gives the free and installed lengths (m)");
        }
    }
    validate_design(v, "/load/spring", &d.spring);
    if let Some(inner) = &d.inner_spring {
        v.check(designed && inner.design.is_some(), "/load/inner_spring/design", "nested springs need the design (free and installed length, m) of both springs");
        v.check(d.spring_preload.is_none(), "/load/spring_preload", "nested springs take their preload from their designs: leave spring_preload out");
        validate_coils(v, "/load/inner_spring", inner);
        v.check(
            inner.mean_diameter + inner.wire_diameter < d.spring.mean_diameter - d.spring.wire_diameter,
            "/load/inner_spring/mean_diameter",
            "the inner spring must fit inside the outer one (its outside diameter below the outer's inside diameter, m)",
        );
        validate_design(v, "/load/inner_spring", inner);
    }
    // Each closing segment of a progressive spring is an event of the integrator, and a bit of
    // its regime (physics::valvetrain::periodic: at most 28 in all).
    let closing: usize = d.springs().filter_map(|(_, s)| s.pitch_groups.as_ref().map(|g| if s.elements == 0 { g.len() } else { s.elements + 1 })).sum();
    v.check(closing <= 28, "/load/spring/elements", format!("progressive springs may have at most 28 chain segments in all (elements + 1 per progressive spring), not {closing} (count)"));
    if let Some(c) = &d.spring_checks {
        v.check(designed, "/load/spring_checks", "needs spring.design (free and installed length) to check the spring");
        if let Some([lo, hi]) = c.speed_range_rpm {
            v.quantity("/load/spring_checks/speed_range_rpm/0", lo, Q::SPEED_RPM);
            v.quantity("/load/spring_checks/speed_range_rpm/1", hi, Q::SPEED_RPM);
            v.check(lo <= hi, "/load/spring_checks/speed_range_rpm", "must be [low, high] in rpm");
        }
        v.in_range("/load/spring_checks/static_fraction", c.static_fraction, 0.05, 1.0);
        v.in_range("/load/spring_checks/min_solid_safety", c.min_solid_safety, 0.0, 100.0);
        v.in_range("/load/spring_checks/min_fatigue_safety", c.min_fatigue_safety, 0.0, 100.0);
        v.in_range("/load/spring_checks/min_overrun", c.min_overrun, 0.0, 100.0);
        v.in_range("/load/spring_checks/min_surge_ratio", c.min_surge_ratio, 0.0, 1e4);
    }
}

/// The coil rules of a spring (as the outer spring's).
pub fn validate_coils(v: &mut Validation, path: &str, sp: &ValveSpringSpec) {
    v.in_range(&format!("{path}/wire_diameter"), sp.wire_diameter, 1e-5, 0.1);
    v.in_range(&format!("{path}/mean_diameter"), sp.mean_diameter, 1e-4, 1.0);
    v.check(sp.mean_diameter > sp.wire_diameter, &format!("{path}/mean_diameter"), "must exceed the wire diameter");
    v.in_range(&format!("{path}/active_coils"), sp.active_coils, 0.5, 1000.0);
    v.in_range(&format!("{path}/shear_modulus"), sp.shear_modulus, 1e6, 1e12);
    v.in_range(&format!("{path}/density"), sp.density, 1.0, 1e5);
    v.count_in_range(&format!("{path}/elements"), sp.elements, 0, 64);
    v.in_range(&format!("{path}/damping_ratio"), sp.damping_ratio, 0.0, 10.0);
    validate_pitch_groups(v, path, sp);
}

/// A progressive spring's groups: coils summing to the active coils, pitches above the wire
/// diameter, at least one chain segment per group.
fn validate_pitch_groups(v: &mut Validation, path: &str, sp: &ValveSpringSpec) {
    let Some(groups) = &sp.pitch_groups else { return };
    let at = format!("{path}/pitch_groups");
    v.check((1..=8).contains(&groups.len()), &at, "needs 1 to 8 coil groups");
    for (i, g) in groups.iter().enumerate() {
        v.in_range(&format!("{at}/{i}/coils"), g.coils, 0.05, 1000.0);
        v.quantity(&format!("{at}/{i}/pitch"), g.pitch, Q::LENGTH);
        v.check(g.pitch > sp.wire_diameter, &format!("{at}/{i}/pitch"), format!("must exceed the wire diameter {:.4e} m (the coils would already touch)", sp.wire_diameter));
    }
    let coils: f64 = groups.iter().map(|g| g.coils).sum();
    v.check((coils - sp.active_coils).abs() <= 1e-6 * sp.active_coils, &at, format!("the groups' coils sum to {coils}, not active_coils = {} (count of coils)", sp.active_coils));
    v.check(
        sp.elements == 0 || groups.len() <= sp.elements + 1,
        &format!("{path}/elements"),
        format!("a progressive spring needs at least one chain segment per coil group: elements + 1 ≥ {} (count)", groups.len()),
    );
}

/// The checks of every designed spring for the valve lift `lift` (m) at camshaft speed
/// `speed_rpm` (the range from `spring_checks` if given).
pub fn spring_checks(d: &DynamicLoadSpec, lift: f64, speed_rpm: f64) -> Result<Option<Vec<SpringCheckResult>>, SolveError> {
    if d.spring.design.is_none() {
        return Ok(None);
    }
    let c = d.spring_checks.unwrap_or_default();
    let criteria = SpringCriteria {
        stress_factor: match c.stress_factor {
            StressFactorSpec::Wahl => StressFactor::Wahl,
            StressFactorSpec::Bergstrasser => StressFactor::Bergstrasser,
        },
        static_fraction: c.static_fraction,
        min_solid_safety: c.min_solid_safety,
        min_fatigue_safety: c.min_fatigue_safety,
        min_overrun: c.min_overrun,
        min_surge_ratio: c.min_surge_ratio,
    };
    let [lo, hi] = c.speed_range_rpm.unwrap_or([speed_rpm, speed_rpm]);
    let mut out = Vec::new();
    for (name, s) in d.springs() {
        let Some(design) = design_of(s) else { continue };
        let ch = check_spring(&design, lift, (lo / 60.0, hi / 60.0), &criteria).map_err(|e| match e {
            SolveError::InvalidInput { message, .. } => SolveError::invalid(format!("/load/{name}/design"), message),
            other => other,
        })?;
        out.push(result_of(name, ch));
    }
    Ok(Some(out))
}

/// The spring checks into the result: `spring_checks` and the summary's decisive figures.
/// `max_cam_lift`: the cam's largest lift, m (times the lever ratio at the valve).
pub fn add_spring_checks(result: &mut super::CamCycleResult, d: &DynamicLoadSpec, max_cam_lift: f64, speed_rpm: f64) -> Result<(), SolveError> {
    let ratio = match d.arrangement {
        Some(super::ArrangementSpec::Rocker { cam_arm, valve_arm, .. }) | Some(super::ArrangementSpec::Finger { cam_arm, valve_arm, .. }) => valve_arm / cam_arm,
        _ => 1.0,
    };
    let Some(checks) = spring_checks(d, ratio * max_cam_lift, speed_rpm)? else { return Ok(()) };
    let min = |f: fn(&SpringCheckResult) -> f64| checks.iter().map(f).reduce(f64::min);
    let summary = &mut result.summary;
    summary.spring_checks_pass = Some(checks.iter().all(|c| c.pass));
    summary.min_spring_fatigue_safety_factor = min(|c| c.fatigue_safety_factor);
    summary.min_coil_clash_margin = min(|c| c.coil_clash_margin);
    result.spring_checks = Some(checks);
    Ok(())
}

fn result_of(name: &str, ch: SpringCheck) -> SpringCheckResult {
    SpringCheckResult {
        spring: name.to_string(),
        pass: ch.pass(),
        spring_index: ch.index,
        rate: ch.rate,
        rate_full_lift: ch.rate_full_lift,
        active_coils_installed: ch.active_coils_installed,
        active_coils_full_lift: ch.active_coils_full_lift,
        solid_length: ch.solid_length,
        installed_force: ch.installed_force,
        full_lift_force: ch.full_lift_force,
        wahl_factor: ch.wahl_factor,
        bergstrasser_factor: ch.bergstrasser_factor,
        stress_installed: ch.stress_installed,
        stress_full_lift: ch.stress_full_lift,
        stress_solid: ch.stress_solid,
        tensile_strength: ch.tensile_strength,
        solid_safety_factor: ch.solid_safety,
        solid_pass: ch.solid_pass,
        fatigue_safety_factor: ch.fatigue_safety,
        fatigue_pass: ch.fatigue_pass,
        coil_clash_margin: ch.clash_margin,
        overrun_ratio: ch.overrun,
        clash_pass: ch.clash_pass,
        surge_frequency: ch.surge_frequency,
        surge_frequency_full_lift: ch.surge_frequency_full_lift,
        surge_ratio: ch.surge_ratio,
        exciting_orders: ch.exciting_orders,
        surge_pass: ch.surge_pass,
    }
}
