//! The linear algebra of one Newton step of the EHL solver: the banded-plus-dense system, kept LU
//! factors (faer, partial pivoting) used as a preconditioner, and right-preconditioned GMRES with
//! a matrix-free product (see `newton` for how they are used).

use super::grid::Grid;
use crate::numerics::krylov;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::{MatMut, MatRef, Par};

const PI: f64 = std::f64::consts::PI;
/// Tightest relative residual of the preconditioned GMRES solve of a Newton step.
pub(super) const GMRES_TOL: f64 = 1e-4;
/// Loosest relative residual of a GMRES solve (see [`forcing`]).
pub(super) const GMRES_TOL_MAX: f64 = 0.1;
/// GMRES iterations of a step above which the kept factors are refreshed at the next step:
/// measured on the seed 003 mixed accurate cycle (issue 46), a refresh after more than 4
/// iterations factorises 2× as often (178 against 90) and halves the GMRES iterations (8124
/// against 16 058): −18 % instructions; after more than 2 or 6: −12 %.
pub(super) const GMRES_REFRESH: usize = 4;

/// Relative GMRES residual (forcing term) of a Newton step at residual `res` towards the
/// tolerance `tol` (Eisenstat–Walker): `min(0.1, max(res, tol/(2 res)))`, at least [`GMRES_TOL`].
/// Far from the solution the Newton error is `O(res²)`, so a linear residual `res·res` keeps the
/// convergence; near it, `tol/(2 res)` asks only what brings the next residual under half the
/// tolerance.
pub(super) fn forcing(res: f64, tol: f64) -> f64 {
    GMRES_TOL_MAX.min(res.max(0.5 * tol / res)).max(GMRES_TOL)
}
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

/// Scratch of the GMRES solver (lent to [`krylov::gmres`] for each solve) and the matrix-free
/// product.
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
    /// Preconditioned directions `M⁻¹ v_i` ([`krylov::Update::Flexible`]).
    pub(super) zs: Vec<f64>,
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
/// `x = 0`: one cycle of the shared GMRES ([`krylov::gmres`]) in this solver's arithmetic
/// (`hypot` rotations, a breakdown ends it unconverged; `|g| ≤ tol‖b‖`; `x = Σ y_i M⁻¹ v_i` from
/// the kept directions, which saves the preconditioner solve of `x = M⁻¹ V y`). Returns
/// the iterations when the relative residual reached `tol` within `GMRES_MAX`.
pub(super) fn gmres(sys: &System, grid: &Grid, factor: &mut Factor, kr: &mut Krylov, x: &mut [f64], tol: f64) -> Option<usize> {
    let take = std::mem::take::<Vec<f64>>;
    let mut ws = krylov::Workspace {
        basis: take(&mut kr.basis),
        hess: take(&mut kr.hess),
        cs: take(&mut kr.cs),
        sn: take(&mut kr.sn),
        g: take(&mut kr.g),
        w: take(&mut kr.w),
        z: take(&mut kr.z),
        zs: take(&mut kr.zs),
        ..Default::default()
    };
    let settings = krylov::Settings {
        restart: GMRES_MAX,
        max_iterations: GMRES_MAX,
        tolerance: tol,
        from_x: false,
        rotation: krylov::Rotation::Hypot,
        test: krylov::Test::Product,
        update: krylov::Update::Flexible,
    };
    // The silent observer never interrupts.
    let out = krylov::gmres(&mut |z, y| apply(sys, grid, kr, z, y), &mut |z| factor.solve(z), &sys.rhs, x, &settings, &mut ws, &crate::Silent);
    (kr.basis, kr.hess, kr.cs, kr.sn, kr.g, kr.w, kr.z, kr.zs) = (ws.basis, ws.hess, ws.cs, ws.sn, ws.g, ws.w, ws.z, ws.zs);
    out.ok().filter(|o| o.converged).map(|o| o.iterations)
}
