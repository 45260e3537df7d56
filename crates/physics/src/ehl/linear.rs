//! The linear algebra of one Newton step of the EHL solver: the banded-plus-dense system, kept LU
//! factors (faer, partial pivoting) used as a preconditioner, and right-preconditioned GMRES with
//! a matrix-free product (see `newton` for how they are used).

use super::grid::Grid;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::{MatMut, MatRef, Par};

const PI: f64 = std::f64::consts::PI;
/// Relative residual of the preconditioned GMRES solve of a Newton step.
pub(super) const GMRES_TOL: f64 = 1e-4;
/// Most GMRES iterations before the Jacobian is factorised afresh.
pub(super) const GMRES_MAX: usize = 12;

/// The scaled, active-set linear system of one Newton step, in banded form: for an interior node
/// `i` (row `i − 1`), `Σ_o aa[o][i] δP_{i+o−2} + Σ_o cg[o][i] δH_{i+o−2}` with
/// `δH = δH0 − (1/π) K δP`; the last row is the load balance. Active (cavitated) rows are the
/// identity. Out-of-range stencil entries are zero.
#[derive(Default)]
pub(super) struct System {
    pub(super) aa: [Vec<f64>; 5],
    pub(super) cg: [Vec<f64>; 5],
    /// `Σ_o cg[o][i]`: the `δH0` column.
    pub(super) gsum: Vec<f64>,
    pub(super) rhs: Vec<f64>,
}

/// Saved LU factors (with partial pivoting) of a Jacobian on one grid.
pub(super) struct Factor {
    /// Grid the factors belong to (0: none).
    pub(super) grid_id: u64,
    pub(super) dim: usize,
    pub(super) lu: Vec<f64>,
    pub(super) perm: Vec<usize>,
    pub(super) perm_inv: Vec<usize>,
    pub(super) stack: MemBuffer,
    pub(super) par: Par,
}

impl Factor {
    pub(super) fn empty() -> Self {
        Factor { grid_id: 0, dim: 0, lu: Vec::new(), perm: Vec::new(), perm_inv: Vec::new(), stack: MemBuffer::new(faer::dyn_stack::StackReq::EMPTY), par: Par::Seq }
    }

    pub(super) fn resize(&mut self, dim: usize) {
        if self.dim != dim {
            self.dim = dim;
            self.lu = vec![0.0; dim * dim];
            self.perm = vec![0; dim];
            self.perm_inv = vec![0; dim];
            // The parallel LU pays off only for large systems; small ones stay on this thread
            // (the transient solver runs two grids side by side).
            self.par = if dim >= 384 { faer::get_global_parallelism() } else { Par::Seq };
            let req = faer::linalg::lu::partial_pivoting::factor::lu_in_place_scratch::<usize, f64>(dim, dim, self.par, Default::default())
                .or(faer::linalg::lu::partial_pivoting::solve::solve_in_place_scratch::<usize, f64>(dim, 1, self.par));
            self.stack = MemBuffer::new(req);
        }
        self.grid_id = 0;
    }

    /// Factorise the matrix stored (column-major) in `self.lu`, in place.
    pub(super) fn factorise(&mut self, grid_id: u64) -> bool {
        let dim = self.dim;
        let a = MatMut::from_column_major_slice_mut(&mut self.lu, dim, dim);
        faer::linalg::lu::partial_pivoting::factor::lu_in_place(
            a,
            &mut self.perm,
            &mut self.perm_inv,
            self.par,
            MemStack::new(&mut self.stack),
            Default::default(),
        );
        // A zero pivot (singular Jacobian) makes the factors useless.
        let ok = (0..dim).all(|k| {
            let d = self.lu[k * dim + k];
            d.is_finite() && d != 0.0
        });
        self.grid_id = if ok { grid_id } else { 0 };
        ok
    }

    /// `x ← A⁻¹ x` with the stored factors.
    pub(super) fn solve(&mut self, x: &mut [f64]) {
        let dim = self.dim;
        let lu = MatRef::from_column_major_slice(&self.lu, dim, dim);
        let perm = unsafe { faer::perm::PermRef::new_unchecked(&self.perm, &self.perm_inv, dim) };
        let rhs = MatMut::from_column_major_slice_mut(x, dim, 1);
        faer::linalg::lu::partial_pivoting::solve::solve_in_place(lu, lu, perm, rhs, self.par, MemStack::new(&mut self.stack));
    }
}

/// Scratch of the GMRES solver and the matrix-free product.
#[derive(Default)]
pub(super) struct Krylov {
    /// Orthonormal basis, `(GMRES_MAX + 1)` vectors of the system dimension.
    pub(super) basis: Vec<f64>,
    /// Hessenberg matrix, column `k` at `k (GMRES_MAX + 1)`.
    pub(super) hess: Vec<f64>,
    pub(super) cs: Vec<f64>,
    pub(super) sn: Vec<f64>,
    pub(super) g: Vec<f64>,
    pub(super) w: Vec<f64>,
    pub(super) z: Vec<f64>,
    /// Padded (two zeros each side) `δP` and `δH` at the nodes, and the deflection.
    pub(super) dp: Vec<f64>,
    pub(super) dh: Vec<f64>,
    pub(super) defl: Vec<f64>,
}

/// `y = A z` for the system `sys` on `grid` (matrix-free: one dense `K δP`).
pub(super) fn apply(sys: &System, grid: &Grid, kr: &mut Krylov, z: &[f64], y: &mut [f64]) {
    let n = grid.n;
    let m = n - 2;
    kr.dp.iter_mut().for_each(|v| *v = 0.0);
    kr.dp[3..3 + m].copy_from_slice(&z[..m]);
    grid.kernel.deflection(&kr.dp[2..2 + n], &mut kr.defl);
    let dh0 = z[m];
    for k in 0..n {
        kr.dh[k + 2] = dh0 - kr.defl[k];
    }
    // Row i − 1 reads the padded index i + o (node i + o − 2).
    let out = &mut y[..m];
    out.iter_mut().for_each(|v| *v = 0.0);
    for o in 0..5 {
        let (aa, cg) = (&sys.aa[o][1..n - 1], &sys.cg[o][1..n - 1]);
        let (dp, dh) = (&kr.dp[1 + o..1 + o + m], &kr.dh[1 + o..1 + o + m]);
        for r in 0..m {
            out[r] += aa[r] * dp[r] + cg[r] * dh[r];
        }
    }
    let load: f64 = kr.dp[2..2 + n].iter().zip(&grid.cell).map(|(p, w)| p * w).sum();
    y[m] = load / (0.5 * PI);
}

/// Assemble the system matrix explicitly (column-major) into `out`.
pub(super) fn assemble(sys: &System, grid: &Grid, kr: &mut Krylov, out: &mut [f64]) {
    let n = grid.n;
    let m = n - 2;
    let dim = m + 1;
    let inv_pi = 1.0 / PI;
    // Elastic part: J[i−1, j−1] = −(1/π) Σ_o cg[o][i] K[i+o−2, j].
    for j in 1..n - 1 {
        let col = &mut out[(j - 1) * dim..j * dim];
        kr.dp[2..2 + n].copy_from_slice(grid.kernel.column(j));
        let rows = &mut col[..m];
        rows.iter_mut().for_each(|v| *v = 0.0);
        for o in 0..5 {
            let cg = &sys.cg[o][1..n - 1];
            let k = &kr.dp[1 + o..1 + o + m];
            for r in 0..m {
                rows[r] -= inv_pi * cg[r] * k[r];
            }
        }
        // Banded part.
        for i in j.saturating_sub(2).max(1)..=(j + 2).min(n - 2) {
            rows[i - 1] += sys.aa[j + 2 - i][i];
        }
        col[m] = grid.cell[j] / (0.5 * PI);
    }
    let last = &mut out[m * dim..(m + 1) * dim];
    last[..m].copy_from_slice(&sys.gsum[1..n - 1]);
    last[m] = 0.0;
    // The padded buffer is shared with `apply`: clear its ends again.
    kr.dp.iter_mut().for_each(|v| *v = 0.0);
}

/// Right-preconditioned GMRES for `A x = b` (`A` from `sys`), preconditioned by `factor`, from
/// `x = 0`. Returns the iterations when the relative residual reached `tol` within `GMRES_MAX`.
pub(super) fn gmres(sys: &System, grid: &Grid, factor: &mut Factor, kr: &mut Krylov, x: &mut [f64], tol: f64) -> Option<usize> {
    let dim = grid.n - 1;
    let k1 = GMRES_MAX + 1;
    let b = &sys.rhs;
    let beta = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    x.iter_mut().for_each(|v| *v = 0.0);
    if beta == 0.0 {
        return Some(0);
    }
    for (v, bv) in kr.basis[..dim].iter_mut().zip(b) {
        *v = bv / beta;
    }
    kr.g.iter_mut().for_each(|v| *v = 0.0);
    kr.g[0] = beta;
    let mut done = None;
    for k in 0..GMRES_MAX {
        // w = A M⁻¹ v_k.
        kr.z.copy_from_slice(&kr.basis[k * dim..(k + 1) * dim]);
        factor.solve(&mut kr.z);
        let z = std::mem::take(&mut kr.z);
        let mut w = std::mem::take(&mut kr.w);
        apply(sys, grid, kr, &z, &mut w);
        kr.z = z;
        // Modified Gram–Schmidt.
        let h = &mut kr.hess[k * k1..(k + 1) * k1];
        for j in 0..=k {
            let vj = &kr.basis[j * dim..(j + 1) * dim];
            let d: f64 = w.iter().zip(vj).map(|(a, b)| a * b).sum();
            h[j] = d;
            for (wv, vv) in w.iter_mut().zip(vj) {
                *wv -= d * vv;
            }
        }
        let norm = w.iter().map(|v| v * v).sum::<f64>().sqrt();
        h[k + 1] = norm;
        if norm > 0.0 {
            for (v, wv) in kr.basis[(k + 1) * dim..(k + 2) * dim].iter_mut().zip(&w) {
                *v = wv / norm;
            }
        }
        kr.w = w;
        // Apply the previous rotations, then a new one to zero h[k+1].
        for j in 0..k {
            let (c, s) = (kr.cs[j], kr.sn[j]);
            let (a, bb) = (h[j], h[j + 1]);
            h[j] = c * a + s * bb;
            h[j + 1] = -s * a + c * bb;
        }
        let r = h[k].hypot(h[k + 1]);
        if r == 0.0 || !r.is_finite() {
            return None;
        }
        let (c, s) = (h[k] / r, h[k + 1] / r);
        kr.cs[k] = c;
        kr.sn[k] = s;
        h[k] = r;
        h[k + 1] = 0.0;
        kr.g[k + 1] = -s * kr.g[k];
        kr.g[k] *= c;
        if kr.g[k + 1].abs() <= tol * beta || norm == 0.0 {
            done = Some(k + 1);
            break;
        }
    }
    let iters = done?;
    // Back substitution H y = g (y stored in g), then x = M⁻¹ V y.
    for i in (0..iters).rev() {
        let mut s = kr.g[i];
        for j in i + 1..iters {
            s -= kr.hess[j * k1 + i] * kr.g[j];
        }
        kr.g[i] = s / kr.hess[i * k1 + i];
    }
    for j in 0..iters {
        let y = kr.g[j];
        for (xv, vv) in x.iter_mut().zip(&kr.basis[j * dim..(j + 1) * dim]) {
            *xv += y * vv;
        }
    }
    factor.solve(x);
    Some(iters)
}
