//! Valve-spring design checks: a round-wire helical compression spring between its installed
//! length and full lift — rate, forces, shear stress with the Wahl or Bergsträsser curvature
//! factor, static (solid) and Goodman fatigue safety, coil clash, surge and the cam orders that
//! excite it. Shigley's *Mechanical Engineering Design* (Budynas & Nisbett, 9th ed., ch. 10;
//! equation numbers of that edition) throughout.
//!
//! Nested springs (an inner spring inside the outer, both between the head and the retainer) act
//! in parallel: the rates and forces add ([`nested_rate`]), each spring is checked on its own.
//! A progressive (variable-pitch) spring ([`SpringDesign::groups`]) has its forces, rates, open
//! coils and surge from [`super::progressive`] at installed length and full lift.

use super::model::HelicalSpring;
use super::progressive::{state_at, CoilGroup};
use crate::SolveError;
use std::f64::consts::PI;

/// End treatment (Shigley Table 10-1: total coils and solid length).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpringEnds {
    /// Plain: `N_t = N_a`, `L_s = d (N_t + 1)`.
    Plain,
    /// Plain and ground: `N_t = N_a + 1`, `L_s = d N_t`.
    PlainGround,
    /// Squared (closed): `N_t = N_a + 2`, `L_s = d (N_t + 1)`.
    Squared,
    /// Squared and ground (valve springs): `N_t = N_a + 2`, `L_s = d N_t`.
    #[default]
    SquaredGround,
}

impl SpringEnds {
    /// Total coils for `active` coils (Shigley Table 10-1).
    pub fn total_coils(self, active: f64) -> f64 {
        match self {
            SpringEnds::Plain => active,
            SpringEnds::PlainGround => active + 1.0,
            SpringEnds::Squared | SpringEnds::SquaredGround => active + 2.0,
        }
    }
    /// Solid length for wire `d` and `total` coils (Shigley Table 10-1).
    pub fn solid_length(self, d: f64, total: f64) -> f64 {
        match self {
            SpringEnds::Plain | SpringEnds::Squared => d * (total + 1.0),
            SpringEnds::PlainGround | SpringEnds::SquaredGround => d * total,
        }
    }
}

/// The curvature (stress-correction) factor on the torsional shear stress.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StressFactor {
    /// Wahl `K_W = (4C − 1)/(4C − 4) + 0.615/C` (Shigley eq. 10-4 discussion).
    #[default]
    Wahl,
    /// Bergsträsser `K_B = (4C + 2)/(4C − 3)` (Shigley eq. 10-5).
    Bergstrasser,
}

/// Wahl factor of spring index `c` = D/d.
pub fn wahl_factor(c: f64) -> f64 {
    (4.0 * c - 1.0) / (4.0 * c - 4.0) + 0.615 / c
}

/// Bergsträsser factor of spring index `c` = D/d.
pub fn bergstrasser_factor(c: f64) -> f64 {
    (4.0 * c + 2.0) / (4.0 * c - 3.0)
}

/// Spring wire: Shigley Table 10-4's minimum tensile strength `S_ut = A/d^m` (A in MPa·mm^m,
/// d in mm), or a given strength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WireStrength {
    /// Music wire A228: m = 0.145, A = 2211 MPa·mm^m.
    MusicWire,
    /// Oil-tempered wire A229: m = 0.187, A = 1855 MPa·mm^m.
    OilTempered,
    /// Chrome-vanadium A232 (valve-spring quality): m = 0.168, A = 2005 MPa·mm^m.
    ChromeVanadium,
    /// Chrome-silicon A401 (valve-spring quality): m = 0.108, A = 1974 MPa·mm^m.
    ChromeSilicon,
    /// Minimum tensile strength S_ut, Pa.
    Given(f64),
}

impl WireStrength {
    /// S_ut, Pa, for wire diameter `d` (m).
    pub fn tensile_strength(self, d: f64) -> f64 {
        let (a, m) = match self {
            WireStrength::MusicWire => (2211.0, 0.145),
            WireStrength::OilTempered => (1855.0, 0.187),
            WireStrength::ChromeVanadium => (2005.0, 0.168),
            WireStrength::ChromeSilicon => (1974.0, 0.108),
            WireStrength::Given(s) => return s,
        };
        a / (d * 1e3).powf(m) * 1e6
    }
}

/// A valve spring's design data.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringDesign {
    /// Wire, coil diameter, active coils, shear modulus, density.
    pub coil: HelicalSpring,
    /// Total coils N_t (None: from the ends, Shigley Table 10-1).
    pub total_coils: Option<f64>,
    pub ends: SpringEnds,
    /// Free length L_0, m.
    pub free_length: f64,
    /// Installed length (valve closed), m (< L_0).
    pub installed_length: f64,
    pub wire: WireStrength,
    /// Shot-peened wire (Zimmerli's peened endurance data).
    pub peened: bool,
    /// Coil groups of a progressive (variable-pitch) spring, their coils summing to the active
    /// coils (empty: uniform pitch).
    pub groups: Vec<CoilGroup>,
}

/// What each check requires.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringCriteria {
    pub stress_factor: StressFactor,
    /// Allowable torsional stress for the static (solid) check as a fraction of S_ut (Shigley
    /// Table 10-6, set not removed: 0.45 music wire and cold-drawn steel, 0.50 hardened and
    /// tempered carbon and low-alloy steel such as Cr-V and Cr-Si valve-spring wire).
    pub static_fraction: f64,
    /// Least safety factor against the allowable stress at solid length (Shigley §10-8: n_s ≥ 1.2).
    pub min_solid_safety: f64,
    /// Least Goodman fatigue safety factor.
    pub min_fatigue_safety: f64,
    /// Least fractional overrun to closure at full lift, `(L_full − L_s)/(L_0 − L_full)`
    /// (Shigley §10-8: ξ ≥ 0.15).
    pub min_overrun: f64,
    /// Least ratio of the surge frequency to the highest cam frequency (Shigley §10-10: 15–20).
    pub min_surge_ratio: f64,
}

impl Default for SpringCriteria {
    fn default() -> Self {
        SpringCriteria { stress_factor: StressFactor::Wahl, static_fraction: 0.5, min_solid_safety: 1.2, min_fatigue_safety: 1.2, min_overrun: 0.15, min_surge_ratio: 15.0 }
    }
}

/// One spring's checks. Stresses in Pa, forces in N, lengths in m, frequencies in Hz.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringCheck {
    /// Spring index C = D/d.
    pub index: f64,
    /// Rate at installed length (the tangent rate of a progressive spring), N/m.
    pub rate: f64,
    /// Rate at full lift, N/m (= `rate` for a uniform pitch).
    pub rate_full_lift: f64,
    /// Coils still open at installed length and at full lift.
    pub active_coils_installed: f64,
    pub active_coils_full_lift: f64,
    pub total_coils: f64,
    pub solid_length: f64,
    pub installed_force: f64,
    pub full_lift_force: f64,
    pub solid_force: f64,
    pub wahl_factor: f64,
    pub bergstrasser_factor: f64,
    /// Shear stress (with the chosen factor) at installed length, full lift and solid length.
    pub stress_installed: f64,
    pub stress_full_lift: f64,
    pub stress_solid: f64,
    /// S_ut and the torsional ultimate strength S_su = 0.67 S_ut (Shigley eq. 10-30).
    pub tensile_strength: f64,
    pub torsional_ultimate: f64,
    /// Allowable static torsional stress (static_fraction × S_ut).
    pub allowable_static: f64,
    pub solid_safety: f64,
    pub solid_pass: bool,
    /// Alternating and mean stress between installed length and full lift.
    pub stress_alternating: f64,
    pub stress_mean: f64,
    /// Goodman fatigue safety factor (Zimmerli endurance, load line through the origin).
    pub fatigue_safety: f64,
    pub fatigue_pass: bool,
    /// Length at full lift and its clearance to solid (coil clash margin), m.
    pub full_lift_length: f64,
    pub clash_margin: f64,
    /// Fractional overrun to closure ξ.
    pub overrun: f64,
    pub clash_pass: bool,
    /// Surge frequency with both ends fixed (Shigley eq. 10-25) of the coils open at installed
    /// length (the lowest of a progressive spring), Hz.
    pub surge_frequency: f64,
    /// The same with the coils open at full lift, Hz.
    pub surge_frequency_full_lift: f64,
    /// Surge frequency over the highest cam frequency.
    pub surge_ratio: f64,
    /// Cam orders k with k × cam frequency = surge frequency within the speed range
    /// (at most [`MAX_ORDERS`], lowest first).
    pub exciting_orders: Vec<u32>,
    pub surge_pass: bool,
}

impl SpringCheck {
    pub fn pass(&self) -> bool {
        self.solid_pass && self.fatigue_pass && self.clash_pass && self.surge_pass
    }
}

/// Most exciting orders listed.
pub const MAX_ORDERS: usize = 64;

/// Zimmerli's torsional endurance data for spring steel wire under 10 mm, infinite life
/// (Shigley §10-9): unpeened `S_sa = 241 MPa` at `S_sm = 379 MPa`, peened 398 MPa at 534 MPa.
pub fn zimmerli(peened: bool) -> (f64, f64) {
    if peened { (398e6, 534e6) } else { (241e6, 379e6) }
}

/// Goodman fatigue safety factor in torsion (Shigley §10-9, Example 10-4(c)): the endurance
/// `S_se = S_sa/(1 − S_sm/S_su)` from Zimmerli's point, the strength on the load line of slope
/// `r = τ_a/τ_m` through the origin `S_a = r S_se S_su/(r S_su + S_se)`, and `n_f = S_a/τ_a`.
pub fn goodman_safety(tau_a: f64, tau_m: f64, s_su: f64, peened: bool) -> f64 {
    let (s_sa, s_sm) = zimmerli(peened);
    let s_se = s_sa / (1.0 - s_sm / s_su);
    if tau_a <= 0.0 {
        // A static spring: the mean stress against the ultimate.
        return s_su / tau_m.max(f64::MIN_POSITIVE);
    }
    let r = tau_a / tau_m;
    r * s_se * s_su / (r * s_su + s_se) / tau_a
}

/// The rate of nested springs in parallel, N/m.
pub fn nested_rate(springs: &[HelicalSpring]) -> f64 {
    springs.iter().map(|s| s.rate()).sum()
}

fn invalid(field: &str, message: &str) -> SolveError {
    SolveError::invalid(format!("SpringDesign.{field}"), message)
}

/// Check `design` for a valve lift `lift` (m, at the spring) and cam frequencies from
/// `cam_frequency.0` to `cam_frequency.1` (Hz, camshaft revolutions per second).
pub fn check_spring(design: &SpringDesign, lift: f64, cam_frequency: (f64, f64), criteria: &SpringCriteria) -> Result<SpringCheck, SolveError> {
    let c = &design.coil;
    let pos = |v: f64| v.is_finite() && v > 0.0;
    if !pos(c.wire_diameter) || !pos(c.mean_diameter) || !pos(c.active_coils) || !pos(c.shear_modulus) || !pos(c.density) {
        return Err(invalid("coil", "wire and coil diameter, active coils, shear modulus and density must be > 0"));
    }
    let index = c.mean_diameter / c.wire_diameter;
    if !(index > 1.0) {
        return Err(invalid("coil.mean_diameter", "the spring index D/d must exceed 1"));
    }
    if !pos(design.free_length) || !pos(design.installed_length) || design.installed_length >= design.free_length {
        return Err(invalid("installed_length", "must be > 0 and below the free length"));
    }
    if !(lift.is_finite() && lift >= 0.0) {
        return Err(invalid("lift", "must be ≥ 0"));
    }
    let (f_lo, f_hi) = cam_frequency;
    if !pos(f_lo) || !pos(f_hi) || f_lo > f_hi {
        return Err(invalid("cam_frequency", "must be > 0, lowest first"));
    }
    let strength = design.wire.tensile_strength(c.wire_diameter);
    if !pos(strength) {
        return Err(invalid("wire", "the tensile strength must be > 0"));
    }
    let total = design.total_coils.unwrap_or_else(|| design.ends.total_coils(c.active_coils));
    if !pos(total) || total < c.active_coils {
        return Err(invalid("total_coils", "must be ≥ the active coils"));
    }
    if !design.groups.is_empty() {
        let coils: f64 = design.groups.iter().map(|g| g.coils).sum();
        if !design.groups.iter().all(|g| pos(g.coils) && g.pitch.is_finite() && g.pitch > c.wire_diameter) || (coils - c.active_coils).abs() > 1e-6 * c.active_coils {
            return Err(invalid("groups", "coil groups need coils > 0 summing to the active coils and a pitch above the wire diameter"));
        }
    }
    // Rate, Shigley eq. 10-9; forces at installed length, full lift and solid (Hooke's law; a
    // progressive spring's groups closing in turn, `progressive::state_at`).
    let solid_length = design.ends.solid_length(c.wire_diameter, total);
    let full_lift_length = design.installed_length - lift;
    let at = |length: f64| state_at(c, &design.groups, (design.free_length - length).max(0.0));
    let (installed, full) = (at(design.installed_length), at(full_lift_length));
    let rate = installed.rate;
    let installed_force = installed.force;
    let full_lift_force = full.force;
    let solid_force = at(solid_length).force;
    let (kw, kb) = (wahl_factor(index), bergstrasser_factor(index));
    let k = match criteria.stress_factor {
        StressFactor::Wahl => kw,
        StressFactor::Bergstrasser => kb,
    };
    // τ = K 8 F D/(π d³), Shigley eq. 10-7 with the curvature factor.
    let tau = |f: f64| k * 8.0 * f * c.mean_diameter / (PI * c.wire_diameter.powi(3));
    let (stress_installed, stress_full_lift, stress_solid) = (tau(installed_force), tau(full_lift_force), tau(solid_force));
    let torsional_ultimate = 0.67 * strength;
    let allowable_static = criteria.static_fraction * strength;
    let solid_safety = if stress_solid > 0.0 { allowable_static / stress_solid } else { f64::MAX };
    let stress_alternating = 0.5 * (stress_full_lift - stress_installed);
    let stress_mean = 0.5 * (stress_full_lift + stress_installed);
    let (_, s_sm) = zimmerli(design.peened);
    let fatigue_safety = if torsional_ultimate > s_sm { goodman_safety(stress_alternating, stress_mean, torsional_ultimate, design.peened) } else { 0.0 };
    let clash_margin = full_lift_length - solid_length;
    let travel = design.free_length - full_lift_length;
    let overrun = clash_margin / travel;
    // Surge of the coils still open (the closed ones move with the fixed end).
    let open = |n: f64| HelicalSpring { active_coils: if n > 0.0 { n } else { c.active_coils }, ..*c }.surge_frequency();
    let surge_frequency = open(installed.active_coils);
    let surge_frequency_full_lift = open(full.active_coils);
    let surge_ratio = surge_frequency / f_hi;
    let (k_lo, k_hi) = ((surge_frequency / f_hi).ceil().max(1.0), (surge_frequency / f_lo).floor());
    let exciting_orders: Vec<u32> = if k_hi >= k_lo { (k_lo as u64..=k_hi as u64).take(MAX_ORDERS).map(|k| k.min(u32::MAX as u64) as u32).collect() } else { Vec::new() };
    let out = SpringCheck {
        index,
        rate,
        rate_full_lift: full.rate,
        active_coils_installed: installed.active_coils,
        active_coils_full_lift: full.active_coils,
        total_coils: total,
        solid_length,
        installed_force,
        full_lift_force,
        solid_force,
        wahl_factor: kw,
        bergstrasser_factor: kb,
        stress_installed,
        stress_full_lift,
        stress_solid,
        tensile_strength: strength,
        torsional_ultimate,
        allowable_static,
        solid_safety: solid_safety.min(1e6),
        solid_pass: solid_safety >= criteria.min_solid_safety,
        stress_alternating,
        stress_mean,
        fatigue_safety: fatigue_safety.min(1e6),
        fatigue_pass: fatigue_safety >= criteria.min_fatigue_safety,
        full_lift_length,
        clash_margin,
        overrun,
        clash_pass: overrun >= criteria.min_overrun,
        surge_frequency,
        surge_frequency_full_lift,
        surge_ratio,
        exciting_orders,
        surge_pass: surge_ratio >= criteria.min_surge_ratio,
    };
    let finite = [out.rate, out.installed_force, out.full_lift_force, out.stress_full_lift, out.stress_solid, out.fatigue_safety, out.overrun, out.surge_frequency, out.surge_ratio];
    crate::ensure_finite("valve-spring checks", finite.iter())?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const IN: f64 = 0.0254;
    const LBF: f64 = 4.448_221_615;
    const KPSI: f64 = 6.894_757e6;

    /// Shigley (9th ed.) Example 10-4: music wire d = 0.092 in, OD 9/16 in, 21 active coils,
    /// squared and ground, unpeened, preload 5 lbf, maximum 35 lbf; G = 11.75 Mpsi, γ = 0.284
    /// lbf/in³, S_ut = 201/d^0.145 = 284.1 kpsi. Its results (as recalled — no copy of the book
    /// here — and each recomputed by hand from these inputs): C = 5.11, K_B = 1.287,
    /// τ_a = 29.7 kpsi, τ_m = 39.6 kpsi, S_su = 190.3 kpsi, Goodman n_f = 1.23 (part c),
    /// k = 48.1 lbf/in and f_n = 281 Hz (part d).
    #[test]
    fn shigley_example_10_4() {
        let d = 0.092 * IN;
        let dm = 0.5625 * IN - d;
        let coil = HelicalSpring { wire_diameter: d, mean_diameter: dm, active_coils: 21.0, shear_modulus: 11.75e6 * KPSI / 1e3, density: 0.284 * 27_679.9 };
        let rate = coil.rate();
        assert!((rate / (LBF / IN) - 48.1).abs() < 0.05, "k = {} lbf/in", rate / (LBF / IN));
        let free = 4.375 * IN;
        let installed = free - 5.0 * LBF / rate;
        let lift = 30.0 * LBF / rate;
        let design = SpringDesign { coil, total_coils: None, ends: SpringEnds::SquaredGround, free_length: free, installed_length: installed, wire: WireStrength::Given(284.1 * KPSI), peened: false, groups: Vec::new() };
        let criteria = SpringCriteria { stress_factor: StressFactor::Bergstrasser, ..Default::default() };
        let ch = check_spring(&design, lift, (1.0, 2.0), &criteria).unwrap();
        assert!((ch.index - 5.11).abs() < 0.01);
        assert!((ch.bergstrasser_factor - 1.287).abs() < 1e-3, "{}", ch.bergstrasser_factor);
        assert!((ch.stress_alternating / KPSI - 29.7).abs() < 0.05, "τa {}", ch.stress_alternating / KPSI);
        assert!((ch.stress_mean / KPSI - 39.6).abs() < 0.05, "τm {}", ch.stress_mean / KPSI);
        assert!((ch.torsional_ultimate / KPSI - 190.3).abs() < 0.1);
        assert!((ch.fatigue_safety - 1.23).abs() < 0.005, "n_f {}", ch.fatigue_safety);
        assert!((ch.surge_frequency - 281.0).abs() < 1.0, "f_n {}", ch.surge_frequency);
        // Table 10-1, squared and ground: N_t = 23, L_s = d N_t = 2.116 in.
        assert_eq!(ch.total_coils, 23.0);
        assert!((ch.solid_length / IN - 2.116).abs() < 1e-9);
        // Shigley's Table 10-4 music wire at d = 0.092 in gives S_ut within 0.3 % of 284.1 kpsi.
        let sut = WireStrength::MusicWire.tensile_strength(d) / KPSI;
        assert!((sut - 284.1).abs() / 284.1 < 3e-3, "{sut}");
    }

    /// The Wahl and Bergsträsser factors agree within 1.5 % over Shigley's range 4 ≤ C ≤ 12
    /// (Wahl the larger: 1.4 % at C = 4, 0.75 % at C = 12) and tend to 1 for large C.
    #[test]
    fn curvature_factors() {
        for (c, tol) in [(4.0, 0.015), (6.0, 0.013), (8.0, 0.011), (12.0, 0.008)] {
            let (w, b) = (wahl_factor(c), bergstrasser_factor(c));
            assert!(w > b && (w - b) / w < tol, "C = {c}: {w} vs {b}");
        }
        assert!((wahl_factor(5.0) - 1.3105).abs() < 1e-4);
        assert!((bergstrasser_factor(1e6) - 1.0).abs() < 1e-5);
    }

    proptest::proptest! {
        /// Any spring input gives finite checks or a typed error, never NaN or a panic.
        #[test]
        fn checks_are_finite_or_refused(d in -1e-3f64..8e-3, dm in 0.0f64..0.05, n in -1.0f64..30.0, l0 in 0.0f64..0.1, li in 0.0f64..0.1,
                                        lift in -1e-3f64..0.03, f0 in 0.0f64..200.0, df in 0.0f64..200.0, peened in proptest::bool::ANY) {
            let coil = HelicalSpring { wire_diameter: d, mean_diameter: dm, active_coils: n, shear_modulus: 79.3e9, density: 7850.0 };
            let design = SpringDesign { coil, total_coils: None, ends: SpringEnds::SquaredGround, free_length: l0, installed_length: li, wire: WireStrength::ChromeSilicon, peened, groups: Vec::new() };
            match check_spring(&design, lift, (f0, f0 + df), &SpringCriteria::default()) {
                Ok(ch) => {
                    for v in [ch.rate, ch.stress_full_lift, ch.stress_solid, ch.fatigue_safety, ch.solid_safety, ch.clash_margin, ch.overrun, ch.surge_frequency, ch.surge_ratio] {
                        proptest::prop_assert!(v.is_finite(), "{ch:?}");
                    }
                    proptest::prop_assert!(ch.exciting_orders.len() <= MAX_ORDERS);
                }
                Err(SolveError::InvalidInput { .. }) | Err(SolveError::NonFinite { .. }) => {}
                Err(e) => proptest::prop_assert!(false, "{e}"),
            }
        }
    }

    /// A progressive spring by hand (the groups of `progressive`'s test): d = 4 mm, D = 24 mm,
    /// two coils of pitch 5 mm and four of 7.5 mm, squared and ground (N_t = 8, L_s = 32 mm),
    /// free length L_s + Σ n (p − d) = 48 mm, installed at 44 mm, 6 mm lift. Installed:
    /// δ = 4 mm, all six coils open, F = K/6 × 4 mm = 122.38 N at 30 594 N/m; full lift:
    /// δ = 10 mm, the 5 mm coils closed at 6 mm (183.56 N), F = 183.56 + K/4 × 4 mm = 367.13 N at
    /// 45 891 N/m with four coils open, the surge 6/4 = 1.5 times the installed one; coil-clash
    /// margin 38 − 32 = 6 mm.
    #[test]
    fn progressive_spring_by_hand() {
        let coil = HelicalSpring { wire_diameter: 4e-3, mean_diameter: 24e-3, active_coils: 6.0, shear_modulus: 79.3e9, density: 7850.0 };
        let groups = vec![CoilGroup { coils: 2.0, pitch: 5e-3 }, CoilGroup { coils: 4.0, pitch: 7.5e-3 }];
        let design = SpringDesign { coil, total_coils: None, ends: SpringEnds::SquaredGround, free_length: 0.048, installed_length: 0.044, wire: WireStrength::ChromeSilicon, peened: true, groups };
        let ch = check_spring(&design, 0.006, (20.0, 50.0), &SpringCriteria::default()).unwrap();
        assert!((ch.installed_force - 122.38).abs() < 0.01, "{}", ch.installed_force);
        assert!((ch.full_lift_force - 367.13).abs() < 0.01, "{}", ch.full_lift_force);
        assert!((ch.rate - 30_594.0).abs() < 1.0 && (ch.rate_full_lift - 45_891.0).abs() < 1.0);
        assert_eq!((ch.active_coils_installed, ch.active_coils_full_lift), (6.0, 4.0));
        assert!((ch.surge_frequency_full_lift / ch.surge_frequency - 1.5).abs() < 1e-12);
        assert!((ch.surge_frequency - coil.surge_frequency()).abs() < 1e-9);
        assert!((ch.clash_margin - 0.006).abs() < 1e-12);
        // τ = K_W 8 F D/(π d³) at full lift with C = 6 (K_W = 1.2525).
        let tau = wahl_factor(6.0) * 8.0 * 367.13 * 24e-3 / (PI * 64e-9);
        assert!((ch.stress_full_lift - tau).abs() < 1e-4 * tau);
        // Groups that do not add up to the active coils are refused.
        let bad = SpringDesign { groups: vec![CoilGroup { coils: 2.0, pitch: 5e-3 }], ..design };
        assert!(check_spring(&bad, 0.006, (20.0, 50.0), &SpringCriteria::default()).is_err());
    }

    /// Orders: f_n = 500 Hz with the cam at 20–30 Hz is excited by orders 17 ..= 25.
    #[test]
    fn exciting_orders_cover_the_speed_range() {
        let coil = HelicalSpring { wire_diameter: 4e-3, mean_diameter: 25e-3, active_coils: 6.0, shear_modulus: 79.3e9, density: 7850.0 };
        let fnat = coil.surge_frequency();
        let design = SpringDesign { coil, total_coils: None, ends: SpringEnds::SquaredGround, free_length: 0.05, installed_length: 0.04, wire: WireStrength::ChromeSilicon, peened: true, groups: Vec::new() };
        let ch = check_spring(&design, 0.008, (20.0, 30.0), &SpringCriteria::default()).unwrap();
        let lo = (fnat / 30.0).ceil() as u32;
        let hi = (fnat / 20.0).floor() as u32;
        assert_eq!(ch.exciting_orders, (lo..=hi).collect::<Vec<_>>());
        for k in &ch.exciting_orders {
            let f = fnat / *k as f64;
            assert!((20.0..=30.0).contains(&f));
        }
    }
}
