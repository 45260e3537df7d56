//! Where the wear of one contact pass lands: a Hertzian pressure band moving across a surface.
//!
//! Archard's law in local form, `dh/dt = k p v_s`, integrated over the time a surface point spends
//! in the contact, gives the depth a pass removes at that point. During one step of the cam
//! cycle (one cam angle, duration `Δt`) the contact centre sweeps a stretch `[c1, c2]` of the
//! surface (length `Δc = u Δt`, `u` the speed of the contact relative to that surface) while the
//! pressure along the rolling direction through the contact centre is the Hertz semi-ellipse
//! `p(x) = p0 √(1 − x²/b²)` (line contacts: `b` the half-width; point contacts: the semi-axis along
//! the rolling direction, the wear track's centre line). The volume per unit width the step
//! removes from a surface cell `[a1, a2]` is
//!
//! `V = k v_s Δt · (1/Δc) ∫_{a1}^{a2} ∫_{c1}^{c2} p(σ − c) dc dσ`,
//!
//! and the double integral has a closed form, `p0 b² [G2((a2−c1)/b) − G2((a1−c1)/b) −
//! G2((a2−c2)/b) + G2((a1−c2)/b)]`, with `G1(x) = ∫_{−1}^x √(1−t²) dt` and
//! `G2(x) = ∫_{−1}^x G1` (below). Summed over all cells it is `Δc ∫p dx` exactly, so the volume is
//! conserved whatever the ratio of contact width to cell size: coarse cells receive the whole
//! pass (the plain `k (v_s/u) ∫p dx` per pass), fine cells resolve the smearing of the wear over
//! the contact width. When the contact barely moves on a surface (`Δc ≪ b`: a flat follower face
//! where the contact turns round) the stationary limit `Δt ∫_{a1}^{a2} p(σ − c) dσ` is used.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// `G1(x) = ∫_{−1}^{x} √(1 − t²) dt` (0 below −1, π/2 above 1).
pub fn g1(x: f64) -> f64 {
    if x <= -1.0 {
        0.0
    } else if x >= 1.0 {
        FRAC_PI_2
    } else {
        0.5 * (x * (1.0 - x * x).sqrt() + x.asin()) + FRAC_PI_4
    }
}

/// `G2(x) = ∫_{−1}^{x} G1(t) dt` (0 below −1, `πx/2` above 1).
pub fn g2(x: f64) -> f64 {
    if x <= -1.0 {
        0.0
    } else if x >= 1.0 {
        FRAC_PI_2 * x
    } else {
        let r = (1.0 - x * x).sqrt();
        -(r * r * r) / 6.0 + 0.5 * (x * x.asin() + r) + FRAC_PI_4 * x
    }
}

/// `∫_{a1}^{a2} ∫_{c1}^{c2} p0 √(1 − (σ − c)²/b²) dc dσ`.
pub fn double_integral(a1: f64, a2: f64, c1: f64, c2: f64, p0: f64, b: f64) -> f64 {
    let s = |x: f64| g2(x / b);
    p0 * b * b * (s(a2 - c1) - s(a1 - c1) - s(a2 - c2) + s(a1 - c2))
}

/// `∫_{a1}^{a2} p0 √(1 − (σ − c)²/b²) dσ`.
pub fn single_integral(a1: f64, a2: f64, c: f64, p0: f64, b: f64) -> f64 {
    p0 * b * (g1((a2 - c) / b) - g1((a1 - c) / b))
}

/// A closed surface (the cam) cut into `n` cells; cell `k` is the stretch the contact centre
/// sweeps during cam step `k`. `edges` has `n + 1` entries from 0 to the perimeter.
#[derive(Debug, Clone)]
pub struct PeriodicCells {
    pub edges: Vec<f64>,
}

impl PeriodicCells {
    /// Cells of the given widths laid end to end.
    pub fn new(widths: &[f64]) -> Self {
        let mut edges = Vec::with_capacity(widths.len() + 1);
        let mut x = 0.0;
        edges.push(x);
        for w in widths {
            x += w;
            edges.push(x);
        }
        PeriodicCells { edges }
    }

    pub fn len(&self) -> usize {
        self.edges.len() - 1
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn perimeter(&self) -> f64 {
        self.edges[self.len()]
    }

    pub fn width(&self, j: usize) -> f64 {
        self.edges[j + 1] - self.edges[j]
    }

    /// Add to `volume[j]` (per unit width) the share of cell `j` of `strength · (1/Δc_k) ∫∫ p`
    /// for a contact of peak pressure `p0` and half-width `b` sweeping cell `k`. `strength` is
    /// `k v_s Δt` (m³/N); the result is a volume per unit width, m².
    pub fn deposit(&self, k: usize, p0: f64, b: f64, strength: f64, volume: &mut [f64]) {
        let n = self.len();
        let p = self.perimeter();
        let (c1, c2) = (self.edges[k], self.edges[k + 1]);
        let dc = c2 - c1;
        if !(dc > 0.0) || !(b > 0.0) || strength == 0.0 || p0 == 0.0 {
            return;
        }
        let scale = strength / dc;
        // Rightwards from k (including k), then leftwards, never visiting a cell twice.
        let mut visited = 0;
        for m in 0..n {
            let j = (k + m) % n;
            let off = if k + m >= n { p } else { 0.0 };
            let (a1, a2) = (self.edges[j] + off, self.edges[j + 1] + off);
            if a1 >= c2 + b {
                break;
            }
            volume[j] += scale * double_integral(a1, a2, c1, c2, p0, b);
            visited += 1;
        }
        for m in 1..n.saturating_sub(visited - 1) {
            let j = (k + n - m) % n;
            let off = if m > k { -p } else { 0.0 };
            let (a1, a2) = (self.edges[j] + off, self.edges[j + 1] + off);
            if a2 <= c1 - b {
                break;
            }
            volume[j] += scale * double_integral(a1, a2, c1, c2, p0, b);
        }
    }
}

/// An open surface (a flat follower face) cut into `n` equal bins from `lo` to `hi`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bins {
    pub lo: f64,
    pub hi: f64,
    pub n: usize,
}

impl Bins {
    pub fn width(&self) -> f64 {
        (self.hi - self.lo) / self.n as f64
    }

    pub fn centre(&self, j: usize) -> f64 {
        self.lo + (j as f64 + 0.5) * self.width()
    }

    /// Add to `volume[j]` the share of bin `j` of a pass whose contact centre sweeps `[c1, c2]`
    /// (either order) with strength `k v_s Δt`. Material beyond the bins is not recorded.
    pub fn deposit(&self, c1: f64, c2: f64, p0: f64, b: f64, strength: f64, volume: &mut [f64]) {
        if !(b > 0.0) || strength == 0.0 || p0 == 0.0 {
            return;
        }
        let (c1, c2) = if c1 <= c2 { (c1, c2) } else { (c2, c1) };
        let h = self.width();
        let first = (((c1 - b - self.lo) / h).floor().max(0.0) as usize).min(self.n);
        let last = (((c2 + b - self.lo) / h).ceil().max(0.0) as usize).min(self.n);
        let dc = c2 - c1;
        let stationary = dc < 1e-4 * b;
        let mid = 0.5 * (c1 + c2);
        for (j, v) in volume.iter_mut().enumerate().take(last).skip(first) {
            let (a1, a2) = (self.lo + j as f64 * h, self.lo + (j + 1) as f64 * h);
            *v += if stationary {
                strength * single_integral(a1, a2, mid, p0, b)
            } else {
                strength / dc * double_integral(a1, a2, c1, c2, p0, b)
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn antiderivatives_match_quadrature() {
        // G1' = √(1 − x²), G2' = G1, continuous at ±1.
        for x in [-0.99, -0.5, 0.0, 0.3, 0.9] {
            let h = 1e-6;
            assert!(((g1(x + h) - g1(x - h)) / (2.0 * h) - (1.0 - x * x).sqrt()).abs() < 1e-8);
            assert!(((g2(x + h) - g2(x - h)) / (2.0 * h) - g1(x)).abs() < 1e-8);
        }
        assert!(g2(-1.0).abs() < 1e-15 && (g2(1.0 - 1e-12) - FRAC_PI_2).abs() < 1e-9);
        assert!((g1(1.0 - 1e-14) - FRAC_PI_2).abs() < 1e-6);
    }

    #[test]
    fn periodic_deposit_conserves_the_pass_whatever_the_cell_size() {
        // Non-uniform cells; contacts from much narrower to much wider than a cell.
        let widths: Vec<f64> = (0..50).map(|i| 1e-4 * (1.0 + 0.5 * (i as f64 * 0.7).sin())).collect();
        let cells = PeriodicCells::new(&widths);
        for b in [1e-6, 3e-5, 2e-4, 1e-3] {
            for k in [0, 7, 49] {
                let mut v = vec![0.0; 50];
                let p0 = 1e9;
                cells.deposit(k, p0, b, 2.0, &mut v);
                let total: f64 = v.iter().sum();
                // strength × ∫p dx = 2 × π p0 b/2.
                let expect = 2.0 * PI * p0 * b / 2.0;
                assert!((total / expect - 1.0).abs() < 1e-9, "b = {b}, k = {k}: {total} vs {expect}");
                assert!(v.iter().all(|x| *x >= -1e-9 * expect));
            }
        }
    }

    #[test]
    fn uniform_cells_and_uniform_sources_give_uniform_depth() {
        let cells = PeriodicCells::new(&[1e-4; 40]);
        let mut v = vec![0.0; 40];
        for k in 0..40 {
            cells.deposit(k, 1e9, 3e-4, 1.0, &mut v);
        }
        let expect = PI * 1e9 * 3e-4 / 2.0;
        for x in v {
            assert!((x / expect - 1.0).abs() < 1e-10);
        }
    }

    #[test]
    fn bins_conserve_moving_and_stationary_passes() {
        let bins = Bins { lo: -0.01, hi: 0.01, n: 200 };
        for (c1, c2) in [(0.0, 0.0), (0.001, 0.0012), (0.002, 0.0), (-0.003, -0.003 + 1e-12)] {
            let mut v = vec![0.0; 200];
            bins.deposit(c1, c2, 1e9, 2e-4, 1.0, &mut v);
            let total: f64 = v.iter().sum();
            let expect = PI * 1e9 * 2e-4 / 2.0;
            assert!((total / expect - 1.0).abs() < 1e-9, "{c1}..{c2}: {total}");
        }
    }
}
