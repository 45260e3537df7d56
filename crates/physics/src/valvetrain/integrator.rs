//! A small stiff integrator for piecewise-linear mechanical systems: TR-BDF2 with an embedded
//! error estimate, step-size control, dense (Hermite) output and event location.
//!
//! TR-BDF2 (Bank et al. 1985; as an ESDIRK and with the error estimate of Hosea & Shampine,
//! "Analysis and implementation of TR-BDF2", Appl. Numer. Math. 20 (1996) 21–37): a trapezoidal
//! stage to `t + γh` followed by a BDF2 stage to `t + h`, `γ = 2 − √2`, `d = γ/2`,
//! `w = √2/4`; tableau `c = (0, γ, 1)`, `A = [[0], [d, d], [w, w, d]]`, `b = (w, w, d)` (stiffly
//! accurate), embedded `b̂ = ((1 − w)/3, (3w + 1)/3, d/3)`. It is L-stable and second order; the
//! local error estimate `h Σ (b − b̂)ᵢ kᵢ` is filtered through `(I − d h J)⁻¹` (Shampine's device
//! against the estimate's growth on stiff components, as Hosea & Shampine do).
//!
//! The systems here are affine within a *regime* (which unilateral contacts are closed): the
//! Jacobian is constant there and one Newton step with it solves a stage exactly. A stage whose
//! Newton iterate changes regime is iterated with the new regime's Jacobian (a semismooth
//! Newton); the iteration matrix `I − d h J` is factorised once per `(h, regime)` and reused.
//! Step sizes change only when the controller asks for a ratio outside `[1, 1.25]` so that
//! factorisations are reused along smooth stretches.
//!
//! Events (regime switches: contact loss, re-contact, seating) are located on the Hermite
//! interpolant by the Illinois method; a step whose interior holds a switch is retaken to end
//! just past it, so that no step integrates across a kink of the right-hand side.

use crate::SolveError;

/// A first-order system `y' = f(t, y)`, affine in `y` within each regime.
pub trait System {
    fn dim(&self) -> usize;
    /// `f(t, y)`.
    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]);
    /// Bit set of the closed unilateral constraints at `(t, y)`.
    fn regime(&self, t: f64, y: &[f64]) -> u32;
    /// `∂f/∂y` (row-major, `dim × dim`) in `regime`.
    fn jacobian(&self, regime: u32, j: &mut [f64]);
    /// Number of event functions.
    fn events(&self) -> usize;
    /// Event functions at `(t, y)` (an event is a sign change).
    fn event_values(&self, t: f64, y: &[f64], g: &mut [f64]);
    /// Absolute error scale of each component (the relative part is the tolerance times |y|).
    fn scale(&self) -> &[f64];
    /// Whether event `e` switches the regime (a step is retaken to end at it); other events are
    /// only reported.
    fn switches(&self, e: usize) -> bool {
        let _ = e;
        true
    }
    /// Whether component `i` takes part in the error norm and the Newton iteration (quadratures
    /// do not: their stage derivative is taken at the solved stage).
    fn controlled(&self, i: usize) -> bool {
        let _ = i;
        true
    }
}

/// Dense LU factorisation with partial pivoting (Golub & Van Loan, Alg. 3.4.1), for the small
/// systems of a lumped model (n ≲ 50). Row-major storage.
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
}

impl Lu {
    /// Factorise `a` (row-major `n × n`); `None` when it is singular.
    pub fn new(n: usize, mut a: Vec<f64>) -> Option<Self> {
        let mut piv = vec![0; n];
        for k in 0..n {
            let mut p = k;
            let mut best = a[k * n + k].abs();
            for i in k + 1..n {
                let v = a[i * n + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if !(best > 0.0) || !best.is_finite() {
                return None;
            }
            piv[k] = p;
            if p != k {
                for j in 0..n {
                    a.swap(k * n + j, p * n + j);
                }
            }
            let inv = 1.0 / a[k * n + k];
            for i in k + 1..n {
                let l = a[i * n + k] * inv;
                a[i * n + k] = l;
                if l != 0.0 {
                    for j in k + 1..n {
                        a[i * n + j] -= l * a[k * n + j];
                    }
                }
            }
        }
        Some(Lu { n, a, piv })
    }

    /// Solve `A x = b` in place.
    pub fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        for k in 0..n {
            b.swap(k, self.piv[k]);
        }
        for i in 0..n {
            let mut s = b[i];
            for j in 0..i {
                s -= self.a[i * n + j] * b[j];
            }
            b[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = b[i];
            for j in i + 1..n {
                s -= self.a[i * n + j] * b[j];
            }
            b[i] = s / self.a[i * n + i];
        }
    }
}

/// Step control of [`integrate`].
#[derive(Debug, Clone, Copy)]
pub struct StepControl {
    /// Relative tolerance; absolute tolerances are this times [`System::scale`].
    pub tolerance: f64,
    /// Largest step, s.
    pub max_step: f64,
    /// First step tried, s.
    pub first_step: f64,
    /// Most steps (accepted and rejected) before the integration gives up.
    pub max_steps: usize,
}

/// A located event.
#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    /// Which event function.
    pub index: usize,
    pub time: f64,
    /// `true` when the function went from ≤ 0 to > 0.
    pub rising: bool,
    /// Interpolated state at the event.
    pub state: Vec<f64>,
}

/// Counters of one integration.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    pub accepted: usize,
    pub rejected: usize,
    pub factorisations: usize,
    /// Step size at the end (to continue with).
    pub last_step: f64,
}

const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;
const D: f64 = GAMMA / 2.0;
const W: f64 = std::f64::consts::SQRT_2 / 4.0;

struct Factor {
    h: f64,
    regime: u32,
    lu: Lu,
}

/// Cubic Hermite interpolant on `[t0, t0 + h]` through `(y0, f0)`, `(y1, f1)`, at fraction `s`.
fn hermite(y0: &[f64], f0: &[f64], y1: &[f64], f1: &[f64], h: f64, s: f64, out: &mut [f64]) {
    let (s2, s3) = (s * s, s * s * s);
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    for i in 0..out.len() {
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
    }
}

/// Integrate `sys` from `(t0, y0)` to `t1`. `samples` (increasing times in `(t0, t1]`) receive
/// the interpolated state through `on_sample(index, t, y)`; located events go to `on_event`.
/// Returns the state at `t1` and the counters.
pub fn integrate<S: System>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t1: f64,
    control: StepControl,
    samples: &[f64],
    mut on_sample: impl FnMut(usize, f64, &[f64]),
    mut on_event: impl FnMut(Event),
) -> Result<(Vec<f64>, Stats), SolveError> {
    let n = sys.dim();
    let tol = control.tolerance;
    let ne = sys.events();
    let mut stages = Stages::new(sys);
    let mut t = t0;
    let mut y = y0.to_vec();
    let mut f0 = vec![0.0; n];
    sys.rhs(t, &y, &mut f0);
    let mut g0 = vec![0.0; ne];
    sys.event_values(t, &y, &mut g0);
    let mut h = control.first_step.min(control.max_step).min(t1 - t0);
    let mut next_sample = samples.partition_point(|&s| s <= t0);
    let mut w = Work::new(n, ne);
    let mut retakes = 0;
    let mut steps = 0usize;

    while t < t1 {
        steps += 1;
        if steps > control.max_steps {
            return Err(gave_up("valve-train integrator (step cap)", steps, h, tol));
        }
        let last = t + h >= t1 - 1e-12 * t1.abs().max(1.0);
        let hh = if last { t1 - t } else { h };
        if !(hh > 1e-14 * t1.abs().max(1e-3)) {
            return Err(gave_up("valve-train integrator (step size underflow)", steps, hh, tol));
        }
        if !stages.take_step(t, &y, &f0, hh, &mut w)? {
            stages.stats.rejected += 1;
            h = hh * 0.25;
            continue;
        }
        let norm = stages.error_norm(tol, &y, &f0, hh, &mut w);
        if !norm.is_finite() {
            stages.stats.rejected += 1;
            h = hh * 0.25;
            continue;
        }
        let ratio = (0.9 * norm.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, 4.0);
        if norm > 1.0 {
            stages.stats.rejected += 1;
            h = hh * ratio.min(0.9);
            continue;
        }
        // Events in the step.
        sys.event_values(t + hh, &w.y3, &mut w.g1);
        let span = Span { t, h: hh, y0: &y, f0: &f0, y1: &w.y3, f1: &w.k3 };
        if let Some((_, s)) = span.first_switch(sys, &g0, &w.g1, &mut w.tmp) {
            // A switch inside the step: retake the step to end just past it.
            if s < 0.99 && s * hh > 1e-12 * t1.abs().max(1e-3) && retakes < 3 {
                retakes += 1;
                h = s * hh * (1.0 + 1e-6);
                continue;
            }
        }
        retakes = 0;
        // Accept.
        stages.stats.accepted += 1;
        span.report_switches(sys, &g0, &w.g1, &mut w.tmp, &mut on_event);
        let t_new = if last { t1 } else { t + hh };
        let end = if last { t1 + 1e-9 * (t1 - t0).abs() } else { t_new };
        while next_sample < samples.len() && samples[next_sample] <= end {
            let s = ((samples[next_sample] - t) / hh).clamp(0.0, 1.0);
            span.state(s, &mut w.tmp);
            on_sample(next_sample, samples[next_sample], &w.tmp);
            next_sample += 1;
        }
        t = t_new;
        y.copy_from_slice(&w.y3);
        // FSAL: the last stage's derivative is f at the new point.
        f0.copy_from_slice(&w.k3);
        g0.copy_from_slice(&w.g1);
        // Step size: keep h (and its factorisation) unless the controller wants a real change.
        let grow = if (1.0..=1.25).contains(&ratio) { 1.0 } else { ratio };
        h = (hh * grow).min(control.max_step);
        if last {
            h = hh.max(h.min(control.max_step));
        }
        stages.stats.last_step = h;
    }
    Ok((y, stages.stats))
}

/// The integration gave up (`residual`: the step size at that point).
fn gave_up(solver: &'static str, steps: usize, residual: f64, tolerance: f64) -> SolveError {
    SolveError::NotConverged { solver, iterations: steps as u32, residual, tolerance, history: vec![] }
}

/// Work arrays of one step.
struct Work {
    /// Stage values and derivatives (stage 2 at `t + γh`, stage 3 at `t + h`).
    y2: Vec<f64>,
    y3: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    /// Right-hand side of a stage equation.
    rhs: Vec<f64>,
    /// Event functions at the end of the step.
    g1: Vec<f64>,
    /// Scratch (Newton corrections, interpolated states).
    tmp: Vec<f64>,
    /// Error estimate.
    err: Vec<f64>,
}

impl Work {
    fn new(n: usize, ne: usize) -> Self {
        let (y2, y3, k2, k3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let (rhs, g1, tmp, err) = (vec![0.0; n], vec![0.0; ne], vec![0.0; n], vec![0.0; n]);
        Work { y2, y3, k2, k3, rhs, g1, tmp, err }
    }
}

/// The implicit stages of TR-BDF2: the system, the factorisation of `I − d h J` for the last
/// `(h, regime)`, and the counters.
struct Stages<'s, S: System> {
    sys: &'s S,
    n: usize,
    scale: Vec<f64>,
    factor: Option<Factor>,
    jac: Vec<f64>,
    stats: Stats,
}

impl<'s, S: System> Stages<'s, S> {
    fn new(sys: &'s S) -> Self {
        let n = sys.dim();
        Stages { sys, n, scale: sys.scale().to_vec(), factor: None, jac: vec![0.0; n * n], stats: Stats::default() }
    }

    /// Factorise I − d h J in `regime` unless cached.
    fn ensure(&mut self, h: f64, regime: u32) -> Result<(), SolveError> {
        if self.factor.as_ref().is_some_and(|f| f.h == h && f.regime == regime) {
            return Ok(());
        }
        let n = self.n;
        self.sys.jacobian(regime, &mut self.jac);
        let mut m: Vec<f64> = self.jac.iter().map(|j| -D * h * j).collect();
        for i in 0..n {
            m[i * n + i] += 1.0;
        }
        let lu = Lu::new(n, m).ok_or_else(|| SolveError::NonFinite { quantity: "valve-train iteration matrix".into() })?;
        self.stats.factorisations += 1;
        self.factor = Some(Factor { h, regime, lu });
        Ok(())
    }

    /// Solve the stage equation Y − d h f(ts, Y) = rhs from the guess in `yy`; the stage
    /// derivative goes to `kk`. `false`: no convergence.
    fn stage(&mut self, ts: f64, h: f64, rhs: &[f64], yy: &mut [f64], kk: &mut [f64], tmp: &mut [f64]) -> Result<bool, SolveError> {
        let (sys, n) = (self.sys, self.n);
        let mut regime = sys.regime(ts, yy);
        for _ in 0..8 {
            self.ensure(h, regime)?;
            sys.rhs(ts, yy, kk);
            for i in 0..n {
                tmp[i] = rhs[i] + D * h * kk[i] - yy[i];
            }
            self.factor.as_ref().unwrap().lu.solve(tmp);
            for i in 0..n {
                yy[i] += tmp[i];
            }
            let after = sys.regime(ts, yy);
            if after == regime {
                // Affine within the regime: the step with its exact Jacobian solved the stage.
                // Components outside the Jacobian (quadratures such as the cam's work) take the
                // derivative at the solved stage.
                sys.rhs(ts, yy, kk);
                for i in 0..n {
                    if !sys.controlled(i) {
                        yy[i] = rhs[i] + D * h * kk[i];
                    }
                }
                return Ok(yy.iter().all(|v| v.is_finite()));
            }
            regime = after;
        }
        Ok(false)
    }

    /// Both stages of a step of size `hh` from `(t, y)` with `f0 = f(t, y)`: the trapezoid to
    /// `t + γh`, then BDF2 to `t + h` (into `w.y3`, `w.k3`). `false`: a stage did not converge.
    fn take_step(&mut self, t: f64, y: &[f64], f0: &[f64], hh: f64, w: &mut Work) -> Result<bool, SolveError> {
        let n = self.n;
        // Stage 2 (trapezoid to t + γh).
        for i in 0..n {
            w.rhs[i] = y[i] + D * hh * f0[i];
            w.y2[i] = y[i] + GAMMA * hh * f0[i];
        }
        let ok2 = self.stage(t + GAMMA * hh, hh, &w.rhs, &mut w.y2, &mut w.k2, &mut w.tmp)?;
        let ok3 = ok2 && {
            for i in 0..n {
                w.rhs[i] = y[i] + W * hh * (f0[i] + w.k2[i]);
                w.y3[i] = y[i] + (w.y2[i] - y[i]) / GAMMA;
            }
            self.stage(t + hh, hh, &w.rhs, &mut w.y3, &mut w.k3, &mut w.tmp)?
        };
        Ok(ok3)
    }

    /// Weighted RMS norm of the step's error estimate (filtered through the last factorisation)
    /// over the controlled components; relative tolerance `tol`.
    fn error_norm(&self, tol: f64, y: &[f64], f0: &[f64], hh: f64, w: &mut Work) -> f64 {
        let (e1, e2, e3) = (W - (1.0 - W) / 3.0, W - (3.0 * W + 1.0) / 3.0, D - D / 3.0);
        for (i, err) in w.err.iter_mut().enumerate() {
            *err = hh * (e1 * f0[i] + e2 * w.k2[i] + e3 * w.k3[i]);
        }
        if let Some(f) = self.factor.as_ref() {
            f.lu.solve(&mut w.err);
        }
        let mut norm: f64 = 0.0;
        let mut count = 0;
        for (i, (yi, err)) in y.iter().zip(&w.err).enumerate() {
            if self.sys.controlled(i) {
                let wi = tol * (self.scale[i] + yi.abs().max(w.y3[i].abs()));
                norm += (err / wi).powi(2);
                count += 1;
            }
        }
        (norm / count.max(1) as f64).sqrt()
    }
}

/// A step `[t, t + h]` from `(y0, f0)` to `(y1, f1)` with its dense output.
struct Span<'v> {
    t: f64,
    h: f64,
    y0: &'v [f64],
    f0: &'v [f64],
    y1: &'v [f64],
    f1: &'v [f64],
}

impl Span<'_> {
    /// Interpolated state at fraction `s` of the step.
    fn state(&self, s: f64, out: &mut [f64]) {
        hermite(self.y0, self.f0, self.y1, self.f1, self.h, s, out);
    }

    /// Event function `e` on the interpolated state at fraction `s` (`tmp` receives the state).
    fn event<S: System>(&self, sys: &S, e: usize, s: f64, tmp: &mut [f64]) -> f64 {
        self.state(s, tmp);
        let mut g = vec![0.0; sys.events()];
        sys.event_values(self.t + s * self.h, tmp, &mut g);
        g[e]
    }

    /// The earliest regime switch in the step (event functions `g0` at its start, `g1` at its
    /// end): the event and the fraction of the step just past it.
    fn first_switch<S: System>(&self, sys: &S, g0: &[f64], g1: &[f64], tmp: &mut [f64]) -> Option<(usize, f64)> {
        let mut first: Option<(usize, f64)> = None;
        for e in 0..sys.events() {
            if sys.switches(e) && (g0[e] > 0.0) != (g1[e] > 0.0) {
                let b = self.illinois(sys, e, g0[e], g1[e], tmp);
                if first.is_none_or(|(_, s)| b < s) {
                    first = Some((e, b));
                }
            }
        }
        first
    }

    /// Illinois on the interpolated event function `e` (`fa`, `fb`: its values at the step's
    /// ends): the end of the final bracket just past the sign change.
    fn illinois<S: System>(&self, sys: &S, e: usize, fa: f64, fb: f64, tmp: &mut [f64]) -> f64 {
        let (mut a, mut b) = (0.0, 1.0);
        let (mut fa, mut fb) = (fa, fb);
        let mut side = 0;
        for _ in 0..60 {
            let c = (a * fb - b * fa) / (fb - fa);
            let c = if c.is_finite() && c > a && c < b { c } else { 0.5 * (a + b) };
            let fc = self.event(sys, e, c, tmp);
            if (fc > 0.0) == (fa > 0.0) {
                a = c;
                fa = fc;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            } else {
                b = c;
                fb = fc;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            }
            if b - a < 1e-12 {
                break;
            }
        }
        b
    }

    /// Locate each switch of this step (usually one) by bisection and report it to `on_event`.
    fn report_switches<S: System>(&self, sys: &S, g0: &[f64], g1: &[f64], tmp: &mut [f64], on_event: &mut impl FnMut(Event)) {
        for e in 0..sys.events() {
            if (g0[e] > 0.0) != (g1[e] > 0.0) {
                let (mut a, mut b) = (0.0, 1.0);
                for _ in 0..60 {
                    let c = 0.5 * (a + b);
                    if (self.event(sys, e, c, tmp) > 0.0) == (g0[e] > 0.0) {
                        a = c;
                    } else {
                        b = c;
                    }
                    if b - a < 1e-10 {
                        break;
                    }
                }
                self.state(b, tmp);
                on_event(Event { index: e, time: self.t + b * self.h, rising: g1[e] > 0.0, state: tmp.to_vec() });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_a_pivoting_system() {
        let a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let lu = Lu::new(3, a.clone()).unwrap();
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3).map(|i| (0..3).map(|j| a[i * 3 + j] * x[j]).sum()).collect();
        lu.solve(&mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14);
        }
        assert!(Lu::new(2, vec![1.0, 2.0, 2.0, 4.0]).is_none());
    }

    /// y'' = −ω² y (undamped oscillator): second-order accuracy of TR-BDF2 with its controller.
    struct Osc(f64, [f64; 2]);
    impl System for Osc {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], f: &mut [f64]) {
            f[0] = y[1];
            f[1] = -self.0 * self.0 * y[0];
        }
        fn regime(&self, _t: f64, _y: &[f64]) -> u32 {
            0
        }
        fn jacobian(&self, _r: u32, j: &mut [f64]) {
            j.copy_from_slice(&[0.0, 1.0, -self.0 * self.0, 0.0]);
        }
        fn events(&self) -> usize {
            1
        }
        fn event_values(&self, _t: f64, y: &[f64], g: &mut [f64]) {
            g[0] = y[0];
        }
        fn scale(&self) -> &[f64] {
            &self.1
        }
    }

    #[test]
    fn oscillator_is_integrated_within_tolerance_and_zero_crossings_located() {
        let w = 2.0 * std::f64::consts::PI;
        let sys = Osc(w, [1.0, w]);
        let mut events = Vec::new();
        let control = StepControl { tolerance: 1e-8, max_step: 0.1, first_step: 1e-4, max_steps: 1_000_000 };
        let (y, _) = integrate(&sys, 0.0, &[1.0, 0.0], 3.0, control, &[], |_, _, _| {}, |e| events.push(e)).unwrap();
        assert!((y[0] - 1.0).abs() < 1e-5, "{y:?}");
        // cos(2πt) crosses zero at t = 0.25 + k/2.
        assert_eq!(events.len(), 6);
        for (k, e) in events.iter().enumerate() {
            assert!((e.time - (0.25 + 0.5 * k as f64)).abs() < 1e-5, "{k}: {}", e.time);
        }
    }
}
