//! Closed-form EHL film thickness formulas. All use Hamrock's reduced modulus `E' = 2E*`
//! ([`crate::contact::effective_modulus`]), the mean entrainment velocity
//! `u = (u1 + u2)/2` (its magnitude: the film does not care which way the oil is dragged), the
//! low-shear viscosity `η0` at the inlet temperature and the low-pressure pressure–viscosity
//! coefficient `α` (`G = αE'`).
//!
//! | formula | contact | central | minimum | fitted to |
//! | --- | --- | --- | --- | --- |
//! | Pan & Hamrock (J. Tribol. 111, 1989) | line | `2.922 W'^-0.166 U^0.692 G^0.470` | `1.714 W'^-0.128 U^0.694 G^0.568` | isothermal, compressible, Roelands numerical solutions in the elastic–piezoviscous regime |
//! | Dowson & Higginson (1977 form) | line | `4/3 h_min` (customary ratio) | `2.65 W'^-0.13 U^0.70 G^0.54` | elastic–piezoviscous regime, Barus |
//! | Kushwaha, Rahnejat & Johns-Rahnejat (seed 003 eq. 17–18) | finite line | `1.67 W*^0.059 U*^0.541 G*^0.421 e^(−96.775 W_s*)` | side constriction `1150 W*^-0.037 U*^0.857 G*^0.406 e^(−138.059 W_s*)` | 18 finite-line EHL runs: G* 5700–9650, W* 0.34e-6–5.6e-6, U* 0.63e-11–3.3e-11, W_s* −0.005–0 (seed 003 Table 3) |
//! | Hamrock & Dowson (1977) | point | `2.69 W^-0.067 U^0.67 G^0.53 (1 − 0.61 e^(−0.73k))` | `3.63 W^-0.073 U^0.68 G^0.49 (1 − e^(−0.68k))` | elliptical contacts, elastic–piezoviscous, k = 1–8 |
//!
//! Line: `W' = w/(E'R)` with `w` the load per unit length; `U = η0 u/(E'R)`; film `h = H R`.
//! Point: `W = F/(E'R_x²)`, `U = η0 u/(E'R_x)`, `h = H R_x`, ellipticity `k = 1.0339 (R_y/R_x)^0.636`
//! (Hamrock & Brewe), entrainment along x.
//! Seed 003: its nomenclature writes `E` for the modulus in `W* = W/(ERL)`, `U* = uη/(ER)`,
//! `G* = αE`; its G* range (5700–9650 for mineral oils on steel) only fits the reduced modulus, so
//! `E = E'` here. `W_s* = ḣ/u` is the squeeze-to-roll ratio (`ḣ = dh/dt`, negative on approach),
//! clamped to the fitted range [−0.005, 0].
//!
//! Pan–Hamrock is implemented once, in `physics::ehl::formulas::pan_hamrock_groups` (below the
//! film models; [`pan_hamrock`] here and the films of `physics::ehl::formulas` call it).
//! Check (issue 5): the two copies that existed carried identical coefficients — the form quoted
//! from Pan & Hamrock (1989) in Hamrock's *Fundamentals of Fluid Film Lubrication* (rectangular
//! conjunctions, mean velocity in `U`, `E'` in all groups); the paper itself is not in the
//! reference corpora available here, so the coefficients rest on that form and on the
//! hand-computed check below. Against the numerical solver (`physics::ehl`, Roelands +
//! Dowson–Higginson, 384 nodes) the regression is within 5 % only at small `L` (≈ 4–7) and
//! moderate `M` (2–100); at `L = 10–20` its central film is 4–26 % thinner (growing with `M`) and
//! its minimum film 2–12 % thinner; at light loads (`M ≤ 1`) its minimum film is 15–38 % thinner
//! (table in [`super::auto`]). These are deviations of the regression (fitted to coarse 1980s
//! solutions with its own Roelands constants), not a coefficient error: the 8–14 % differences
//! reported in issue 5 phase 1 fall in the `L ≥ 10` band.
//!
//! Regime indicators (Johnson 1970, as used by Hamrock for rectangular conjunctions):
//! `g_V = G W'^{3/2}/U^{1/2}` and `g_E = W'/U^{1/2}`. The elastic–piezoviscous formulas above hold
//! when both are large (heavily loaded, hard contacts); light loads or soft/isoviscous oils leave
//! their range — the numerical EHL solver (`accurate` fidelity) covers those.

/// Dimensionless groups of a line contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineGroups {
    /// `W' = w/(E'R)`.
    pub load: f64,
    /// `U = η0 u/(E'R)`.
    pub speed: f64,
    /// `G = αE'`.
    pub material: f64,
}

impl LineGroups {
    pub fn new(load_per_length: f64, reduced_radius: f64, entrainment: f64, eta0: f64, alpha: f64, e_prime: f64) -> Self {
        LineGroups {
            load: load_per_length / (e_prime * reduced_radius),
            speed: eta0 * entrainment.abs() / (e_prime * reduced_radius),
            material: alpha * e_prime,
        }
    }
    /// Johnson's viscous parameter `g_V = G W'^{3/2}/U^{1/2}`.
    pub fn viscous_parameter(&self) -> f64 {
        self.material * self.load.powf(1.5) / self.speed.sqrt()
    }
    /// Johnson's elastic parameter `g_E = W'/U^{1/2}`.
    pub fn elastic_parameter(&self) -> f64 {
        self.load / self.speed.sqrt()
    }
}

/// Goksem & Hargreaves (J. Lubr. Technol. 100, 1978), isothermal: the rolling (Poiseuille)
/// resistance of a fully flooded line contact, dimensionless `F_R α/(L R) = 4.318 (GU)^0.658
/// W'^0.0126` (`F_R` on each surface, N, against the entrainment; `GU = α η0 u/R` does not
/// depend on the modulus convention). The coefficients were quoted from memory of the paper and
/// agree with the thermal-loading form of it used in rolling-bearing codes (at zero thermal
/// loading it reduces to `0.8499 (11.81 GU/W'^{3/2})^0.658 W'`); the test
/// `goksem_hargreaves_matches_the_numerical_rolling_force` checks it against the numerical EHL
/// solution's `∫ (h/2) dp/dx dx`.
pub fn goksem_hargreaves_rolling(g: &LineGroups) -> f64 {
    4.318 * (g.material * g.speed).powf(0.658) * g.load.powf(0.0126)
}

/// Pan–Hamrock line contact `(h_c/R, h_min/R)` (computed by
/// [`crate::ehl::formulas::pan_hamrock_groups`]).
pub fn pan_hamrock(g: &LineGroups) -> (f64, f64) {
    crate::ehl::formulas::pan_hamrock_groups(g.load, g.speed, g.material)
}

/// Dowson–Higginson line contact `(h_c/R, h_min/R)` with `h_c = 4/3 h_min`.
pub fn dowson_higginson(g: &LineGroups) -> (f64, f64) {
    if g.speed == 0.0 {
        return (0.0, 0.0);
    }
    let hm = 2.65 * g.load.powf(-0.13) * g.speed.powf(0.70) * g.material.powf(0.54);
    (4.0 / 3.0 * hm, hm)
}

/// Fitted range of the squeeze-to-roll ratio in seed 003's regression (Table 3).
pub const SEED003_SQUEEZE_RANGE: (f64, f64) = (-0.005, 0.0);

/// Seed 003 eq. 17 (central) and eq. 18 (side-constriction, i.e. minimum, film) as `h/R`, for
/// `W* = W/(E'RL)`, `U* = uη0/(E'R)`, `G* = αE'` and squeeze-to-roll ratio `ws` (clamped to the
/// fitted range).
pub fn seed003(w_star: f64, u_star: f64, g_star: f64, ws: f64) -> (f64, f64) {
    if u_star == 0.0 {
        return (0.0, 0.0);
    }
    let ws = ws.clamp(SEED003_SQUEEZE_RANGE.0, SEED003_SQUEEZE_RANGE.1);
    // seed 003 eq. (17)
    let hc = 1.67 * w_star.powf(0.059) * u_star.powf(0.541) * g_star.powf(0.421) * (-96.775 * ws).exp();
    // seed 003 eq. (18)
    let hsc = 1150.0 * w_star.powf(-0.037) * u_star.powf(0.857) * g_star.powf(0.406) * (-138.059 * ws).exp();
    (hc, hsc)
}

/// Hamrock–Dowson elliptical contact `(h_c/R_x, h_min/R_x)` for `W = F/(E'R_x²)`,
/// `U = η0 u/(E'R_x)`, `G = αE'` and ellipticity `k`.
pub fn hamrock_dowson_point(w: f64, u: f64, g: f64, k: f64) -> (f64, f64) {
    if u == 0.0 {
        return (0.0, 0.0);
    }
    let hc = 2.69 * u.powf(0.67) * g.powf(0.53) * w.powf(-0.067) * (1.0 - 0.61 * (-0.73 * k).exp());
    let hm = 3.63 * u.powf(0.68) * g.powf(0.49) * w.powf(-0.073) * (1.0 - (-0.68 * k).exp());
    (hc, hm)
}

/// Hamrock–Brewe ellipticity `k = 1.0339 (R_y/R_x)^0.636` (entrainment along x).
pub fn ellipticity(rx: f64, ry: f64) -> f64 {
    1.0339 * (ry / rx).powf(0.636)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One film value by hand: seed 001 nose point (Table 1–2): w = 12 500/0.021 N/m,
    /// R = 10.5 mm, u = 3.98 m/s, η0 = 0.013 Pa·s, α = 1.84e-8 1/Pa, E = 200 GPa, ν = 0.3.
    /// E' = 200e9/0.91 = 2.19780e11; W' = 595 238/(2.19780e11·0.0105) = 2.57937e-4;
    /// U = 0.013·3.98/(2.19780e11·0.0105) = 2.24207e-11; G = 4043.96.
    /// H_c = 2.922 · (2.57937e-4)^-0.166 · (2.24207e-11)^0.692 · 4043.96^0.470
    ///     = 2.922 · 3.94175 · 4.27217e-8 · 49.5677 = 2.43903e-5 → h_c = 0.25610 µm
    /// (the paper's full numerical solution gives ≈ 0.27 µm at the nose).
    #[test]
    fn pan_hamrock_by_hand_at_the_seed001_nose() {
        let e_prime = 200e9 / 0.91;
        let g = LineGroups::new(12_500.0 / 0.021, 0.0105, 3.98, 0.013, 1.84e-8, e_prime);
        assert!((g.load / 2.57937e-4 - 1.0).abs() < 1e-5);
        assert!((g.speed / 2.24207e-11 - 1.0).abs() < 1e-5);
        let (hc, hm) = pan_hamrock(&g);
        assert!((hc * 0.0105 / 0.25610e-6 - 1.0).abs() < 1e-4, "h_c = {}", hc * 0.0105);
        assert!(hm < hc);
        assert!((hc * 0.0105 / 0.27e-6 - 1.0).abs() < 0.06);
    }

    #[test]
    fn exponents_behave() {
        let base = LineGroups { load: 1e-4, speed: 1e-11, material: 5000.0 };
        let faster = LineGroups { speed: 2e-11, ..base };
        let ratio = pan_hamrock(&faster).0 / pan_hamrock(&base).0;
        assert!((ratio - 2f64.powf(0.692)).abs() < 1e-12);
        let (c, m) = dowson_higginson(&base);
        assert!((c / m - 4.0 / 3.0).abs() < 1e-12);
        // Squeeze on approach thickens seed 003's film; clamping holds it at the range end.
        let (h0, _) = seed003(1e-6, 1e-11, 8000.0, 0.0);
        let (h1, _) = seed003(1e-6, 1e-11, 8000.0, -0.005);
        let (h2, _) = seed003(1e-6, 1e-11, 8000.0, -0.5);
        assert!((h1 / h0 - (96.775f64 * 0.005).exp()).abs() < 1e-12 && h2 == h1);
        assert_eq!(pan_hamrock(&LineGroups { speed: 0.0, ..base }), (0.0, 0.0));
    }
}
