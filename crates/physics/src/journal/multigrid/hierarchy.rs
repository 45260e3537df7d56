use super::*;

impl Hierarchy {
    /// Build the hierarchy for `nt` circumferential nodes (periodic) and `nz` axial nodes.
    /// `alpha = (R/L)²` sets the anisotropy that decides the coarsening direction.
    pub fn new(nt: usize, nz: usize, alpha: f64, groove: bool) -> Self {
        Self::with_grooves(nt, nz, alpha, groove as usize)
    }

    /// [`Hierarchy::new`] with 0, 1 or 2 supply lines (the second opposite the first).
    pub fn with_grooves(nt: usize, nz: usize, alpha: f64, grooves: usize) -> Self {
        Self::build(nt, nz, alpha, grooves, false)
    }

    /// The hierarchy of the half `Z ∈ [0, ½]` of an axially symmetric problem whose full grid
    /// has `nz_full = 2m + 1` axial nodes (odd: the mid-plane is a node row): `m + 1` rows up to
    /// the mid-plane, which carries the mirror condition, plus a ghost row (see
    /// [`Level::mirror`]). On the finest level the discrete equations are the full grid's
    /// (row `m` halved); the coarser levels are the halves of grids with about the full
    /// hierarchy's spacings and only precondition.
    pub fn mirrored(nt: usize, nz_full: usize, alpha: f64, grooves: usize) -> Self {
        assert!(nz_full % 2 == 1 && nz_full >= 5, "the mirrored half needs an odd axial node count");
        Self::build(nt, nz_full / 2 + 2, alpha, grooves, true)
    }

    pub(super) fn build(nt: usize, nz: usize, alpha: f64, grooves: usize, mirror: bool) -> Self {
        let mut levels = vec![Level::new(nt, nz, grooves, mirror)];
        // rows that are not the ghost row
        let real = |nz: usize| if mirror { nz - 1 } else { nz };
        loop {
            let l = levels.last().unwrap();
            let (nt, nz) = (l.nt, l.nz);
            let can_t = nt >= 8;
            let can_z = real(nz) > 4;
            if (!can_t && !can_z) || nt * nz <= 80 {
                break;
            }
            // ratio of axial to circumferential coupling per node
            let a = alpha * (l.dt / l.dz).powi(2);
            let (mut ct, mut cz) = (true, true);
            if a > 2.0 {
                ct = false;
            } else if a < 0.5 {
                cz = false;
            }
            if !can_t {
                ct = false;
                cz = true;
            }
            if !can_z {
                cz = false;
                ct = true;
            }
            let nt_c = if ct { nt.div_ceil(2) } else { nt };
            let nz_c = if cz { (real(nz) - 1).div_ceil(2) + 1 + (nz - real(nz)) } else { nz };
            let tt = if ct { Transfer1D::periodic(nt, nt_c) } else { Transfer1D::identity(nt) };
            let tz = match (cz, mirror) {
                (false, _) => Transfer1D::identity(nz),
                (true, false) => Transfer1D::open(nz, nz_c),
                (true, true) => Transfer1D::open_with_ghost(nz - 1, nz_c - 1),
            };
            let fine = levels.last_mut().unwrap();
            let nearest = |t: &Transfer1D| (0..t.s_w.len()).map(|m| if t.s_w[m] < 0.5 { t.s_lo[m] } else { t.s_hi[m] }).collect();
            fine.inj_t = nearest(&tt);
            fine.inj_z = nearest(&tz);
            fine.tt = Some(tt);
            fine.tz = Some(tz);
            fine.tmp = vec![0.0; nz_c * nt];
            levels.push(Level::new(nt_c, nz_c, grooves, mirror));
        }
        let dz0 = levels[0].dz;
        for l in &mut levels[1..] {
            l.zq = ((l.dz / dz0).round() as usize).max(1);
        }
        let n = levels.len();
        Hierarchy { levels, alpha, sweeps: 2, cycle_count: vec![0; n], step_count: vec![0; n], eager_tight: false, scratch: Default::default() }
    }

    /// A new full-grid finest level for this mirrored half (see [`Hierarchy::unfold_into`]).
    pub fn full_level(&self) -> Level {
        let h = &self.levels[0];
        let grooves = if h.second_groove.is_some() { 2 } else { h.groove as usize };
        Level::new(h.nt, 2 * (h.nz - 2) + 1, grooves, false)
    }

    /// The finest level of this mirrored half unfolded onto `full`, the full grid's finest
    /// level: its coefficients and film set for the same film and node angles, and its
    /// pressure the even extension `P_{m+j} = P_{m−j}` of the half's (the figures of the
    /// analysis are then those of the full grid).
    pub fn unfold_into(&self, full: &mut Level) {
        let h = &self.levels[0];
        assert!(h.mirror && full.nt == h.nt && full.nz == 2 * (h.nz - 2) + 1 && !full.mirror);
        let (film, alpha, theta0) = h.coeffs_of.expect("the half has been solved");
        full.set_film(&film, alpha, theta0);
        let (nt, m) = (h.nt, h.nz - 2);
        for j in 0..full.nz {
            let s = if j <= m { j } else { 2 * m - j };
            full.u[j * nt..(j + 1) * nt].copy_from_slice(&h.u[s * nt..(s + 1) * nt]);
        }
    }

    /// Rebuild the coefficients of every level for `film`, node 0 at angle `theta0`.
    pub fn set_film(&mut self, film: &Film, theta0: f64) {
        self.set_film_from(0, film, theta0);
    }

    /// Back to the state of a new hierarchy (work counters and smoothing kept), without
    /// reallocating: see [`Level::reset_state`].
    pub fn reset_state(&mut self) {
        for l in &mut self.levels {
            l.reset_state();
        }
        for s in &mut self.scratch {
            s.clear();
        }
    }

    /// Rebuild the coefficients of level `k` only.
    pub fn set_film_level(&mut self, k: usize, film: &Film, theta0: f64) {
        let alpha = self.alpha;
        self.levels[k].set_film(film, alpha, theta0);
    }

    /// Rebuild the coefficients of levels `k` and coarser.
    pub fn set_film_from(&mut self, k: usize, film: &Film, theta0: f64) {
        let alpha = self.alpha;
        for l in &mut self.levels[k..] {
            l.set_film(film, alpha, theta0);
        }
    }

    /// Rebuild the coefficients of level `k`; the coarser levels keep theirs if they were built
    /// for a film of the same shape within `near` of this one (mid-plane centre and the angle
    /// of node 0): while level `k` is solved they only precondition it (its own residual defines
    /// the solution), so a nearby position's coarse operators do.
    pub fn set_film_near(&mut self, k: usize, film: &Film, theta0: f64, near: f64) {
        let alpha = self.alpha;
        self.levels[k].set_film(film, alpha, theta0);
        for l in &mut self.levels[k + 1..] {
            let close = match &l.coeffs_of {
                Some((f, a, t)) => {
                    *a == alpha
                        && f.misalignment == film.misalignment
                        && f.profile == film.profile
                        && (f.x_mid - film.x_mid).abs() <= near
                        && (f.y_mid - film.y_mid).abs() <= near
                        && (t - theta0).abs() <= near
                }
                None => false,
            };
            if !close {
                l.set_film(film, alpha, theta0);
            }
        }
    }

    /// Complementarity residual of `levels[k].u`: `‖min(P, λ/d)‖₂ / ‖f/d‖₂` with `d` the
    /// diagonal of `A` — the size of the pressure change one projected Jacobi step would make,
    /// relative to the size of the source term in the same units.
    pub fn lcp_residual(&mut self, k: usize) -> f64 {
        let l = &mut self.levels[k];
        let mut lam = std::mem::take(&mut l.r);
        l.lambda(&l.u, &mut lam);
        let res = l.lcp_residual_of(&lam);
        l.r = lam;
        res
    }

    /// Solve the LCP on level `k` starting from `levels[k].u` (any non-negative guess) by the
    /// primal–dual active-set method; each linear solve by multigrid-preconditioned CG to the
    /// relative tolerance `tol`. Stops when the active set is unchanged and the linear solve
    /// met `tol`, or after `max_steps` steps / `max_cycles` V-cycles.
    pub fn solve_lcp(&mut self, k: usize, tol: f64, max_steps: u32, max_cycles: u32) -> LcpReport {
        let mut steps = 0;
        let mut cycles = 0;
        let mut converged = false;
        let mut lam = std::mem::take(&mut self.scratch[2]);
        lam.resize(self.levels[k].u.len(), 0.0);
        // Inexact steps while the active set still moves: a linear solve to `loose` is enough
        // to decide the next active set; the last solve (set unchanged) is taken to `tol`. In a
        // load balance (`eager_tight`) 1e-3 decides the set as well as 1e-4 and saves a V-cycle
        // in most solves (misaligned 361×181: finest grid 6 + 3 → 5 + 3 cycles; BENCHMARKS.md,
        // speed fifth round); the other analyses keep 1e-4 (the roller–pin tables of the cam
        // kinds are built on them).
        let loose = tol.max(if self.eager_tight { 1e-3 } else { 1e-4 });
        let mut tight = loose <= tol;
        while steps < max_steps && cycles < max_cycles {
            let n_changed = self.levels[k].lambda_and_classify(&mut lam);
            let changed = n_changed > 0;
            if !changed && steps > 0 {
                if tight {
                    // `lam` is λ of the final pressure (an unchanged set leaves `u` as it was)
                    converged = true;
                    break;
                }
                tight = true;
            }
            if self.eager_tight && n_changed * 1000 <= lam.len() {
                tight = true;
            }
            if changed || steps == 0 {
                self.levels[k].refresh_dirty();
                self.inject_active_set(k);
            }
            steps += 1;
            let t = if tight { tol } else { loose };
            let (c, ok) = self.pcg(k, t, max_cycles - cycles);
            cycles += c;
            if !ok {
                break;
            }
        }
        // the pressure is non-negative by construction up to the linear tolerance
        let l = &mut self.levels[k];
        let mut clipped = false;
        for v in &mut l.u {
            if *v < 0.0 {
                *v = 0.0;
                clipped = true;
            }
        }
        // on convergence the last active-set check computed λ of this very pressure (unless a
        // negative value was clipped): the residual from it, without another operator pass
        let residual = if converged && !clipped { l.lcp_residual_of(&lam) } else { self.lcp_residual(k) };
        self.scratch[2] = lam;
        self.cycle_count[k] += cycles;
        self.step_count[k] += steps;
        LcpReport { steps, cycles, residual, converged }
    }

    /// Conjugate gradients on the free nodes of level `k` for `A_II P_I = f_I`, starting from
    /// `levels[k].u`, preconditioned by one symmetric V-cycle. Returns (iterations, converged).
    pub(super) fn pcg(&mut self, k: usize, tol: f64, max_iter: u32) -> (u32, bool) {
        let n = self.levels[k].u.len();
        let [mut p, mut q, lam] = std::mem::take(&mut self.scratch);
        for v in [&mut p, &mut q] {
            if v.len() < n {
                v.resize(n, 0.0);
            }
        }
        let out = self.pcg_inner(k, tol, max_iter, &mut p[..n], &mut q[..n]);
        self.scratch = [p, q, lam];
        out
    }

    /// The CG iteration. The residual lives in the level's `b` (the V-cycle's right-hand side)
    /// and the preconditioned residual in its `x` (the V-cycle's result), so the preconditioner
    /// copies nothing.
    pub(super) fn pcg_inner(&mut self, k: usize, tol: f64, max_iter: u32, p: &mut [f64], q: &mut [f64]) -> (u32, bool) {
        let l = &mut self.levels[k];
        // r = f − A u on free nodes
        let mut r = std::mem::take(&mut l.b);
        let rr = l.residual_free_dot(&l.u, &mut r);
        let fnorm = *l.free_src_norm.get_or_insert_with(|| l.src.iter().zip(&l.mask).map(|(f, m)| m * f * f).sum::<f64>().sqrt().max(1e-300));
        let mut rnorm = rr.sqrt();
        l.b = r;
        if rnorm <= tol * fnorm {
            return (0, true);
        }
        let mut rz = self.vcycle(k);
        p.copy_from_slice(&self.levels[k].x);
        let mut beta = None;
        let mut it = 0;
        while it < max_iter {
            it += 1;
            let l = &self.levels[k];
            let pq = l.apply_free_dot(&l.x, beta, p, q);
            if pq <= 0.0 {
                break;
            }
            let a = rz / pq;
            let l = &mut self.levels[k];
            let mut rr = 0.0;
            // on the free ranges: outside them `p`, `q` and the residual are 0
            let nt = l.nt;
            for (j, span) in l.free_span.iter().enumerate() {
                for (lo, hi) in *span {
                    let (a0, a1) = (j * nt + lo, j * nt + hi);
                    for (((u, r), p), q) in l.u[a0..a1].iter_mut().zip(l.b[a0..a1].iter_mut()).zip(&p[a0..a1]).zip(&q[a0..a1]) {
                        *u += a * p;
                        *r -= a * q;
                        rr += *r * *r;
                    }
                }
            }
            rnorm = rr.sqrt();
            if rnorm <= tol * fnorm {
                return (it, true);
            }
            let rz_new = self.vcycle(k);
            beta = Some(rz_new / rz);
            rz = rz_new;
        }
        (it, rnorm <= tol * fnorm)
    }

    /// One symmetric correction-scheme V-cycle on level `k` for `A x = b` (free nodes), from
    /// `x = 0` (the old `x` is not read). Returns `b·x` (computed in the last smoothing pass).
    pub(super) fn vcycle(&mut self, k: usize) -> f64 {
        self.vcycle_inner(k, k)
    }

    /// [`Hierarchy::vcycle`] on level `k` of a cycle that started on level `top`.
    pub(super) fn vcycle_inner(&mut self, k: usize, top: usize) -> f64 {
        let last = self.levels.len() - 1;
        if k == last {
            let l = &mut self.levels[last];
            // coarsest (≤ 80 nodes): exact solve by a dense Cholesky factor, rebuilt only when
            // the coefficients or the free set change; symmetric Gauss–Seidel to (near)
            // round-off if the factorisation fails
            if l.chol.is_some() || l.factor_dense() {
                l.solve_dense();
            } else {
                l.x.fill(0.0);
                for _ in 0..200 {
                    l.smooth_pass(1, false, false, false, false, None, None);
                    l.smooth_pass(1, true, false, false, false, None, None);
                }
            }
            return if k == top { dot(&l.b, &l.x) } else { 0.0 };
        }
        let nu = self.sweeps;
        {
            let (head, tail) = self.levels.split_at_mut(k + 1);
            let fine = &mut head[k];
            let coarse = &mut tail[0];
            // pre-smoothing from zero, the residual and its restriction in one pass
            fine.smooth_pass(nu, false, true, true, false, None, Some(coarse));
        }
        self.vcycle_inner(k + 1, top);
        {
            let (head, tail) = self.levels.split_at_mut(k + 1);
            // the coarse correction, prolonged row by row inside the post-smoothing pass
            head[k].smooth_pass(nu, true, false, false, k == top, Some(&tail[0]), None)
        }
    }

    /// Copy the cavitated set of level `k` down to every coarser level (injection: a coarse node
    /// is fixed when the fine node nearest to it is).
    pub fn inject_active_set(&mut self, k: usize) {
        for l in k..self.levels.len() - 1 {
            let (head, tail) = self.levels.split_at_mut(l + 1);
            let fine = &head[l];
            let coarse = &mut tail[0];
            let (ntf, ntc) = (fine.nt, coarse.nt);
            for (a, &jf) in fine.inj_z.iter().enumerate() {
                let frow = &fine.fixed[jf * ntf..(jf + 1) * ntf];
                let mut changed = false;
                for (c, &iff) in coarse.fixed[a * ntc..(a + 1) * ntc].iter_mut().zip(&fine.inj_t) {
                    if *c == BOUNDARY {
                        continue;
                    }
                    let flag = if frow[iff] == FREE { FREE } else { CAVITATED };
                    if *c != flag {
                        *c = flag;
                        changed = true;
                    }
                }
                coarse.dirty[a] |= changed;
            }
            coarse.refresh_dirty();
        }
    }

    /// Solve the LCP on the coarsest level from scratch, then on every finer level down to `k`,
    /// each started from the interpolated coarser solution (nested iteration).
    pub fn nested_solve(&mut self, k: usize, tol: f64, max_steps: u32, max_cycles: u32) -> LcpReport {
        let last = self.levels.len() - 1;
        self.levels[last].u.fill(0.0);
        let mut rep = self.solve_lcp(last, tol, max_steps, max_cycles);
        for lv in (k..last).rev() {
            self.interpolate_up(lv);
            rep = self.solve_lcp(lv, tol, max_steps, max_cycles);
        }
        rep
    }

    /// `sweeps` projected red–black Gauss–Seidel sweeps for the LCP on level `k`,
    /// `P = max(0, (f + Σ c_nb P_nb)/d)` at every non-boundary node (Cryer's projected SOR at
    /// ω = 1): after interpolation from a coarser grid they settle the free boundary locally
    /// before the active-set steps classify the nodes.
    pub fn projected_sweeps(&mut self, k: usize, sweeps: usize) {
        let l = &mut self.levels[k];
        let nz = l.nz;
        for _ in 0..sweeps {
            for color in 0..2 {
                for j in 1..nz - 1 {
                    l.projected_row(j, color);
                }
            }
        }
    }

    /// `levels[k].u = max(0, P levels[k+1].u)`: the nested-iteration start on level `k`.
    pub fn interpolate_up(&mut self, k: usize) {
        let (head, tail) = self.levels.split_at_mut(k + 1);
        let fine = &mut head[k];
        let coarse = &tail[0];
        let tt = fine.tt.as_ref().unwrap();
        let tz = fine.tz.as_ref().unwrap();
        let ntf = fine.nt;
        let ntc = coarse.nt;
        let tmp = &mut fine.tmp;
        for a in 0..coarse.nz {
            let c = &coarse.u[a * ntc..(a + 1) * ntc];
            let out = &mut tmp[a * ntf..(a + 1) * ntf];
            tt.prolong_row(c, out);
        }
        for j in 0..fine.nz {
            let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
            for i in 0..ntf {
                let k = j * ntf + i;
                fine.u[k] = if fine.fixed[k] == BOUNDARY {
                    0.0
                } else {
                    ((1.0 - w) * tmp[a * ntf + i] + w * tmp[b * ntf + i]).max(0.0)
                };
            }
        }
    }
}

impl Hierarchy {
    /// Solve `A_II x = b` on the free nodes of level `k` (the cavitation set of the last LCP
    /// solve, injected on every coarser level) by multigrid-preconditioned CG from zero, to the
    /// relative residual `tol`. Returns (iterations, converged, relative residual).
    pub(crate) fn solve_free(&mut self, k: usize, b: &[f64], x: &mut [f64], tol: f64, max_iter: u32) -> (u32, bool, f64) {
        self.inject_active_set(k);
        let l = &mut self.levels[k];
        let src = std::mem::replace(&mut l.src, b.to_vec());
        let u = std::mem::replace(&mut l.u, vec![0.0; b.len()]);
        for (v, m) in l.src.iter_mut().zip(&l.mask) {
            *v *= m;
        }
        // the CG scale of this right-hand side (and the LCP's again after it)
        let saved_norm = l.free_src_norm.take();
        let (it, ok) = self.pcg(k, tol, max_iter);
        self.cycle_count[k] += it;
        let l = &mut self.levels[k];
        let mut r = vec![0.0; b.len()];
        l.residual_free(&l.u, &mut r);
        let fnorm = dot(&l.src, &l.src).sqrt();
        let res = if fnorm > 0.0 { dot(&r, &r).sqrt() / fnorm } else { 0.0 };
        x.copy_from_slice(&l.u);
        l.src = src;
        l.u = u;
        l.free_src_norm = saved_norm;
        (it, ok, res)
    }
}

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
