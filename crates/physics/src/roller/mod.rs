//! Roller follower dynamics: the roller's own speed from the torque balance of seed 000 eq. 1 /
//! seed 001 eq. 26,
//!
//! `I dΩ/dt = R_f F_t(u_s) − T_pin(Ω)`,   `u_s = u_c − u_f`,   `u_f = R_f Ω + u_fb`,
//!
//! where `F_t` is the cam–roller traction (film shear + asperity friction, from a
//! [`FilmModel`]), `T_pin` the roller–pin friction torque ([`pin`]), `u_c` the cam surface velocity
//! and `u_fb` the follower-surface velocity of the moving contact point (see
//! [`crate::cam::kinematics`]). Traction against slip is stiff (a thick viscous film
//! locks the roller within microseconds), so time integration is implicit (variable-step BDF2,
//! L-stable) and each step solves `g(Ω) = 0` for the new speed. `g` is monotone increasing in Ω,
//! with possible jumps where a friction law is set-valued (Coulomb asperities at `u_s = 0`, a
//! Coulomb pin at `Ω = 0`); [`monotone_root`] finds the unique root, returning the jump point
//! itself when zero lies inside the jump (sticking).
//!
//! Slide-to-roll ratio (seed 000): `SRR = 2(u_c − u_r)/(u_c + u_r) = u_s/u_e`.

pub mod pin;
pub mod pin_finite;
pub mod point;

// The crown lives in the geometry room (`crate::geometry`); its paths here stay.
pub use crate::geometry::crown::{self, Crown, CrownProfile, CrownedContact};
pub use pin::{pin_film_temperature, pin_film_temperature_warm, pin_torque, pin_torque_warm, PinFriction};
pub use pin_finite::{FinitePin, FinitePinState, PinTable, PinThermal};
pub use point::{PointBalance, PointCase};

use crate::film::{ContactInput, FilmModel, FilmSolution, Traction};
use crate::SolveError;

/// The roller, as far as its own rotation is concerned.
#[derive(Debug, Clone, PartialEq)]
pub struct RollerParams {
    /// Outer radius R_f, m.
    pub radius: f64,
    /// Moment of inertia about its axis, kg·m².
    pub inertia: f64,
    pub pin: PinFriction,
}

/// Moment of inertia of a solid ring (a roller on its pin bore) about its axis, kg·m²:
/// `J = ½ ρ π L (R⁴ − r⁴)` (thick-walled cylinder).
pub fn ring_inertia(density: f64, radius: f64, bore_radius: f64, length: f64) -> f64 {
    0.5 * density * std::f64::consts::PI * length * (radius.powi(4) - bore_radius.powi(4))
}

/// Root of a monotone non-decreasing function `f(x, side)` that may jump at the points `jumps`
/// (`side` −1/+1 asks for the left/right limit there, 0 elsewhere). Returns a jump point when
/// zero lies within its jump. `f` returns `(value, slope)`; `scale` is a typical |x|.
pub fn monotone_root(
    f: impl Fn(f64, i8) -> (f64, f64),
    jumps: &[f64],
    guess: f64,
    scale: f64,
) -> Result<f64, SolveError> {
    let mut js: Vec<f64> = jumps.iter().copied().filter(|j| j.is_finite()).collect();
    js.sort_by(|a, b| a.total_cmp(b));
    js.dedup();
    let mut lo: Option<f64> = None; // f(lo+) < 0
    let mut hi: Option<f64> = None; // f(hi−) > 0
    for &j in &js {
        let (l, _) = f(j, -1);
        if l > 0.0 {
            // Root strictly left of j (f is non-decreasing): later jumps cannot hold it.
            hi = Some(j);
            break;
        }
        let (r, _) = f(j, 1);
        if r >= 0.0 {
            return Ok(j);
        }
        lo = Some(j);
    }
    let scale = scale.abs().max(1e-12);
    let val = |x: f64, at_lo: bool| -> (f64, f64) {
        if js.contains(&x) { f(x, if at_lo { 1 } else { -1 }) } else { f(x, 0) }
    };
    // Safeguarded Newton from the guess (the roller's caller predicts the root closely, and with
    // an exact slope two or three evaluations suffice): the iterates themselves bracket the root
    // (`a`: f < 0, `b`: f > 0); a Newton step leaving the bracket is replaced by bisection, and
    // without a usable slope on an open side the search expands in doubling steps. Stop when the
    // Newton step (or the bracket) is below 1e-12 of the scale — the residual is a difference of
    // large torques, so asking for more only chases round-off.
    let (mut a, mut b) = (lo, hi);
    let mut x = guess;
    if let Some(lo) = a {
        if x <= lo {
            x = match b { Some(hi) => 0.5 * (lo + hi), None => lo + scale };
        }
    }
    if let Some(hi) = b {
        if x >= hi {
            x = match a { Some(lo) => 0.5 * (lo + hi), None => hi - scale };
        }
    }
    let mut expand = scale;
    // Last residuals (ring buffer, for the error report).
    let mut history = [f64::NAN; 10];
    let mut count = 0usize;
    let mut tol = 1e-12 * scale.max(x.abs());
    for _ in 0..300 {
        let (g, dg) = val(x, false);
        history[count % 10] = g.abs();
        count += 1;
        if g == 0.0 {
            return Ok(x);
        }
        if g < 0.0 { a = Some(x) } else { b = Some(x) }
        tol = 1e-12 * scale.max(x.abs());
        if let (Some(lo), Some(hi)) = (a, b) {
            if hi - lo <= tol {
                return Ok(0.5 * (lo + hi));
            }
        }
        let newton = if dg > 0.0 { x - g / dg } else { f64::NAN };
        // A converged step may round onto the bracket end x itself: test it first.
        if (newton - x).abs() <= tol {
            return Ok(newton);
        }
        let inside = newton.is_finite() && a.is_none_or(|lo| newton > lo) && b.is_none_or(|hi| newton < hi);
        if inside {
            x = newton;
        } else {
            x = match (a, b) {
                (Some(lo), Some(hi)) => 0.5 * (lo + hi),
                (Some(lo), None) => lo + expand,
                (None, Some(hi)) => hi - expand,
                (None, None) => unreachable!("g is either negative or positive"),
            };
            expand *= 2.0;
        }
    }
    if a.is_none() || b.is_none() {
        return Err(SolveError::physical(crate::PhysicalFailure::RollerSpeedUnbounded, "the roller torque balance has no root (no sign change found)"));
    }
    Err(SolveError::NotConverged {
        solver: "roller torque balance",
        iterations: 300,
        residual: history[(count + 9) % 10],
        tolerance: tol,
        history: (0..10).map(|k| history[(count + k) % 10]).collect(),
    })
}

/// One implicit step of the roller speed: everything but Ω is fixed.
pub struct SlipStep<'a> {
    pub model: &'a dyn FilmModel,
    pub film: &'a FilmSolution,
    pub input: &'a ContactInput<'a>,
    /// Cam surface velocity u_c, m/s.
    pub cam_surface_velocity: f64,
    /// Follower surface velocity of the contact point's own motion u_fb, m/s.
    pub follower_surface_base: f64,
    pub roller: &'a RollerParams,
    /// Load on the pin, N.
    pub pin_load: f64,
    /// The inertia torque is approximated as `inertia_coefficient · Ω + inertia_offset` (N·m)
    /// by the time discretisation (0 and 0 for a quasi-static balance).
    pub inertia_coefficient: f64,
    pub inertia_offset: f64,
    /// Warm start of the pin's eccentricity solve (NaN: none); see [`pin_torque_warm`].
    pub pin_warm: std::cell::Cell<f64>,
}

/// Result of a roller-speed solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipSolution {
    /// Roller angular speed Ω, rad/s.
    pub omega: f64,
    /// Sliding velocity u_s = u_c − u_f, m/s.
    pub sliding: f64,
    /// Traction on the roller, N.
    pub traction: Traction,
    /// Roller–pin friction torque, N·m.
    pub pin_torque: f64,
    /// Effective film temperature of a finite hydrodynamic pin, K ([`pin_film_temperature`];
    /// `None` for the other pin models).
    pub pin_temperature: Option<f64>,
}

impl SlipStep<'_> {
    fn sliding(&self, omega: f64) -> f64 {
        self.cam_surface_velocity - self.follower_surface_base - self.roller.radius * omega
    }
    /// Speed at which the roller rolls without sliding.
    pub fn rolling_speed(&self) -> f64 {
        (self.cam_surface_velocity - self.follower_surface_base) / self.roller.radius
    }
    /// `(g, dg/dΩ)` of the balance, and the traction and pin torque `(T, dT/dΩ)` behind it.
    fn residual(&self, omega: f64, side: i8) -> ((f64, f64), Traction, (f64, f64)) {
        let (g, t, pin, _) = self.residual_local(omega, side);
        (g, t, pin)
    }

    /// [`Self::residual`] and the traction's curvature bound `(bound, reach)` in `u_s`
    /// ([`FilmModel::traction_local`]).
    fn residual_local(&self, omega: f64, side: i8) -> ((f64, f64), Traction, (f64, f64), (f64, f64)) {
        let rf = self.roller.radius;
        let us = self.sliding(omega);
        let (t, curvature) = self.model.traction_local(self.film, self.input, us);
        let roll = self.rolling_speed();
        // Traction jump at u_s = 0 (Ω = Ω_roll): left of it u_s > 0.
        let ft = if omega == roll && side != 0 { -(side as f64) * t.stick_limit + t.force } else { t.force };
        let pin_side = if omega == 0.0 { side } else { 0 };
        let (tp, dtp) = pin_torque_warm(&self.roller.pin, omega, self.pin_load, pin_side, &self.pin_warm);
        (
            (
                self.inertia_coefficient * omega + self.inertia_offset - rf * ft + tp,
                self.inertia_coefficient + rf * rf * t.slope + dtp,
            ),
            t,
            (tp, dtp),
            curvature,
        )
    }

    /// The common case of a good predictor: one evaluation of the balance at `x` and a Newton
    /// step, accepted when the root provably lies within `tol` of its end — the pin torque is
    /// evaluated there (cheap), the traction's deviation from its tangent is bounded by its
    /// curvature ([`FilmModel::traction_local`]), and the slope of the balance stays above
    /// half its value within twice the step. Traction at the end follows from its tangent (error
    /// within the same bound). `Err(x')`: not accepted; `x'` is where to continue the search
    /// (the Newton point when usable, else `x`).
    fn one_newton_step(&self, x: f64, jumps: &[f64; 2], tol: f64) -> Result<SlipSolution, f64> {
        if x == 0.0 || jumps.contains(&x) || !x.is_finite() {
            return Err(x);
        }
        let ((g, dg), t, (tp, dtp), (curvature, smooth)) = self.residual_local(x, 0);
        if !(dg > 0.0 && g.is_finite()) {
            return Err(x);
        }
        let delta = -g / dg;
        let x1 = x + delta;
        if !x1.is_finite() {
            return Err(x);
        }
        let reach = 2.0 * delta.abs();
        if jumps.iter().any(|&j| (j - x).abs() <= reach) || x.abs() <= reach {
            return Err(x1);
        }
        let rf = self.roller.radius;
        let du = -rf * delta;
        if rf * reach > smooth {
            return Err(x1);
        }
        let (tp1, dtp1) = pin_torque_warm(&self.roller.pin, x1, self.pin_load, 0, &self.pin_warm);
        // g(x1) is what the tangents missed: the pin's (exact) and the traction's (bounded).
        let residual = (tp1 - (tp + dtp * delta)).abs() + rf * 0.5 * curvature * du * du;
        let slope_min = self.inertia_coefficient + rf * rf * (t.slope - curvature * rf * reach) + dtp.min(dtp1);
        if !(slope_min > 0.5 * dg) || !(residual <= tol * slope_min) {
            return Err(x1);
        }
        let traction = Traction { force: t.force + t.slope * du, viscous: t.viscous + t.slope * du, ..t };
        let pin_temperature = pin_film_temperature_warm(&self.roller.pin, x1, self.pin_load, &self.pin_warm);
        Ok(SlipSolution { omega: x1, sliding: self.sliding(x1), traction, pin_torque: tp1, pin_temperature })
    }

    /// Speeds where the balance jumps (NaN: none): the rolling speed when asperities can stick,
    /// and Ω = 0 with a Coulomb pin.
    fn jumps(&self) -> [f64; 2] {
        let stick = self.model.stick_limit(self.film, self.input) > 0.0;
        let coulomb_pin = matches!(self.roller.pin, PinFriction::Coefficient { .. });
        [if stick { self.rolling_speed() } else { f64::NAN }, if coulomb_pin { 0.0 } else { f64::NAN }]
    }

    /// Solve for Ω, starting the search at `guess`.
    pub fn solve(&self, guess: f64) -> Result<SlipSolution, SolveError> {
        let roll = self.rolling_speed();
        let scale = roll.abs().max(guess.abs()).max(1e-6);
        let jumps = self.jumps();
        let tol = 1e-12 * scale.max(guess.abs());
        let guess = match self.one_newton_step(guess, &jumps, tol) {
            Ok(solution) => return Ok(solution),
            Err(next) => next,
        };
        // The last smooth evaluation (Ω, traction, pin torque and slope): the root is at most a
        // converged Newton step (≤ 1e-12 of the scale) away from it, so traction and pin torque
        // there follow to first order — error ~(1e-12)² relative — without evaluating them again.
        let last: std::cell::Cell<Option<(f64, Traction, (f64, f64))>> = std::cell::Cell::new(None);
        let omega = monotone_root(
            |x, side| {
                let (g, t, pin) = self.residual(x, side);
                last.set((side == 0).then_some((x, t, pin)));
                g
            },
            &jumps,
            guess,
            scale,
        )?;
        let us = self.sliding(omega);
        let (mut traction, tp) = match last.get() {
            Some((x, t, (tp, dtp))) if omega != roll && omega != 0.0 && (omega - x).abs() <= 1e-9 * scale => {
                // u_s = u_c − u_fb − R_f Ω. The viscous part takes the total slope too: exact
                // with Coulomb asperities (no slope away from u_s = 0); with Carter's law it is
                // off by the asperity share of a correction that is itself ~1e-12 relative.
                let dus = -self.roller.radius * (omega - x);
                let traction = Traction { force: t.force + t.slope * dus, viscous: t.viscous + t.slope * dus, ..t };
                (traction, tp + dtp * (omega - x))
            }
            _ => (
                self.model.traction(self.film, self.input, us),
                pin_torque_warm(&self.roller.pin, omega, self.pin_load, 0, &self.pin_warm).0,
            ),
        };
        if omega == roll {
            // Stuck: the asperities carry whatever the balance requires.
            traction.force = (self.inertia_coefficient * omega + self.inertia_offset + tp) / self.roller.radius;
        }
        let pin = if omega == 0.0 {
            // Stuck on the pin: the pin carries the rest of the balance.
            self.roller.radius * traction.force - self.inertia_offset
        } else {
            tp
        };
        let pin_temperature = pin_film_temperature_warm(&self.roller.pin, omega, self.pin_load, &self.pin_warm);
        Ok(SlipSolution { omega, sliding: us, traction, pin_torque: pin, pin_temperature })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::closed_form::test_inputs::{oil, seed001_nose};
    use crate::film::{ClosedForm, FilmFormula};
    use crate::friction::{AsperityFriction, AsperityModel, Rheology, Roughness, TractionLaw};

    /// The balance of one implicit (BDF1) step of 1e-5 s from `previous` (rad/s), cam surface
    /// speed `uc`, pin load = contact load.
    fn bdf1_step<'a>(
        model: &'a ClosedForm,
        film: &'a FilmSolution,
        input: &'a ContactInput<'a>,
        roller: &'a RollerParams,
        uc: f64,
        previous: f64,
    ) -> SlipStep<'a> {
        let (c, o) = if roller.inertia > 0.0 { (roller.inertia / 1e-5, -roller.inertia * previous / 1e-5) } else { (0.0, 0.0) };
        SlipStep {
            model,
            film,
            input,
            cam_surface_velocity: uc,
            follower_surface_base: 0.0,
            roller,
            pin_load: input.load,
            inertia_coefficient: c,
            inertia_offset: o,
            pin_warm: std::cell::Cell::new(f64::NAN),
        }
    }

    /// Seed 001's pin as a finite bearing with the energy balance (L/D = 21/18.2).
    fn finite_seed001_pin() -> PinFriction {
        let (r, l) = (0.0091, 0.021);
        PinFriction::FiniteBearing(FinitePin {
            pin_radius: r,
            clearance: 10e-6,
            length: l,
            lubricant: crate::lubricant::Lubricant { viscosity: 0.013, ..crate::lubricant::Lubricant::SEED000 },
            ambient_temperature: 313.0,
            thermal: Some(PinThermal {
                oil_specific_heat: 1700.0,
                oil_density: 870.0,
                convection_coefficient: 80.0,
                cooled_area: pin_finite::roller_cooled_area(0.0125, r, l),
            }),
            table: pin_finite::tests::table(l / (2.0 * r)),
        })
    }

    /// Seed 001-like nose contact with an Eyring film, rough surfaces and the three pin models.
    #[test]
    fn one_newton_step_agrees_with_the_bracketed_search() {
        let lub = oil();
        let rough = Roughness { sigma: 0.3e-6, eta_beta_sigma: 0.05, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
        let law = TractionLaw { rheology: Rheology::Eyring { tau0: 5e6 }, limiting_shear_coefficient: None };
        let model = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
        let pins = [
            PinFriction::ShortBearing { pin_radius: 0.0091, clearance: 10e-6, length: 0.021, viscosity: 0.013 },
            PinFriction::Coefficient { coefficient: 0.005, pin_radius: 0.0091 },
            finite_seed001_pin(),
        ];
        let mut fast = 0;
        for (asp_model, pin, inertia, load) in [
            (AsperityModel::Coulomb, pins[0].clone(), 0.0, 12_500.0),
            (AsperityModel::Carter, pins[0].clone(), 2e-5, 12_500.0),
            (AsperityModel::Coulomb, pins[1].clone(), 2e-5, 3_000.0),
            (AsperityModel::Carter, pins[1].clone(), 0.0, 800.0),
            // The finite (thermal) pin without inertia: with 2e-5 kg·m² the 1e-9 traction check
            // below reads the inertia term's 2·tol freedom in Ω (ΔF = I/Δt · ΔΩ/R_f ≈ 1e-8
            // relative), not the pin.
            (AsperityModel::Coulomb, pins[2].clone(), 0.0, 12_500.0),
            (AsperityModel::Carter, pins[2].clone(), 0.0, 3_000.0),
        ] {
            let asp = AsperityFriction { coefficient: 0.12, model: asp_model, map: None };
            let input = ContactInput { load, ..seed001_nose(&lub, &rough, &law, &asp) };
            let film = model.solve(&input, None).unwrap();
            let roller = RollerParams { radius: 0.0125, inertia, pin };
            // Implicit steps from a few previous speeds.
            for previous in [600.0, 630.0, 636.0, 636.7] {
                let step = || bdf1_step(&model, &film, &input, &roller, 7.96, previous);
                let reference = step().solve(previous - 50.0).unwrap(); // far guess: bracketed search
                for rel in [1e-9, 1e-7, 1e-5, 1e-3] {
                    let p = step();
                    let jumps = p.jumps();
                    let tol = 1e-12 * reference.omega.abs();
                    let guess = reference.omega * (1.0 + rel);
                    let got = p.solve(guess).unwrap();
                    let scale = reference.omega.abs();
                    assert!((got.omega - reference.omega).abs() <= 2.0 * tol, "{asp_model:?} {:?}: {} vs {}", roller.pin, got.omega, reference.omega);
                    // The traction agrees to 1e-9 of itself plus what the speeds' own difference
                    // (≤ 2e-12 relative) moves it by: the film's rolling resistance (≈ −1 N here)
                    // offsets the force, so a relative bound alone reads that slope.
                    let speed_part = got.traction.slope.abs() * (got.omega - reference.omega).abs() * roller.radius;
                    assert!((got.traction.force - reference.traction.force).abs() <= 1e-9 * reference.traction.force.abs().max(1e-9) + 1.01 * speed_part, "{asp_model:?} prev {previous} rel {rel}: F {} vs {}, Ω {} vs {}, pin {} vs {}", got.traction.force, reference.traction.force, got.omega, reference.omega, got.pin_torque, reference.pin_torque);
                    assert!((got.pin_torque - reference.pin_torque).abs() <= 1e-9 * reference.pin_torque.abs().max(1e-12));
                    assert_eq!(got.pin_temperature.is_some(), matches!(roller.pin, PinFriction::FiniteBearing(_)));
                    if let (Some(a), Some(b)) = (got.pin_temperature, reference.pin_temperature) {
                        assert!(a > 313.0 && (a - b).abs() <= 1e-9 * b, "pin temperature {a} vs {b}");
                    }
                    if p.one_newton_step(guess, &jumps, 1e-12 * scale).is_ok() {
                        fast += 1;
                    }
                }
            }
        }
        // Close guesses take the one-evaluation path.
        assert!(fast >= 16, "{fast} one-step solves");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 256, ..Default::default() })]
        /// Wherever the one-evaluation step is accepted, its speed lies within the tolerance of
        /// the root found by the bracketed search, across loads, speeds, Eyring stresses,
        /// asperity laws, pins, inertia and guess errors from 1e-11 to 1e-2.
        #[test]
        fn one_newton_step_lands_within_tolerance_of_the_root(
            load in 50.0f64..3e4,
            uc in 0.2f64..20.0,
            tau0 in 1e6f64..3e7,
            rq in 0.0f64..0.5e-6,
            carter in proptest::bool::ANY,
            coulomb_pin in proptest::bool::ANY,
            inertia in 0.0f64..1e-4,
            lag in 0.0f64..0.3,
            log_offset in -11.0f64..-2.0,
            above in proptest::bool::ANY,
        ) {
            let lub = oil();
            let rough = Roughness { sigma: rq, eta_beta_sigma: 0.05, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None };
            let law = TractionLaw { rheology: Rheology::Eyring { tau0 }, limiting_shear_coefficient: None };
            let model = ClosedForm { formula: FilmFormula::PanHamrock, squeeze: false };
            let asp = AsperityFriction { coefficient: 0.12, model: if carter { AsperityModel::Carter } else { AsperityModel::Coulomb }, map: None };
            let input = ContactInput { load, entrainment_velocity: 0.5 * uc, ..seed001_nose(&lub, &rough, &law, &asp) };
            let film = model.solve(&input, None).unwrap();
            let pin = if coulomb_pin {
                PinFriction::Coefficient { coefficient: 0.005, pin_radius: 0.0091 }
            } else {
                PinFriction::ShortBearing { pin_radius: 0.0091, clearance: 10e-6, length: 0.021, viscosity: 0.013 }
            };
            let roller = RollerParams { radius: 0.0125, inertia, pin };
            let roll = uc / roller.radius;
            // From a previous speed lagging the rolling speed.
            let p = bdf1_step(&model, &film, &input, &roller, uc, roll * (1.0 - lag));
            let jumps = p.jumps();
            let root = monotone_root(|x, side| p.residual(x, side).0, &jumps, roll * (1.0 - lag), roll).unwrap();
            let guess = root * (1.0 + if above { 1.0 } else { -1.0 } * 10f64.powf(log_offset));
            let tol = 1e-12 * roll.max(guess.abs());
            if let Ok(sol) = p.one_newton_step(guess, &jumps, tol) {
                // The bracketed search itself stops within its own 1e-12 of the scale.
                proptest::prop_assert!((sol.omega - root).abs() <= 2.0 * tol, "{} vs {root}", sol.omega);
                proptest::prop_assert!(sol.traction.force.is_finite() && sol.pin_torque.is_finite());
            }
        }
    }

    #[test]
    fn monotone_root_finds_smooth_roots_and_sticks_inside_jumps() {
        let f = |x: f64, _s: i8| (x * x * x + x - 2.0, 3.0 * x * x + 1.0);
        let r = monotone_root(f, &[], 0.0, 1.0).unwrap();
        assert!((r - 1.0).abs() < 1e-12);
        // Coulomb-like jump at 0.5: f = x − 0.4 + 0.3 sign(x − 0.5): −0.2 → +0.4 at x = 0.5.
        let g = |x: f64, s: i8| {
            let sg = if x > 0.5 { 1.0 } else if x < 0.5 { -1.0 } else { s as f64 };
            (x - 0.4 + 0.3 * sg, 1.0)
        };
        assert_eq!(monotone_root(g, &[0.5], 0.0, 1.0).unwrap(), 0.5);
        // Shifted so that the root lies on the right branch: x − 1.0 + 0.3 sign → root 0.7.
        let h = |x: f64, s: i8| {
            let sg = if x > 0.5 { 1.0 } else if x < 0.5 { -1.0 } else { s as f64 };
            (x - 1.0 + 0.3 * sg, 1.0)
        };
        assert!((monotone_root(h, &[0.5], 0.0, 1.0).unwrap() - 0.7).abs() < 1e-12);
        // Stiff: slope 1e12 around the root.
        let k = |x: f64, _s: i8| (1e12 * (x - 3.0) + (x - 3.0).powi(3), 1e12 + 3.0 * (x - 3.0).powi(2));
        assert!((monotone_root(k, &[], 0.0, 1.0).unwrap() - 3.0).abs() < 1e-11);
    }
}


