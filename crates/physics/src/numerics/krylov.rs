//! Restarted GMRES (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7 (1986)), matrix-free and right
//! preconditioned: the caller passes the operator `y = A x` and the preconditioner `z ← M⁻¹ z`
//! as closures, so the matrix is never formed. The one implementation of the crate: the 1-D EHL
//! Newton steps (`crate::ehl::linear`) and the 2-D ones (`crate::ehl::twod::solver`) both call
//! [`gmres`].
//!
//! The Arnoldi basis is orthogonalised by modified Gram–Schmidt, the Hessenberg matrix reduced by
//! Givens rotations as it grows, so the residual estimate `|g_{k+1}|` of the least-squares problem
//! is known after every iteration; the solve stops when it meets the tolerance, after a lucky
//! breakdown (`‖w‖ = 0`) or at the iteration cap. After `restart` iterations the iterate is updated,
//! the true residual `b − A x` computed and the Arnoldi process started afresh from it.
//!
//! The two callers grew with small differences in the floating-point operations; [`Settings`]
//! keeps each one's exact sequence ([`Rotation`], [`Test`], [`Update`]) so that their results stay
//! bit-identical.

use crate::{Interrupt, Observer};

/// `Σ a_i b_i`, summed in order.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// How the Givens rotation that zeroes `h_{k+1,k}` is formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rotation {
    /// `r = hypot(h_kk, h_k+1,k)`; `r = 0` or a non-finite `r` is a breakdown: the solve stops,
    /// unconverged, with the iterate as it was before the cycle.
    Hypot,
    /// `r = sqrt(h_kk² + h_k+1,k²)`; `r = 0` takes the identity rotation and a non-finite residual
    /// estimate ends the solve (the iterate updated).
    Sqrt,
}

/// The convergence test on the residual estimate `|g|` against `‖b‖`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Test {
    /// `|g| ≤ tol·‖b‖` after each iteration (the residual a cycle starts from is not tested).
    Product,
    /// `|g|/‖b‖ ≤ tol` after each iteration, and the residual every cycle starts from (`b` itself
    /// for the first from 0) tested alike.
    Ratio,
}

/// How a cycle's least-squares solution `y` updates the iterate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Update {
    /// `x ← x + M⁻¹ (V y)`: one more preconditioner application per cycle.
    Right,
    /// `x ← x + Σ y_i z_i` with the preconditioned directions `z_i = M⁻¹ v_i` kept (restart × n
    /// more storage).
    Flexible,
}

/// Parameters of one solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Iterations per cycle (the Krylov dimension before a restart).
    pub restart: usize,
    /// Most iterations, over all cycles.
    pub max_iterations: usize,
    /// Relative residual `‖b − A x‖/‖b‖` asked for (as estimated by the rotations).
    pub tolerance: f64,
    /// Start from the given `x` (when all its values are finite), else from 0.
    pub from_x: bool,
    pub rotation: Rotation,
    pub test: Test,
    pub update: Update,
}

/// What a solve did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Iterations (operator applications in the Arnoldi process).
    pub iterations: usize,
    /// The last relative residual estimate `|g|/‖b‖` (1 before the first iteration, 0 for `b = 0`).
    pub residual: f64,
    /// Whether the tolerance was met (or the Krylov space became invariant).
    pub converged: bool,
}

/// Work arrays of [`gmres`], grown on demand and kept between solves. The Hessenberg matrix is
/// stored by columns of `min(restart, max_iterations) + 1` entries.
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    /// Orthonormal basis, `min(restart, max_iterations) + 1` vectors of the system dimension.
    pub basis: Vec<f64>,
    pub hess: Vec<f64>,
    pub cs: Vec<f64>,
    pub sn: Vec<f64>,
    /// Right-hand side of the least-squares problem (overwritten by its solution `y`).
    pub g: Vec<f64>,
    pub w: Vec<f64>,
    pub z: Vec<f64>,
    /// Preconditioned directions ([`Update::Flexible`]).
    pub zs: Vec<f64>,
    /// Residual a cycle starts from (unused by a single cycle from 0: that is `b`).
    pub r: Vec<f64>,
}

fn at_least(v: &mut Vec<f64>, n: usize) {
    if v.len() < n {
        v.resize(n, 0.0);
    }
}

impl Workspace {
    fn size(&mut self, n: usize, k: usize, update: Update) {
        at_least(&mut self.basis, (k + 1) * n);
        at_least(&mut self.hess, (k + 1) * k);
        at_least(&mut self.cs, k);
        at_least(&mut self.sn, k);
        at_least(&mut self.g, k + 1);
        at_least(&mut self.w, n);
        at_least(&mut self.z, n);
        if update == Update::Flexible {
            at_least(&mut self.zs, k * n);
        }
    }
}

/// The end of one Arnoldi cycle after `k` iterations.
enum Cycle {
    /// The tolerance met (or the Krylov space invariant: `‖w‖ = 0`), or not (the iteration cap,
    /// the cycle's length, or a non-finite estimate).
    Done { k: usize, converged: bool },
    /// Breakdown of [`Rotation::Hypot`]: the solve ends, the iterate untouched.
    Breakdown,
    /// The mean reduction rate could not reach the tolerance within the cap.
    GaveUp { k: usize },
}

/// Restarted, right-preconditioned GMRES for `A x = b` (`a(x, y)`: `y = A x`; `m(z)`: `z ← M⁻¹ z`),
/// at most `settings.max_iterations` iterations. `observer` is polled once per iteration (before
/// the operator is applied); an interrupt ends the solve with `Err`.
///
/// A cap below one cycle (`max_iterations < restart`: a solve with an older preconditioner that
/// may not be worth it) gives up after 4 or more iterations when the mean reduction per
/// iteration so far would not reach the tolerance within the cap.
pub fn gmres(
    a: &mut dyn FnMut(&[f64], &mut [f64]),
    m: &mut dyn FnMut(&mut [f64]),
    b: &[f64],
    x: &mut [f64],
    settings: &Settings,
    ws: &mut Workspace,
    observer: &dyn Observer,
) -> Result<Outcome, Interrupt> {
    let n = b.len();
    let tol = settings.tolerance;
    let bnorm = dot(b, b).sqrt();
    if bnorm == 0.0 {
        x.iter_mut().for_each(|v| *v = 0.0);
        return Ok(Outcome { iterations: 0, residual: 0.0, converged: true });
    }
    ws.size(n, settings.restart.min(settings.max_iterations), settings.update);
    // Whether `x` is 0 (the cycle then starts from `b` and may form its update in place).
    let mut x_zero = true;
    if settings.from_x && x.iter().all(|v| v.is_finite()) {
        residual(a, b, x, ws);
        x_zero = false;
    } else {
        x.iter_mut().for_each(|v| *v = 0.0);
    }
    let mut iters = 0;
    let mut rel = 1.0;
    while iters < settings.max_iterations {
        let r: &[f64] = if x_zero { b } else { &ws.r[..n] };
        let beta = dot(r, r).sqrt();
        rel = beta / bnorm;
        if settings.test == Test::Ratio && rel <= tol {
            break;
        }
        let (k, converged, stop) = match cycle(a, m, x_zero.then_some(b), n, (beta, bnorm), settings, ws, (&mut iters, &mut rel), observer)? {
            Cycle::Breakdown => return Ok(Outcome { iterations: iters, residual: rel, converged: false }),
            Cycle::Done { k, converged } => (k, converged, converged || !rel.is_finite()),
            Cycle::GaveUp { k } => (k, false, true),
        };
        update(m, x, x_zero, k, n, settings, ws);
        x_zero = false;
        if stop || iters >= settings.max_iterations {
            return Ok(Outcome { iterations: iters, residual: rel, converged });
        }
        // True residual for the restart.
        residual(a, b, x, ws);
    }
    Ok(Outcome { iterations: iters, residual: rel, converged: settings.test == Test::Ratio && rel <= tol })
}

/// `ws.r = b − A x` (`ws.w` its scratch).
fn residual(a: &mut dyn FnMut(&[f64], &mut [f64]), b: &[f64], x: &[f64], ws: &mut Workspace) {
    let n = b.len();
    at_least(&mut ws.r, n);
    a(x, &mut ws.w[..n]);
    for ii in 0..n {
        ws.r[ii] = b[ii] - ws.w[ii];
    }
}

/// Whether the residual estimate `g` meets the tolerance of `settings.test`.
#[inline]
fn met(test: Test, g: f64, bnorm: f64, tol: f64) -> bool {
    match test {
        Test::Product => g <= tol * bnorm,
        Test::Ratio => g / bnorm <= tol,
    }
}

/// One Arnoldi cycle from the residual `start` (`None`: `ws.r`) of norm `beta`, `n` unknowns:
/// the basis, the rotated Hessenberg matrix and the residual estimates, iteration by iteration.
#[allow(clippy::too_many_arguments)]
fn cycle(
    a: &mut dyn FnMut(&[f64], &mut [f64]),
    m: &mut dyn FnMut(&mut [f64]),
    start: Option<&[f64]>,
    n: usize,
    (beta, bnorm): (f64, f64),
    settings: &Settings,
    ws: &mut Workspace,
    (iters, rel): (&mut usize, &mut f64),
    observer: &dyn Observer,
) -> Result<Cycle, Interrupt> {
    let tol = settings.tolerance;
    let cap = settings.max_iterations;
    let k1 = settings.restart.min(cap) + 1;
    let Workspace { basis, hess, cs, sn, g, w, z, zs, r } = ws;
    let start = match start {
        Some(b) => b,
        None => &r[..n],
    };
    let (w, z) = (&mut w[..n], &mut z[..n]);
    for (v, rv) in basis[..n].iter_mut().zip(start) {
        *v = rv / beta;
    }
    g[0] = beta;
    let mut k = 0;
    while k < settings.restart && *iters < cap {
        // One operator application per iteration: a cancel takes effect within one.
        observer.check()?;
        // w = A M⁻¹ v_k.
        let zk: &mut [f64] = match settings.update {
            Update::Flexible => &mut zs[k * n..(k + 1) * n],
            Update::Right => &mut z[..],
        };
        zk.copy_from_slice(&basis[k * n..(k + 1) * n]);
        m(zk);
        a(zk, w);
        // Modified Gram–Schmidt.
        let h = &mut hess[k * k1..(k + 1) * k1];
        for j in 0..=k {
            let vj = &basis[j * n..(j + 1) * n];
            let d = dot(w, vj);
            h[j] = d;
            for (wv, vv) in w.iter_mut().zip(vj) {
                *wv -= d * vv;
            }
        }
        let wn = dot(w, w).sqrt();
        h[k + 1] = wn;
        // Apply the previous rotations, then a new one to zero h[k+1].
        for j in 0..k {
            let (c, s) = (cs[j], sn[j]);
            let t = c * h[j] + s * h[j + 1];
            h[j + 1] = -s * h[j] + c * h[j + 1];
            h[j] = t;
        }
        let (c, s, den) = match settings.rotation {
            Rotation::Hypot => {
                let den = h[k].hypot(h[k + 1]);
                if den == 0.0 || !den.is_finite() {
                    return Ok(Cycle::Breakdown);
                }
                (h[k] / den, h[k + 1] / den, den)
            }
            Rotation::Sqrt => {
                let den = (h[k] * h[k] + h[k + 1] * h[k + 1]).sqrt();
                let (c, s) = if den > 0.0 { (h[k] / den, h[k + 1] / den) } else { (1.0, 0.0) };
                (c, s, den)
            }
        };
        cs[k] = c;
        sn[k] = s;
        h[k] = den;
        h[k + 1] = 0.0;
        g[k + 1] = -s * g[k];
        g[k] *= c;
        *iters += 1;
        k += 1;
        *rel = g[k].abs() / bnorm;
        let converged = met(settings.test, g[k].abs(), bnorm, tol);
        if converged || wn == 0.0 || !rel.is_finite() {
            return Ok(Cycle::Done { k, converged: converged || wn == 0.0 });
        }
        // A cap below a cycle: give up early when the mean reduction per iteration so far would
        // not reach the tolerance within the cap.
        if cap < settings.restart && *iters >= 4 && *iters < cap && rel.ln() * cap as f64 > tol.ln() * *iters as f64 {
            return Ok(Cycle::GaveUp { k });
        }
        for (v, wv) in basis[k * n..(k + 1) * n].iter_mut().zip(w.iter()) {
            *v = wv / wn;
        }
    }
    Ok(Cycle::Done { k, converged: false })
}

/// The cycle's update of the iterate from its `k` directions: the least-squares solution `y` of
/// the rotated Hessenberg system by back substitution (in `ws.g`), then `x ← x + M⁻¹ V y`
/// ([`Update::Right`]; formed in `x` itself when it is 0) or `x ← x + Σ y_i z_i`.
fn update(m: &mut dyn FnMut(&mut [f64]), x: &mut [f64], x_zero: bool, k: usize, n: usize, settings: &Settings, ws: &mut Workspace) {
    let k1 = settings.restart.min(settings.max_iterations) + 1;
    let Workspace { basis, hess, g, z, zs, .. } = ws;
    for i in (0..k).rev() {
        let mut s = g[i];
        for j in i + 1..k {
            s -= hess[j * k1 + i] * g[j];
        }
        g[i] = if hess[i * k1 + i] != 0.0 { s / hess[i * k1 + i] } else { 0.0 };
    }
    match settings.update {
        Update::Flexible => {
            for i in 0..k {
                for (xv, zv) in x.iter_mut().zip(&zs[i * n..(i + 1) * n]) {
                    *xv += g[i] * zv;
                }
            }
        }
        Update::Right => {
            let t: &mut [f64] = if x_zero { &mut *x } else { &mut z[..n] };
            if !x_zero {
                t.iter_mut().for_each(|v| *v = 0.0);
            }
            for j in 0..k {
                let y = g[j];
                for (tv, vv) in t.iter_mut().zip(&basis[j * n..(j + 1) * n]) {
                    *tv += y * vv;
                }
            }
            m(t);
            if !x_zero {
                for (xv, zv) in x.iter_mut().zip(&z[..n]) {
                    *xv += zv;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A nonsymmetric convection–diffusion matrix (`n × n`, row-major), not diagonally dominant
    /// enough for Jacobi alone to be a good preconditioner.
    fn matrix(n: usize) -> Vec<f64> {
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + i] = 2.0 + 0.01 * i as f64;
            if i > 0 {
                a[i * n + i - 1] = -1.6;
            }
            if i + 1 < n {
                a[i * n + i + 1] = -0.4;
            }
        }
        a
    }

    fn residual_of(a: &[f64], b: &[f64], x: &[f64]) -> f64 {
        let n = b.len();
        let r: f64 = (0..n).map(|i| (b[i] - (0..n).map(|j| a[i * n + j] * x[j]).sum::<f64>()).powi(2)).sum();
        r.sqrt() / dot(b, b).sqrt()
    }

    fn solve(settings: &Settings, observer: &dyn Observer) -> (Result<Outcome, Interrupt>, f64) {
        let n = 60;
        let a = matrix(n);
        let b: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64).collect();
        let mut x = vec![0.0; n];
        let mut op = |z: &[f64], y: &mut [f64]| {
            for i in 0..n {
                y[i] = (0..n).map(|j| a[i * n + j] * z[j]).sum();
            }
        };
        let mut jacobi = |z: &mut [f64]| {
            for (i, zi) in z.iter_mut().enumerate() {
                *zi /= a[i * n + i];
            }
        };
        let out = gmres(&mut op, &mut jacobi, &b, &mut x, settings, &mut Workspace::default(), observer);
        (out, residual_of(&a, &b, &x))
    }

    /// Both arithmetics reach the tolerance, in one cycle and through restarts; the estimate is
    /// the true residual to rounding.
    #[test]
    fn both_arithmetics_solve_a_nonsymmetric_system() {
        let one_d = Settings { restart: 60, max_iterations: 60, tolerance: 1e-10, from_x: false, rotation: Rotation::Hypot, test: Test::Product, update: Update::Right };
        let two_d = Settings { rotation: Rotation::Sqrt, test: Test::Ratio, update: Update::Flexible, ..one_d };
        for s in [one_d, two_d, Settings { restart: 8, max_iterations: 400, ..one_d }, Settings { restart: 8, max_iterations: 400, ..two_d }] {
            let (out, res) = solve(&s, &crate::Silent);
            let out = out.unwrap();
            assert!(out.converged && out.residual <= 1e-10, "{s:?}: {out:?}");
            assert!(res <= 1e-9, "{s:?}: true residual {res:e}");
            if s.restart == 8 {
                assert!(out.iterations > 8, "{s:?}: {out:?} (no restart)");
            }
        }
        // A cap below a cycle gives up when the reduction rate cannot reach the tolerance.
        let capped = Settings { restart: 40, max_iterations: 25, tolerance: 1e-14, ..two_d };
        let (out, _) = solve(&capped, &crate::Silent);
        let out = out.unwrap();
        assert!(!out.converged && out.iterations < 25, "{out:?}");
    }

    /// An interrupting observer ends the solve at once.
    #[test]
    fn an_interrupt_ends_the_solve() {
        struct Stop;
        impl Observer for Stop {
            fn check(&self) -> Result<(), Interrupt> {
                Err(Interrupt::Canceled)
            }
        }
        let s = Settings { restart: 10, max_iterations: 10, tolerance: 1e-8, from_x: false, rotation: Rotation::Sqrt, test: Test::Ratio, update: Update::Flexible };
        assert!(matches!(solve(&s, &Stop).0, Err(Interrupt::Canceled)));
    }
}
