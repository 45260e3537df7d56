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

/// A tabulated pressure along the surface, piecewise linear between `d` (m, increasing, offset
/// from the contact centre along the surface) and zero outside `[d_0, d_last]`, with the
/// antiderivatives `P1`, `P2` at the nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedBand {
    d: Vec<f64>,
    p: Vec<f64>,
    p1: Vec<f64>,
    p2: Vec<f64>,
}

impl TabulatedBand {
    /// The band of pressures `p` (Pa, ≥ 0) at the increasing offsets `d` (m). `None` when fewer
    /// than two nodes, offsets not increasing, or a value is not finite.
    pub fn new(d: Vec<f64>, p: Vec<f64>) -> Option<Self> {
        let n = d.len();
        if n < 2 || p.len() != n || !d.windows(2).all(|w| w[1] > w[0]) || !d.iter().chain(&p).all(|x| x.is_finite()) {
            return None;
        }
        let (mut p1, mut p2) = (vec![0.0; n], vec![0.0; n]);
        for j in 1..n {
            let h = d[j] - d[j - 1];
            // Exact integrals of the linear segment: ∫p = h(p_a + p_b)/2, ∫P1 = h P1_a + h²(2p_a + p_b)/6.
            p1[j] = p1[j - 1] + 0.5 * h * (p[j - 1] + p[j]);
            p2[j] = p2[j - 1] + h * p1[j - 1] + h * h * (2.0 * p[j - 1] + p[j]) / 6.0;
        }
        Some(TabulatedBand { d, p, p1, p2 })
    }

    /// `∫ p dd` over the band, Pa·m (N/m).
    pub fn integral(&self) -> f64 {
        self.p1[self.p1.len() - 1]
    }

    /// The band with every pressure multiplied by `factor`.
    pub fn scaled(mut self, factor: f64) -> Self {
        for v in self.p.iter_mut().chain(self.p1.iter_mut()).chain(self.p2.iter_mut()) {
            *v *= factor;
        }
        self
    }

    /// Offsets of the first and last node, m.
    pub fn extent(&self) -> (f64, f64) {
        (self.d[0], self.d[self.d.len() - 1])
    }

    /// Largest pressure, Pa.
    pub fn max_pressure(&self) -> f64 {
        self.p.iter().copied().fold(0.0, f64::max)
    }

    /// Segment holding `x` (`d_j ≤ x < d_{j+1}`) and the offset into it.
    fn locate(&self, x: f64) -> (usize, f64) {
        let j = self.d.partition_point(|&v| v <= x).saturating_sub(1).min(self.d.len() - 2);
        (j, x - self.d[j])
    }

    /// `P1(x) = ∫_{−∞}^x p`.
    pub fn p1_at(&self, x: f64) -> f64 {
        let n = self.d.len();
        if x <= self.d[0] {
            return 0.0;
        }
        if x >= self.d[n - 1] {
            return self.p1[n - 1];
        }
        let (j, t) = self.locate(x);
        let s = (self.p[j + 1] - self.p[j]) / (self.d[j + 1] - self.d[j]);
        self.p1[j] + t * (self.p[j] + 0.5 * s * t)
    }

    /// `P2(x) = ∫_{−∞}^x P1`.
    pub fn p2_at(&self, x: f64) -> f64 {
        let n = self.d.len();
        if x <= self.d[0] {
            return 0.0;
        }
        if x >= self.d[n - 1] {
            return self.p2[n - 1] + self.p1[n - 1] * (x - self.d[n - 1]);
        }
        let (j, t) = self.locate(x);
        let s = (self.p[j + 1] - self.p[j]) / (self.d[j + 1] - self.d[j]);
        self.p2[j] + t * (self.p1[j] + t * (0.5 * self.p[j] + s * t / 6.0))
    }
}

/// The pressure of one contact pass along the surface (offset `σ − c` from the contact centre).
#[derive(Debug, Clone, PartialEq)]
pub enum Band {
    /// Hertz semi-ellipse of peak `p0` (Pa) and half-width `b` (m).
    Hertz { p0: f64, b: f64 },
    /// Tabulated pressure (numerical EHL or asperity pressure).
    Tabulated(TabulatedBand),
}

impl Band {
    /// Nothing to deposit.
    fn is_empty(&self) -> bool {
        match self {
            Band::Hertz { p0, b } => !(*b > 0.0) || *p0 == 0.0,
            Band::Tabulated(t) => !(t.integral() > 0.0),
        }
    }

    /// Offsets bounding the band, m: `(−b, b)` for Hertz.
    pub fn extent(&self) -> (f64, f64) {
        match self {
            Band::Hertz { b, .. } => (-*b, *b),
            Band::Tabulated(t) => t.extent(),
        }
    }

    /// `∫_{a1}^{a2} ∫_{c1}^{c2} p(σ − c) dc dσ`.
    pub fn double(&self, a1: f64, a2: f64, c1: f64, c2: f64) -> f64 {
        match self {
            Band::Hertz { p0, b } => double_integral(a1, a2, c1, c2, *p0, *b),
            Band::Tabulated(t) => t.p2_at(a2 - c1) - t.p2_at(a1 - c1) - t.p2_at(a2 - c2) + t.p2_at(a1 - c2),
        }
    }

    /// `∫_{a1}^{a2} p(σ − c) dσ`.
    pub fn single(&self, a1: f64, a2: f64, c: f64) -> f64 {
        match self {
            Band::Hertz { p0, b } => single_integral(a1, a2, c, *p0, *b),
            Band::Tabulated(t) => t.p1_at(a2 - c) - t.p1_at(a1 - c),
        }
    }
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
    /// for a contact pass of pressure `band` sweeping cell `k`. `strength` is `k v_s Δt` (m³/N);
    /// the result is a volume per unit width, m².
    pub fn deposit(&self, k: usize, band: &Band, strength: f64, volume: &mut [f64]) {
        let n = self.len();
        let p = self.perimeter();
        let (c1, c2) = (self.edges[k], self.edges[k + 1]);
        let dc = c2 - c1;
        if !(dc > 0.0) || strength == 0.0 || band.is_empty() {
            return;
        }
        let (lo, hi) = band.extent();
        let scale = strength / dc;
        // Rightwards from k (including k), then leftwards, never visiting a cell twice.
        let mut visited = 0;
        for m in 0..n {
            let j = (k + m) % n;
            let off = if k + m >= n { p } else { 0.0 };
            let (a1, a2) = (self.edges[j] + off, self.edges[j + 1] + off);
            if a1 >= c2 + hi {
                break;
            }
            volume[j] += scale * band.double(a1, a2, c1, c2);
            visited += 1;
        }
        for m in 1..n.saturating_sub(visited - 1) {
            let j = (k + n - m) % n;
            let off = if m > k { -p } else { 0.0 };
            let (a1, a2) = (self.edges[j] + off, self.edges[j + 1] + off);
            if a2 <= c1 + lo {
                break;
            }
            volume[j] += scale * band.double(a1, a2, c1, c2);
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

    /// Add to `volume[j]` the share of bin `j` of a pass of pressure `band` whose contact centre
    /// sweeps `[c1, c2]` (either order) with strength `k v_s Δt`. Material beyond the bins is
    /// not recorded.
    pub fn deposit(&self, c1: f64, c2: f64, band: &Band, strength: f64, volume: &mut [f64]) {
        if strength == 0.0 || band.is_empty() {
            return;
        }
        let (lo, hi) = band.extent();
        let (c1, c2) = if c1 <= c2 { (c1, c2) } else { (c2, c1) };
        let h = self.width();
        let first = (((c1 + lo - self.lo) / h).floor().max(0.0) as usize).min(self.n);
        let last = (((c2 + hi - self.lo) / h).ceil().max(0.0) as usize).min(self.n);
        let dc = c2 - c1;
        let stationary = dc < 1e-4 * (0.5 * (hi - lo));
        let mid = 0.5 * (c1 + c2);
        for (j, v) in volume.iter_mut().enumerate().take(last).skip(first) {
            let (a1, a2) = (self.lo + j as f64 * h, self.lo + (j + 1) as f64 * h);
            *v += if stationary { strength * band.single(a1, a2, mid) } else { strength / dc * band.double(a1, a2, c1, c2) };
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
                cells.deposit(k, &Band::Hertz { p0, b }, 2.0, &mut v);
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
            cells.deposit(k, &Band::Hertz { p0: 1e9, b: 3e-4 }, 1.0, &mut v);
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
            bins.deposit(c1, c2, &Band::Hertz { p0: 1e9, b: 2e-4 }, 1.0, &mut v);
            let total: f64 = v.iter().sum();
            let expect = PI * 1e9 * 2e-4 / 2.0;
            assert!((total / expect - 1.0).abs() < 1e-9, "{c1}..{c2}: {total}");
        }
    }

    fn tabulated_hertz(p0: f64, b: f64, n: usize) -> TabulatedBand {
        let d: Vec<f64> = (0..n).map(|i| -b + 2.0 * b * i as f64 / (n - 1) as f64).collect();
        let p: Vec<f64> = d.iter().map(|x| p0 * (1.0 - (x / b).powi(2)).max(0.0).sqrt()).collect();
        TabulatedBand::new(d, p).unwrap()
    }

    #[test]
    fn tabulated_antiderivatives_are_exact_for_a_linear_band() {
        // p = 2 + 3d on [0, 1] (nodes unevenly spaced): P1(x) = 2x + 1.5x², P2(x) = x² + x³/2.
        let d = vec![0.0, 0.1, 0.45, 0.5, 1.0];
        let t = TabulatedBand::new(d.clone(), d.iter().map(|x| 2.0 + 3.0 * x).collect()).unwrap();
        for x in [-0.5f64, 0.0, 0.05, 0.3, 0.47, 0.99, 1.0, 1.7] {
            let c = x.clamp(0.0, 1.0);
            let p1 = 2.0 * c + 1.5 * c * c;
            let p2 = c * c + c * c * c / 2.0 + if x > 1.0 { 3.5 * (x - 1.0) } else { 0.0 };
            assert!((t.p1_at(x) - p1).abs() < 1e-14 && (t.p2_at(x) - p2).abs() < 1e-14, "{x}");
        }
        assert!((t.integral() - 3.5).abs() < 1e-14);
        assert!(TabulatedBand::new(vec![0.0, 0.0], vec![1.0, 1.0]).is_none());
    }

    #[test]
    fn tabulated_passes_conserve_volume_and_approach_the_hertz_deposit() {
        let widths: Vec<f64> = (0..60).map(|i| 1e-4 * (1.0 + 0.4 * (i as f64 * 0.9).cos())).collect();
        let cells = PeriodicCells::new(&widths);
        let (p0, b) = (1e9, 2.5e-4);
        let hertz = Band::Hertz { p0, b };
        let tab = Band::Tabulated(tabulated_hertz(p0, b, 2001));
        for k in [0, 13, 59] {
            let (mut vh, mut vt) = (vec![0.0; 60], vec![0.0; 60]);
            cells.deposit(k, &hertz, 1.0, &mut vh);
            cells.deposit(k, &tab, 1.0, &mut vt);
            let Band::Tabulated(t) = &tab else { unreachable!() };
            let total: f64 = vt.iter().sum();
            assert!((total / t.integral() - 1.0).abs() < 1e-9, "{total}");
            let scale = vh.iter().copied().fold(0.0, f64::max);
            let diff = vh.iter().zip(&vt).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(diff < 1e-4 * scale, "k = {k}: {diff} vs {scale}");
        }
        // An asymmetric band lands where it is: all of it right of the centre.
        let right = Band::Tabulated(TabulatedBand::new(vec![2e-4, 3e-4, 4e-4], vec![0.0, 1e9, 0.0]).unwrap());
        let bins = Bins { lo: -1e-3, hi: 1e-3, n: 20 };
        let mut v = vec![0.0; 20];
        bins.deposit(0.0, 0.0, &right, 1.0, &mut v);
        assert!(v[..12].iter().all(|x| *x == 0.0) && (v[12] + v[13] - 1e5).abs() < 1e-6 * 1e5, "{v:?}");
    }
}
