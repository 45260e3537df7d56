//! The computational grid of the line-contact problem, in the Hertzian coordinate `X = x/b`, and
//! its elastic influence matrix.
//!
//! In `X` the deflection kernel does not depend on the load, the radius or the modulus
//! ([`super::elastic`]): a grid fixed in `X` has one influence matrix for a whole cam cycle. A
//! [`Layout`] (domain and grading) and a node count define a [`Grid`]; [`GridCache`] keeps the
//! few grids a sequence of solves uses, so the `O(n²)` logarithms of the kernel and the grading
//! are computed once per layout rather than once per solve.

use super::elastic::Kernel;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

const PI: f64 = std::f64::consts::PI;

/// Domain and grading of a grid (dimensionless, `X = x/b`), independent of the node count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Upstream end (for `dir = +1`, the inlet), `X`.
    pub x_in: f64,
    /// Downstream end, `X`.
    pub x_out: f64,
    /// Film estimate `H = hR/b²` the grading is designed for (bump widths `3 H^(2/3)`).
    pub h_design: f64,
    /// Entrainment direction, `+1` or `−1`: which side of the contact is the inlet.
    pub dir: f64,
    /// Graded (`true`) or uniform.
    pub grading: bool,
}

impl Layout {
    /// The layout for a film estimate `h_est` (`H = hR/b²`) and entrainment direction `dir`:
    /// inlet `max(4.5, 16 sqrt(2H))` and outlet `max(1.5, 1.5 sqrt(2H))` half-widths unless
    /// given (far enough for a fully flooded inlet and for the cavitation boundary).
    pub fn for_film(h_est: f64, dir: f64, inlet: Option<f64>, outlet: Option<f64>, grading: bool) -> Self {
        let up = inlet.unwrap_or_else(|| 4.5_f64.max(16.0 * (2.0 * h_est).sqrt()));
        let down = outlet.unwrap_or_else(|| 1.5_f64.max(1.5 * (2.0 * h_est).sqrt()));
        let (x_in, x_out) = if dir >= 0.0 { (-up, down) } else { (-down, up) };
        Layout { x_in, x_out, h_design: h_est, dir: if dir >= 0.0 { 1.0 } else { -1.0 }, grading }
    }
}

/// Nodes, cell widths and influence matrix of one grid.
#[derive(Debug)]
pub struct Grid {
    /// Unique identity (a factorisation is valid only on the grid it was computed on).
    pub id: u64,
    pub layout: Layout,
    pub n: usize,
    /// Node positions `X`, increasing.
    pub x: Vec<f64>,
    /// Cell widths (midpoint to midpoint, half cells at the ends): the load quadrature weights
    /// and the cells of the elastic kernel.
    pub cell: Vec<f64>,
    pub kernel: Kernel,
}

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

impl Grid {
    pub fn new(n: usize, layout: Layout) -> Self {
        let x = graded_grid(n, layout.x_in, layout.x_out, layout.h_design, layout.dir, layout.grading);
        Grid {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            layout,
            n,
            kernel: Kernel::new(&x),
            cell: cells(&x),
            x,
        }
    }
}

/// The most recently used grids (at most [`GridCache::CAPACITY`]), keyed by node count and layout.
#[derive(Debug, Default)]
pub struct GridCache {
    grids: Vec<Arc<Grid>>,
}

impl GridCache {
    /// Grids kept. A cycle alternates between a few layouts (two entrainment directions and a
    /// few film classes); a cold start adds its coarse levels.
    pub const CAPACITY: usize = 6;

    /// The grid of `n` nodes and `layout`, built on a miss.
    pub fn get(&mut self, n: usize, layout: Layout) -> Arc<Grid> {
        if let Some(k) = self.grids.iter().position(|g| g.n == n && g.layout == layout) {
            let g = self.grids.remove(k);
            self.grids.push(g.clone());
            return g;
        }
        let g = Arc::new(Grid::new(n, layout));
        if self.grids.len() == Self::CAPACITY {
            self.grids.remove(0);
        }
        self.grids.push(g.clone());
        g
    }
}

/// Cell widths of a grid: from midpoint to midpoint, half cells at the two ends.
pub fn cells(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    (0..n)
        .map(|j| {
            let a = if j == 0 { x[0] } else { 0.5 * (x[j - 1] + x[j]) };
            let b = if j + 1 == n { x[n - 1] } else { 0.5 * (x[j] + x[j + 1]) };
            b - a
        })
        .collect()
}

/// The nodes on `[x_in, x_out]`: uniform, or graded towards the inlet edge of the Hertzian zone
/// (`X = −1 − w/4` upstream, where the film is formed) and the exit constriction (`X = 1 − w/3`
/// downstream, the pressure spike), with bump widths `w = 3 H^(2/3)` from the film estimate `H` (the
/// scale of the inlet zone where the Hertzian gap equals the film). The node density is a smooth
/// sum: a quarter of the nodes uniform, a quarter on the Hertzian zone and a quarter in each
/// Gaussian bump; the nodes are placed by inverting its cumulative integral. The same density at
/// `n` and `2n − 1` nodes gives (to the accuracy of the tabulated integral) nested grids, which
/// Richardson extrapolation needs.
pub fn graded_grid(n: usize, x_in: f64, x_out: f64, h_est: f64, dir: f64, grading: bool) -> Vec<f64> {
    let uniform = || (0..n).map(|i| x_in + (x_out - x_in) * i as f64 / (n - 1) as f64).collect();
    if !grading || !(h_est.is_finite() && h_est > 0.0) || h_est > 0.3 {
        return uniform();
    }
    let w = (3.0 * h_est.powf(2.0 / 3.0)).clamp(0.01, 0.5);
    let (c_in, c_out) = (-dir * (1.0 + 0.25 * w), dir * (1.0 - w / 3.0));
    let len = x_out - x_in;
    let sq_pi = PI.sqrt();
    let density = |x: f64| {
        let zone = 0.5 * (((x + 1.05) / 0.05).tanh() - ((x - 1.05) / 0.05).tanh()) / 2.1;
        let g = |c: f64| (-((x - c) / w).powi(2)).exp() / (w * sq_pi);
        0.25 / len + 0.25 * zone + 0.25 * g(c_in) + 0.25 * g(c_out)
    };
    // A table independent of n (up to 774 nodes), so that grids of different n share one mapping.
    let fine = (8 * n + 2000).max(8192);
    let hstep = len / fine as f64;
    let mut cum = vec![0.0; fine + 1];
    let mut prev = density(x_in);
    for k in 1..=fine {
        let d = density(x_in + k as f64 * hstep);
        cum[k] = cum[k - 1] + 0.5 * (prev + d) * hstep;
        prev = d;
    }
    let total = cum[fine];
    let mut x = Vec::with_capacity(n);
    let mut k = 0;
    for i in 0..n {
        let target = total * i as f64 / (n - 1) as f64;
        while k + 1 < fine && cum[k + 1] < target {
            k += 1;
        }
        let t = ((target - cum[k]) / (cum[k + 1] - cum[k]).max(1e-300)).clamp(0.0, 1.0);
        x.push(x_in + (k as f64 + t) * hstep);
    }
    x[0] = x_in;
    x[n - 1] = x_out;
    x
}
