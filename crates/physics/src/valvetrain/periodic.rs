//! The valve train driven by a cam at constant speed: the first-order system, transient runs and
//! the periodic steady state sampled at uniform cam angles.

use super::integrator::{integrate, Event, StepControl, Stats, System};
use super::model::{Assembly, HydraulicLashAdjuster, Lash, ValveTrain};
use crate::{ensure_finite, Convergence, Observer, SolveError, Termination};
use std::f64::consts::TAU;

/// Follower lift of the cam: `(s, ds/dθ)` at cam angle θ (rad, any real), m and m/rad.
pub type CamLift<'a> = &'a (dyn Fn(f64) -> (f64, f64) + Sync);

/// The cam drive.
#[derive(Clone, Copy)]
pub struct Drive<'a> {
    pub lift: CamLift<'a>,
    /// Camshaft speed ω, rad/s (> 0).
    pub omega: f64,
    /// Largest lift of the cam, m (scales the error tolerances).
    pub max_lift: f64,
}

/// Integration settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicsOptions {
    /// Relative local error tolerance of the integrator (absolute: this times the lift and
    /// lift × ω).
    pub tolerance: f64,
    /// Change of the state at the start of a revolution between revolutions (relative to the
    /// lift and lift × ω) that ends the periodic iteration.
    pub periodic_tolerance: f64,
    /// Most revolutions.
    pub max_revolutions: usize,
    /// Most integrator steps per revolution.
    pub max_steps: usize,
}

impl Default for DynamicsOptions {
    fn default() -> Self {
        DynamicsOptions { tolerance: 1e-8, periodic_tolerance: 1e-6, max_revolutions: 200, max_steps: 1_000_000 }
    }
}

/// The first-order system `y = (x, v, W)`.
pub struct TrainSystem<'a> {
    pub asm: Assembly,
    pub drive: Drive<'a>,
    scale: Vec<f64>,
    kx: Vec<f64>,
    cv: Vec<f64>,
    /// Per regime (bit 0 contact, bit 1 seat, bit 2 the adjuster's check valve open).
    jacobians: Vec<Vec<f64>>,
    /// Seating reference height above the closed position, m.
    seating_height: f64,
    /// Speed ramp `(ω₀, α)`: cam angle `ω₀ t + α t²/2` instead of `ω t` (run-up).
    ramp: Option<(f64, f64)>,
}

/// Event functions of [`TrainSystem`].
pub const EVENT_CONTACT: usize = 0;
pub const EVENT_SEATING: usize = 1;
pub const EVENT_SEAT: usize = 2;

impl<'a> TrainSystem<'a> {
    pub fn new(train: &ValveTrain, drive: Drive<'a>) -> Self {
        let asm = train.assemble();
        let n = asm.dofs();
        let h = drive.max_lift.max(1e-6);
        let mut scale = vec![h; n];
        scale.extend(std::iter::repeat_n(h * drive.omega, n));
        scale.push((train.ratio() * train.preload).abs().max(1.0) * h);
        if asm.hla.is_some() {
            scale.push(h);
        }
        let (kx, cv) = (vec![0.0; n * n], vec![0.0; n * n]);
        let regimes = if asm.hla.is_some() { 8 } else { 4 };
        // With progressive springs the regimes multiply: their Jacobians are built on demand.
        let jacobians = if asm.spring_events() == 0 { (0..regimes).map(|r| jacobian_of(&asm, r)).collect() } else { Vec::new() };
        // The cam work row (Ẇ = F_c ṡ) is left out of the Jacobian: W does not feed back, and its
        // stage values follow from the stage equation exactly enough for a quadrature checked
        // against the energy.
        // Just above where the valve touches its seat (with a lash the preloaded seat is
        // compressed by P/k_seat at the closed position).
        let seating_height = asm.seat_touch_height() + 1e-6 * h;
        TrainSystem { asm, drive, scale, kx, cv, jacobians, seating_height, ramp: None }
    }

    /// Cam angle and speed at time `t`.
    fn angle_and_speed(&self, t: f64) -> (f64, f64) {
        match self.ramp {
            None => (self.drive.omega * t, self.drive.omega),
            Some((w0, alpha)) => (w0 * t + 0.5 * alpha * t * t, w0 + alpha * t),
        }
    }

    fn cam(&self, t: f64) -> (f64, f64) {
        let (theta, w) = self.angle_and_speed(t);
        let (s, ds) = (self.drive.lift)(theta);
        (s, ds * w)
    }

    /// Contact/seat state, spring end forces and valve acceleration at `(t, y)`.
    pub fn probe(&self, t: f64, y: &[f64]) -> Probe {
        let n = self.asm.dofs();
        let (x, v) = (&y[..n], &y[n..2 * n]);
        let (s, sd) = self.cam(t);
        let u = self.asm.unilateral(x, v, s, sd);
        let (moving, fixed) = self.asm.spring_forces(x, v);
        let iv = self.asm.valve;
        let hla_on_valve = self.asm.hla.as_ref().map_or(0.0, |e| e.force(x, v, y[2 * n + 1]));
        // Valve-side figures from the cam-side coordinates (lever ratio r; 1 direct-acting).
        let r = self.asm.ratio;
        Probe {
            cam_lift: s,
            contact: u.contact,
            seat: u.seat / r,
            follower: x[self.asm.follower],
            valve_lift: r * x[iv],
            valve_velocity: r * v[iv],
            valve_acceleration: r * (self.asm.force_on(iv, x, v, &u) + hla_on_valve) / self.asm.masses[iv],
            spring_moving: moving,
            spring_fixed: fixed,
            energy: self.asm.energy(x, v, s),
            cam_work: y[2 * n],
        }
    }

    /// The static state with the cam at angle θ (all bodies moved with the lift, at its rate).
    pub fn initial_state(&self, theta: f64) -> Vec<f64> {
        let n = self.asm.dofs();
        let (s, ds) = (self.drive.lift)(theta);
        // With a lash the train moves only with the lift beyond it.
        let (s, ds) = if s > self.asm.lash { (s - self.asm.lash, ds) } else { (0.0, 0.0) };
        let mut y = vec![0.0; self.dim()];
        for i in 0..n {
            // Spring nodes share the lift by their coils from the valve (1) to the fixed end (0).
            let share = self.asm.shares[i];
            y[i] = share * s;
            y[n + i] = share * ds * self.drive.omega;
        }
        y
    }
}

/// Derived quantities at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    pub cam_lift: f64,
    pub contact: f64,
    /// Seat force on the valve, N.
    pub seat: f64,
    /// Follower (cam-side) displacement, m.
    pub follower: f64,
    /// Valve lift (m), velocity (m/s), acceleration (m/s²): the valve side.
    pub valve_lift: f64,
    pub valve_velocity: f64,
    pub valve_acceleration: f64,
    pub spring_moving: f64,
    pub spring_fixed: f64,
    /// Kinetic + elastic energy, J.
    pub energy: f64,
    /// Work done by the cam since the start, J.
    pub cam_work: f64,
}

/// `∂f/∂y` of the train in `regime` (bit 0 contact, bit 1 seat, bit 2 the adjuster's check
/// valve open, the progressive springs' stages above).
fn jacobian_of(asm: &Assembly, r: u32) -> Vec<f64> {
    let n = asm.dofs();
    let dim = 2 * n + 1 + asm.hla.is_some() as usize;
    let (mut kx, mut cv) = (vec![0.0; n * n], vec![0.0; n * n]);
    asm.force_jacobian(r, &mut kx, &mut cv);
    if let Some(e) = &asm.hla {
        // The adjuster: F = … + k (x_b − x_a − z) + c (v_b − v_a), on b by −F, a by +F.
        let (k, c) = (e.stiffness(), e.hla.damping);
        for (i, j, sign) in [(e.b, e.b, -1.0), (e.b, e.a, 1.0), (e.a, e.a, -1.0), (e.a, e.b, 1.0)] {
            kx[i * n + j] += sign * k;
            cv[i * n + j] += sign * c;
        }
    }
    let mut j = vec![0.0; dim * dim];
    for i in 0..n {
        j[i * dim + n + i] = 1.0;
        for k in 0..n {
            j[(n + i) * dim + k] = kx[i * n + k] / asm.masses[i];
            j[(n + i) * dim + n + k] = cv[i * n + k] / asm.masses[i];
        }
    }
    if let Some(e) = &asm.hla {
        let iz = 2 * n + 1;
        let k = e.stiffness();
        j[(n + e.b) * dim + iz] = k / asm.masses[e.b];
        j[(n + e.a) * dim + iz] = -k / asm.masses[e.a];
        let (db, da, dz) = e.rate_jacobian(r & 4 != 0);
        j[iz * dim + e.b] = db;
        j[iz * dim + e.a] = da;
        j[iz * dim + iz] = dz;
    }
    j
}

impl System for TrainSystem<'_> {
    fn dim(&self) -> usize {
        2 * self.asm.dofs() + 1 + self.asm.hla.is_some() as usize
    }
    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]) {
        let n = self.asm.dofs();
        let (s, sd) = self.cam(t);
        f[..n].copy_from_slice(&y[n..2 * n]);
        let u = self.asm.forces(&y[..n], &y[n..2 * n], s, sd, &mut f[n..2 * n]);
        if let Some(e) = &self.asm.hla {
            let (x, v, z) = (&y[..n], &y[n..2 * n], y[2 * n + 1]);
            let q = e.force(x, v, z);
            f[n + e.b] -= q;
            f[n + e.a] += q;
            f[2 * n + 1] = e.rate(x, z);
        }
        for i in 0..n {
            f[n + i] /= self.asm.masses[i];
        }
        f[2 * n] = u.contact * sd;
    }
    fn regime(&self, t: f64, y: &[f64]) -> u32 {
        let n = self.asm.dofs();
        let (s, sd) = self.cam(t);
        let u = self.asm.unilateral(&y[..n], &y[n..2 * n], s, sd);
        let open = self.asm.hla.as_ref().is_some_and(|e| e.open(&y[..n], y[2 * n + 1]));
        (u.contact_closed as u32) | ((u.seat_closed as u32) << 1) | ((open as u32) << 2) | self.asm.spring_regime(&y[..n])
    }
    fn jacobian(&self, regime: u32, j: &mut [f64]) {
        let _ = (&self.kx, &self.cv);
        if self.jacobians.is_empty() {
            j.copy_from_slice(&jacobian_of(&self.asm, regime));
        } else {
            j.copy_from_slice(&self.jacobians[regime as usize % self.jacobians.len()]);
        }
    }
    fn events(&self) -> usize {
        (if self.asm.has_seat() { 3 } else { 2 }) + self.asm.spring_events()
    }
    fn event_values(&self, t: f64, y: &[f64], g: &mut [f64]) {
        let n = self.asm.dofs();
        let (s, sd) = self.cam(t);
        let u = self.asm.unilateral(&y[..n], &y[n..2 * n], s, sd);
        g[EVENT_CONTACT] = u.contact_gap;
        g[EVENT_SEATING] = self.seating_height - y[self.asm.valve];
        let first = if self.asm.has_seat() {
            g[EVENT_SEAT] = u.seat_gap;
            EVENT_SEAT + 1
        } else {
            EVENT_SEAT
        };
        self.asm.spring_event_values(&y[..n], &mut g[first..]);
    }
    fn switches(&self, e: usize) -> bool {
        e != EVENT_SEATING
    }
    fn scale(&self) -> &[f64] {
        &self.scale
    }
    fn controlled(&self, i: usize) -> bool {
        let n = self.asm.dofs();
        i < 2 * n || (i == 2 * n + 1 && self.asm.hla.is_some())
    }
}


/// The periodic response sampled at `angles` uniform cam angles `θ_k = 2πk/angles`.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicResponse {
    /// Per angle: cam–follower contact force (N), follower displacement (m), valve lift (m),
    /// velocity (m/s), acceleration (m/s²), spring force at the retainer and at the fixed end
    /// (N), seat force (N).
    pub contact_force: Vec<f64>,
    pub follower_displacement: Vec<f64>,
    pub valve_lift: Vec<f64>,
    pub valve_velocity: Vec<f64>,
    pub valve_acceleration: Vec<f64>,
    pub spring_force_moving: Vec<f64>,
    pub spring_force_fixed: Vec<f64>,
    pub seat_force: Vec<f64>,
    /// Cam angle intervals `(start, end)` (rad; `end` may exceed 2π when an interval runs past
    /// 0) where the contact carries no load.
    pub separation: Vec<(f64, f64)>,
    /// Time without contact per revolution, s.
    pub separation_time: f64,
    /// Valve speed when it first returns to its closed position after the lift, m/s (≥ 0);
    /// `None` when it never does within a revolution (it stays open or never opens).
    pub seating_velocity: Option<f64>,
    /// Cam angle of that seating, rad.
    pub seating_angle: Option<f64>,
    /// With a seat: impacts on the seat per revolution after the first (bounces), and the highest
    /// rebound above the closed position between them, m.
    pub bounces: Option<usize>,
    pub max_bounce_height: Option<f64>,
    /// Revolutions integrated, final periodicity residual.
    pub convergence: Convergence,
    /// Integrator counters of the last revolution.
    pub stats: Stats,
    /// State `(x, v, W = 0)` at θ = 0 of the sampled revolution (to continue or re-run it).
    pub start: Vec<f64>,
    /// The rigid train's jump speed, rad/s ([`super::ValveTrain::rigid_jump_speed`]; filled by
    /// callers that have the lift's second derivative).
    pub rigid_jump_speed: Option<f64>,
    /// Relative velocity of cam and follower (`ṡ − ẋ_f`, cam side, m/s) when the contact first
    /// closes while the cam lifts (with a lash: the impact on the opening ramp; ≈ ramp velocity ×
    /// ω when the follower rests); `None` when it never closes that way.
    pub opening_impact_velocity: Option<f64>,
    /// Lift loss, m: the largest cam lift times the lever ratio less the largest valve lift, over
    /// the sampled angles (the lash and the train's deflection under load).
    pub lift_loss: f64,
}


/// Integrate revolution after revolution until the state at the start of a revolution repeats
/// within `options.periodic_tolerance`, and sample the last one. Starts from the static state at
/// θ = 0.
pub fn periodic_response(
    train: &ValveTrain,
    drive: Drive,
    angles: usize,
    options: &DynamicsOptions,
    observer: &dyn Observer,
) -> Result<PeriodicResponse, SolveError> {
    validate(train, &drive)?;
    let sys = TrainSystem::new(train, drive);
    let period = TAU / drive.omega;
    let n = sys.asm.dofs();
    let times: Vec<f64> = (1..=angles).map(|k| period * k as f64 / angles as f64).collect();
    let mut y0 = sys.initial_state(0.0);
    let mut control = StepControl {
        tolerance: options.tolerance,
        max_step: period / 90.0,
        first_step: period * 1e-4,
        max_steps: options.max_steps,
    };
    let mut history = Vec::new();
    let scale = sys.scale().to_vec();
    let mut probes: Vec<Option<Probe>> = vec![None; angles];
    for rev in 0..options.max_revolutions.max(1) {
        observer.check()?;
        observer.progress(0.1 * (rev as f64 / options.max_revolutions as f64).min(1.0), "valve-train dynamics");
        let mut events: Vec<Event> = Vec::new();
        let mut start = y0.clone();
        start[2 * n] = 0.0;
        let (y1, stats) = integrate(
            &sys,
            0.0,
            &start,
            period,
            control,
            &times,
            |k, t, y| probes[k] = Some(sys.probe(t, y)),
            |e| events.push(e),
        )?;
        ensure_finite("valve-train state", &y1)?;
        ensure_finite("valve-train samples", probes.iter().flatten().flat_map(|p| [&p.contact, &p.valve_lift, &p.valve_acceleration, &p.spring_fixed]))?;
        control.first_step = stats.last_step.max(period * 1e-7);
        let residual = (0..sys.dim()).filter(|&i| sys.controlled(i)).map(|i| (y1[i] - y0[i]).abs() / scale[i]).fold(0.0, f64::max);
        history.push(residual);
        y0 = y1;
        // With contact loss the return map is not smooth and the integration's own error
        // (tolerance-sized, amplified across each event) sets a floor under the residual: a
        // residual within 100× the periodic tolerance that stopped falling (no halving over the
        // last 10 revolutions) or that remains at the revolution cap is accepted as stalled.
        let within = residual <= 100.0 * options.periodic_tolerance;
        let m = history.len();
        let stalled = within
            && ((m >= 30 && {
                let recent = history[m - 10..].iter().copied().fold(f64::INFINITY, f64::min);
                let before = history[m - 20..m - 10].iter().copied().fold(f64::INFINITY, f64::min);
                recent > 0.5 * before
            }) || rev + 1 == options.max_revolutions.max(1));
        if residual <= options.periodic_tolerance || stalled {
            let probes: Vec<Probe> = probes.into_iter().map(|p| p.expect("every angle sampled")).collect();
            let convergence = Convergence {
                iterations: (rev + 1) as u32,
                residual,
                tolerance: options.periodic_tolerance,
                termination: if residual <= options.periodic_tolerance { Termination::Converged } else { Termination::Stalled },
            };
            return Ok(assemble_response(&sys, &start, probes, &events, period, convergence, stats));
        }
    }
    Err(SolveError::NotConverged {
        solver: "valve-train periodic steady state",
        iterations: options.max_revolutions as u32,
        residual: *history.last().unwrap_or(&f64::NAN),
        tolerance: options.periodic_tolerance,
        history: history.iter().rev().take(10).rev().copied().collect(),
    })
}

fn assemble_response(
    sys: &TrainSystem,
    y_start: &[f64],
    probes: Vec<Probe>,
    events: &[Event],
    period: f64,
    convergence: Convergence,
    stats: Stats,
) -> PeriodicResponse {
    let omega = sys.drive.omega;
    let col = |f: fn(&Probe) -> f64| probes.iter().map(f).collect::<Vec<f64>>();
    // Separation intervals: from contact events; the state at the start says whether the
    // revolution begins separated (periodic: the interval then wraps).
    let n = sys.asm.dofs();
    let mut g = vec![0.0; sys.events()];
    sys.event_values(0.0, y_start, &mut g);
    let starts_open = g[EVENT_CONTACT] <= 0.0;
    let mut separation = Vec::new();
    let mut open: Option<f64> = None;
    let mut leading_end: Option<f64> = None;
    for e in events.iter().filter(|e| e.index == EVENT_CONTACT) {
        let angle = e.time * omega;
        if !e.rising {
            open = Some(angle);
        } else if let Some(a) = open.take() {
            separation.push((a, angle));
        } else if starts_open && leading_end.is_none() {
            leading_end = Some(angle);
        }
    }
    match (open, leading_end) {
        (Some(a), Some(b)) => separation.push((a, b + TAU)),
        (Some(a), None) => separation.push((a, a + TAU)),
        (None, Some(b)) => separation.insert(0, (0.0, b)),
        (None, None) if starts_open => separation.push((0.0, TAU)),
        _ => {}
    }
    separation.sort_by(|a, b| a.0.total_cmp(&b.0));
    let separation_time = separation.iter().map(|(a, b)| (b - a) / omega).fold(0.0, |s, d| s + d);
    // Seating: the first return to the closed position after the largest valve lift.
    let lifts = col(|p| p.valve_lift);
    let (k_max, _) = lifts.iter().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, &v)| if v > b.1 { (i, v) } else { b });
    let t_max = period * (k_max + 1) as f64 / probes.len() as f64;
    let seatings: Vec<&Event> = events.iter().filter(|e| e.index == EVENT_SEATING && e.rising).collect();
    let after = |t: f64| (t - t_max).rem_euclid(period);
    let first = seatings.iter().min_by(|a, b| after(a.time).total_cmp(&after(b.time)));
    let seating_velocity = first.map(|e| (-sys.asm.ratio * e.state[n + sys.asm.valve]).max(0.0));
    // Opening impact: the first closing of the contact with the cam lifting.
    let opening_impact_velocity = events
        .iter()
        .filter(|e| e.index == EVENT_CONTACT && e.rising)
        .map(|e| (e.time, sys.cam(e.time).1 - e.state[n + sys.asm.follower]))
        .find(|(t, _)| sys.cam(*t).1 > 0.0)
        .map(|(_, v)| v);
    let max_cam = probes.iter().map(|p| p.cam_lift).fold(f64::NEG_INFINITY, f64::max);
    let lift_loss = sys.asm.ratio * max_cam - lifts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let seating_angle = first.map(|e| (e.time * omega).rem_euclid(TAU));
    let (bounces, max_bounce_height) = if sys.asm.has_seat() {
        let impacts: Vec<&Event> = events.iter().filter(|e| e.index == EVENT_SEAT && e.rising).collect();
        let count = impacts.len().saturating_sub(1);
        // Highest valve lift sampled after the first impact, before the cam lifts again.
        let height = match impacts.iter().min_by(|a, b| after(a.time).total_cmp(&after(b.time))) {
            Some(first_impact) if count > 0 => {
                let t0 = first_impact.time;
                probes
                    .iter()
                    .enumerate()
                    .filter(|(k, p)| {
                        let t = period * (*k + 1) as f64 / probes.len() as f64;
                        (t - t0).rem_euclid(period) < (t_max - t0).rem_euclid(period) && p.cam_lift <= 0.0
                    })
                    .map(|(_, p)| p.valve_lift)
                    .fold(0.0, f64::max)
            }
            _ => 0.0,
        };
        (Some(count), Some(height))
    } else {
        (None, None)
    };
    // Samples are at θ_1 … θ_N = 2π; rotate so that index 0 is θ = 0 (= 2π).
    let rot = |mut v: Vec<f64>| {
        v.rotate_right(1);
        v
    };
    PeriodicResponse {
        contact_force: rot(col(|p| p.contact)),
        follower_displacement: rot(col(|p| p.follower)),
        valve_lift: rot(lifts),
        valve_velocity: rot(col(|p| p.valve_velocity)),
        valve_acceleration: rot(col(|p| p.valve_acceleration)),
        spring_force_moving: rot(col(|p| p.spring_moving)),
        spring_force_fixed: rot(col(|p| p.spring_fixed)),
        seat_force: rot(col(|p| p.seat)),
        separation,
        separation_time,
        seating_velocity,
        seating_angle,
        bounces,
        max_bounce_height,
        convergence,
        stats,
        start: y_start.to_vec(),
        rigid_jump_speed: None,
        opening_impact_velocity,
        lift_loss,
    }
}

/// Integrate from `(t0, y0)` to `t1`, sampling [`Probe`]s at `times` (for transient studies and
/// tests); returns the final state, the probes and the events.
pub fn transient(
    train: &ValveTrain,
    drive: Drive,
    y0: Option<&[f64]>,
    t1: f64,
    times: &[f64],
    options: &DynamicsOptions,
) -> Result<(Vec<f64>, Vec<Probe>, Vec<Event>), SolveError> {
    validate(train, &drive)?;
    let sys = TrainSystem::new(train, drive);
    let y0 = y0.map(|y| y.to_vec()).unwrap_or_else(|| sys.initial_state(0.0));
    let period = TAU / drive.omega;
    let control = StepControl { tolerance: options.tolerance, max_step: period / 90.0, first_step: period * 1e-4, max_steps: options.max_steps };
    let mut probes = vec![None; times.len()];
    let mut events = Vec::new();
    let (y, _) = integrate(&sys, 0.0, &y0, t1, control, times, |k, t, y| probes[k] = Some(sys.probe(t, y)), |e| events.push(e))?;
    ensure_finite("valve-train state", &y)?;
    Ok((y, probes.into_iter().map(|p| p.expect("sampled")).collect(), events))
}

/// A run-up sampled at uniform cam angles over its revolutions.
#[derive(Debug, Clone, PartialEq)]
pub struct RunUpResponse {
    /// Cam angle from the start of the run-up, rad (`samples_per_revolution × revolutions`
    /// points, the first one revolution's step after the start).
    pub angle: Vec<f64>,
    /// Cam speed, rad/s.
    pub speed: Vec<f64>,
    /// Contact force (N), valve lift (m) and velocity (m/s), spring force at the fixed end (N).
    pub contact_force: Vec<f64>,
    pub valve_lift: Vec<f64>,
    pub valve_velocity: Vec<f64>,
    pub spring_force_fixed: Vec<f64>,
    /// Cam angle intervals without contact, rad from the start (located events; an interval
    /// still open at the end closes there).
    pub separation: Vec<(f64, f64)>,
    /// Cam speed when contact is first lost, rad/s.
    pub first_separation_speed: Option<f64>,
    /// Integrator counters summed over the run-up.
    pub stats: Stats,
}

/// The cam accelerated uniformly in angle from `drive.omega` to `omega_end` over `revolutions`
/// revolutions (`θ(t) = ω₀ t + α t²/2`, `α = (ω₁² − ω₀²)/(4π N)`), from the static state at
/// θ = 0 (every body moving with the lift at ω₀, as [`periodic_response`] starts). Sampled at
/// `samples_per_revolution` uniform angles per revolution; polls the observer every revolution.
/// A slow run-up passes the jump speed quasi-statically: its first separation speed approaches
/// the steady-state jump speed from above as the ramp slows (the train needs time to build up
/// the response that separates it).
pub fn run_up(
    train: &ValveTrain,
    drive: Drive,
    omega_end: f64,
    revolutions: usize,
    samples_per_revolution: usize,
    options: &DynamicsOptions,
    observer: &dyn Observer,
) -> Result<RunUpResponse, SolveError> {
    validate(train, &drive)?;
    if !(omega_end.is_finite() && omega_end > 0.0) {
        return Err(SolveError::invalid("run_up.omega_end", "must be > 0"));
    }
    if revolutions == 0 || samples_per_revolution == 0 {
        return Err(SolveError::invalid("run_up.revolutions", "needs ≥ 1 revolution and ≥ 1 sample per revolution"));
    }
    let w0 = drive.omega;
    let w_max = w0.max(omega_end);
    let total = TAU * revolutions as f64;
    let alpha = (omega_end * omega_end - w0 * w0) / (2.0 * total);
    // Time at cam angle θ: the root of α t²/2 + ω₀ t − θ = 0 (written to avoid cancellation).
    let time_at = |theta: f64| 2.0 * theta / (w0 + (w0 * w0 + 2.0 * alpha * theta).max(0.0).sqrt());
    // Scales (velocities) at the highest speed.
    let mut sys = TrainSystem::new(train, Drive { omega: w_max, ..drive });
    sys.ramp = Some((w0, alpha));
    let n_samples = samples_per_revolution * revolutions;
    let angle: Vec<f64> = (1..=n_samples).map(|k| total * k as f64 / n_samples as f64).collect();
    let times: Vec<f64> = angle.iter().map(|&a| time_at(a)).collect();
    let mut control = StepControl {
        tolerance: options.tolerance,
        max_step: TAU / w_max / 90.0,
        first_step: TAU / w_max * 1e-4,
        max_steps: options.max_steps,
    };
    let mut y = sys.initial_state(0.0);
    // initial_state's velocities are at `sys.drive.omega` (the highest speed): rescale to ω₀.
    let nd = sys.asm.dofs();
    for v in &mut y[nd..2 * nd] {
        *v *= w0 / w_max;
    }
    let mut probes: Vec<Option<Probe>> = vec![None; n_samples];
    let mut events: Vec<Event> = Vec::new();
    let mut stats = Stats::default();
    let mut t = 0.0;
    for rev in 0..revolutions {
        observer.check()?;
        observer.progress(rev as f64 / revolutions as f64, "valve-train run-up");
        let t1 = times[(rev + 1) * samples_per_revolution - 1];
        let (y1, st) = integrate(&sys, t, &y, t1, control, &times, |k, tk, yk| probes[k] = Some(sys.probe(tk, yk)), |e| events.push(e))?;
        ensure_finite("valve-train run-up state", &y1)?;
        stats.accepted += st.accepted;
        stats.rejected += st.rejected;
        stats.factorisations += st.factorisations;
        stats.last_step = st.last_step;
        control.first_step = st.last_step.max(TAU / w_max * 1e-7);
        y = y1;
        t = t1;
    }
    let probes: Vec<Probe> = probes.into_iter().map(|p| p.ok_or_else(|| SolveError::invalid("run_up", "a sample was not reached"))).collect::<Result<_, _>>()?;
    ensure_finite("valve-train run-up samples", probes.iter().flat_map(|p| [&p.contact, &p.valve_lift, &p.spring_fixed]))?;
    let mut separation = Vec::new();
    let mut open: Option<f64> = None;
    let mut first_separation_speed = None;
    for e in events.iter().filter(|e| e.index == EVENT_CONTACT) {
        let (theta, w) = sys.angle_and_speed(e.time);
        if !e.rising {
            open = Some(theta);
            first_separation_speed.get_or_insert(w);
        } else if let Some(a) = open.take() {
            separation.push((a, theta));
        }
    }
    if let Some(a) = open {
        separation.push((a, total));
    }
    Ok(RunUpResponse {
        speed: times.iter().map(|&tk| sys.angle_and_speed(tk).1).collect(),
        angle,
        contact_force: probes.iter().map(|p| p.contact).collect(),
        valve_lift: probes.iter().map(|p| p.valve_lift).collect(),
        valve_velocity: probes.iter().map(|p| p.valve_velocity).collect(),
        spring_force_fixed: probes.iter().map(|p| p.spring_fixed).collect(),
        separation,
        first_separation_speed,
        stats,
    })
}

/// A hydraulic lash adjuster's inputs and where it can sit.
fn validate_hla(train: &ValveTrain, h: &HydraulicLashAdjuster) -> Result<(), SolveError> {
    let pos = |v: f64| v.is_finite() && v > 0.0;
    let nonneg = |v: f64| v.is_finite() && v >= 0.0;
    let field = "ValveTrain.lash";
    if ![h.plunger_diameter, h.clearance, h.leak_length, h.viscosity, h.bulk_modulus, h.chamber_volume, h.check_conductance].into_iter().all(pos)
        || ![h.supply_pressure, h.spring_preload, h.damping].into_iter().all(nonneg)
    {
        return Err(SolveError::invalid(field, "the adjuster's dimensions, viscosity, bulk modulus, volume and check-valve conductance must be > 0; supply pressure, plunger spring and damping ≥ 0"));
    }
    if train.lever.is_some() || train.train.is_some() || train.seat.is_none() || !pos(train.valve_mass) {
        return Err(SolveError::invalid(field, "a hydraulic lash adjuster sits between a direct-acting follower and the valve (no lever, no train link) with a seat and a valve mass > 0"));
    }
    if !(train.preload > h.base_force()) {
        return Err(SolveError::invalid(field, "the valve spring's preload must exceed the adjuster's base force (plunger spring + supply pressure × plunger area)"));
    }
    Ok(())
}

/// A spring chain's inputs; a progressive one's groups (shares summing to 1, closing forces > 0,
/// at most as many groups as segments).
fn validate_spring(sp: &super::model::SpringChain, field: &str) -> Result<(), SolveError> {
    let pos = |v: f64| v.is_finite() && v > 0.0;
    let nonneg = |v: f64| v.is_finite() && v >= 0.0;
    if !nonneg(sp.rate) || !nonneg(sp.mass) || !nonneg(sp.damping_ratio) || (sp.elements > 0 && !pos(sp.mass)) {
        return Err(SolveError::invalid(field, "rate ≥ 0, damping ratio ≥ 0, mass > 0 with interior elements"));
    }
    if (sp.elements > 0 || !sp.groups.is_empty()) && !pos(sp.rate) {
        return Err(SolveError::invalid(field, "a spring chain needs a rate > 0"));
    }
    if !sp.groups.is_empty() {
        let total: f64 = sp.groups.iter().map(|g| g.share).sum();
        if !sp.groups.iter().all(|g| pos(g.share) && pos(g.closing_force)) || (total - 1.0).abs() > 1e-9 {
            return Err(SolveError::invalid(field, "a progressive spring's groups need shares > 0 summing to 1 and closing forces > 0"));
        }
        if sp.elements > 0 && sp.groups.len() > sp.elements + 1 {
            return Err(SolveError::invalid(field, "a progressive spring needs at least as many segments (elements + 1) as coil groups"));
        }
    }
    Ok(())
}

/// Inputs the integration cannot use.
fn validate(train: &ValveTrain, drive: &Drive) -> Result<(), SolveError> {
    let pos = |v: f64| v.is_finite() && v > 0.0;
    let nonneg = |v: f64| v.is_finite() && v >= 0.0;
    if let Some(l) = train.lever {
        if !pos(l.cam_arm) || !pos(l.valve_arm) || !nonneg(l.inertia) {
            return Err(SolveError::invalid("ValveTrain.lever", "arm lengths must be > 0, the inertia ≥ 0"));
        }
        if let Some(p) = l.pushrod {
            if !nonneg(p.mass) || !pos(p.link.stiffness) || !nonneg(p.link.damping) {
                return Err(SolveError::invalid("ValveTrain.lever.pushrod", "mass ≥ 0, stiffness > 0, damping ≥ 0"));
            }
        }
        if !nonneg(train.follower_mass) {
            return Err(SolveError::invalid("ValveTrain.follower_mass", "must be ≥ 0"));
        }
    } else if !pos(train.follower_mass) {
        return Err(SolveError::invalid("ValveTrain.follower_mass", "must be > 0"));
    }
    if !nonneg(train.valve_mass) || (train.train.is_some() && !pos(train.valve_mass)) {
        return Err(SolveError::invalid("ValveTrain.valve_mass", "must be > 0 with an elastic train (≥ 0 when rigid)"));
    }
    if let Some(l) = train.train {
        if !pos(l.stiffness) || !nonneg(l.damping) {
            return Err(SolveError::invalid("ValveTrain.train", "stiffness must be > 0, damping ≥ 0"));
        }
    }
    validate_spring(&train.spring, "ValveTrain.spring")?;
    if let Some(inner) = &train.inner_spring {
        validate_spring(&inner.spring, "ValveTrain.inner_spring")?;
        if !(inner.preload.is_finite() && inner.preload >= 0.0 && inner.preload <= train.preload) {
            return Err(SolveError::invalid("ValveTrain.inner_spring.preload", "must be ≥ 0 and at most the total preload"));
        }
    }
    if !pos(train.contact.stiffness) || !nonneg(train.contact.damping) {
        return Err(SolveError::invalid("ValveTrain.contact", "stiffness must be > 0, damping ≥ 0"));
    }
    if !train.preload.is_finite() {
        return Err(SolveError::invalid("ValveTrain.preload", "must be finite"));
    }
    if let Some(s) = train.seat {
        if !pos(s.link.stiffness) || !nonneg(s.link.damping) || !nonneg(s.gap) {
            return Err(SolveError::invalid("ValveTrain.seat", "stiffness > 0, damping ≥ 0, gap ≥ 0"));
        }
    }
    match train.lash {
        Some(Lash::Mechanical(c)) => {
            if !nonneg(c) {
                return Err(SolveError::invalid("ValveTrain.lash", "must be ≥ 0"));
            }
            if c > 0.0 && train.seat.is_none() {
                return Err(SolveError::invalid("ValveTrain.lash", "a lash needs the valve seat, which carries the spring preload while the gap is open"));
            }
            if c > 0.0 && !(drive.max_lift > c) {
                return Err(SolveError::invalid("ValveTrain.lash", "must be below the cam's lift"));
            }
        }
        Some(Lash::Hydraulic(h)) => validate_hla(train, &h)?,
        None => {}
    }
    if !pos(drive.omega) {
        return Err(SolveError::invalid("Drive.omega", "must be > 0"));
    }
    // Every lumped body needs mass (with a lever the follower may be massless when the lever's
    // inertia stands for it; with a pushrod both of its ends need mass).
    let asm = train.assemble();
    if asm.spring_events() > 28 {
        return Err(SolveError::invalid("ValveTrain.spring", "progressive springs with more than 28 closing segments in all (elements + 1 per spring) are not supported"));
    }
    if let Some(i) = asm.masses.iter().position(|m| !pos(*m)) {
        let field = if i == asm.follower { "ValveTrain.follower_mass" } else { "ValveTrain.lever" };
        return Err(SolveError::invalid(field, "a lumped body of the train has no mass (follower, lever or valve)"));
    }
    Ok(())
}
