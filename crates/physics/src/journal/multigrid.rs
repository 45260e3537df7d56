//! Solver of the discrete Reynolds equation with the Swift–Stieber (Reynolds) cavitation
//! condition, posed as a linear complementarity problem (LCP).
//!
//! Seed 002 eq. (4) multiplied by the cell area `ΔθΔZ` and discretised by finite volumes:
//! `A P = f` with `(A P)_ij = Σ_faces c_face (P_ij − P_nb)`, `c_east = H³(θ_{i+½}, Z_j) ΔZ/Δθ`,
//! `c_north = α H³(θ_i, Z_{j+½}) Δθ/ΔZ`, `f_ij = −(H(θ_{i+½}) − H(θ_{i−½})) ΔZ`.
//! `A` is a symmetric M-matrix (ambient pressure at both edges and, with a groove, along the
//! supply line). The Reynolds condition is the LCP `P ≥ 0`, `λ = A P − f ≥ 0`, `P·λ = 0` — the
//! minimiser of `½PᵀAP − fᵀP` over `P ≥ 0`; the film ruptures where `P = 0` and the
//! zero-gradient condition at the rupture line follows from the complementarity.
//!
//! Method (chosen by measurement, see BENCHMARKS.md): the primal–dual active-set method
//! (Hintermüller, Ito & Kunisch, SIAM J. Optim. 13, 2003) — a semismooth Newton method that
//! moves every wrongly classified node at once, with re-activation and de-activation in the same
//! step, and converges in finitely many steps for M-matrices. Each step solves `A_II P_I = f_I`
//! on the inactive (pressurised) set by conjugate gradients preconditioned with one symmetric
//! multigrid V-cycle (red–black Gauss–Seidel, bilinear interpolation, full weighting, coarse
//! operators rediscretised from the analytic film, the cavitated set injected as fixed nodes on
//! every level). Coarsening is chosen per level from the anisotropy `α Δθ²/ΔZ²`
//! (semi-coarsening in the strongly coupled direction), which keeps the point smoother effective
//! from L/D = 0.1 to 4; grids need not be powers of two (non-nested levels interpolate linearly).
//! Nested iteration (the converged pressure and cavitation set of a coarse grid start the next
//! finer grid) and warm starts make the active-set loop take one to three steps.
//!
//! A projected FAS multigrid (Brandt & Cryer 1983) was tried first: with the Reynolds free
//! boundary its coarse corrections oscillated or diverged at 361×181 (residual stuck near 1e-2),
//! so it was dropped.

use super::film::Film;

/// Linear interpolation between a fine and a coarse 1-D grid (periodic or with two end nodes).
#[derive(Debug, Clone)]
struct Transfer1D {
    /// fine node → two coarse nodes and the weight of the second.
    p_lo: Vec<usize>,
    p_hi: Vec<usize>,
    p_w: Vec<f64>,
    /// coarse node → two fine nodes (where it lies on the fine grid) and the weight of the second.
    s_lo: Vec<usize>,
    s_hi: Vec<usize>,
    s_w: Vec<f64>,
    /// `IDENTITY`, `HALF` (periodic, the coarse grid every other fine node: fine node `2m` is
    /// coarse node `m`, `2m + 1` the mean of `m` and `m + 1`) or `GENERAL`; the first two take
    /// loops without index gathers (the same arithmetic).
    kind: u8,
}

const GENERAL: u8 = 0;
const IDENTITY: u8 = 1;
const HALF: u8 = 2;

impl Transfer1D {
    fn identity(n: usize) -> Self {
        let idx: Vec<usize> = (0..n).collect();
        Transfer1D {
            p_lo: idx.clone(),
            p_hi: idx.clone(),
            p_w: vec![0.0; n],
            s_lo: idx.clone(),
            s_hi: idx,
            s_w: vec![0.0; n],
            kind: IDENTITY,
        }
    }

    /// `nf` fine and `nc` coarse nodes on a periodic interval (node 0 shared).
    fn periodic(nf: usize, nc: usize) -> Self {
        let map = |n_from: usize, n_to: usize| {
            let (mut lo, mut hi, mut w) = (Vec::new(), Vec::new(), Vec::new());
            for k in 0..n_from {
                // position in units of the target grid, exact rational arithmetic first
                let num = k * n_to;
                let m = num / n_from;
                let t = (num % n_from) as f64 / n_from as f64;
                lo.push(m % n_to);
                hi.push((m + 1) % n_to);
                w.push(t);
            }
            (lo, hi, w)
        };
        let (p_lo, p_hi, p_w) = map(nf, nc);
        let (s_lo, s_hi, s_w) = map(nc, nf);
        let kind = if nf == 2 * nc { HALF } else { GENERAL };
        Transfer1D { p_lo, p_hi, p_w, s_lo, s_hi, s_w, kind }
    }

    /// `nf` fine and `nc` coarse nodes on a closed interval (both ends are nodes).
    fn open(nf: usize, nc: usize) -> Self {
        let map = |n_from: usize, n_to: usize| {
            let (mut lo, mut hi, mut w) = (Vec::new(), Vec::new(), Vec::new());
            for k in 0..n_from {
                let num = k * (n_to - 1);
                let den = n_from - 1;
                let m = (num / den).min(n_to - 2);
                let t = (num - m * den) as f64 / den as f64;
                lo.push(m);
                hi.push(m + 1);
                w.push(t);
            }
            (lo, hi, w)
        };
        let (p_lo, p_hi, p_w) = map(nf, nc);
        let (s_lo, s_hi, s_w) = map(nc, nf);
        Transfer1D { p_lo, p_hi, p_w, s_lo, s_hi, s_w, kind: GENERAL }
    }

    /// [`Transfer1D::open`] on `nf` and `nc` nodes plus a ghost node after each (the mirrored
    /// half's ghost row, fixed at 0): the ghosts map to each other only.
    fn open_with_ghost(nf: usize, nc: usize) -> Self {
        let mut t = Self::open(nf, nc);
        t.p_lo.push(nc);
        t.p_hi.push(nc);
        t.p_w.push(0.0);
        t.s_lo.push(nf);
        t.s_hi.push(nf);
        t.s_w.push(0.0);
        t
    }

    /// `out[i] = (1 − w_i) c[lo_i] + w_i c[hi_i]`: interpolation of the coarse row `c` to the
    /// fine row `out`.
    #[inline]
    fn prolong_row(&self, c: &[f64], out: &mut [f64]) {
        match self.kind {
            // (1 − 0)·c + 0·c = c exactly
            IDENTITY => out.copy_from_slice(c),
            HALF => {
                // pairs of fine nodes against pairs of neighbouring coarse nodes (no bounds
                // checks, no wrap test per node), the last pair wrapping to coarse node 0
                let nc = c.len();
                let (body, tail) = out[..2 * nc].split_at_mut(2 * (nc - 1));
                for (o, w) in body.chunks_exact_mut(2).zip(c.windows(2)) {
                    o[0] = w[0];
                    o[1] = 0.5 * w[0] + 0.5 * w[1];
                }
                tail[0] = c[nc - 1];
                tail[1] = 0.5 * c[nc - 1] + 0.5 * c[0];
            }
            _ => {
                for i in 0..out.len() {
                    let w = self.p_w[i];
                    out[i] = (1.0 - w) * c[self.p_lo[i]] + w * c[self.p_hi[i]];
                }
            }
        }
    }

    /// `out += Pᵀ t` for the fine row `t` (`out` the coarse row, zero on entry), in the order
    /// of the general loop over the fine nodes.
    #[inline]
    fn restrict_row(&self, t: &[f64], out: &mut [f64]) {
        match self.kind {
            IDENTITY => {
                for (o, v) in out.iter_mut().zip(t) {
                    *o += v;
                }
            }
            HALF => {
                let nc = out.len();
                let nf = t.len();
                // coarse node 0 takes fine nodes 0 and 1 first and fine node nf − 1 last
                out[0] += t[0];
                out[0] += 0.5 * t[1];
                for m in 1..nc {
                    let mut v = out[m];
                    v += 0.5 * t[2 * m - 1];
                    v += t[2 * m];
                    v += 0.5 * t[2 * m + 1];
                    out[m] = v;
                }
                out[0] += 0.5 * t[nf - 1];
            }
            _ => {
                for i in 0..t.len() {
                    let w = self.p_w[i];
                    out[self.p_lo[i]] += (1.0 - w) * t[i];
                    if w != 0.0 {
                        out[self.p_hi[i]] += w * t[i];
                    }
                }
            }
        }
    }
}


/// One grid of the hierarchy with its coefficients and work arrays. Node `(i, j)` is stored at
/// `j·nt + i`; `i` runs around the bearing (periodic), `j` along the axis (`j = 0` and
/// `j = nz − 1` are the edges, at ambient pressure).
#[derive(Debug, Clone)]
pub struct Level {
    /// Nodes around the circumference (periodic: node `nt` is node 0).
    pub nt: usize,
    /// Nodes along the axis, both edges included.
    pub nz: usize,
    pub dt: f64,
    pub dz: f64,
    /// Column 0 is held at ambient pressure (a supply groove).
    pub groove: bool,
    /// A second supply line held at ambient pressure (two axial grooves 180° apart).
    pub second_groove: Option<usize>,
    /// Half of an axially symmetric film (`Z` in `[0, ½]`): row `nz − 2` lies on the mid-plane
    /// `Z = ½` with a mirror condition and row `nz − 1` is a ghost row (fixed at 0, joined to the
    /// mid-plane by a zero conductance). See [`Hierarchy::mirrored`].
    pub mirror: bool,
    /// Absolute angle of node 0.
    pub theta0: f64,
    pub cos_n: Vec<f64>,
    pub sin_n: Vec<f64>,
    ce: Vec<f64>,
    cn: Vec<f64>,
    diag: Vec<f64>,
    /// The discretised source `f` (0 at boundary nodes).
    pub src: Vec<f64>,
    /// Film at the nodes.
    pub h: Vec<f64>,
    /// Pressure (the LCP unknown) on this level.
    pub u: Vec<f64>,
    /// 1 where the node is fixed at zero pressure in the current linear solve (boundary or
    /// cavitated), 2 for boundary nodes (always fixed), 0 free.
    fixed: Vec<u8>,
    /// 1 at free nodes, 0 at fixed ones (branch-free loops).
    mask: Vec<f64>,
    /// `1/diag` at free nodes, 0 at fixed ones.
    inv_d: Vec<f64>,
    /// `1/diag` at every node (set with the coefficients; `inv_d` is it masked).
    inv_diag: Vec<f64>,
    /// Per row, two ascending column ranges `a₁..b₁`, `a₂..b₂` that hold every free node: the
    /// row without its longest (cyclic) run of fixed nodes. Outside them the V-cycle's
    /// correction, residual and `A p` are 0, so the smoother and the operator kernels skip them.
    free_span: Vec<Span>,
    /// Rows whose `fixed` changed since their masks and span were last refreshed.
    dirty: Vec<bool>,
    /// Face cosines and sines of the last `set_film` (scratch kept to avoid allocation).
    cos_f: Vec<f64>,
    sin_f: Vec<f64>,
    /// Axial samples per cell for the face conductances of a profiled film: the finest grid's
    /// axial cells in one of this level's (1 on the finest level: point values).
    zq: usize,
    /// Film rows at the axial samples of one face (scratch of `set_film`).
    zrows: Vec<super::film::Row>,
    /// 1 at every node that is not on the boundary (edges, supply line).
    interior: Vec<f64>,
    // linear multigrid work arrays (correction scheme)
    x: Vec<f64>,
    b: Vec<f64>,
    r: Vec<f64>,
    /// Scratch for transfers to the next coarser level: (coarse rows) × nt.
    tmp: Vec<f64>,
    tt: Option<Transfer1D>,
    tz: Option<Transfer1D>,
    /// For the injection of the cavitated set to the next coarser level: per coarse column and
    /// per coarse row, the fine column / row nearest to it.
    inj_t: Vec<usize>,
    inj_z: Vec<usize>,
    /// Dense Cholesky factor of `A_II` on this level's free nodes (used on the coarsest level
    /// only): the free node indices and the row-major lower factor; `None` when the
    /// coefficients or the free set changed since it was built.
    chol: Option<(Vec<usize>, Vec<f64>)>,
    /// Film, `theta0` and `alpha` of the coefficients now held (a rebuild for the same ones is
    /// skipped: it would produce the same numbers).
    coeffs_of: Option<(Film, f64, f64)>,
    /// `Σ (f/d)²` over the non-boundary nodes for the coefficients now held (the denominator of
    /// [`Hierarchy::lcp_residual`]; `None` until first needed after a rebuild).
    src_norm2: Option<f64>,
    /// `‖f‖` over the free nodes (the scale of the CG stopping test) for the coefficients and
    /// free set now held; `None` after any change of either.
    free_src_norm: Option<f64>,
}

const BOUNDARY: u8 = 2;
const CAVITATED: u8 = 1;
const FREE: u8 = 0;

impl Level {
    /// `grooves`: 0 (periodic film), 1 (ambient line at column 0) or 2 (also at column
    /// `round(nt/2)`, the opposite line when `nt` is even).
    fn new(nt: usize, nz: usize, grooves: usize, mirror: bool) -> Self {
        let n = nt * nz;
        let groove = grooves > 0;
        let second = (grooves > 1).then(|| (nt + 1) / 2 % nt);
        let mut l = Level {
            nt,
            nz,
            dt: std::f64::consts::TAU / nt as f64,
            // the mirrored half: `nz − 2` intervals over `[0, ½]` (0.5/m and 1/(2m) are the
            // same double: both the correctly rounded 1/(2m))
            dz: if mirror { 0.5 / (nz - 2) as f64 } else { 1.0 / (nz - 1) as f64 },
            groove,
            second_groove: second,
            mirror,
            theta0: 0.0,
            cos_n: vec![0.0; nt],
            sin_n: vec![0.0; nt],
            ce: vec![0.0; n],
            cn: vec![0.0; n],
            diag: vec![0.0; n],
            src: vec![0.0; n],
            h: vec![0.0; n],
            u: vec![0.0; n],
            fixed: vec![FREE; n],
            mask: vec![0.0; n],
            inv_d: vec![0.0; n],
            inv_diag: vec![0.0; n],
            free_span: vec![[(0, nt), (nt, nt)]; nz],
            dirty: vec![true; nz],
            cos_f: vec![0.0; nt],
            sin_f: vec![0.0; nt],
            zq: 1,
            zrows: Vec::new(),
            interior: vec![0.0; n],
            x: vec![0.0; n],
            b: vec![0.0; n],
            r: vec![0.0; n],
            tmp: Vec::new(),
            tt: None,
            tz: None,
            inj_t: Vec::new(),
            inj_z: Vec::new(),
            chol: None,
            coeffs_of: None,
            src_norm2: None,
            free_src_norm: None,
        };
        for j in 0..nz {
            for i in 0..nt {
                if j == 0 || j + 1 == nz || (groove && i == 0) || second == Some(i) {
                    l.fixed[j * nt + i] = BOUNDARY;
                } else {
                    l.interior[j * nt + i] = 1.0;
                }
            }
        }
        l
    }

    /// Back to the state of [`Level::new`] without reallocating: no coefficients, zero
    /// pressure and work arrays, every non-boundary node free. What a solve on this level does
    /// then depends only on its inputs, not on what the level solved before.
    fn reset_state(&mut self) {
        for f in &mut self.fixed {
            if *f != BOUNDARY {
                *f = FREE;
            }
        }
        for v in [&mut self.u, &mut self.x, &mut self.b, &mut self.r, &mut self.mask, &mut self.inv_d] {
            v.fill(0.0);
        }
        self.free_span.fill([(0, self.nt), (self.nt, self.nt)]);
        self.dirty.fill(true);
        self.theta0 = 0.0;
        self.chol = None;
        self.coeffs_of = None;
        self.src_norm2 = None;
        self.free_src_norm = None;
    }

    /// Absolute angle of node `i`.
    pub fn theta(&self, i: usize) -> f64 {
        self.theta0 + i as f64 * self.dt
    }

    /// Rebuild coefficients for `film` with node 0 at absolute angle `theta0`.
    fn set_film(&mut self, film: &Film, alpha: f64, theta0: f64) {
        // the coefficients are a function of (film, alpha, theta0) only, and nothing else writes
        // them; the masks are kept consistent with `fixed` by every change of it
        if self.coeffs_of == Some((*film, alpha, theta0)) {
            return;
        }
        self.coeffs_of = Some((*film, alpha, theta0));
        self.src_norm2 = None;
        let (nt, nz, dt, dz) = (self.nt, self.nz, self.dt, self.dz);
        self.theta0 = theta0;
        let mut cos_f = std::mem::take(&mut self.cos_f);
        let mut sin_f = std::mem::take(&mut self.sin_f);
        for i in 0..nt {
            let t = theta0 + i as f64 * dt;
            let (s, c) = t.sin_cos();
            self.cos_n[i] = c;
            self.sin_n[i] = s;
            let (s, c) = (t + 0.5 * dt).sin_cos();
            cos_f[i] = c;
            sin_f[i] = s;
        }
        let ke = dz / dt;
        let kn = alpha * dt / dz;
        let mut prev: Option<(super::film::Row, super::film::Row)> = None;
        for j in 0..nz {
            let z = j as f64 * dz;
            let r = film.row(z);
            let rn = film.row((z + 0.5 * dz).min(1.0));
            let row = j * nt;
            let (z_lo, z_hi) = ((z - 0.5 * dz).max(0.0), (z + 0.5 * dz).min(1.0));
            let east_avg = self.sub_cell_profile(film) && profile_in(film, z_lo, z_hi);
            let north_avg = self.sub_cell_profile(film) && j + 1 < nz && profile_in(film, z, (z + dz).min(1.0));
            if !east_avg && !north_avg && j + 1 < nz && prev == Some((r, rn)) {
                // the same film data as the row below (an aligned film, or the unprofiled middle
                // of a profiled one): the same coefficients
                for v in [&mut self.ce, &mut self.h, &mut self.cn, &mut self.src] {
                    v.copy_within(row - nt..row, row);
                }
                continue;
            }
            prev = (j + 1 < nz && !east_avg && !north_avg).then_some((r, rn));
            let base = 1.0 + r.gamma;
            let base_n = 1.0 + rn.gamma;
            // on slices of one length (no bounds checks, no reloads of the angle tables per node)
            let ce = &mut self.ce[row..row + nt];
            let h = &mut self.h[row..row + nt];
            let (cos_n, sin_n) = (&self.cos_n[..nt], &self.sin_n[..nt]);
            let faces = cos_f[..nt].iter().zip(&sin_f[..nt]);
            let nodes = cos_n.iter().zip(sin_n);
            for (((ce, h), (cf, sf)), (cn, sn)) in ce.iter_mut().zip(h.iter_mut()).zip(faces).zip(nodes) {
                let he = base + r.x * cf + r.y * sf;
                *ce = he * he * he * ke;
                *h = base + r.x * cn + r.y * sn;
            }
            if east_avg {
                face_means(film, z_lo, z_hi, self.zq, false, ke, &cos_f, &sin_f, &mut self.zrows, &mut self.ce[row..row + nt]);
            }
            let cn = &mut self.cn[row..row + nt];
            if north_avg {
                face_means(film, z, (z + dz).min(1.0), self.zq, true, kn, &self.cos_n, &self.sin_n, &mut self.zrows, cn);
            } else if j + 1 < nz {
                for ((c, cs), sn) in cn.iter_mut().zip(&self.cos_n[..nt]).zip(&self.sin_n[..nt]) {
                    let hn = base_n + rn.x * cs + rn.y * sn;
                    *c = hn * hn * hn * kn;
                }
            } else {
                cn.fill(0.0);
            }
            // f = −∂H/∂θ ΔθΔZ in flux form (faces): the profile Γ(Z) drops out.
            let src = &mut self.src[row..row + nt];
            src[0] = -dz * (r.x * (cos_f[0] - cos_f[nt - 1]) + r.y * (sin_f[0] - sin_f[nt - 1]));
            for i in 1..nt {
                src[i] = -dz * (r.x * (cos_f[i] - cos_f[i - 1]) + r.y * (sin_f[i] - sin_f[i - 1]));
            }
        }
        if self.mirror {
            // Mirror condition on the mid-plane row `m = nz − 2` (the full grid's row with
            // `P_{m+1} = P_{m−1}` and `c_{n,m} = c_{n,m−1}`): the full grid's equation of row `m`
            // halved, `½ c_e` east/west, `c_{n,m−1}` to the south, `½ f`, and no face to the
            // ghost row. `A` stays symmetric: it is `EᵀA_full E` (E: the even extension) with the
            // rows `j < m` halved, and the complementarity is node-wise, so the half problem's
            // solution is the full one's restricted (a positive row scale does not change it).
            let m = nz - 2;
            let row = m * nt..(m + 1) * nt;
            for v in &mut self.ce[row.clone()] {
                *v *= 0.5;
            }
            for v in &mut self.src[row.clone()] {
                *v *= 0.5;
            }
            self.cn[row].fill(0.0);
        }
        // the diagonal on the interior rows (on slices, so that the loop vectorises), then the
        // boundary nodes (edge rows, supply lines) set to the identity row
        for j in 1..nz - 1 {
            let row = j * nt;
            let ce = &self.ce[row..row + nt];
            let cn = &self.cn[row..row + nt];
            let cs = &self.cn[row - nt..row];
            let d = &mut self.diag[row..row + nt];
            let inv = &mut self.inv_diag[row..row + nt];
            d[0] = ce[0] + ce[nt - 1] + cn[0] + cs[0];
            inv[0] = 1.0 / d[0];
            for i in 1..nt {
                d[i] = ce[i] + ce[i - 1] + cn[i] + cs[i];
                inv[i] = 1.0 / d[i];
            }
        }
        for k in 0..self.fixed.len() {
            if self.fixed[k] == BOUNDARY {
                self.diag[k] = 1.0;
                self.inv_diag[k] = 1.0;
                self.src[k] = 0.0;
            }
        }
        self.cos_f = cos_f;
        self.sin_f = sin_f;
        // `fixed` is not changed here, so the masks and free spans of the rows not marked dirty
        // still match it: only their `inv_d` follows the new diagonal (`1/diag` at free nodes, 0
        // at fixed ones, as `refresh_dirty` writes it); the marked rows are refreshed in full
        let nt = self.nt;
        for (j, dirty) in self.dirty.iter().enumerate() {
            if !dirty {
                let row = j * nt..(j + 1) * nt;
                for ((inv, m), id) in self.inv_d[row.clone()].iter_mut().zip(&self.mask[row.clone()]).zip(&self.inv_diag[row]) {
                    *inv = if *m != 0.0 { *id } else { 0.0 };
                }
            }
        }
        self.refresh_dirty();
        // new coefficients: the dense factor and the free source norm are stale
        self.chol = None;
        self.free_src_norm = None;
    }

    /// Whether this level's face conductances take the film's edge profile as a cell mean
    /// ([`face_means`]): on a coarse level whose axial cell is wider than the profiled zone
    /// (`ψ < ΔZ`), where a point value at the face misses most of the profile. A profile that
    /// spans a cell or more keeps the point values: measured on the L9's nine cases (BENCHMARKS.md,
    /// speed seventh round), cell means there put the coarse equilibria farther from the
    /// finest grid's (one more finest Newton step in three of the six cases with ψ ≥ 0.2).
    fn sub_cell_profile(&self, film: &Film) -> bool {
        self.zq > 1 && film.profile.is_some_and(|p| p.length_fraction < self.dz)
    }

    /// [`Hierarchy::lcp_residual`] with `lam = A u − f` already computed (at the non-boundary
    /// nodes). The denominator `‖f/d‖²` depends on the coefficients only: it is kept with them.
    fn lcp_residual_of(&mut self, lam: &[f64]) -> f64 {
        let mut num = 0.0;
        for (((f, u), lam), d) in self.fixed.iter().zip(&self.u).zip(lam).zip(&self.diag) {
            if *f == BOUNDARY {
                continue;
            }
            let m = u.min(lam / d);
            num += m * m;
        }
        let den = match self.src_norm2 {
            Some(d) => d,
            None => {
                let mut den = 0.0;
                for idx in 0..lam.len() {
                    if self.fixed[idx] == BOUNDARY {
                        continue;
                    }
                    let s = self.src[idx] / self.diag[idx];
                    den += s * s;
                }
                self.src_norm2 = Some(den);
                den
            }
        };
        if den > 0.0 { (num / den).sqrt() } else { num.sqrt() }
    }

    /// Recompute `mask`, `inv_d` and the free spans of every row from `fixed` and `diag`.
    #[cfg(test)]
    fn refresh_masks(&mut self) {
        self.dirty.fill(true);
        self.refresh_dirty();
    }

    /// `mask`, `inv_d` and the free span of the rows marked in `dirty` from `fixed` and `diag`
    /// (the others' already match `fixed`: every change of `fixed` marks its row), clearing the
    /// marks.
    /// The dense factor and the free source norm are dropped when any row changed.
    fn refresh_dirty(&mut self) {
        let nt = self.nt;
        let mut any = false;
        for (j, d) in self.dirty.iter_mut().enumerate() {
            if !std::mem::take(d) {
                continue;
            }
            any = true;
            let row = j * nt..(j + 1) * nt;
            let (m, inv, f, id) = (&mut self.mask[row.clone()], &mut self.inv_d[row.clone()], &self.fixed[row.clone()], &self.inv_diag[row]);
            // the mask, and the free nodes' extent and longest inner run of fixed nodes
            let (mut first, mut last) = (usize::MAX, 0);
            let (mut gap, mut gap_start) = (0, 0);
            for i in 0..nt {
                let free = f[i] == FREE;
                m[i] = if free { 1.0 } else { 0.0 };
                inv[i] = if free { id[i] } else { 0.0 };
                if free {
                    if first != usize::MAX && i - last - 1 > gap {
                        (gap, gap_start) = (i - last - 1, last + 1);
                    }
                    first = first.min(i);
                    last = i;
                }
            }
            self.free_span[j] = free_ranges(nt, first, last, gap, gap_start);
        }
        if any {
            self.chol = None;
            self.free_src_norm = None;
        }
    }

    /// Factor `A_II` (free nodes) densely: `A_II = L Lᵀ` (Cholesky; `A` is a symmetric
    /// M-matrix with at least one fixed node in each connected part, hence positive definite).
    /// Returns false (and keeps no factor) if a pivot is not positive.
    fn factor_dense(&mut self) -> bool {
        let nt = self.nt;
        let idx: Vec<usize> = (0..self.fixed.len()).filter(|&k| self.fixed[k] == FREE).collect();
        let m = idx.len();
        let mut pos = vec![usize::MAX; self.fixed.len()];
        for (a, &k) in idx.iter().enumerate() {
            pos[k] = a;
        }
        let mut a = vec![0.0; m * m];
        for (r, &k) in idx.iter().enumerate() {
            a[r * m + r] = self.diag[k];
            let i = k % nt;
            let kw = if i == 0 { k + nt - 1 } else { k - 1 };
            let ke = if i + 1 == nt { k + 1 - nt } else { k + 1 };
            for (nb, c) in [(ke, self.ce[k]), (kw, self.ce[kw]), (k + nt, self.cn[k]), (k - nt, self.cn[k - nt])] {
                let q = pos[nb];
                if q != usize::MAX {
                    a[r * m + q] -= c;
                }
            }
        }
        // in-place Cholesky, lower triangle (Golub & Van Loan, alg. 4.2.1)
        for c in 0..m {
            let mut d = a[c * m + c];
            for t in 0..c {
                d -= a[c * m + t] * a[c * m + t];
            }
            if !(d > 0.0) {
                self.chol = None;
                return false;
            }
            let d = d.sqrt();
            a[c * m + c] = d;
            for r in c + 1..m {
                let mut v = a[r * m + c];
                for t in 0..c {
                    v -= a[r * m + t] * a[c * m + t];
                }
                a[r * m + c] = v / d;
            }
        }
        self.chol = Some((idx, a));
        true
    }

    /// `x = A_II⁻¹ b` on the free nodes with the dense factor (0 at fixed nodes).
    fn solve_dense(&mut self) {
        let (idx, l) = self.chol.as_ref().unwrap();
        let m = idx.len();
        // `r` is free on the coarsest level (no residual is restricted from it): the work vector
        let y = &mut self.r[..m];
        for (a, &k) in idx.iter().enumerate() {
            y[a] = self.b[k];
        }
        for r in 0..m {
            let mut v = y[r];
            for t in 0..r {
                v -= l[r * m + t] * y[t];
            }
            y[r] = v / l[r * m + r];
        }
        for r in (0..m).rev() {
            let mut v = y[r];
            for t in r + 1..m {
                v -= l[t * m + r] * y[t];
            }
            y[r] = v / l[r * m + r];
        }
        self.x.fill(0.0);
        for (a, &k) in idx.iter().enumerate() {
            self.x[k] = y[a];
        }
    }

    /// `Σ c_nb v_nb` at node `k` (neighbour sum of the operator).
    #[cfg(test)]
    #[inline(always)]
    fn nb_sum(&self, v: &[f64], k: usize, kw: usize, ke: usize) -> f64 {
        let nt = self.nt;
        self.ce[k] * v[ke] + self.ce[kw] * v[kw] + self.cn[k] * v[k + nt] + self.cn[k - nt] * v[k - nt]
    }

    /// `out = A v − f` at every non-boundary node (the LCP multiplier `λ` when `v` solves the
    /// inactive equations), 0 at boundary nodes.
    fn lambda(&self, v: &[f64], out: &mut [f64]) {
        self.kernel::<{ Self::MINUS_SUB }>(v, out, &self.interior, &self.src);
    }

    /// `lam = λ = A u − f` ([`Level::lambda`]) and the new active set from it in one pass: a
    /// node is cavitated where `λ − d·P > 0` (`d` the diagonal, a per-node scale; `P` set to 0
    /// there), free elsewhere; rows whose flags change are marked dirty. Row `j` is classified
    /// once `λ` of row `j + 1` is computed, so every `λ` reads the pressure before the
    /// classification zeroes it: the values of a `lambda` pass followed by a classification
    /// pass. Returns the number of nodes whose flag changed.
    fn lambda_and_classify(&mut self, lam: &mut [f64]) -> usize {
        let (nt, nz) = (self.nt, self.nz);
        lam[..nt].fill(0.0);
        lam[(nz - 1) * nt..].fill(0.0);
        let mut n_changed = 0usize;
        for j in 0..nz {
            if j + 2 < nz {
                self.kernel_row::<{ Self::MINUS_SUB }>(j + 1, [(0, nt), (nt, nt)], &self.u, lam, &self.interior, &self.src);
            }
            let row = j * nt..(j + 1) * nt;
            let before = n_changed;
            let (f, u, lam, d) = (&mut self.fixed[row.clone()], &mut self.u[row.clone()], &lam[row.clone()], &self.diag[row]);
            for (((f, u), lam), d) in f.iter_mut().zip(u.iter_mut()).zip(lam).zip(d) {
                if *f == BOUNDARY {
                    continue;
                }
                let active = lam - d * *u > 0.0;
                let flag = if active { CAVITATED } else { FREE };
                if flag != *f {
                    n_changed += 1;
                    *f = flag;
                }
                if active {
                    *u = 0.0;
                }
            }
            self.dirty[j] |= n_changed > before;
        }
        n_changed
    }

    /// The CG direction and its image in one pass: with `beta`, first `v = z + β v` (each row
    /// one row ahead of its use); then `out = A v` restricted to the free nodes (0 at fixed
    /// nodes), and returns `v·out` (summed in index order, as [`dot`]).
    fn apply_free_dot(&self, z: &[f64], beta: Option<f64>, v: &mut [f64], out: &mut [f64]) -> f64 {
        let nt = self.nt;
        let nz = self.nz;
        // on the free ranges only: outside them `z` is 0, and so `v` stays (it starts as `z`)
        let update = |v: &mut [f64], j: usize| {
            if let Some(beta) = beta {
                for (lo, hi) in self.free_span[j] {
                    for (p, z) in v[j * nt + lo..j * nt + hi].iter_mut().zip(&z[j * nt + lo..j * nt + hi]) {
                        *p = z + beta * *p;
                    }
                }
            }
        };
        update(v, 0);
        update(v, 1);
        out[..nt].fill(0.0);
        out[(nz - 1) * nt..].fill(0.0);
        let mut s = 0.0;
        for j in 1..nz - 1 {
            update(v, j + 1);
            self.kernel_row::<{ Self::PLAIN }>(j, self.free_span[j], v, out, &self.mask, &self.src);
            let row = j * nt;
            for (lo, hi) in self.free_span[j] {
                for (a, b) in v[row + lo..row + hi].iter().zip(&out[row + lo..row + hi]) {
                    s += a * b;
                }
            }
        }
        s
    }

    /// `out = f − A v` at the free nodes, 0 at fixed nodes.
    fn residual_free(&self, v: &[f64], out: &mut [f64]) {
        self.kernel::<{ Self::SUB_MINUS }>(v, out, &self.mask, &self.src);
    }

    /// [`Level::residual_free`] and `out·out` in one pass (each row summed as soon as it is
    /// written, in index order as [`dot`]; the edge rows are 0 and every term is ≥ 0, so the
    /// sum is that of `dot(out, out)` bit for bit).
    fn residual_free_dot(&self, v: &[f64], out: &mut [f64]) -> f64 {
        let nt = self.nt;
        out[..nt].fill(0.0);
        out[(self.nz - 1) * nt..].fill(0.0);
        let mut acc = 0.0;
        for j in 1..self.nz - 1 {
            self.kernel_row::<{ Self::SUB_MINUS }>(j, [(0, nt), (nt, nt)], v, out, &self.mask, &self.src);
            for r in &out[j * nt..(j + 1) * nt] {
                acc += r * r;
            }
        }
        acc
    }

    /// Red–black Gauss–Seidel on the free nodes for `A x = b`; `reverse` swaps the colour order
    /// (the post-smoother of a symmetric cycle). All `2·sweeps` half-sweeps are pipelined in one
    /// pass over memory: at step `j` half-sweep `s` updates row `j − s`, so every row sees its
    /// neighbours exactly as in sweep after sweep (the same arithmetic, bit for bit) while the
    /// rows in flight stay in cache. `from_zero`: `x` is taken as 0 on entry (its old values are
    /// never read: the first half-sweep sets `x = b/d` on its colour, and a Gauss–Seidel update
    /// does not read the node's own value). `residual`: also `r = b − A x` at the free nodes (0
    /// at fixed ones), each row as soon as its neighbours are final. `dot`: returns `b·x` summed
    /// over the rows as they become final (in index order, as [`dot`]; the edge rows are 0).
    /// `prolong`: first `x += P·(coarse correction)` with the coarse level's correction `x`:
    /// each coarse row is interpolated around the circumference into `tmp` when first needed
    /// (as `prolong_theta`, the test reference) and each fine row gets its axial interpolation
    /// just before the first half-sweep needs it. `restrict`: with `residual`, also `coarse.b = Pᵀ r` (zero
    /// at the coarse fixed nodes, as `restrict`), each residual row accumulated into `tmp` while it
    /// is in cache and each coarse row finished as soon as no later fine row contributes to it.
    #[allow(clippy::too_many_arguments)]
    fn smooth_pass(&mut self, sweeps: usize, reverse: bool, from_zero: bool, residual: bool, want_dot: bool, prolong: Option<&Level>, mut restrict: Option<&mut Level>) -> f64 {
        let nz = self.nz;
        let first = if reverse { 1 } else { 0 };
        let stages = 2 * sweeps;
        let last = if residual { nz - 2 + stages } else { nz - 2 + stages - 1 };
        let mut acc = 0.0;
        if residual {
            let nt = self.nt;
            self.r[..nt].fill(0.0);
            self.r[(nz - 1) * nt..].fill(0.0);
        }
        // restriction: `tmp` rows zeroed so far, coarse rows finished so far;
        // prolongation: `tmp` rows interpolated so far
        let (mut zeroed, mut finished, mut made) = (0, 0, 0);
        if let Some(c) = prolong {
            self.prolong_row_z(1, c, &mut made);
        }
        for j in 1..=last {
            if let Some(c) = prolong
                && j + 1 <= nz - 2
            {
                self.prolong_row_z(j + 1, c, &mut made);
            }
            for s in 0..stages {
                if j > s && j - s <= nz - 2 {
                    let color = if s % 2 == 0 { first } else { 1 - first };
                    if s == 0 && from_zero {
                        self.smooth_row_zero(j, color);
                    } else {
                        self.smooth_row(j - s, color);
                    }
                }
            }
            if residual && j > stages && j - stages <= nz - 2 {
                let jr = j - stages;
                self.residual_row(jr);
                if let Some(c) = restrict.as_deref_mut() {
                    self.restrict_row_z(jr, &mut zeroed);
                    // later fine rows contribute to coarse rows `p_lo[jr + 1]` and above only
                    let done = self.tz.as_ref().unwrap().p_lo[jr + 1];
                    self.restrict_finish(done, c, &mut zeroed, &mut finished);
                }
            }
            if want_dot && j >= stages && j + 1 - stages <= nz - 2 {
                let row = (j + 1 - stages) * self.nt;
                for (b, x) in self.b[row..row + self.nt].iter().zip(&self.x[row..row + self.nt]) {
                    acc += b * x;
                }
            }
        }
        if let Some(c) = restrict {
            let nzc = c.nz;
            self.restrict_finish(nzc, c, &mut zeroed, &mut finished);
        }
        acc
    }

    /// The axial half of the restriction for fine row `j` (its residual final): `tmp` rows
    /// `p_lo[j]` and `p_hi[j]` += the row's weighted residual on its free ranges (outside them
    /// the residual is 0), in the order of `restrict` (the test reference); the `tmp` rows are
    /// zeroed when first touched (`zeroed`: the rows zeroed so far).
    #[inline(always)]
    fn restrict_row_z(&mut self, j: usize, zeroed: &mut usize) {
        let tz = self.tz.as_ref().unwrap();
        let nt = self.nt;
        let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
        let top = if w != 0.0 { b } else { a };
        if *zeroed <= top {
            self.tmp[*zeroed * nt..(top + 1) * nt].fill(0.0);
            *zeroed = top + 1;
        }
        let src = &self.r[j * nt..(j + 1) * nt];
        let wa = 1.0 - w;
        for (lo, hi) in self.free_span[j] {
            for (t, s) in self.tmp[a * nt + lo..a * nt + hi].iter_mut().zip(&src[lo..hi]) {
                *t += wa * s;
            }
            if w != 0.0 {
                for (t, s) in self.tmp[b * nt + lo..b * nt + hi].iter_mut().zip(&src[lo..hi]) {
                    *t += w * s;
                }
            }
        }
    }

    /// The circumferential half of the restriction for the coarse rows `finished..upto` (no
    /// later fine row contributes to them): `coarse.b` row `a` = `Pᵀ` of `tmp` row `a`, 0 at the
    /// coarse fixed nodes.
    fn restrict_finish(&mut self, upto: usize, coarse: &mut Level, zeroed: &mut usize, finished: &mut usize) {
        let nt = self.nt;
        let ntc = coarse.nt;
        if *zeroed < upto {
            self.tmp[*zeroed * nt..upto * nt].fill(0.0);
            *zeroed = upto;
        }
        let tt = self.tt.as_ref().unwrap();
        for a in *finished..upto {
            let t = &self.tmp[a * nt..(a + 1) * nt];
            let out = &mut coarse.b[a * ntc..(a + 1) * ntc];
            out.fill(0.0);
            tt.restrict_row(t, out);
            for (v, f) in out.iter_mut().zip(&coarse.fixed[a * ntc..(a + 1) * ntc]) {
                if *f != FREE {
                    *v = 0.0;
                }
            }
        }
        *finished = (*finished).max(upto);
    }

    /// `x += mask·(z-interpolation of the rows of tmp)` on row `j`, the `tmp` rows it reads
    /// first interpolated around the circumference from `coarse.x` (`made`: the rows done).
    #[inline(always)]
    fn prolong_row_z(&mut self, j: usize, coarse: &Level, made: &mut usize) {
        let tz = self.tz.as_ref().unwrap();
        let nt = self.nt;
        let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
        if *made <= b {
            let tt = self.tt.as_ref().unwrap();
            let ntc = coarse.nt;
            for c in *made..=b {
                tt.prolong_row(&coarse.x[c * ntc..(c + 1) * ntc], &mut self.tmp[c * nt..(c + 1) * nt]);
            }
            *made = b + 1;
        }
        let row = j * nt;
        let (ta, tb) = (&self.tmp[a * nt..(a + 1) * nt], &self.tmp[b * nt..(b + 1) * nt]);
        let m = &self.mask[row..row + nt];
        let x = &mut self.x[row..row + nt];
        // outside the free ranges the mask is 0 (the correction adds nothing)
        for (lo, hi) in self.free_span[j] {
            for i in lo..hi {
                x[i] += m[i] * ((1.0 - w) * ta[i] + w * tb[i]);
            }
        }
    }

    /// The first half-sweep from `x = 0`: `x = b/d` on the nodes of colour `color` in row `j`
    /// within its free span, and `x = 0` on both colours outside it (the later half-sweeps
    /// skip those nodes: every one is fixed).
    #[inline(always)]
    fn smooth_row_zero(&mut self, j: usize, color: usize) {
        let nt = self.nt;
        let row = j * nt;
        let inv = &self.inv_d[row..row + nt];
        let b = &self.b[row..row + nt];
        let cur = &mut self.x[row..row + nt];
        let span = self.free_span[j];
        fill_gaps(cur, span);
        for (lo, hi) in span {
            let mut i = lo + (color + j + lo) % 2;
            while i < hi {
                cur[i] = b[i] * inv[i];
                i += 2;
            }
        }
    }

    /// `r = b − A x` on row `j` (free nodes; 0 at fixed ones).
    #[inline(always)]
    fn residual_row(&mut self, j: usize) {
        let mut r = std::mem::take(&mut self.r);
        self.kernel_row::<{ Self::SUB_MINUS }>(j, self.free_span[j], &self.x, &mut r, &self.mask, &self.b);
        self.r = r;
    }

    /// Gauss–Seidel update of the nodes of colour `color` (`(i + j) % 2`) in row `j` within its
    /// free span (outside it every node is fixed and `x` stays 0).
    #[inline(always)]
    fn smooth_row(&mut self, j: usize, color: usize) {
        for (lo, hi) in self.free_span[j] {
            self.smooth_range(j, color, lo, hi);
        }
    }

    /// [`Level::smooth_row`] on the columns `lo..hi`.
    #[inline(always)]
    fn smooth_range(&mut self, j: usize, color: usize, lo: usize, hi: usize) {
        let nt = self.nt;
        let row = j * nt;
        let ce = &self.ce[row..row + nt];
        let cn_s = &self.cn[row - nt..row];
        let cn_n = &self.cn[row..row + nt];
        let inv = &self.inv_d[row..row + nt];
        let b = &self.b[row..row + nt];
        let (below, rest) = self.x.split_at_mut(row);
        let below = &below[row - nt..];
        let (cur, above) = rest.split_at_mut(nt);
        let above = &above[..nt];
        #[inline(always)]
        #[allow(clippy::too_many_arguments)]
        fn upd(cur: &mut [f64], b: &[f64], ce: &[f64], cn_n: &[f64], cn_s: &[f64], above: &[f64], below: &[f64], inv: &[f64], i: usize, iw: usize, ie: usize) {
            let s = b[i] + ce[i] * cur[ie] + ce[iw] * cur[iw] + cn_n[i] * above[i] + cn_s[i] * below[i];
            cur[i] = s * inv[i];
        }
        let mut i = lo + (color + j + lo) % 2;
        if i >= hi {
            return;
        }
        if i == 0 {
            upd(cur, b, ce, cn_n, cn_s, above, below, inv, 0, nt - 1, 1);
            i = 2;
        }
        // interior nodes of this colour: 1 ≤ i ≤ nt − 2 and i < hi, step 2
        let end = hi.min(nt - 1);
        let mut k = i;
        while k < end {
            // SAFETY: 1 ≤ k − 1 < k + 1 < nt and every slice has length nt.
            unsafe {
                let s = *b.get_unchecked(k)
                    + *ce.get_unchecked(k) * *cur.get_unchecked(k + 1)
                    + *ce.get_unchecked(k - 1) * *cur.get_unchecked(k - 1)
                    + *cn_n.get_unchecked(k) * *above.get_unchecked(k)
                    + *cn_s.get_unchecked(k) * *below.get_unchecked(k);
                *cur.get_unchecked_mut(k) = s * *inv.get_unchecked(k);
            }
            k += 2;
        }
        if k + 1 == nt && k < hi {
            upd(cur, b, ce, cn_n, cn_s, above, below, inv, k, k - 1, 0);
        }
    }

    /// Projected Gauss–Seidel update of the nodes of colour `color` in row `j` for the LCP
    /// ([`Hierarchy::projected_sweeps`]): `P = max(0, (f + Σ c_nb P_nb)/d)`, 0 at boundary nodes.
    #[inline(always)]
    fn projected_row(&mut self, j: usize, color: usize) {
        let nt = self.nt;
        let row = j * nt;
        let ce = &self.ce[row..row + nt];
        let cn_s = &self.cn[row - nt..row];
        let cn_n = &self.cn[row..row + nt];
        let inv = &self.inv_diag[row..row + nt];
        let f = &self.src[row..row + nt];
        let int = &self.interior[row..row + nt];
        let (below, rest) = self.u.split_at_mut(row);
        let below = &below[row - nt..];
        let (cur, above) = rest.split_at_mut(nt);
        let above = &above[..nt];
        let upd = |cur: &mut [f64], i: usize, iw: usize, ie: usize| {
            let s = f[i] + ce[i] * cur[ie] + ce[iw] * cur[iw] + cn_n[i] * above[i] + cn_s[i] * below[i];
            cur[i] = (s * inv[i]).max(0.0) * int[i];
        };
        let mut i = (color + j) % 2;
        if i == 0 {
            upd(cur, 0, nt - 1, 1);
            i = 2;
        }
        while i + 1 < nt {
            // SAFETY: 1 ≤ i − 1 < i + 1 < nt and every slice has length nt.
            unsafe {
                let s = *f.get_unchecked(i)
                    + *ce.get_unchecked(i) * *cur.get_unchecked(i + 1)
                    + *ce.get_unchecked(i - 1) * *cur.get_unchecked(i - 1)
                    + *cn_n.get_unchecked(i) * *above.get_unchecked(i)
                    + *cn_s.get_unchecked(i) * *below.get_unchecked(i);
                *cur.get_unchecked_mut(i) = (s * *inv.get_unchecked(i)).max(0.0) * *int.get_unchecked(i);
            }
            i += 2;
        }
        if i + 1 == nt {
            upd(cur, i, i - 1, 0);
        }
    }

    const PLAIN: u8 = 0;
    const MINUS_SUB: u8 = 1;
    const SUB_MINUS: u8 = 2;

    /// One pass of the five-point operator: `out = m·(A v)` (`PLAIN`), `m·(A v − s)`
    /// (`MINUS_SUB`) or `m·(s − A v)` (`SUB_MINUS`); 0 on the edge rows. The interior of each
    /// row is written on equal-length slices so that the loop vectorises.
    fn kernel<const MODE: u8>(&self, v: &[f64], out: &mut [f64], mask: &[f64], sub: &[f64]) {
        let nt = self.nt;
        out[..nt].fill(0.0);
        out[(self.nz - 1) * nt..].fill(0.0);
        for j in 1..self.nz - 1 {
            self.kernel_row::<MODE>(j, [(0, nt), (nt, nt)], v, out, mask, sub);
        }
    }

    /// Row `j` (not an edge row) of [`Level::kernel`] on the column ranges `span`; 0 on the
    /// other columns (where `mask` is 0).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn kernel_row<const MODE: u8>(&self, j: usize, span: Span, v: &[f64], out: &mut [f64], mask: &[f64], sub: &[f64]) {
        let row = j * self.nt;
        fill_gaps(&mut out[row..row + self.nt], span);
        for (lo, hi) in span {
            self.kernel_range::<MODE>(j, lo, hi, v, out, mask, sub);
        }
    }

    /// [`Level::kernel_row`] on the columns `lo..hi` (the others untouched).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn kernel_range<const MODE: u8>(&self, j: usize, lo: usize, hi: usize, v: &[f64], out: &mut [f64], mask: &[f64], sub: &[f64]) {
        #[inline(always)]
        fn finish<const MODE: u8>(m: f64, a: f64, s: f64) -> f64 {
            match MODE {
                0 => m * a,
                1 => m * (a - s),
                _ => m * (s - a),
            }
        }
        let nt = self.nt;
        let row = j * nt;
        let ce = &self.ce[row..row + nt];
        let cs = &self.cn[row - nt..row];
        let cnn = &self.cn[row..row + nt];
        let d = &self.diag[row..row + nt];
        let m = &mask[row..row + nt];
        let sb = &sub[row..row + nt];
        let vb = &v[row - nt..row];
        let vc = &v[row..row + nt];
        let va = &v[row + nt..row + 2 * nt];
        let o = &mut out[row..row + nt];
        if lo == 0 && hi > 0 {
            let a0 = d[0] * vc[0] - ce[0] * vc[1] - ce[nt - 1] * vc[nt - 1] - cnn[0] * va[0] - cs[0] * vb[0];
            o[0] = finish::<MODE>(m[0], a0, sb[0]);
        }
        if hi == nt && lo < nt {
            let an = d[nt - 1] * vc[nt - 1] - ce[nt - 1] * vc[0] - ce[nt - 2] * vc[nt - 2] - cnn[nt - 1] * va[nt - 1] - cs[nt - 1] * vb[nt - 1];
            o[nt - 1] = finish::<MODE>(m[nt - 1], an, sb[nt - 1]);
        }
        // the interior columns of the range, 1 ≤ i ≤ nt − 2
        let (a, b) = (lo.max(1), hi.min(nt - 1));
        if a >= b {
            return;
        }
        let (d1, ce0, ce1, cn1, cs1) = (&d[a..b], &ce[a - 1..b - 1], &ce[a..b], &cnn[a..b], &cs[a..b]);
        let (vw, vcc, ve, va1, vb1) = (&vc[a - 1..b - 1], &vc[a..b], &vc[a + 1..b + 1], &va[a..b], &vb[a..b]);
        let (m1, s1) = (&m[a..b], &sb[a..b]);
        let o1 = &mut o[a..b];
        let n = b - a;
        for i in 0..n {
            let a = d1[i] * vcc[i] - ce1[i] * ve[i] - ce0[i] * vw[i] - cn1[i] * va1[i] - cs1[i] * vb1[i];
            o1[i] = finish::<MODE>(m1[i], a, s1[i]);
        }
    }
}

/// Face conductances of one row of a coarse level under a profiled film whose edge profile
/// varies inside one coarse cell (a point value at the face does not see a profile narrower
/// than the cell): the film across the axial interval `[z0, z1]` sampled at `m` midpoints (the
/// finest grid's resolution), at the angles `(cs, sn)`. East faces (`north = false`, flow
/// around the bearing: the sub-cells conduct in parallel) take the arithmetic mean of `H³`
/// over the cell's axial extent; north faces (`north = true`, flow along the axis: the
/// sub-cells conduct in series) the harmonic mean over `[Z_j, Z_{j+1}]` (finite-volume
/// conductances of a varying coefficient, Patankar 1980, §4.2-3). `k` is the grid factor
/// `ΔZ/Δθ` or `αΔθ/ΔZ`; `zrows` is scratch.
#[allow(clippy::too_many_arguments)]
fn face_means(film: &Film, z0: f64, z1: f64, m: usize, north: bool, k: f64, cs: &[f64], sn: &[f64], zrows: &mut Vec<super::film::Row>, out: &mut [f64]) {
    zrows.clear();
    zrows.extend((0..m).map(|q| film.row(z0 + (q as f64 + 0.5) / m as f64 * (z1 - z0))));
    let inv_m = 1.0 / m as f64;
    for ((o, c), s) in out.iter_mut().zip(cs).zip(sn) {
        let mut acc = 0.0;
        for r in zrows.iter() {
            let h = 1.0 + r.gamma + r.x * c + r.y * s;
            let h3 = h * h * h;
            acc += if north { 1.0 / h3 } else { h3 };
        }
        let mean = acc * inv_m;
        *o = if north { k / mean } else { mean * k };
    }
}

/// Two ascending column ranges of one row (see `Level::free_span`).
type Span = [(usize, usize); 2];

/// The columns of a row of `nt` nodes without its longest cyclic run of fixed nodes, as two
/// ascending ranges (both empty when no node is free), from the first and last free column
/// (`first = usize::MAX` when there is none) and the longest run of fixed nodes between them
/// (`gap` nodes from `gap_start`).
fn free_ranges(nt: usize, first: usize, last: usize, gap: usize, gap_start: usize) -> Span {
    if first == usize::MAX {
        return [(0, 0), (0, 0)];
    }
    // the run around column 0 against the longest inside the row
    if first + (nt - 1 - last) >= gap {
        [(first, last + 1), (nt, nt)]
    } else {
        [(0, gap_start), (gap_start + gap, nt)]
    }
}

/// Zero of `row` outside the ranges of `span`.
#[inline(always)]
fn fill_gaps(row: &mut [f64], span: Span) {
    let [(a1, b1), (a2, b2)] = span;
    row[..a1].fill(0.0);
    row[b1..a2].fill(0.0);
    row[b2..].fill(0.0);
}

/// Whether the film's edge profile is non-zero anywhere in `[z0, z1]` (it is zero exactly on
/// `[ψ, 1 − ψ]` and non-zero elsewhere when its height is).
fn profile_in(film: &Film, z0: f64, z1: f64) -> bool {
    film.profile.is_some_and(|p| p.opening(z0) != 0.0 || p.opening(z1) != 0.0)
}

/// The grid hierarchy for one bearing: level 0 is the finest.
#[derive(Debug, Clone)]
pub struct Hierarchy {
    pub levels: Vec<Level>,
    pub alpha: f64,
    /// Red–black sweeps before and after the coarse-grid correction.
    pub sweeps: usize,
    /// V-cycles spent on each level since the hierarchy was built (work accounting).
    pub cycle_count: Vec<u32>,
    /// Active-set steps on each level since the hierarchy was built.
    pub step_count: Vec<u32>,
    /// Solve to the full tolerance as soon as an active-set step changes at most 0.1 % of the
    /// nodes (instead of only once it changes none): saves the loose solve of a step that
    /// rarely moves the set again; and the inexact solves of the steps before are taken to
    /// 1e-3 instead of 1e-4. Off by default (it changes the last digits of a solve).
    pub eager_tight: bool,
    scratch: [Vec<f64>; 3],
}

/// Outcome of one LCP solve on one level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LcpReport {
    /// Active-set (semismooth Newton) steps.
    pub steps: u32,
    /// Preconditioned CG iterations (= V-cycles) over all steps.
    pub cycles: u32,
    /// Relative complementarity residual `‖min(P, λ)‖` scaled as described in [`Hierarchy::lcp_residual`].
    pub residual: f64,
    /// Whether the active set settled and the linear residual met the tolerance.
    pub converged: bool,
}

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

    fn build(nt: usize, nz: usize, alpha: f64, grooves: usize, mirror: bool) -> Self {
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
    fn pcg(&mut self, k: usize, tol: f64, max_iter: u32) -> (u32, bool) {
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
    fn pcg_inner(&mut self, k: usize, tol: f64, max_iter: u32, p: &mut [f64], q: &mut [f64]) -> (u32, bool) {
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
    fn vcycle(&mut self, k: usize) -> f64 {
        self.vcycle_inner(k, k)
    }

    /// [`Hierarchy::vcycle`] on level `k` of a cycle that started on level `top`.
    fn vcycle_inner(&mut self, k: usize, top: usize) -> f64 {
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

impl Level {
    /// Right-hand sides of the linearised Reynolds equation at the converged pressure `p0` of
    /// this level, for a journal perturbation `δH = s(Z)·(cos θ, sin θ)[dir]` (`dir` 0: along
    /// the load, `X`; 1: across it, `Y`), on the cavitation set of `p0` (the free nodes):
    /// - `disp`: displacement, `∂f/∂X − (∂A/∂X) p0` — the derivative of `A(H) P = f(H)` with
    ///   the face conductances `c = H³ k` differentiated, `∂c/∂X = 3H² (∂H/∂X) k`;
    /// - `vel`: velocity `dX/d(ωt)`, the squeeze term of the time-dependent Reynolds equation,
    ///   `−2 ∂H/∂(ωt)` integrated over the cell (seed 002 eq. (4) with `∂h/∂t`; Lund 1987).
    ///
    /// Both are 0 at fixed (boundary or cavitated) nodes. `s` is the axial shape of the
    /// perturbation (1 for a translation).
    pub(super) fn linearised_sources(&self, film: &Film, alpha: f64, dir: usize, s: &dyn Fn(f64) -> f64, p0: &[f64], disp: &mut [f64], vel: &mut [f64]) {
        let (nt, nz, dt, dz) = (self.nt, self.nz, self.dt, self.dz);
        let trig = |t: f64| if dir == 0 { t.cos() } else { t.sin() };
        // ∫ trig over a cell: d/dθ of the antiderivative at the faces
        let anti = |t: f64| if dir == 0 { t.sin() } else { -t.cos() };
        let ke = dz / dt;
        let kn = alpha * dt / dz;
        let g_f: Vec<f64> = (0..nt).map(|i| trig(self.theta0 + (i as f64 + 0.5) * dt)).collect();
        let a_f: Vec<f64> = (0..nt).map(|i| anti(self.theta0 + (i as f64 + 0.5) * dt)).collect();
        let g_n: Vec<f64> = (0..nt).map(|i| trig(self.theta0 + i as f64 * dt)).collect();
        let (s_face, s_node): (Vec<f64>, Vec<f64>) =
            (0..nz).map(|j| (s(((j as f64 + 0.5) * dz).min(1.0)), s(j as f64 * dz))).unzip();
        disp.fill(0.0);
        vel.fill(0.0);
        // derivatives of the face conductances
        let mut dce = vec![0.0; nt * nz];
        let mut dcn = vec![0.0; nt * nz];
        // the face angles' cosines and sines, once per column (not per node)
        let (cos_f, sin_f): (Vec<f64>, Vec<f64>) = (0..nt)
            .map(|i| {
                let tf = self.theta0 + (i as f64 + 0.5) * dt;
                (tf.cos(), tf.sin())
            })
            .unzip();
        for j in 0..nz {
            let z = j as f64 * dz;
            let r = film.row(z);
            let rn = film.row((z + 0.5 * dz).min(1.0));
            for i in 0..nt {
                let k = j * nt + i;
                let he = 1.0 + r.gamma + r.x * cos_f[i] + r.y * sin_f[i];
                dce[k] = 3.0 * he * he * s_node[j] * g_f[i] * ke;
                if j + 1 < nz {
                    let hn = 1.0 + rn.gamma + rn.x * self.cos_n[i] + rn.y * self.sin_n[i];
                    dcn[k] = 3.0 * hn * hn * s_face[j] * g_n[i] * kn;
                }
            }
        }
        for j in 1..nz - 1 {
            for i in 0..nt {
                let k = j * nt + i;
                if self.fixed[k] != FREE {
                    continue;
                }
                let iw = if i == 0 { nt - 1 } else { i - 1 };
                let ie = if i + 1 == nt { 0 } else { i + 1 };
                let (kw, kee) = (j * nt + iw, j * nt + ie);
                let dap = dce[k] * (p0[k] - p0[kee]) + dce[kw] * (p0[k] - p0[kw]) + dcn[k] * (p0[k] - p0[k + nt]) + dcn[k - nt] * (p0[k] - p0[k - nt]);
                // f = −∂H/∂θ ΔθΔZ in flux form
                let df = -dz * s_node[j] * (g_f[i] - g_f[iw]);
                disp[k] = df - dap;
                vel[k] = -2.0 * dz * s_node[j] * (a_f[i] - a_f[iw]);
            }
        }
    }
}

impl Hierarchy {
    /// Solve `A_II x = b` on the free nodes of level `k` (the cavitation set of the last LCP
    /// solve, injected on every coarser level) by multigrid-preconditioned CG from zero, to the
    /// relative residual `tol`. Returns (iterations, converged, relative residual).
    pub(super) fn solve_free(&mut self, k: usize, b: &[f64], x: &mut [f64], tol: f64, max_iter: u32) -> (u32, bool, f64) {
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

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `coarse.b = Pᵀ fine.r` (full weighting for nested grids), zero at coarse fixed nodes, as a
/// pass of its own: the V-cycle does it inside the pre-smoothing pass ([`Level::smooth_pass`]);
/// kept as the reference of the test.
#[cfg(test)]
fn restrict(fine: &mut Level, coarse: &mut Level) {
    let tt = fine.tt.as_ref().unwrap();
    let tz = fine.tz.as_ref().unwrap();
    let (ntf, nzf) = (fine.nt, fine.nz);
    let ntc = coarse.nt;
    let tmp = &mut fine.tmp;
    tmp.fill(0.0);
    for j in 0..nzf {
        let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
        let src = &fine.r[j * ntf..(j + 1) * ntf];
        let wa = 1.0 - w;
        // the residual is 0 outside the row's free ranges
        for (lo, hi) in fine.free_span[j] {
            for i in lo..hi {
                tmp[a * ntf + i] += wa * src[i];
            }
            if w != 0.0 {
                for i in lo..hi {
                    tmp[b * ntf + i] += w * src[i];
                }
            }
        }
    }
    coarse.b.fill(0.0);
    for a in 0..coarse.nz {
        let t = &tmp[a * ntf..(a + 1) * ntf];
        let out = &mut coarse.b[a * ntc..(a + 1) * ntc];
        tt.restrict_row(t, out);
    }
    for (v, f) in coarse.b.iter_mut().zip(&coarse.fixed) {
        if *f != FREE {
            *v = 0.0;
        }
    }
}

/// The circumferential half of `fine.x += P coarse.x`: `fine.tmp` row `a` = the coarse
/// correction's row `a` interpolated around the circumference (the axial half and the addition
/// are [`Level::prolong_row_z`]), as a pass of its own: the V-cycle interpolates each row when
/// the post-smoothing pass first needs it; kept as the reference of the test.
#[cfg(test)]
fn prolong_theta(coarse: &Level, fine: &mut Level) {
    let tt = fine.tt.as_ref().unwrap();
    let ntf = fine.nt;
    let ntc = coarse.nt;
    let tmp = &mut fine.tmp;
    for a in 0..coarse.nz {
        let c = &coarse.x[a * ntc..(a + 1) * ntc];
        let out = &mut tmp[a * ntf..(a + 1) * ntf];
        tt.prolong_row(c, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn aligned_hierarchy(nt: usize, nz: usize, ld: f64, eps: f64) -> Hierarchy {
        let alpha = 1.0 / (4.0 * ld * ld);
        let mut h = Hierarchy::new(nt, nz, alpha, true);
        h.set_film(&Film::aligned(eps, 0.0), 0.0);
        h
    }

    #[test]
    fn nested_active_set_converges_for_the_seed_case() {
        let mut h = aligned_hierarchy(144, 49, 1.25, 0.6);
        let rep = h.nested_solve(0, 1e-10, 30, 400);
        assert!(rep.converged, "{rep:?}");
        assert!(rep.residual < 1e-8, "{rep:?}");
        assert!(h.levels[0].u.iter().all(|p| *p >= 0.0));
    }

    #[test]
    fn projected_sweeps_keep_the_lcp_solution_and_settle_an_interpolated_start() {
        // the converged LCP solution is a fixed point of the projected sweeps
        let mut h = aligned_hierarchy(144, 49, 1.0, 0.6);
        let rep = h.nested_solve(0, 1e-13, 30, 400);
        assert!(rep.converged);
        let u0 = h.levels[0].u.clone();
        let m = u0.iter().fold(0.0f64, |a, b| a.max(*b));
        h.projected_sweeps(0, 3);
        for (a, b) in u0.iter().zip(&h.levels[0].u) {
            assert!((a - b).abs() < 1e-9 * m, "{a} {b}");
        }
        // from the coarser grid's solution interpolated, two sweeps reduce the complementarity
        // residual, and the active-set solve still reaches the same solution
        h.interpolate_up(0);
        let r0 = h.lcp_residual(0);
        h.projected_sweeps(0, 2);
        let r1 = h.lcp_residual(0);
        assert!(r1 < 0.5 * r0, "{r0} {r1}");
        let rep = h.solve_lcp(0, 1e-13, 30, 400);
        assert!(rep.converged);
        for (a, b) in u0.iter().zip(&h.levels[0].u) {
            assert!((a - b).abs() < 1e-9 * m, "{a} {b}");
        }
    }

    #[test]
    fn reported_residual_is_that_of_the_returned_pressure() {
        // the residual of a converged solve comes from the λ of the last active-set check: it
        // must equal the residual recomputed from the returned pressure, bit for bit
        let mut h = aligned_hierarchy(96, 33, 1.0, 0.7);
        h.eager_tight = true;
        let rep = h.nested_solve(0, 1e-7, 30, 400);
        assert!(rep.converged);
        assert_eq!(rep.residual.to_bits(), h.lcp_residual(0).to_bits());
        h.set_film(&Film::aligned(0.71, 0.02), 0.0);
        let rep = h.solve_lcp(0, 1e-9, 30, 400);
        assert!(rep.converged && rep.steps >= 1);
        assert_eq!(rep.residual.to_bits(), h.lcp_residual(0).to_bits());
    }

    #[test]
    fn coarse_operators_of_a_nearby_position_give_the_same_solution() {
        // warm solve at a position 5e-4 away: with the coarse levels rebuilt, and with the
        // coarse levels of the old position kept (they only precondition level 0)
        let film = |e: f64| Film { misalignment: super::super::film::Misalignment { vertical: 0.3, horizontal: 0.2 }, ..Film::aligned(e, 0.4) };
        let mut a = Hierarchy::new(120, 41, 0.25, true);
        a.eager_tight = true;
        a.set_film(&film(0.5), 0.0);
        assert!(a.nested_solve(0, 1e-9, 30, 400).converged);
        let mut b = a.clone();
        a.set_film_from(0, &film(0.5005), 0.0);
        b.set_film_near(0, &film(0.5005), 0.0, 1e-3);
        // the coarse levels of `b` still hold the old position's coefficients
        assert!(b.levels[1].coeffs_of.unwrap().0 == film(0.5));
        assert!(a.levels[1].coeffs_of.unwrap().0 == film(0.5005));
        let (ra, rb) = (a.solve_lcp(0, 1e-9, 30, 400), b.solve_lcp(0, 1e-9, 30, 400));
        assert!(ra.converged && rb.converged, "{ra:?} {rb:?}");
        let m = a.levels[0].u.iter().fold(0.0f64, |x, y| x.max(*y));
        for (x, y) in a.levels[0].u.iter().zip(&b.levels[0].u) {
            assert!((x - y).abs() < 1e-7 * m, "{x} {y}");
        }
        // a position farther than `near` rebuilds them
        b.set_film_near(0, &film(0.52), 0.0, 1e-3);
        assert!(b.levels[1].coeffs_of.unwrap().0 == film(0.52));
    }

    #[test]
    fn transfers_inside_the_smoothing_passes_match_the_separate_passes() {
        // the restriction fused into the pre-smoothing pass and the circumferential
        // prolongation done row by row inside the post-smoothing pass give the values of the
        // separate passes bit for bit, on every level pair (halving, general and identity
        // transfers; a misaligned film with a cavitated zone)
        let film = Film { misalignment: super::super::film::Misalignment { vertical: 0.4, horizontal: 0.3 }, ..Film::aligned(0.6, 0.3) };
        for (nt, nz, alpha) in [(120, 61, 0.16), (90, 33, 0.16), (61, 41, 4.0), (64, 17, 0.01)] {
            let mut h = Hierarchy::new(nt, nz, alpha, true);
            h.eager_tight = true;
            h.set_film(&film, 0.1);
            assert!(h.nested_solve(0, 1e-6, 30, 400).converged);
            for k in 0..h.levels.len() - 1 {
                // a right-hand side on the free nodes and a coarse correction
                let (head, tail) = h.levels.split_at_mut(k + 1);
                let (fine, coarse) = (&mut head[k], &mut tail[0]);
                for (idx, (b, m)) in fine.b.iter_mut().zip(&fine.mask).enumerate() {
                    *b = m * ((idx as f64 * 0.37).sin() + 0.2);
                }
                for (idx, x) in coarse.x.iter_mut().enumerate() {
                    *x = (idx as f64 * 0.11).cos();
                }
                let (mut f1, mut c1) = (fine.clone(), coarse.clone());
                f1.smooth_pass(2, false, true, true, false, None, None);
                restrict(&mut f1, &mut c1);
                let (mut f2, mut c2) = (fine.clone(), coarse.clone());
                f2.smooth_pass(2, false, true, true, false, None, Some(&mut c2));
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&c1.b), bits(&c2.b), "restriction, {nt}×{nz} level {k}");
                assert_eq!(bits(&f1.x), bits(&f2.x));
                // reference: the whole correction added first (each row's addition precedes
                // every read of it in the pass), then the plain post-smoothing pass
                prolong_theta(coarse, &mut f1);
                let (tz, nt) = (f1.tz.clone().unwrap(), f1.nt);
                for j in 0..f1.nz {
                    let (a, b, w) = (tz.p_lo[j], tz.p_hi[j], tz.p_w[j]);
                    for (lo, hi) in f1.free_span[j] {
                        for i in lo..hi {
                            let add = f1.mask[j * nt + i] * ((1.0 - w) * f1.tmp[a * nt + i] + w * f1.tmp[b * nt + i]);
                            f1.x[j * nt + i] += add;
                        }
                    }
                }
                let d1 = f1.smooth_pass(2, true, false, false, true, None, None);
                let d2 = f2.smooth_pass(2, true, false, false, true, Some(coarse), None);
                assert_eq!(bits(&f1.x), bits(&f2.x), "prolongation, {nt}×{nz} level {k}");
                assert_eq!(d1.to_bits(), d2.to_bits());
            }
        }
    }

    #[test]
    fn free_span_drops_the_longest_cyclic_run_of_fixed_nodes() {
        // 12 columns, supply line at column 0, three interior rows
        let mut l = Level::new(12, 5, 1, false);
        let (f, c) = (FREE, CAVITATED);
        // row 1: free on both sides of a cavitated middle: the middle run (5) is dropped
        // row 2: free in 1..6 with a short inner run: the run around column 0 (7) is dropped
        // row 3: cavitated throughout
        let rows: [[u8; 11]; 3] = [[f, f, f, c, c, c, c, c, f, f, f], [f, f, c, c, f, c, c, c, c, c, c], [c; 11]];
        for (a, row) in rows.iter().enumerate() {
            let j = a + 1;
            l.fixed[j * 12 + 1..j * 12 + 12].copy_from_slice(row);
        }
        l.refresh_masks();
        assert_eq!(l.free_span[0], [(0, 0), (0, 0)]);
        assert_eq!(l.free_span[1], [(0, 4), (9, 12)]);
        assert_eq!(l.free_span[2], [(1, 6), (12, 12)]);
        assert_eq!(l.free_span[3], [(0, 0), (0, 0)]);
        assert_eq!(l.free_span[4], [(0, 0), (0, 0)]);
        // every free node lies in a range
        for j in 0..5 {
            for i in 0..12 {
                let inside = l.free_span[j].iter().any(|(lo, hi)| (*lo..*hi).contains(&i));
                assert!(l.fixed[j * 12 + i] != FREE || inside, "{j} {i}");
            }
        }
    }

    #[test]
    fn active_set_matches_projected_gauss_seidel() {
        // The same discrete LCP solved by plain projected Gauss–Seidel to round-off.
        let mut h = aligned_hierarchy(48, 17, 1.0, 0.7);
        let rep = h.nested_solve(0, 1e-13, 30, 400);
        assert!(rep.converged);
        let l = &h.levels[0];
        let mut u = vec![0.0; l.u.len()];
        for _ in 0..20000 {
            for j in 1..l.nz - 1 {
                for i in 1..l.nt {
                    let k = j * l.nt + i;
                    let ke = if i + 1 == l.nt { j * l.nt } else { k + 1 };
                    let s = l.src[k] + l.nb_sum(&u, k, k - 1, ke);
                    u[k] = (s / l.diag[k]).max(0.0);
                }
            }
        }
        let m = u.iter().fold(0.0f64, |a, b| a.max(*b));
        for (a, b) in u.iter().zip(&l.u) {
            assert!((a - b).abs() < 1e-9 * m, "{a} {b}");
        }
    }
}
