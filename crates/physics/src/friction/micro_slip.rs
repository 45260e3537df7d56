//! Seed 001's micro-slip map along the contact (eq. 19, 22–23, 25): the asperity friction of each
//! point of the contact from its own film `h(x)` and tangential displacement `δx(x)`.
//!
//! * [`MicroSlipMap`]: the gross-sliding displacement `δx_gs(h)` and the local shape exponent
//!   `n(h)` per film, as a `rough_contact` job with `friction_limit` reports them (seed 001's
//!   precalculated map `μ_a = f(h, δx)`, eq. 19, in the form `μ_a/μ_lim = 1 − (1 − δx/δx_gs)^n`
//!   below `δx_gs` and `μ_lim` beyond it).
//! * [`AsperityNode`]: one node of a solved asperity pressure `p_a(x)` (the numerical mixed film):
//!   its load `A p_a`, its travel `x − x_in` since the upstream edge of the asperity contact, and
//!   `δx_gs`, `n` at its film. The asperity traction is then `Σ μ_lim A p_a g(δx/δx_gs; n)` with
//!   `δx = |SRR| (x − x_in)` (eq. 22) — [`nodal_traction`].
//!
//! The upstream edge `x_in` (eq. 22's `x_inlet`, "the starting point of the p̄_a(x) curve") is
//! the first node, going downstream, whose asperity pressure reaches [`INLET_EDGE_SHARE`] of the
//! largest: the Greenwood–Tripp and tabulated laws are positive at every film, so the curve has no
//! sharp start. Nodes upstream of it have not been displaced (`δx = 0`: no traction); their load
//! is counted in `W_a` but not in the capacity that can slide ([`nodal_capacity`]). For a
//! semi-elliptic pressure on `[−a, a]` the edge is `−a` (seed 001's `x_inlet = −a`).

/// Share of the largest asperity pressure at which the asperity contact starts (see the module
/// docs): 1e-3.
pub const INLET_EDGE_SHARE: f64 = 1e-3;

/// Most rows of a [`MicroSlipMap`].
pub const MAX_MAP_ROWS: usize = 1000;

/// `δx_gs(h)` and `n(h)` (see the module docs). Between rows `ln δx_gs` and `n` are linear in
/// `h`; outside the rows the end values hold.
#[derive(Debug, Clone, PartialEq)]
pub struct MicroSlipMap {
    film: Vec<f64>,
    gross_sliding_displacement: Vec<f64>,
    exponent: Vec<f64>,
}

impl MicroSlipMap {
    /// `film` strictly ascending and positive (m), `gross_sliding_displacement` in [1e-12, 1e-3] m,
    /// `exponent` in [2, 8] (below 2 the local law's curvature is unbounded at `δx = δx_gs`), the
    /// same length, 1 to [`MAX_MAP_ROWS`] rows. `Err` names the column and the rule.
    pub fn new(film: Vec<f64>, gross_sliding_displacement: Vec<f64>, exponent: Vec<f64>) -> Result<Self, (&'static str, String)> {
        let n = film.len();
        if !(1..=MAX_MAP_ROWS).contains(&n) {
            return Err(("film", format!("needs 1 to {MAX_MAP_ROWS} rows")));
        }
        if gross_sliding_displacement.len() != n {
            return Err(("gross_sliding_displacement", "needs one value per film".into()));
        }
        if exponent.len() != n {
            return Err(("exponent", "needs one value per film".into()));
        }
        if !film.iter().all(|h| h.is_finite() && *h > 0.0) || !film.windows(2).all(|w| w[1] > w[0]) {
            return Err(("film", "must be positive and strictly ascending".into()));
        }
        if !gross_sliding_displacement.iter().all(|d| (1e-12..=1e-3).contains(d)) {
            return Err(("gross_sliding_displacement", "must be in [1e-12, 1e-3] m".into()));
        }
        if !exponent.iter().all(|e| (2.0..=8.0).contains(e)) {
            return Err(("exponent", "must be in [2, 8] (2 is Carter's shape)".into()));
        }
        Ok(MicroSlipMap { film, gross_sliding_displacement, exponent })
    }

    /// `(δx_gs, n)` at film `h`, m.
    pub fn at(&self, h: f64) -> (f64, f64) {
        let (f, d, e) = (&self.film, &self.gross_sliding_displacement, &self.exponent);
        let last = f.len() - 1;
        if !(h > f[0]) {
            return (d[0], e[0]);
        }
        if h >= f[last] {
            return (d[last], e[last]);
        }
        let i = f.partition_point(|&v| v <= h) - 1;
        let w = (h - f[i]) / (f[i + 1] - f[i]);
        (((1.0 - w) * d[i].ln() + w * d[i + 1].ln()).exp(), (1.0 - w) * e[i] + w * e[i + 1])
    }
}

/// One node of a solved asperity pressure (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AsperityNode {
    /// Asperity load of the node `A p_a`, N.
    pub load: f64,
    /// Distance from the upstream edge of the asperity contact along the entrainment, m (≥ 0).
    pub travel: f64,
    /// Film at the node, m.
    pub film: f64,
    /// Gross-sliding displacement at the node's film, m.
    pub gross_sliding_displacement: f64,
    /// Local shape exponent at the node's film.
    pub exponent: f64,
}

/// Asperity nodes of a solved profile: positions `x` (m, positive along positive entrainment), films `h` (m), asperity pressures `p_a` (Pa) and cell widths (m) over a contact
/// `length` (m), the entrainment's sign choosing the upstream side; `local(h)` gives `(δx_gs, n)`.
/// Nodes without asperity pressure are left out.
pub fn asperity_nodes(
    x: &[f64],
    film: &[f64],
    pressure: &[f64],
    cell: &[f64],
    length: f64,
    entrainment: f64,
    local: impl Fn(f64) -> (f64, f64),
) -> Vec<AsperityNode> {
    let n = x.len().min(film.len()).min(pressure.len()).min(cell.len());
    let peak = pressure[..n].iter().cloned().fold(0.0, f64::max);
    if !(peak > 0.0) {
        return Vec::new();
    }
    let forward = entrainment >= 0.0;
    // The most upstream node at the threshold (the grid's order does not matter).
    let edge = (0..n)
        .filter(|&i| pressure[i] >= INLET_EDGE_SHARE * peak)
        .map(|i| x[i])
        .fold(if forward { f64::INFINITY } else { f64::NEG_INFINITY }, |e, v| if forward { e.min(v) } else { e.max(v) });
    (0..n)
        .filter(|&i| pressure[i] > 0.0)
        .map(|i| {
            let travel = if forward { x[i] - edge } else { edge - x[i] };
            let (d, e) = local(film[i]);
            AsperityNode { load: pressure[i] * cell[i] * length, travel: travel.max(0.0), film: film[i], gross_sliding_displacement: d, exponent: e }
        })
        .collect()
}

/// The asperity traction over `nodes` with limiting friction `mu` (seed 001 eq. 22–23, 25's
/// asperity term) at sliding `u_s` and entrainment `u_e`: `(force, dforce/du_s, bound, reach)`.
/// Force in N with the sign of `u_s`; slope at fixed entrainment. Per node `t = |u_s| k`,
/// `k = travel/(δx_gs |u_e|)`, `g = 1 − (1 − t)^n` below `t = 1`, 1 beyond. `bound =
/// μ Σ W_i k_i² n_i(n_i − 1)` bounds `|d²F/du_s²|` wherever it exists and is a Lipschitz constant
/// of the slope on each side of `u_s = 0` (the slope is continuous where a node reaches gross
/// sliding, `n ≥ 2`); `reach = |u_s|` (the curvature's sign flips at 0). Without entrainment the
/// nodes slide at any sliding (Coulomb-like, no slope).
pub fn nodal_traction(nodes: &[AsperityNode], mu: f64, sliding: f64, entrainment: f64) -> (f64, f64, f64, f64) {
    let ue = entrainment.abs();
    let us = sliding.abs();
    let sign = if sliding < 0.0 { -1.0 } else { 1.0 };
    let (mut force, mut slope, mut bound) = (0.0, 0.0, 0.0);
    for nd in nodes {
        let q = mu * nd.load;
        if !(q > 0.0) {
            continue;
        }
        if !(ue > 0.0) {
            if sliding != 0.0 && nd.travel > 0.0 {
                force += q;
            }
            continue;
        }
        let k = nd.travel / (nd.gross_sliding_displacement * ue);
        let n = nd.exponent;
        bound += q * k * k * n * (n - 1.0);
        let t = us * k;
        if t >= 1.0 {
            force += q;
        } else {
            let rest = 1.0 - t;
            let r1 = rest.powf(n - 1.0);
            force += q * (1.0 - r1 * rest);
            slope += q * k * n * r1;
        }
    }
    (sign * force, slope, bound, us)
}

/// `μ Σ W_i` over the nodes that have travelled (`travel > 0`): the most the nodes transmit, N.
pub fn nodal_capacity(nodes: &[AsperityNode], mu: f64) -> f64 {
    mu * nodes.iter().filter(|n| n.travel > 0.0).map(|n| n.load).sum::<f64>()
}

/// The slide-to-roll ratio `|u_s/u_e|` at which the nodes transmit `share` (< 1) of
/// [`nodal_capacity`] (bisection to 1e-12 relative; the traction grows with the ratio and is full
/// at `max δx_gs/travel`). `None` without capacity.
pub fn nodal_saturation_creep(nodes: &[AsperityNode], share: f64) -> Option<f64> {
    let cap = nodal_capacity(nodes, 1.0);
    if !(cap > 0.0) {
        return None;
    }
    let full = nodes.iter().filter(|n| n.travel > 0.0 && n.load > 0.0).map(|n| n.gross_sliding_displacement / n.travel).fold(0.0, f64::max);
    let (mut lo, mut hi) = (0.0, full);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if nodal_traction(nodes, 1.0, mid, 1.0).0 < share * cap { lo = mid } else { hi = mid }
        if hi - lo <= 1e-12 * hi {
            break;
        }
    }
    Some(hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::friction::micro_slip_share;

    /// A semi-elliptic asperity pressure on `[−a, a]` sampled at `m` cell midpoints.
    fn semi_elliptic(m: usize, a: f64, load: f64, d: f64, n: f64) -> Vec<AsperityNode> {
        let dx = 2.0 * a / m as f64;
        let x: Vec<f64> = (0..m).map(|i| -a + (i as f64 + 0.5) * dx).collect();
        let p: Vec<f64> = x.iter().map(|x| 2.0 * load / (std::f64::consts::PI * a) * (1.0 - (x / a).powi(2)).max(0.0).sqrt()).collect();
        let h = vec![0.27e-6; m];
        let mut nodes = asperity_nodes(&x, &h, &p, &vec![dx; m], 1.0, 3.98, |_| (d, n));
        // The sampled edge sits half a cell inside −a: measure the travel from −a as eq. 22 does.
        let shift = x[0] + a;
        for nd in &mut nodes {
            nd.travel += shift;
        }
        nodes
    }

    /// With a constant map and a semi-elliptic pressure, the nodal sum is the closed form of
    /// [`micro_slip_share`] (midpoint rule, error O(m^-1.5) from the square-root edges).
    #[test]
    fn nodal_traction_of_a_semi_ellipse_is_the_closed_form() {
        let (a, load, d, mu, ue) = (0.35e-3, 1000.0, 45e-9, 0.12, 3.98);
        for n in [2.0, 3.0, 5.5] {
            let nodes = semi_elliptic(20_000, a, load, d, n);
            let xi = d / a;
            let mut worst: f64 = 0.0;
            for t in [0.0, 0.05, 0.3, 0.5, 0.8, 1.0, 2.0, 10.0] {
                let us = t * xi * ue;
                let (f, s, bound, _) = nodal_traction(&nodes, mu, us, ue);
                let (phi, dphi, b) = micro_slip_share(t, n);
                worst = worst.max((f / (mu * load) - phi).abs());
                assert!((f / (mu * load) - phi).abs() < 2e-6, "n={n} t={t}: {} vs {phi}", f / (mu * load));
                assert!((s * xi * ue / (mu * load) - dphi).abs() < 2e-4 * dphi.max(1.0), "n={n} t={t}");
                assert!((bound * (xi * ue).powi(2) / (mu * load) - b).abs() < 1e-3 * b, "n={n}");
            }
            println!("n {n}: worst share difference {worst:.2e}");
            // The saturation creep: where Φ reaches 99 %.
            let t99 = nodal_saturation_creep(&nodes, 0.99).unwrap() / xi;
            assert!((micro_slip_share(t99, n).0 - 0.99).abs() < 1e-5, "n={n}");
        }
    }

    /// The bound holds against finite differences of the slope, and the traction is odd.
    #[test]
    fn nodal_slope_and_bound_against_finite_differences() {
        let x: Vec<f64> = (0..50).map(|i| -0.4e-3 + i as f64 * 1.6e-5).collect();
        let h: Vec<f64> = x.iter().map(|x| 0.25e-6 + 0.2 * x * x).collect();
        let p: Vec<f64> = h.iter().map(|h| 4e7 * (-(h - 0.25e-6) / 0.05e-6).exp()).collect();
        let map = MicroSlipMap::new(vec![0.2e-6, 0.3e-6], vec![60e-9, 35e-9], vec![3.0, 2.0]).unwrap();
        let nodes = asperity_nodes(&x, &h, &p, &vec![1.6e-5; 50], 0.02, -2.0, |h| map.at(h));
        assert_eq!(nodes.iter().filter(|n| n.travel == 0.0).count(), 1, "the edge is the last node at negative entrainment");
        let ue = -2.0;
        let (_, _, bound, _) = nodal_traction(&nodes, 0.1, 1e-5, ue);
        for us in [1e-7, 1e-6, 1e-5, 5e-5, 2e-4] {
            let e = 1e-4 * us;
            let (f, s, _, reach) = nodal_traction(&nodes, 0.1, us, ue);
            let fd = (nodal_traction(&nodes, 0.1, us + e, ue).0 - nodal_traction(&nodes, 0.1, us - e, ue).0) / (2.0 * e);
            assert!((fd - s).abs() <= 1e-5 * s.max(1e-9) + 1e-9, "{us}: {fd} vs {s}");
            let fd2 = (nodal_traction(&nodes, 0.1, us + e, ue).1 - nodal_traction(&nodes, 0.1, us - e, ue).1) / (2.0 * e);
            assert!(fd2 <= 1e-6 * bound && -fd2 <= bound * (1.0 + 1e-6), "{us}: {fd2} vs {bound}");
            assert_eq!(reach, us);
            assert_eq!(nodal_traction(&nodes, 0.1, -us, ue).0, -f);
        }
        // Saturated: every node past its gross-sliding displacement.
        let (f, s, _, _) = nodal_traction(&nodes, 0.1, 10.0, ue);
        assert!((f - nodal_capacity(&nodes, 0.1)).abs() < 1e-12 * f && s == 0.0);
    }

    #[test]
    fn map_interpolates_and_holds_its_ends() {
        let m = MicroSlipMap::new(vec![0.1e-6, 0.3e-6], vec![80e-9, 20e-9], vec![3.0, 2.0]).unwrap();
        let (d, n) = m.at(0.2e-6);
        assert!((d - 40e-9).abs() < 1e-20 && (n - 2.5).abs() < 1e-12);
        assert_eq!(m.at(0.05e-6), (80e-9, 3.0));
        assert_eq!(m.at(1e-6), (20e-9, 2.0));
        let one = MicroSlipMap::new(vec![0.27e-6], vec![45e-9], vec![3.0]).unwrap();
        assert_eq!(one.at(0.1e-6), (45e-9, 3.0));
        assert_eq!(MicroSlipMap::new(vec![0.2e-6, 0.1e-6], vec![1e-8; 2], vec![3.0; 2]).unwrap_err().0, "film");
        assert_eq!(MicroSlipMap::new(vec![0.1e-6], vec![1e-8], vec![1.9]).unwrap_err().0, "exponent");
        assert_eq!(MicroSlipMap::new(vec![0.1e-6], vec![1e-8, 2e-8], vec![3.0]).unwrap_err().0, "gross_sliding_displacement");
    }
}
