//! Load distribution along a crowned roller (seed 000 Table 1: total length L, straight-ish middle
//! L1, crown height h_td, end radius R_d) by the thin-slice model.
//!
//! Axial gap of the unloaded roller against a straight generator (y from the roller centre):
//! `g(y) = h_td (2y/L1)²` for `|y| ≤ L1/2` and `g(y) = h_td + (|y| − L1/2)²/(2R_d)` beyond, up to
//! `L/2` ([`CrownProfile::Convex`], the default). Seed 000 eq. 3 prints the middle term as
//! `h_td (1 − (2y/L1)²)` and the ends as `(|y| − L1/2)²/(2R_d)`, which makes the roller's centre
//! the *thinnest* section (relieved by h_td) and its highest points the transitions at `±L1/2`;
//! the default reads it as a sign slip of the usual convex crown, and
//! [`CrownProfile::Seed000Eq3`] keeps it as printed (the paper's picture of edge pressure peaks at
//! the crown transitions and the minimum film towards the ends at every load follows from it).
//! Table 1 lists h_td in mm (4.5), read here in µm (4.5 mm of crown on a 12 mm section would not
//! touch at all).
//!
//! Each slice is a 2D Hertz contact whose approach is `δ_s = c w'` with the compliance
//! `c = (2 ln(4R/b) − 1)/(π E*)` (Johnson, *Contact Mechanics* §5.6, two cylinders of the same
//! material approximated with the reduced radius R). With a rigid approach δ of the roller, the
//! slice load is `w'(y) = (δ − g(y))⁺/c`; the total load fixes δ through
//! `G(δ) = ∫ (δ − g)⁺ dy = c F`, which is closed-form for this profile and inverted by Newton
//! (`G'(δ)` is the loaded length). `c` depends on the peak slice load through `b`, so the solve
//! is repeated with the updated `c` (three passes: the load then integrates back within 1e-3).

/// Which axial profile the crown parameters describe (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CrownProfile {
    /// Convex crown: `h_td (2y/L1)²` on the middle, `h_td + (|y| − L1/2)²/(2R_d)` beyond.
    #[default]
    Convex,
    /// Seed 000 eq. 3 as printed: `h_td (1 − (2y/L1)²)` on the middle (a relieved centre),
    /// `(|y| − L1/2)²/(2R_d)` beyond.
    Seed000Eq3,
}

/// Crowned roller profile, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crown {
    /// Total length L.
    pub length: f64,
    /// Middle length L1 (≤ L).
    pub middle_length: f64,
    /// Crown height h_td at the ends of the middle section.
    pub crown_height: f64,
    /// End profile radius R_d.
    pub end_radius: f64,
    /// How the middle and end terms are shaped.
    pub profile: CrownProfile,
}

/// Load distribution of a crowned roller at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrownedContact {
    /// Peak load per unit length (at the slice of the smallest gap: the centre of a convex crown,
    /// the transitions of seed 000 eq. 3 as printed), N/m.
    pub peak_load_per_length: f64,
    /// Axially loaded length, m.
    pub effective_length: f64,
    /// `F / w'_max`: the length of a uniform line contact with the same peak, m.
    pub equivalent_length: f64,
    /// Rigid approach δ of the roller, m: slice `y` carries `w'_max (δ − g(y))⁺/δ`.
    pub approach: f64,
}

impl Crown {
    /// Seed 000 Table 1's roller: length 14 mm, straight middle L1 = 12 mm, crown drop
    /// h_td = 4.5 µm, end radius R_d = 12.5 mm.
    pub const SEED000: Crown = Crown { length: 0.014, middle_length: 0.012, crown_height: 4.5e-6, end_radius: 0.0125, profile: CrownProfile::Convex };

    /// Axial gap of the unloaded roller at `y` (m from the roller centre) against a straight
    /// generator through its highest point, m (the profiles of the module docs; seed 000 eq. 3):
    /// convex `h_td (2y/L1)²` on the middle, `h_td + (|y| − L1/2)²/(2R_d)` beyond; as printed
    /// `h_td (1 − (2y/L1)²)` on the middle, `(|y| − L1/2)²/(2R_d)` beyond.
    pub fn gap(&self, y: f64) -> f64 {
        let half1 = 0.5 * self.middle_length;
        let ya = y.abs();
        let (middle, step) = match self.profile {
            CrownProfile::Convex => (if half1 > 0.0 { self.crown_height * (ya / half1).powi(2) } else { 0.0 }, self.crown_height),
            CrownProfile::Seed000Eq3 => (if half1 > 0.0 { self.crown_height * (1.0 - (ya / half1).powi(2)) } else { 0.0 }, 0.0),
        };
        if ya <= half1 {
            middle
        } else {
            let z = ya - half1;
            step + if self.end_radius.is_finite() && self.end_radius > 0.0 { z * z / (2.0 * self.end_radius) } else { 0.0 }
        }
    }

    /// Seed 000 eq. 3 as printed with a relieved middle: the roller's highest points are the
    /// transitions `±L1/2`, which carry the load at every load (the loaded zone is not an interval
    /// around the centre).
    pub fn loads_the_transitions(&self) -> bool {
        self.profile == CrownProfile::Seed000Eq3
    }

    /// `(G(δ), G'(δ))` for this profile.
    fn g_integral(&self, delta: f64) -> (f64, f64) {
        if delta <= 0.0 {
            return (0.0, 0.0);
        }
        let half1 = 0.5 * self.middle_length;
        let half_end = 0.5 * (self.length - self.middle_length);
        let c = if self.middle_length > 0.0 { 4.0 * self.crown_height / (self.middle_length * self.middle_length) } else { 0.0 };
        let (i1, y1, step) = match self.profile {
            // Middle: g = c y², c = 4 h_td/L1², loaded over |y| < y1.
            CrownProfile::Convex => {
                let y1 = if c > 0.0 { half1.min((delta / c).sqrt()) } else { half1 };
                (delta * y1 - c * y1 * y1 * y1 / 3.0, y1, self.crown_height)
            }
            // Middle: g = h_td − c y², loaded over y0 < |y| ≤ L1/2.
            CrownProfile::Seed000Eq3 => {
                let y0 = if c > 0.0 && delta < self.crown_height { ((self.crown_height - delta) / c).sqrt().min(half1) } else { 0.0 };
                let i = (delta - self.crown_height) * (half1 - y0) + c * (half1.powi(3) - y0.powi(3)) / 3.0;
                (i, half1 - y0, 0.0)
            }
        };
        // Ends: g = step + z²/(2R_d).
        let d2 = delta - step;
        let (i2, z1) = if d2 > 0.0 && half_end > 0.0 {
            let z1 = if self.end_radius.is_finite() { half_end.min((2.0 * self.end_radius * d2).sqrt()) } else { half_end };
            let quad = if self.end_radius.is_finite() { z1 * z1 * z1 / (6.0 * self.end_radius) } else { 0.0 };
            (d2 * z1 - quad, z1)
        } else {
            (0.0, 0.0)
        };
        (2.0 * (i1 + i2), 2.0 * (y1 + z1))
    }

    /// Slice-model load distribution for total load `load` (N), reduced radius `r` (m) and
    /// contact modulus `E*` (Pa).
    pub fn distribute(&self, load: f64, r: f64, contact_modulus: f64) -> CrownedContact {
        self.distribute_warm(load, r, contact_modulus, &mut [f64::NAN; 3])
    }

    /// [`Self::distribute`] with warm starts: `hint[k]` is the approach δ of pass `k` at a nearby
    /// state (NaN: none), updated. Neighbouring cam angles then need two or three Newton steps
    /// per pass; the result differs only within the Newton tolerance (1e-13 of δ).
    pub fn distribute_warm(&self, load: f64, r: f64, contact_modulus: f64, hint: &mut [f64; 3]) -> CrownedContact {
        if !(load > 0.0) {
            return CrownedContact { peak_load_per_length: 0.0, effective_length: 0.0, equivalent_length: self.length, approach: 0.0 };
        }
        let pi = std::f64::consts::PI;
        // First compliance guess from a uniform load over the whole length.
        let mut w_peak = load / self.length;
        let mut delta: f64 = 0.0;
        let mut eff = self.length;
        for pass_hint in hint.iter_mut() {
            let b = (4.0 * w_peak * r / (pi * contact_modulus)).sqrt();
            let compliance = ((2.0 * (4.0 * r / b).ln() - 1.0) / (pi * contact_modulus)).max(1e-30);
            let target = compliance * load;
            // Newton on the convex increasing G from a lower bound (δ ≥ target/L) or the hint
            // (from either side: after one step the iterates decrease monotonically to the root).
            delta = if pass_hint.is_finite() && *pass_hint > 0.0 { *pass_hint } else { delta.max(target / self.length) };
            for _ in 0..100 {
                let (g, dg) = self.g_integral(delta);
                let step = if dg > 0.0 { (g - target) / dg } else { -delta.max(1e-12) };
                delta -= step;
                if delta <= 0.0 {
                    delta = 1e-15;
                }
                if step.abs() <= 1e-13 * delta {
                    break;
                }
            }
            *pass_hint = delta;
            eff = self.g_integral(delta).1;
            w_peak = delta / compliance;
        }
        CrownedContact { peak_load_per_length: w_peak, effective_length: eff, equivalent_length: load / w_peak, approach: delta }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed000() -> Crown {
        Crown::SEED000
    }

    #[test]
    fn slice_loads_add_up_and_length_grows_with_load() {
        let crown = seed000();
        let (r, es) = (0.01, 2.1e11 / 2.0);
        let mut prev = 0.0;
        for load in [50.0, 300.0, 1000.0, 3000.0, 10_000.0] {
            let c = crown.distribute(load, r, es);
            assert!(c.effective_length > prev && c.effective_length <= crown.length + 1e-15);
            prev = c.effective_length;
            // Integrate w'(y) = w_peak (1 − g/δ)⁺ numerically: must equal the load.
            let delta_over_w = {
                let b = (4.0 * c.peak_load_per_length * r / (std::f64::consts::PI * es)).sqrt();
                (2.0 * (4.0 * r / b).ln() - 1.0) / (std::f64::consts::PI * es)
            };
            let delta = c.peak_load_per_length * delta_over_w;
            let n = 20_000;
            let mut total = 0.0;
            for i in 0..n {
                let y = -0.007 + 0.014 * (i as f64 + 0.5) / n as f64;
                let g = if y.abs() <= 0.006 {
                    4.5e-6 * (y / 0.006).powi(2)
                } else {
                    4.5e-6 + (y.abs() - 0.006).powi(2) / (2.0 * 0.0125)
                };
                total += (delta - g).max(0.0) / delta_over_w * 0.014 / n as f64;
            }
            assert!((total / load - 1.0).abs() < 1e-3, "load {load}: {total}");
        }
    }

    /// Seed 000 eq. 3 as printed: the closed-form `G(δ)` integrates the printed gap, the load goes
    /// to the transitions first (below the relief the centre is unloaded) and reaches the centre
    /// once the approach exceeds h_td.
    #[test]
    fn printed_profile_loads_the_transitions_first() {
        let crown = Crown { profile: CrownProfile::Seed000Eq3, ..seed000() };
        assert_eq!(crown.gap(0.0), 4.5e-6);
        assert_eq!(crown.gap(0.006), 0.0);
        assert!((crown.gap(0.007) - 1e-6 / (2.0 * 0.0125)).abs() < 1e-18);
        for delta in [1e-6, 4e-6, 6e-6, 3e-5] {
            let (g, dg) = crown.g_integral(delta);
            let n = 200_000;
            let (mut total, mut len) = (0.0, 0.0);
            for i in 0..n {
                let y = -0.007 + 0.014 * (i as f64 + 0.5) / n as f64;
                let d = (delta - crown.gap(y)).max(0.0);
                total += d * 0.014 / n as f64;
                len += if d > 0.0 { 0.014 / n as f64 } else { 0.0 };
            }
            assert!((g / total - 1.0).abs() < 1e-4, "δ {delta}: {g} vs {total}");
            assert!((dg - len).abs() < 1e-6, "δ {delta}: {dg} vs {len}");
        }
        let (r, es) = (0.01037, 2.1e11 / 2.0);
        // 300 N: the centre is not touched (two loaded bands at the transitions).
        let light = crown.distribute(300.0, r, es);
        assert!(light.approach < 4.5e-6 && light.effective_length < 0.5 * 0.014, "{light:?}");
        // The nose (954 N): the centre slice carries (δ − h_td)/δ of the transitions' load per
        // length (measured 0.15).
        let nose = crown.distribute(954.0, r, es);
        let share = (nose.approach - 4.5e-6) / nose.approach;
        assert!(share > 0.0 && share < 0.2, "{nose:?}");
    }

    #[test]
    fn uncrowned_roller_is_a_uniform_line_contact() {
        let flat = Crown { length: 0.014, middle_length: 0.014, crown_height: 0.0, end_radius: f64::INFINITY, profile: CrownProfile::Convex };
        let c = flat.distribute(2000.0, 0.01, 1.15e11);
        assert!((c.effective_length - 0.014).abs() < 1e-12);
        assert!((c.peak_load_per_length - 2000.0 / 0.014).abs() < 1e-6);
    }
}
