//! The Newton preconditioner: the near-field Newton matrix (`Problem::precondition`), bordered by
//! the `H0` column and the load row and solved through the Schur complement ([`Precond`]).

use super::near::{nested_dissection, NearLu, NearPattern};
use super::*;

impl Problem {
    /// The near-field preconditioner (scaled like the Newton matrix) and the row scales `c`;
    /// `factor` false: the row scales and the active set only (`None`).
    /// `observer`: a large factorisation runs beside the caller, which polls it
    /// ([`NearLu::new_watched`]); an interrupt there is `Err`.
    pub(super) fn precondition(&self, p: &[f64], v: &Fields, active: &mut [u8], c: &mut [f64], factor: bool, observer: &dyn Observer) -> Result<Option<Precond>, SolveError> {
        if !factor {
            self.row_scales(p, v, active, c);
            return Ok(None);
        }
        let (ent, row_ptr) = self.near_rows(p, v, active, c);
        // The bordered system `[B u; wᵀ 0]` (the `H0` column `u`, the load row `w`) by its Schur
        // complement: factorising it with the dense border made the sparse LU fill in (35 s at
        // 97², measured), the block `B` alone factorises in a fraction of a second.
        let Some(pattern) = self.near_pattern(&row_ptr, &ent) else { return Ok(None) };
        let (values, mut ucol) = self.near_values(&pattern, active, &row_ptr, &ent);
        let Some(lu) = NearLu::new_watched(pattern, values, observer)? else { return Ok(None) };
        lu.solve_in_place(&mut ucol);
        let sum_bu = ucol.iter().sum::<f64>();
        Ok((sum_bu.is_finite() && ucol.iter().all(|x| x.is_finite())).then_some(Precond { lu, bu: ucol, sum_bu, c: c.to_vec(), active: active.to_vec() }))
    }

    /// The row scales `c` and the active set without the near-field rows: the diagonal alone,
    /// summed in the order [`Problem::near_rows`] pushes its entries (the same row scales to the
    /// last bit): the Poiseuille terms, then per wedge point its own `ρ̄'H` term and the
    /// deflection self-coefficient reaching this node.
    fn row_scales(&self, p: &[f64], v: &Fields, active: &mut [u8], c: &mut [f64]) {
        let (nx, dx2, dy2) = (self.nx, self.dx * self.dx, self.dy * self.dy);
        for (u, &k) in self.nodes.iter().enumerate() {
            let i = k % nx;
            let e = &v.eps;
            let mut diag = 0.0;
            for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                let (ef, w1, _) = face_of(self.theta, e[k], e[nb]);
                diag += -ef / d2 + w1 * v.deps[k] * (p[nb] - p[k]) / d2;
            }
            for (s, wt) in self.stencil(i) {
                if wt == 0.0 {
                    continue;
                }
                let kk = k - s;
                if s == 0 {
                    diag += -wt * v.drho[kk] * v.h[kk];
                }
                if s <= self.near {
                    diag += -wt * v.on[kk] * v.rho[kk] * self.defl.coefficient(s, 0);
                }
            }
            let cu = 1.0 / diag.abs().max(1e-300);
            c[u] = cu;
            active[u] = self.row_kind(p, v, cu, k);
        }
    }

    /// Every row's entries (column, value; column `m` the `H0` border), scaled by the row scale,
    /// cavitated rows too: the pattern is then that of the grid alone, its symbolic LU computed
    /// once ([`NearPattern`]). Row `u`'s entries are `ent[row_ptr[u]..row_ptr[u + 1]]`; `c` and
    /// `active` are set on the way.
    fn near_rows(&self, p: &[f64], v: &Fields, active: &mut [u8], c: &mut [f64]) -> (Vec<(usize, f64)>, Vec<usize>) {
        let (nx, ny, dx2, dy2) = (self.nx, self.ny, self.dx * self.dx, self.dy * self.dy);
        let m = self.nodes.len();
        let r = self.near as isize;
        let mut ent: Vec<(usize, f64)> = Vec::with_capacity(m * (10 + (2 * self.near + 3) * (2 * self.near + 1)));
        let mut row_ptr: Vec<usize> = Vec::with_capacity(m + 1);
        row_ptr.push(0);
        let mut row: Vec<(usize, f64)> = Vec::with_capacity(64);
        for (u, &k) in self.nodes.iter().enumerate() {
            let (i, j) = (k % nx, k / nx);
            let zone = self.x[i] >= -NEAR_ZONE;
            row.clear();
            let e = &v.eps;
            for (nb, d2) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)] {
                let (ef, w1, w2) = face_of(self.theta, e[k], e[nb]);
                let dpf = p[nb] - p[k];
                row.push((u, -ef / d2 + w1 * v.deps[k] * dpf / d2));
                if self.unk[nb] != usize::MAX {
                    row.push((self.unk[nb], ef / d2 + w2 * v.deps[nb] * dpf / d2));
                }
            }
            for (s, wt) in self.stencil(i) {
                if wt == 0.0 {
                    continue;
                }
                let kk = k - s;
                let (ki, kj) = (i - s, j);
                let lw = -wt;
                if self.unk[kk] != usize::MAX {
                    row.push((self.unk[kk], lw * v.drho[kk] * v.h[kk]));
                }
                let lw = lw * v.on[kk];
                row.push((m, lw * v.rho[kk]));
                if !zone {
                    // Outside the zone: the deflection's self term alone (the row scale unchanged).
                    if s <= self.near {
                        row.push((u, lw * v.rho[kk] * self.defl.coefficient(s, 0)));
                    }
                    continue;
                }
                for dj in -r..=r {
                    let lj = kj as isize + dj;
                    if lj < 1 || lj >= ny as isize - 1 {
                        continue;
                    }
                    for di in -r..=r {
                        let li = ki as isize + di;
                        if li < 1 || li >= nx as isize - 1 {
                            continue;
                        }
                        let l = lj as usize * nx + li as usize;
                        row.push((self.unk[l], lw * v.rho[kk] * self.defl.coefficient(di.unsigned_abs(), dj.unsigned_abs())));
                    }
                }
            }
            let diag: f64 = row.iter().filter(|(col, _)| *col == u).map(|(_, val)| val).sum();
            if poiseuille_film() && zone {
                self.poiseuille_film_entries(p, v, k, &mut row);
            }
            let cu = 1.0 / diag.abs().max(1e-300);
            c[u] = cu;
            active[u] = self.row_kind(p, v, cu, k);
            ent.extend(row.iter().map(|&(col, val)| (col, cu * val)));
            row_ptr.push(ent.len());
        }
        (ent, row_ptr)
    }

    /// The Poiseuille terms' film dependence `∂ε_f/∂H = w·3ε/H` at node `k` and its four
    /// neighbours, through the near-field deflection, within the columns the wedge terms already
    /// occupy (the pattern's box `i − 2 − r … i + r`, `j − r … j + r`), pushed onto `row`: with
    /// the geometric face mean (`θ → 1`) a face between an inlet node (large ε) and a contact
    /// node (small ε) weighs the contact node's film by `1.5 sqrt(ε_b/ε_a)`, which the wedge-only
    /// near field left out. The row scale `c` ([`Problem::near_rows`]) is unchanged, so is the
    /// residual.
    fn poiseuille_film_entries(&self, p: &[f64], v: &Fields, k: usize, row: &mut Vec<(usize, f64)>) {
        let (nx, ny, dx2, dy2) = (self.nx, self.ny, self.dx * self.dx, self.dy * self.dy);
        let m = self.nodes.len();
        let r = self.near as isize;
        let (i, j) = (k % nx, k / nx);
        let e = &v.eps;
        let lo = (if i >= 2 && self.second { 2 } else { 1 }) + r;
        let mut pts = [(k, 0.0); 5];
        for (q, (nb, d2)) in [(k + 1, dx2), (k - 1, dx2), (k + nx, dy2), (k - nx, dy2)].into_iter().enumerate() {
            let (_, w1, w2) = face_of(self.theta, e[k], e[nb]);
            let dpf = (p[nb] - p[k]) / d2;
            pts[0].1 += w1 * 3.0 * e[k] / v.h[k] * v.on[k] * dpf;
            pts[q + 1] = (nb, w2 * 3.0 * e[nb] / v.h[nb] * v.on[nb] * dpf);
        }
        for &(q, a) in &pts {
            if a == 0.0 || !a.is_finite() {
                continue;
            }
            let (qi, qj) = ((q % nx) as isize, (q / nx) as isize);
            row.push((m, a));
            for dj in -r..=r {
                let lj = j as isize + dj;
                if lj < 1 || lj >= ny as isize - 1 || (lj - qj).abs() > r {
                    continue;
                }
                for di in -lo..=r {
                    let li = i as isize + di;
                    if li < 1 || li >= nx as isize - 1 || (li - qi).abs() > r {
                        continue;
                    }
                    let l = lj as usize * nx + li as usize;
                    row.push((self.unk[l], a * self.defl.coefficient((li - qi).unsigned_abs(), (lj - qj).unsigned_abs())));
                }
            }
        }
    }

    /// The grid's [`NearPattern`] (kept in `self.pattern` while it covers the rows' entries, else
    /// computed afresh with a nested-dissection ordering); `None` when its symbolic
    /// factorisation fails.
    fn near_pattern(&self, row_ptr: &[usize], ent: &[(usize, f64)]) -> Option<std::sync::Arc<NearPattern>> {
        let m = self.nodes.len();
        let mut cache = self.pattern.borrow_mut();
        match cache.as_ref().filter(|pat| pat.covers(m, row_ptr, ent)) {
            Some(pat) => Some(pat.clone()),
            None => {
                let order = nested_dissection(self.nx - 2, self.ny - 2, 2 + 2 * self.near, 2 * self.near.max(1));
                let pat = std::sync::Arc::new(NearPattern::new(m, row_ptr, ent, order)?);
                *cache = Some(pat.clone());
                Some(pat)
            }
        }
    }

    /// The values of `B` on `pattern`'s CSC and the `H0` column `u` from the rows' entries: a
    /// cavitated row the identity, a contact row `s (H0 + W_k)` (the deflection's near field about
    /// the node, inside the box the row's wedge terms occupy, and the `H0` border).
    fn near_values(&self, pattern: &NearPattern, active: &[u8], row_ptr: &[usize], ent: &[(usize, f64)]) -> (Vec<f64>, Vec<f64>) {
        let (nx, ny) = (self.nx, self.ny);
        let m = self.nodes.len();
        let r = self.near as isize;
        let mut ucol = vec![0.0; m];
        let mut values = vec![0.0; pattern.row_idx.len()];
        let mut slot = vec![usize::MAX; m];
        for u in 0..m {
            let (a, b) = (pattern.row_ptr[u], pattern.row_ptr[u + 1]);
            for (&col, &pos) in pattern.row_col[a..b].iter().zip(&pattern.row_pos[a..b]) {
                slot[col] = pos;
            }
            if active[u] == CAVITATED {
                values[slot[u]] = 1.0;
                continue;
            }
            if active[u] == CONTACT {
                let sc = self.contact_scale();
                let k = self.nodes[u];
                let (i, j) = ((k % nx) as isize, (k / nx) as isize);
                ucol[u] += sc;
                for lj in (j - r).max(1)..=(j + r).min(ny as isize - 2) {
                    for li in (i - r).max(1)..=(i + r).min(nx as isize - 2) {
                        let l = lj as usize * nx + li as usize;
                        // Only the columns of this row's pattern (a row outside the near-field
                        // zone carries its own column alone).
                        if pattern.row_col[a..b].binary_search(&self.unk[l]).is_ok() {
                            values[slot[self.unk[l]]] += sc * self.defl.coefficient((li - i).unsigned_abs(), (lj - j).unsigned_abs());
                        }
                    }
                }
                continue;
            }
            for &(col, val) in &ent[row_ptr[u]..row_ptr[u + 1]] {
                if col == m {
                    ucol[u] += val;
                } else {
                    values[slot[col]] += val;
                }
            }
        }
        (values, ucol)
    }
}

/// The preconditioner: the near-field Newton matrix `[B u; wᵀ 0]` (unknowns `P`, then `H0`),
/// solved by the sparse LU of `B` and the Schur complement `s = wᵀB⁻¹u` (`w` the constant
/// load-row weight, taken from the problem at each use: a kept factor may come from another load).
pub(super) struct Precond {
    pub(super) lu: NearLu,
    /// `B⁻¹u`.
    pub(super) bu: Vec<f64>,
    /// `Σ B⁻¹u` (the Schur complement is `w` times it).
    pub(super) sum_bu: f64,
    /// The row scales and the active set it was factorised with.
    pub(super) c: Vec<f64>,
    pub(super) active: Vec<u8>,
}

impl Precond {
    /// `z ← M⁻¹ z`: `x1 = B⁻¹f`, `y = (wᵀx1 − g)/s`, `x = x1 − y B⁻¹u`.
    pub(super) fn apply(&self, z: &mut [f64], w: f64, rescale: &[f64]) {
        let m = self.bu.len();
        let g = z[m];
        if !rescale.is_empty() {
            for (zi, s) in z[..m].iter_mut().zip(rescale) {
                *zi *= s;
            }
        }
        self.lu.solve_in_place(&mut z[..m]);
        let schur = w * self.sum_bu;
        let y = if schur != 0.0 { (w * z[..m].iter().sum::<f64>() - g) / schur } else { 0.0 };
        for (zi, bi) in z[..m].iter_mut().zip(&self.bu) {
            *zi -= y * bi;
        }
        z[m] = y;
    }
}
