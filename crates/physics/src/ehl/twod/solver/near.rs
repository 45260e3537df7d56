//! The near-field matrix's sparse LU: its pattern and symbolic factorisation per grid
//! ([`NearPattern`], nested-dissection ordering), and the numeric factorisation ([`NearLu`]).

use crate::{Observer, SolveError};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::supernodal::{self, SupernodalLu, SymbolicSupernodalLu};
use faer::sparse::linalg::{qr, SymbolicSupernodalParams};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

/// The sparsity pattern of the near-field matrix `B` of a grid and its symbolic LU (a
/// nested-dissection column ordering of the grid, [`nested_dissection`], and the supernodal
/// elimination structure). Every row carries its full stencil, cavitated rows too (their values
/// are the identity and structural zeros), so the pattern depends on the grid only and its
/// symbolic LU is computed once per grid, not at every change of the active set and every new
/// solve: faer's default ordering (colamd) of each pattern cost 1.4× a numeric factorisation on
/// 65×129 (`BENCHMARKS.md` issue 16, `ehl2d-10`).
pub(super) struct NearPattern {
    /// CSC of `B` (row indices sorted in each column).
    pub(super) col_ptr: Vec<usize>,
    pub(super) row_idx: Vec<usize>,
    /// Per row `u`, `row_ptr[u]..row_ptr[u + 1]`: its columns (sorted) and their positions in
    /// the CSC arrays.
    pub(super) row_ptr: Vec<usize>,
    pub(super) row_col: Vec<usize>,
    pub(super) row_pos: Vec<usize>,
    /// Column ordering (position → column) and its inverse.
    pub(super) col_fwd: Vec<usize>,
    pub(super) col_inv: Vec<usize>,
    pub(super) symbolic: SymbolicSupernodalLu<usize>,
}

impl NearPattern {
    /// The pattern of rows `ent[row_ptr[u]..row_ptr[u + 1]]` (column `m`, the `H0` border, left
    /// out); `None` when the symbolic factorisation fails.
    pub(super) fn new(m: usize, row_ptr: &[usize], ent: &[(usize, f64)], col_fwd: Vec<usize>) -> Option<Self> {
        if col_fwd.len() != m {
            return None;
        }
        let mut rp = Vec::with_capacity(m + 1);
        let mut row_col: Vec<usize> = Vec::with_capacity(ent.len());
        rp.push(0);
        for u in 0..m {
            let start = row_col.len();
            row_col.extend(ent[row_ptr[u]..row_ptr[u + 1]].iter().map(|e| e.0).filter(|&col| col < m));
            row_col[start..].sort_unstable();
            let mut w = start;
            for r in start..row_col.len() {
                if r == start || row_col[r] != row_col[w - 1] {
                    row_col[w] = row_col[r];
                    w += 1;
                }
            }
            row_col.truncate(w);
            rp.push(row_col.len());
        }
        // Transpose to CSC: rows visited in order, so each column's row indices come sorted.
        let mut col_ptr = vec![0usize; m + 1];
        for &col in &row_col {
            col_ptr[col + 1] += 1;
        }
        for cc in 0..m {
            col_ptr[cc + 1] += col_ptr[cc];
        }
        let mut next = col_ptr.clone();
        let mut row_idx = vec![0usize; row_col.len()];
        let mut row_pos = vec![0usize; row_col.len()];
        for u in 0..m {
            for q in rp[u]..rp[u + 1] {
                let col = row_col[q];
                row_idx[next[col]] = u;
                row_pos[q] = next[col];
                next[col] += 1;
            }
        }
        let mut col_inv = vec![0usize; m];
        for (pos, &col) in col_fwd.iter().enumerate() {
            col_inv[col] = pos;
        }
        // faer's supernodal LU with partial pivoting, symbolic part with a given column ordering:
        // the column elimination tree (that of `BᵀB`), its postorder, the column counts of `BᵀB`
        // and the supernodal structure.
        let a = SymbolicSparseColMatRef::new_checked(m, m, &col_ptr, None, &row_idx);
        let values = vec![0.0; row_idx.len()];
        let at = SparseColMatRef::new(a, &values).transpose().to_col_major().ok()?;
        let perm = PermRef::new_checked(&col_fwd, &col_inv, m);
        let (mut etree, mut post, mut col_counts, mut min_col) = (vec![0usize; m], vec![0usize; m], vec![0usize; m], vec![0usize; m]);
        let et = qr::col_etree(a, Some(perm), &mut etree, MemStack::new(&mut MemBuffer::new(qr::col_etree_scratch::<usize>(m, m))));
        qr::postorder(&mut post, et, MemStack::new(&mut MemBuffer::new(qr::postorder_scratch::<usize>(m))));
        qr::column_counts_ata(&mut col_counts, &mut min_col, at.symbolic(), Some(perm), et, &post, MemStack::new(&mut MemBuffer::new(StackReq::new::<usize>(6 * m))));
        let symbolic = supernodal::factorize_supernodal_symbolic_lu::<usize>(a, Some(perm), &min_col, et, &col_counts, MemStack::new(&mut MemBuffer::new(supernodal::factorize_supernodal_symbolic_lu_scratch::<usize>(m, m))), SymbolicSupernodalParams::default()).ok()?;
        Some(NearPattern { col_ptr, row_idx, row_ptr: rp, row_col, row_pos, col_fwd, col_inv, symbolic })
    }

    /// Whether every entry of the rows is in the pattern (same size, each row's columns a subset).
    pub(super) fn covers(&self, m: usize, row_ptr: &[usize], ent: &[(usize, f64)]) -> bool {
        if self.row_ptr.len() != m + 1 {
            return false;
        }
        (0..m).all(|u| {
            let cols = &self.row_col[self.row_ptr[u]..self.row_ptr[u + 1]];
            ent[row_ptr[u]..row_ptr[u + 1]].iter().all(|&(col, _)| col == m || cols.binary_search(&col).is_ok())
        })
    }
}

/// Unknowns from which the near-field factorisation runs beside its caller ([`NearLu::new_watched`]):
/// ≈ 0.3 s at 257² (66k unknowns), a thread start is noise beside it.
pub(super) const WATCHED_LU_UNKNOWNS: usize = 60_000;

/// The numeric LU (faer's supernodal, partial pivoting) of a near-field matrix on its
/// [`NearPattern`].
/// The factor is single precision: half the bytes the triangular solves of every GMRES iteration
/// stream, and a faster factorisation; measured on the seed 000 finite cycle, 360 angles, 65×129
/// (`BENCHMARKS.md` issue 46): CPU −27 % (with the x transforms skipped in the deflection),
/// GMRES iterations −0.8 %, factorisations −0.7 %, films within 1.5e-7 of the double factor's.
pub(super) struct NearLu {
    pattern: std::sync::Arc<NearPattern>,
    lu: SupernodalLu<usize, f32>,
    row_fwd: Vec<usize>,
    row_inv: Vec<usize>,
}

impl NearLu {
    /// Factorise the matrix with `values` on `pattern`'s CSC; `None` when it is singular.
    pub(super) fn new(pattern: std::sync::Arc<NearPattern>, values: &[f64]) -> Option<Self> {
        let m = pattern.col_fwd.len();
        let (mut row_fwd, mut row_inv) = (vec![0usize; m], vec![0usize; m]);
        // Single precision (a preconditioner: the operator GMRES applies stays the double one).
        let v32: Vec<f32> = values.iter().map(|&v| v as f32).collect();
        let lu = factorise(&pattern, &v32, &mut row_fwd, &mut row_inv)?;
        Some(NearLu { pattern, lu, row_fwd, row_inv })
    }

    /// [`NearLu::new`], run beside the caller when the matrix is large ([`WATCHED_LU_UNKNOWNS`]
    /// or more unknowns: 3–3.5 s at 513², release): the caller polls `observer` every 50 ms and
    /// returns an interrupt at once, leaving the factorisation to finish (and be dropped) on its
    /// own thread, so a cancel, time limit or shutdown does not wait for it.
    pub(super) fn new_watched(pattern: std::sync::Arc<NearPattern>, values: Vec<f64>, observer: &dyn Observer) -> Result<Option<Self>, SolveError> {
        if pattern.col_fwd.len() < WATCHED_LU_UNKNOWNS {
            return Ok(NearLu::new(pattern, &values));
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let spawned = std::thread::Builder::new().name("ehl2d-lu".into()).spawn(move || {
            let _ = tx.send(NearLu::new(pattern, &values));
        });
        if spawned.is_err() {
            // No thread to be had (a process at its limit): no preconditioner this step.
            return Ok(None);
        }
        loop {
            match rx.recv_timeout(std::time::Duration::from_millis(50)) {
                Ok(lu) => return Ok(lu),
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => observer.check()?,
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => return Ok(None),
            }
        }
    }

    /// `x ← B⁻¹ x`.
    pub(super) fn solve_in_place(&self, x: &mut [f64]) {
        let m = self.row_fwd.len();
        let par = faer::get_global_parallelism();
        let rows = PermRef::new_checked(&self.row_fwd, &self.row_inv, m);
        let cols = PermRef::new_checked(&self.pattern.col_fwd, &self.pattern.col_inv, m);
        let mut y: Vec<f32> = x.iter().map(|&v| v as f32).collect();
        let mut mem = MemBuffer::new(supernodal::solve_in_place_scratch::<usize, f32>(m, 1, par));
        self.lu.solve_in_place_with_conj(rows, cols, faer::Conj::No, faer::MatMut::from_column_major_slice_mut(&mut y, m, 1), par, MemStack::new(&mut mem));
        for (xi, yi) in x.iter_mut().zip(&y) {
            *xi = *yi as f64;
        }
    }
}

/// faer's supernodal numeric LU of the matrix with `values` on `pattern` (`None`: singular).
fn factorise<T: faer::traits::ComplexField + Copy>(pattern: &NearPattern, values: &[T], row_fwd: &mut [usize], row_inv: &mut [usize]) -> Option<SupernodalLu<usize, T>> {
    let m = pattern.col_fwd.len();
    let a = SparseColMatRef::new(SymbolicSparseColMatRef::new_checked(m, m, &pattern.col_ptr, None, &pattern.row_idx), values);
    let at = a.transpose().to_col_major().ok()?;
    let mut lu = SupernodalLu::<usize, T>::new();
    let perm = PermRef::new_checked(&pattern.col_fwd, &pattern.col_inv, m);
    let mut mem = MemBuffer::new(supernodal::factorize_supernodal_numeric_lu_scratch::<usize, T>(&pattern.symbolic, Default::default()));
    supernodal::factorize_supernodal_numeric_lu(row_fwd, row_inv, &mut lu, a, at.as_ref(), perm, &pattern.symbolic, faer::get_global_parallelism(), MemStack::new(&mut mem), Default::default()).ok()?;
    Some(lu)
}

/// A nested-dissection ordering of the `mx × my` interior grid (unknown `j·mx + i`): the
/// rectangle is cut by a separator `wx` columns wide (a cut across x) or `wy` rows wide, whichever
/// is smaller, the halves ordered first (recursively), the separator last; blocks of at most 32
/// unknowns in natural order. The widths are the reach of the column-intersection graph of the
/// near-field matrix (`BᵀB`, whose Cholesky structure bounds the LU with partial pivoting):
/// a row's columns span `i − 2 − r … i + r` and `j − r … j + r` (upwind wedge and near field `r`),
/// so `wx = 2 + 2r`, `wy = 2r`. George, SIAM J. Numer. Anal. 10 (1973) for the method; against
/// colamd on the seed 000 roller's 63×127 unknowns (full pattern): numeric factorisation
/// 139 against 157 M instructions, triangular solve 6.25 against 6.5 M (`ehl2d-10`).
pub(super) fn nested_dissection(mx: usize, my: usize, wx: usize, wy: usize) -> Vec<usize> {
    const LEAF: usize = 32;
    #[allow(clippy::too_many_arguments)]
    fn part(x0: usize, x1: usize, y0: usize, y1: usize, mx: usize, wx: usize, wy: usize, out: &mut Vec<usize>) {
        let (lx, ly) = (x1 - x0, y1 - y0);
        let (cut_x, cut_y) = (lx > 2 * wx + 2, ly > 2 * wy + 2);
        if lx * ly <= LEAF || !(cut_x || cut_y) {
            for j in y0..y1 {
                out.extend((x0..x1).map(|i| j * mx + i));
            }
            return;
        }
        if cut_x && (!cut_y || wx * ly <= wy * lx) {
            let c = x0 + (lx - wx) / 2;
            part(x0, c, y0, y1, mx, wx, wy, out);
            part(c + wx, x1, y0, y1, mx, wx, wy, out);
            for j in y0..y1 {
                out.extend((c..c + wx).map(|i| j * mx + i));
            }
        } else {
            let c = y0 + (ly - wy) / 2;
            part(x0, x1, y0, c, mx, wx, wy, out);
            part(x0, x1, c + wy, y1, mx, wx, wy, out);
            for j in c..c + wy {
                out.extend((x0..x1).map(|i| j * mx + i));
            }
        }
    }
    let mut out = Vec::with_capacity(mx * my);
    part(0, mx, 0, my, mx, wx, wy.max(1), &mut out);
    out
}
