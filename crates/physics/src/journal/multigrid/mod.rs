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

mod transfer;
mod level;
mod smoothing;
mod hierarchy;
#[cfg(test)]
use transfer::{prolong_theta, restrict};

use level::*;


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

/// Two ascending column ranges of one row (see `Level::free_span`).
type Span = [(usize, usize); 2];

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
