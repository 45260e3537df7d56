//! The bound-constrained conjugate gradient shared by the normal and tangential problems:
//! minimise `½ xᵀK x − xᵀ(target − shift)` subject to `lower ≤ x ≤ upper`, with `K` a periodic
//! convolution (symmetric positive semi-definite). Its gradient `g = K x − target + shift` is the
//! gap (normal problem) or the negative slip (tangential problem); the optimum satisfies the
//! contact conditions: `g = 0` where `x` is strictly inside its bounds, `g ≥ 0` at the lower and
//! `g ≤ 0` at the upper bound.
//!
//! Polonsky & Keer (Wear 231, 1999) with the box constraint: conjugate directions on the free
//! set, projection onto the bounds after each step, and their re-entry rule (a bound node whose
//! gradient points inwards is moved by `−τ g` and the conjugacy restarted) applied at both
//! bounds; with a prescribed mean of `x` (load control) the shift is the multiplier of that
//! constraint (the mean of `−(K x − target)` over the free set) and `x` is rescaled after each
//! step (with the upper bound, the scale solving `Σ min(s x, upper) = N·mean`).
//!
//! Those steps need not lower the objective, and with the plastic cap they can cycle: from a
//! cold start with many nodes at `upper` and positive gaps, the re-entry step empties the contact
//! (every node to `lower`), and from there the next re-entry step (τ = 1/K_ii) restores the start,
//! a 2-cycle that no iteration cap ends (issue 40: 66 of 100 seeds of the example surface stalled
//! at residual 0.1–0.2). A step is therefore kept only if it passes the non-monotone test of
//! Grippo, Lampariello & Lucidi (SIAM J. Numer. Anal. 23, 1986, eq. 4): the objective after it is
//! at most the largest of the last [`MEMORY`] objectives plus `γ gᵀd`. Otherwise the iterate
//! moves to the exact minimiser of the objective on the segment from the old to the rejected
//! iterate (feasible: both ends are inside the box) and the conjugacy restarts. The objective
//! change of a step `d` is `gᵀd + ½ dᵀK d`, with `K d` the change of `u = K x` the step computes
//! anyway: the test costs no extra convolution. Polonsky–Keer's own steps, including their
//! occasional non-monotone re-entries, pass it unchanged.

use super::fft::Convolution;
use crate::{Convergence, Observer, SolveError, Termination};

#[derive(Debug, Clone, Copy)]
pub(crate) enum Control {
    /// The shift is given (separation or tangential displacement control).
    Shift(f64),
    /// The mean of `x` is given (load control; needs `lower = 0`).
    Mean(f64),
}

pub(crate) struct BoxCg<'a> {
    pub op: &'a Convolution,
    pub target: &'a [f64],
    pub lower: &'a [f64],
    pub upper: &'a [f64],
    pub control: Control,
    /// Residual normalisation (a length), > 0.
    pub scale: f64,
    pub tolerance: f64,
    pub max_iterations: u32,
    pub solver: &'static str,
}

pub(crate) struct BoxSolution {
    pub x: Vec<f64>,
    /// The gradient `K x − target + shift` at the solution.
    pub gradient: Vec<f64>,
    pub shift: f64,
    pub convergence: Convergence,
}

/// Full recomputation of `K x` at least this often (the update `u −= τ K t` drifts by rounding).
const REFRESH: u32 = 25;

/// Objectives the non-monotone acceptance test looks back over (Grippo et al. 1986 use 10).
const MEMORY: usize = 10;

/// Sufficient-decrease factor γ of that test (Grippo et al. 1986: 1e-4).
const SUFFICIENT_DECREASE: f64 = 1e-4;

impl BoxCg<'_> {
    pub(crate) fn solve(&self, mut x: Vec<f64>, observer: &dyn Observer) -> Result<BoxSolution, SolveError> {
        let n = x.len();
        let (lo, hi) = (self.lower, self.upper);
        for i in 0..n {
            x[i] = x[i].clamp(lo[i], hi[i]);
        }
        if let Control::Mean(m) = self.control {
            rescale(&mut x, hi, m);
        }
        let mut ws = self.op.workspace();
        let (mut u, mut g, mut t, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut free = vec![false; n];
        let (mut x_old, mut u_old) = (vec![0.0; n], vec![0.0; n]);
        let mut recent = RecentObjectives::new();
        self.op.apply(&x, &mut u, &mut ws);
        let (mut g_old, mut conjugate, mut since_refresh) = (1.0, false, 0u32);
        let mut history: Vec<f64> = Vec::new();
        let mut iteration = 0u32;
        loop {
            observer.check()?;
            let (n_f, shift) = self.gradient(&x, &u, &mut g, &mut free);
            let residual = violation(&x, &g, &free, lo, hi) / self.scale;
            if !residual.is_finite() {
                return Err(SolveError::NonFinite { quantity: format!("{} residual", self.solver) });
            }
            history.push(residual);
            if residual <= self.tolerance || iteration >= self.max_iterations {
                let termination = if residual <= self.tolerance {
                    Termination::Converged
                } else if residual <= 10.0 * self.tolerance {
                    Termination::Stalled
                } else {
                    let keep = history.len().saturating_sub(20);
                    return Err(SolveError::NotConverged {
                        solver: self.solver,
                        iterations: iteration,
                        residual,
                        tolerance: self.tolerance,
                        history: history.split_off(keep),
                    });
                };
                let convergence = Convergence { iterations: iteration, residual, tolerance: self.tolerance, termination };
                return Ok(BoxSolution { x, gradient: g, shift, convergence });
            }
            iteration += 1;
            // Conjugate direction on the free set.
            let big_g: f64 = (0..n).filter(|&i| free[i]).map(|i| g[i] * g[i]).sum();
            let beta = if conjugate && g_old > 0.0 { big_g / g_old } else { 0.0 };
            for i in 0..n {
                t[i] = if free[i] { g[i] + beta * t[i] } else { 0.0 };
            }
            g_old = big_g;
            self.op.apply(&t, &mut r, &mut ws);
            let r_mean = match self.control {
                Control::Mean(_) if n_f > 0 => (0..n).filter(|&i| free[i]).map(|i| r[i]).sum::<f64>() / n_f as f64,
                _ => 0.0,
            };
            let (mut num, mut den) = (0.0, 0.0);
            for i in 0..n {
                if free[i] {
                    num += g[i] * t[i];
                    den += (r[i] - r_mean) * t[i];
                }
            }
            let tau = if den > 0.0 && num > 0.0 { num / den } else { 1.0 / self.op.diagonal };
            // Step, projection and re-entry.
            x_old.copy_from_slice(&x);
            u_old.copy_from_slice(&u);
            let mut changed = false;
            let mut entered = false;
            for i in 0..n {
                if free[i] {
                    let v = x[i] - tau * t[i];
                    let c = v.clamp(lo[i], hi[i]);
                    changed |= c != v;
                    x[i] = c;
                } else if lo[i] < hi[i] && ((x[i] <= lo[i] && g[i] < 0.0) || (x[i] >= hi[i] && g[i] > 0.0)) {
                    x[i] = (x[i] - tau * g[i]).clamp(lo[i], hi[i]);
                    entered = true;
                }
            }
            conjugate = !entered;
            changed |= entered;
            let scale = match self.control {
                Control::Mean(m) => rescale(&mut x, hi, m),
                Control::Shift(_) => Some(1.0),
            };
            since_refresh += 1;
            match scale {
                Some(s) if !changed && since_refresh < REFRESH => {
                    for i in 0..n {
                        u[i] = s * (u[i] - tau * r[i]);
                    }
                }
                _ => {
                    self.op.apply(&x, &mut u, &mut ws);
                    since_refresh = 0;
                }
            }
            if !recent.accept(&mut x, &mut u, &x_old, &u_old, &g) {
                conjugate = false;
            }
        }
    }

    /// The gradient `g = K x − target + shift` (with `u = K x`), the free set, and the shift:
    /// given, or (load control) the multiplier of the mean. Returns the free count and the shift.
    fn gradient(&self, x: &[f64], u: &[f64], g: &mut [f64], free: &mut [bool]) -> (usize, f64) {
        let (lo, hi, target) = (self.lower, self.upper, self.target);
        let (mut sum_f, mut n_f) = (0.0, 0usize);
        for i in 0..x.len() {
            g[i] = u[i] - target[i];
            free[i] = x[i] > lo[i] && x[i] < hi[i];
            if free[i] {
                sum_f += g[i];
                n_f += 1;
            }
        }
        let shift = match self.control {
            Control::Shift(c) => c,
            Control::Mean(_) if n_f > 0 => -sum_f / n_f as f64,
            // No free node: the smallest shift that opens every unloaded gap.
            Control::Mean(_) => -(0..x.len()).filter(|&i| x[i] <= lo[i]).map(|i| g[i]).fold(f64::INFINITY, f64::min).min(f64::MAX),
        };
        for v in g.iter_mut() {
            *v += shift;
        }
        (n_f, shift)
    }
}

/// Largest violation of the contact conditions: `|g|` on free nodes, `−g` at the lower and `g`
/// at the upper bound (none where the bounds coincide).
fn violation(x: &[f64], g: &[f64], free: &[bool], lo: &[f64], hi: &[f64]) -> f64 {
    let mut viol: f64 = 0.0;
    for i in 0..x.len() {
        let v = if free[i] {
            g[i].abs()
        } else if lo[i] >= hi[i] {
            0.0
        } else if x[i] <= lo[i] {
            (-g[i]).max(0.0)
        } else {
            g[i].max(0.0)
        };
        viol = viol.max(v);
    }
    viol
}

/// The objectives of the last iterates, relative to the first (each the previous plus the exact
/// change of a step, so no large values cancel), for the non-monotone acceptance test.
struct RecentObjectives {
    values: std::collections::VecDeque<f64>,
}

impl RecentObjectives {
    fn new() -> Self {
        RecentObjectives { values: std::collections::VecDeque::from([0.0]) }
    }

    /// Keep the step from `(x_old, u_old)` to `(x, u)` if it passes the test of Grippo et al.
    /// (1986, eq. 4) with `g` the gradient at `x_old`; otherwise move `(x, u)` to the minimiser of
    /// the objective on the segment (none if the step is not a descent direction) and return
    /// false. `u − u_old = K (x − x_old)` is what makes the objective change exact.
    fn accept(&mut self, x: &mut [f64], u: &mut [f64], x_old: &[f64], u_old: &[f64], g: &[f64]) -> bool {
        let (mut gd, mut dkd) = (0.0, 0.0);
        for i in 0..x.len() {
            let d = x[i] - x_old[i];
            gd += g[i] * d;
            dkd += d * (u[i] - u_old[i]);
        }
        let now = *self.values.back().unwrap_or(&0.0);
        let reference = self.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let change = gd + 0.5 * dkd;
        let kept = now + change <= reference + SUFFICIENT_DECREASE * gd.min(0.0);
        let change = if kept {
            change
        } else {
            // The objective along the segment is now + s gᵀd + ½ s² dᵀK d, s ∈ [0, 1].
            let s = if gd < 0.0 && dkd > 0.0 { (-gd / dkd).min(1.0) } else { 0.0 };
            for i in 0..x.len() {
                x[i] = x_old[i] + s * (x[i] - x_old[i]);
                u[i] = u_old[i] + s * (u[i] - u_old[i]);
            }
            s * gd + 0.5 * s * s * dkd
        };
        if self.values.len() == MEMORY {
            self.values.pop_front();
        }
        self.values.push_back(now + change);
        kept
    }
}

/// Scales `x ≥ 0` so that `mean(min(s x, upper)) = m`. `Some(s)` when no value was clipped (so
/// `K x` scales by `s`), `None` otherwise.
fn rescale(x: &mut [f64], upper: &[f64], m: f64) -> Option<f64> {
    let n = x.len();
    let want = m * n as f64;
    let sum: f64 = x.iter().sum();
    if !(sum > 0.0) {
        for (v, &h) in x.iter_mut().zip(upper) {
            *v = m.min(h);
        }
        return None;
    }
    // f(s) = Σ min(s x, upper) − want is concave, increasing: Newton from below converges
    // monotonically (finitely, it is piecewise linear).
    let mut s = want / sum;
    for _ in 0..60 {
        let (mut f, mut df) = (-want, 0.0);
        for (v, &h) in x.iter().zip(upper) {
            if s * v < h {
                f += s * v;
                df += v;
            } else {
                f += h;
            }
        }
        if f.abs() <= 1e-14 * want || df <= 0.0 {
            break;
        }
        s -= f / df;
    }
    let mut clipped = false;
    for (v, &h) in x.iter_mut().zip(upper) {
        let w = s * *v;
        if w > h {
            clipped = true;
            *v = h;
        } else {
            *v = w;
        }
    }
    (!clipped).then_some(s)
}
