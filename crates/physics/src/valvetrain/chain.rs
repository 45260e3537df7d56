//! The valve spring in the assembly: a chain of lumped coil masses between the valve and the
//! fixed end ([`SpringChain`]), uniform or progressive — the coil groups of a variable-pitch
//! spring ([`super::progressive`]: each group closes at its own force) as segments whose
//! stiffness rises by [`SOLID_STIFFNESS_FACTOR`] when their coils touch — and nested springs as
//! parallel chains.
//!
//! A segment is a piecewise-linear spring ([`Law`]): affine between the closing events, so the
//! integrator's regimes (which contacts are closed) take the segments' stages too.

use std::f64::consts::PI;

/// The valve spring as a chain: `elements` interior masses joined by `elements + 1` equal
/// segments of stiffness `(elements + 1) k_s`. Each segment's mass `m_s/(elements + 1)` is
/// lumped half on each end node (the fixed end's half goes to ground, the moving end's to the
/// valve), so the fixed–fixed chain's first mode is
/// `ω₁ = 2 (N+1) √(k_s/m_s) sin(π/(2(N+1)))` → `π √(k_s/m_s)` (the continuous spring's surge,
/// error ≈ (π/(2(N+1)))²/6). `elements = 0`: a massless spring with Rayleigh's `m_s/3` on the
/// valve. Internal damping is stiffness-proportional, `c_seg = β k_seg` with
/// `β = 2ζ/(π√(k_s/m_s))`, giving the first surge mode the damping ratio `ζ`.
/// A progressive (variable-pitch) spring lists its coil `groups` ([`attach`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SpringChain {
    /// Rate k_s, N/m.
    pub rate: f64,
    /// Active mass m_s, kg.
    pub mass: f64,
    /// Interior masses N.
    pub elements: usize,
    /// Damping ratio of the first surge mode.
    pub damping_ratio: f64,
    /// Coil groups of a progressive spring, from the fixed end (empty: uniform pitch). `rate`
    /// and `mass` are then those with every coil open.
    pub groups: Vec<ClosingGroup>,
}

/// One preloaded element between two nodes (`None`: ground), compression
/// `P + k (x_b − x_a) + c (v_b − v_a)`; it pushes `b` by −compression and `a` by +compression
/// (`b` lies on the cam side of `a`). With a `law` (a progressive spring's segment) the elastic
/// part and the rate are the law's at `x_b − x_a`, the damping its `beta` × the stage's rate.
#[derive(Debug, Clone, Copy)]
pub(super) struct Element {
    pub b: Option<usize>,
    pub a: Option<usize>,
    pub k: f64,
    pub c: f64,
    pub preload: f64,
    pub law: Option<usize>,
}

/// Stiffness of a closed coil group over its open rate. Touching coils are far stiffer than the
/// open spring (the wire in compression and the Hertz contact of the coils); a finite factor
/// keeps the closed stage a stiff, damped element the integrator resolves (the dynamics beyond
/// closure are not meant to be accurate: a group closing is the design's rate change, and the
/// whole spring going solid fails the coil-clash check).
pub const SOLID_STIFFNESS_FACTOR: f64 = 1000.0;

/// One coil group of a progressive spring in the chain: its share of the active coils and the
/// (valve-side) spring force at which its coils touch, N (`K (p − d)`,
/// [`super::progressive::closing_forces`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosingGroup {
    pub share: f64,
    pub closing_force: f64,
}

/// A preloaded piecewise-linear spring: compression `preload` at Δ = 0, rate `rates[i]` between
/// the compression thresholds `thresholds[i − 1]` and `thresholds[i]` (ascending), the breaks
/// `breaks[i]` the Δ where the compression reaches `thresholds[i]`. Internal damping `beta × rate`
/// of the current stage (stiffness-proportional, as the uniform chain's).
#[derive(Debug, Clone, PartialEq)]
pub struct Law {
    preload: f64,
    thresholds: Vec<f64>,
    rates: Vec<f64>,
    breaks: Vec<f64>,
    pub beta: f64,
}

impl Law {
    /// `rates.len() == thresholds.len() + 1`, every rate > 0.
    pub fn new(preload: f64, thresholds: Vec<f64>, rates: Vec<f64>, beta: f64) -> Self {
        let m = thresholds.len();
        let s0 = thresholds.partition_point(|t| *t < preload);
        let mut breaks = vec![0.0; m];
        // Upwards from (Δ = 0, preload), downwards likewise.
        let (mut at, mut f) = (0.0, preload);
        for i in s0..m {
            at += (thresholds[i] - f) / rates[i];
            f = thresholds[i];
            breaks[i] = at;
        }
        let (mut at, mut f) = (0.0, preload);
        for i in (0..s0).rev() {
            at -= (f - thresholds[i]) / rates[i + 1];
            f = thresholds[i];
            breaks[i] = at;
        }
        Law { preload, thresholds, rates, breaks, beta }
    }
    /// Stage (thresholds passed) at Δ.
    pub fn stage(&self, d: f64) -> usize {
        self.breaks.partition_point(|b| *b < d)
    }
    pub fn stages(&self) -> usize {
        self.rates.len()
    }
    pub fn rate(&self, stage: usize) -> f64 {
        self.rates[stage.min(self.rates.len() - 1)]
    }
    pub fn breaks(&self) -> &[f64] {
        &self.breaks
    }
    /// Elastic compression at Δ, N.
    pub fn force(&self, d: f64) -> f64 {
        if self.breaks.is_empty() {
            return self.preload + self.rates[0] * d;
        }
        match self.stage(d) {
            0 => self.thresholds[0] + self.rates[0] * (d - self.breaks[0]),
            i => self.thresholds[i - 1] + self.rates[i] * (d - self.breaks[i - 1]),
        }
    }
    /// `∫₀^Δ force`, J (exact: the trapezoid on each linear piece).
    pub fn energy(&self, d: f64) -> f64 {
        let (lo, hi) = if d >= 0.0 { (0.0, d) } else { (d, 0.0) };
        let mut pts = vec![lo];
        pts.extend(self.breaks.iter().copied().filter(|b| *b > lo && *b < hi));
        pts.push(hi);
        let area: f64 = pts.windows(2).map(|w| 0.5 * (self.force(w[0]) + self.force(w[1])) * (w[1] - w[0])).sum();
        if d >= 0.0 { area } else { -area }
    }
}

/// `β` of the stiffness-proportional damping that gives the first surge mode the damping ratio
/// ζ: `β = 2ζ/(π √(k_s/m_s))`.
pub fn surge_beta(sp: &SpringChain) -> f64 {
    if sp.mass > 0.0 && sp.rate > 0.0 {
        2.0 * sp.damping_ratio / (PI * (sp.rate / sp.mass).sqrt())
    } else {
        0.0
    }
}

/// Segments per group: at least one each, the rest in proportion to the coils (largest
/// remainder). `segments ≥ groups`.
fn allocate(shares: &[f64], segments: usize) -> Vec<usize> {
    let ideal: Vec<f64> = shares.iter().map(|s| s * segments as f64).collect();
    let mut count: Vec<usize> = ideal.iter().map(|v| (v.floor() as usize).max(1)).collect();
    let gap = |c: &[usize], i: usize| ideal[i] - c[i] as f64;
    while count.iter().sum::<usize>() < segments {
        let i = (0..count.len()).max_by(|&a, &b| gap(&count, a).total_cmp(&gap(&count, b))).expect("groups");
        count[i] += 1;
    }
    while count.iter().sum::<usize>() > segments {
        let i = (0..count.len()).filter(|&i| count[i] > 1).min_by(|&a, &b| gap(&count, a).total_cmp(&gap(&count, b))).expect("segments ≥ groups");
        count[i] -= 1;
    }
    count
}

/// What [`attach`] adds to the assembly.
pub(super) struct Parts<'a> {
    pub masses: &'a mut Vec<f64>,
    /// Per degree of freedom: its share of the valve's lift in the static state.
    pub shares: &'a mut Vec<f64>,
    pub elements: &'a mut Vec<Element>,
    pub laws: &'a mut Vec<Law>,
}

/// Attach the spring `sp` (valve-side preload `preload`, lever ratio `r`) between node `valve`
/// and ground: its masses and elements in cam-side coordinates (masses and stiffnesses × r²,
/// forces × r). Returns the element indices at the moving and at the fixed end.
///
/// Uniform: `elements + 1` equal segments ([`SpringChain`]). Progressive (`sp.groups`, listed
/// from the fixed end): with interior elements, each group's coils are segments of their own (at
/// least one per group, the rest in proportion to the coils), a segment of share φ of the coils
/// having rate `k_s/φ`, mass `φ m_s` (half on each end node) and closing when the force reaches
/// its group's; without, one massless element with the series curve (the rate `k_s/φ_open` of
/// the coils still open) and Rayleigh's third of the mass on the valve.
pub(super) fn attach(p: Parts, valve: usize, r: f64, sp: &SpringChain, preload: f64) -> (usize, usize) {
    let (r2, beta, pre) = (r * r, surge_beta(sp), r * preload);
    let solid = |k: f64| SOLID_STIFFNESS_FACTOR * k;
    if sp.elements == 0 {
        p.masses[valve] += r2 * sp.mass / 3.0;
        let law = (!sp.groups.is_empty()).then(|| {
            let mut g = sp.groups.clone();
            g.sort_by(|a, b| a.closing_force.total_cmp(&b.closing_force));
            // Compliance of the coils in series: a share φ of the coils has rate k/φ when open,
            // SOLID_STIFFNESS_FACTOR × that when closed (as the chain's segments).
            let k = r2 * sp.rate;
            let mut open: f64 = g.iter().map(|x| x.share).sum();
            let mut rates = vec![k / open];
            for x in &g {
                open = (open - x.share).max(0.0);
                rates.push(1.0 / (open / k + (1.0 - open) / solid(k)));
            }
            p.laws.push(Law::new(pre, g.iter().map(|x| r * x.closing_force).collect(), rates, beta));
            p.laws.len() - 1
        });
        p.elements.push(Element { b: Some(valve), a: None, k: r2 * sp.rate, c: beta * r2 * sp.rate, preload: pre, law });
        let i = p.elements.len() - 1;
        return (i, i);
    }
    let segs = sp.elements + 1;
    // Segments from the valve to the fixed end: (share of the coils, closing force).
    let segments: Vec<(f64, Option<f64>)> = if sp.groups.is_empty() {
        vec![(1.0 / segs as f64, None); segs]
    } else {
        let shares: Vec<f64> = sp.groups.iter().map(|g| g.share).collect();
        let count = allocate(&shares, segs);
        let mut out = Vec::with_capacity(segs);
        for (g, c) in sp.groups.iter().zip(&count).rev() {
            out.extend(std::iter::repeat_n((g.share / *c as f64, Some(g.closing_force)), *c));
        }
        out
    };
    // A uniform chain in the arithmetic of its closed form (k_s (N+1), m_s/(N+1)); a
    // progressive one from each segment's share of the coils.
    let uniform = sp.groups.is_empty();
    let n1 = segs as f64;
    let seg_mass = |share: f64| if uniform { r2 * sp.mass / n1 } else { r2 * sp.mass * share };
    let seg_rate = |share: f64| if uniform { r2 * sp.rate * n1 } else { r2 * sp.rate / share };
    p.masses[valve] += 0.5 * seg_mass(segments[0].0);
    let first = p.masses.len();
    let mut deflected = 0.0;
    for j in 1..segs {
        p.masses.push(if uniform { seg_mass(0.0) } else { 0.5 * (seg_mass(segments[j - 1].0) + seg_mass(segments[j].0)) });
        deflected += segments[j - 1].0;
        p.shares.push(if uniform { 1.0 - j as f64 / n1 } else { 1.0 - deflected });
    }
    // Valve → node 1 → … → node N → ground (the fixed end).
    let node = |j: usize| if j == 0 { valve } else { first + j - 1 };
    let moving = p.elements.len();
    for (j, (share, closing)) in segments.iter().enumerate() {
        let k = seg_rate(*share);
        let law = closing.map(|fc| {
            p.laws.push(Law::new(pre, vec![r * fc], vec![k, solid(k)], beta));
            p.laws.len() - 1
        });
        let a = if j + 1 == segs { None } else { Some(node(j + 1)) };
        p.elements.push(Element { b: Some(node(j)), a, k, c: beta * k, preload: pre, law });
    }
    (moving, p.elements.len() - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The law is continuous, its breaks where the thresholds are reached, below and above the
    /// preload; the energy is the integral of the force.
    #[test]
    fn piecewise_law() {
        let law = Law::new(100.0, vec![50.0, 200.0], vec![1e4, 2e4, 1e6], 0.0);
        assert!((law.force(0.0) - 100.0).abs() < 1e-9);
        assert!((law.breaks()[0] + 50.0 / 2e4).abs() < 1e-15 && (law.breaks()[1] - 100.0 / 2e4).abs() < 1e-15);
        assert!((law.force(law.breaks()[1] + 1e-6) - 201.0).abs() < 1e-6);
        assert!((law.force(-0.0025 - 1e-3) - 40.0).abs() < 1e-9);
        let d = 0.006;
        let exact = 100.0 * 0.005 + 0.5 * 2e4 * 0.005f64.powi(2) + 200.0 * 0.001 + 0.5 * 1e6 * 1e-6;
        assert!((law.energy(d) - exact).abs() < 1e-12, "{} vs {exact}", law.energy(d));
        assert_eq!(allocate(&[0.25, 0.75], 9), vec![2, 7]);
        assert_eq!(allocate(&[0.05, 0.95], 3), vec![1, 2]);
    }
}
