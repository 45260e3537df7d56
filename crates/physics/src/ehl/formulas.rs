//! Closed-form line-contact film formulas and the dimensionless groups they use.
//!
//! Hamrock–Dowson groups (all with the EHL modulus `E' = 2E*`, see [`crate::contact`]):
//! `W = w'/(E'R)`, `U = η0 |u_m|/(E'R)` with the mean velocity `u_m`, `G = α E'`. Moes' groups
//! use the *sum* velocity `u1 + u2 = 2u_m` (Venner & Lubrecht's convention): `U_Σ = 2U`,
//! `M = W U_Σ^(−1/2)`, `L = G U_Σ^(1/4)`, film `H_M = (h/R) U_Σ^(−1/2)`.
//!
//! * Moes (1992) central film, the smooth interpolation between the four asymptotes
//!   rigid-isoviscous (Martin), rigid-piezoviscous, elastic-isoviscous (Herrebrugh) and
//!   elastic-piezoviscous (Ertel–Grubin) (Venner & Lubrecht, *Multilevel Methods in Lubrication*,
//!   2000, §8.5).
//! * Pan & Hamrock (1989) regressions of compressible Roelands solutions for the central and
//!   minimum film, valid in the elastic-piezoviscous regime.
//! * Martin's rigid-isoviscous minimum film `h_min = 4.9 η0 u_m R / w'`.
//!
//! Every formula takes the Barus coefficient `α`; for a Roelands lubricant pass
//! [`Lubricant::alpha_star`]'s value or `α` itself (the formula's own convention: Pan–Hamrock fitted
//! Roelands solutions with the low-pressure slope `α`, which is what `pressure_viscosity` is).

use crate::lubricant::Lubricant;

/// Dimensionless groups of a line contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Groups {
    /// Load `W = w'/(E'R)`.
    pub load: f64,
    /// Speed `U = η0 |u_m| /(E'R)` (mean velocity).
    pub speed: f64,
    /// Material `G = α E'`.
    pub material: f64,
    /// Moes load `M = W (2U)^(−1/2)`.
    pub moes_m: f64,
    /// Moes material `L = G (2U)^(1/4)`.
    pub moes_l: f64,
}

impl Groups {
    /// Groups for load per length `w'` (N/m), reduced radius `R` (m), `E'` (Pa), entrainment
    /// `u_m` (m/s, its magnitude is used), ambient viscosity `η0` (Pa·s) and `α` (1/Pa).
    pub fn new(load_per_length: f64, radius: f64, e_prime: f64, speed: f64, eta0: f64, alpha: f64) -> Self {
        let w = load_per_length / (e_prime * radius);
        let u = eta0 * speed.abs() / (e_prime * radius);
        let g = alpha * e_prime;
        let u_sum = 2.0 * u;
        Groups { load: w, speed: u, material: g, moes_m: w / u_sum.sqrt(), moes_l: g * u_sum.powf(0.25) }
    }

    /// Groups of a lubricant at temperature `t` (K): `η0 = η(0, t)`, `α` the lubricant's
    /// low-pressure slope.
    pub fn of(load_per_length: f64, radius: f64, e_prime: f64, speed: f64, lubricant: &Lubricant, t: f64) -> Self {
        let eta0 = lubricant.viscosity_at(0.0, t);
        Self::new(load_per_length, radius, e_prime, speed, eta0, lubricant.pressure_viscosity)
    }
}

/// Moes' central film `H_M = (h_c/R) (2U)^(−1/2)` for line contacts (Venner & Lubrecht §8.5).
pub fn moes_central(m: f64, l: f64) -> f64 {
    let h_ri = 3.0 / m;
    let h_ei = 2.621 * m.powf(-0.2);
    let h_rp = 1.287 * l.powf(2.0 / 3.0);
    let h_ep = 1.311 * m.powf(-0.125) * l.powf(0.75);
    let s = 1.5 * (1.0 + (-1.2 * h_ei / h_ri).exp());
    let a = (h_ri.powf(7.0 / 3.0) + h_ei.powf(7.0 / 3.0)).powf(3.0 / 7.0 * s);
    let b = (h_rp.powf(-3.5) + h_ep.powf(-3.5)).powf(-2.0 / 7.0 * s);
    (a + b).powf(1.0 / s)
}

/// Moes' central film, m.
pub fn moes_central_film(g: &Groups, radius: f64) -> f64 {
    moes_central(g.moes_m, g.moes_l) * radius * (2.0 * g.speed).sqrt()
}

/// Pan–Hamrock central film `h_c/R = 2.922 W^−0.166 U^0.692 G^0.470`, as a film in m (one
/// implementation: [`pan_hamrock_groups`]).
pub fn pan_hamrock_central_film(g: &Groups, radius: f64) -> f64 {
    pan_hamrock_films(g).0 * radius
}

/// Pan–Hamrock minimum film `h_min/R = 1.714 W^−0.128 U^0.694 G^0.568`, m.
pub fn pan_hamrock_minimum_film(g: &Groups, radius: f64) -> f64 {
    pan_hamrock_films(g).1 * radius
}

fn pan_hamrock_films(g: &Groups) -> (f64, f64) {
    pan_hamrock_groups(g.load, g.speed, g.material)
}

/// Pan–Hamrock line contact `(h_c/R, h_min/R)` for `W = load`, `U = speed`, `G = material`: the
/// one implementation (the films above and [`crate::film::formulas::pan_hamrock`] call it; the
/// form and its check in `crate::film::formulas`).
pub fn pan_hamrock_groups(load: f64, speed: f64, material: f64) -> (f64, f64) {
    if speed == 0.0 {
        return (0.0, 0.0);
    }
    // The six powers through three shared logarithms.
    let (lw, lu, lg) = (load.ln(), speed.ln(), material.ln());
    let hc = 2.922 * (-0.166 * lw + 0.692 * lu + 0.470 * lg).exp();
    let hm = 1.714 * (-0.128 * lw + 0.694 * lu + 0.568 * lg).exp();
    (hc, hm)
}

/// Martin's rigid-isoviscous minimum film `h_min = 4.9 η0 u_m R / w'`, m.
pub fn martin_minimum_film(g: &Groups, radius: f64) -> f64 {
    4.9 * g.speed / g.load * radius
}

/// Moes groups of an elliptic point contact (entrainment along x): `W = F/(E'R_x²)`,
/// `U = η0 u_m/(E'R_x)` (mean velocity), `M = W (2U)^(−3/4)`, `L = G (2U)^(1/4)`; films scale as
/// `H = (h/R_x)(2U)^(−1/2)` (Nijenbanning, Venner & Moes, Wear 176 (1994) 217–229, §2).
pub fn point_moes_groups(load: f64, rx: f64, e_prime: f64, speed: f64, eta0: f64, alpha: f64) -> (f64, f64, f64) {
    let w = load / (e_prime * rx * rx);
    let u_sum = 2.0 * eta0 * speed.abs() / (e_prime * rx);
    (w * u_sum.powf(-0.75), alpha * e_prime * u_sum.powf(0.25), u_sum)
}

/// Central film of an elliptic EHL contact in Moes units, `H_c = (h_c/R_x)(2U)^(−1/2)`, by the
/// formula of Nijenbanning, Venner & Moes (Wear 176 (1994) 217–229, eq. 17–21), for the ratio of
/// reduced radii `λ = R_x/R_y` (1: circular; < 1: the major axis of the ellipse across the
/// entrainment, as in rollers) and the Moes parameters `M`, `L` of [`point_moes_groups`]:
/// `H_c = [(H_RI^{3/2} + (H_EI^{−4} + 0.1^4)^{−3/8})^{2s/3} + (H_RP^{−8} + H_EP^{−8})^{−s/8}]^{1/s}`,
/// `s = 1.5 (1 + exp(−1.2 H_EI/H_RI))`, with the asymptotes
/// `H_RI = 145 (1 + 0.796 λ^{14/15})^{−15/7} λ^{−1} M^{−2}`,
/// `H_EI = 3.18 (1 + 0.006 ln λ + 0.63 λ^{4/7})^{−14/25} λ^{−1/15} M^{−2/15}`,
/// `H_RP = 1.29 (1 + 0.691 λ)^{−2/3} L^{2/3}`,
/// `H_EP = 1.48 (1 + 0.006 ln λ + 0.63 λ^{4/7})^{−7/20} M^{−1/12} L^{3/4}`.
/// The paper states agreement with its numerical solutions within a few percent over its survey
/// (M = 3–1000, L = 0–25, λ = 0.04–1; larger deviations, up to ~10 %, at the transitions).
/// The coefficients were transcribed from a secondary memory of the paper, not checked against
/// the printed text in this repository (see `BENCHMARKS.md`, issue 16).
pub fn nijenbanning_central(m: f64, l: f64, lambda: f64) -> f64 {
    let lam = lambda;
    let q = 1.0 + 0.006 * lam.ln() + 0.63 * lam.powf(4.0 / 7.0);
    let h_ri = 145.0 * (1.0 + 0.796 * lam.powf(14.0 / 15.0)).powf(-15.0 / 7.0) / lam * m.powi(-2);
    let h_ei = 3.18 * q.powf(-14.0 / 25.0) * lam.powf(-1.0 / 15.0) * m.powf(-2.0 / 15.0);
    let h_rp = 1.29 * (1.0 + 0.691 * lam).powf(-2.0 / 3.0) * l.powf(2.0 / 3.0);
    let h_ep = 1.48 * q.powf(-7.0 / 20.0) * m.powf(-1.0 / 12.0) * l.powf(0.75);
    let s = 1.5 * (1.0 + (-1.2 * h_ei / h_ri).exp());
    let first = (h_ri.powf(1.5) + (h_ei.powi(-4) + 1e-4).powf(-0.375)).powf(2.0 * s / 3.0);
    let second = if l > 0.0 { (h_rp.powi(-8) + h_ep.powi(-8)).powf(-s / 8.0) } else { 0.0 };
    (first + second).powf(1.0 / s)
}

/// Nijenbanning–Venner–Moes central film, m, of a point contact: load `F` (N), radii `R_x`
/// (entrainment direction) and `R_y` (m), `E'` (Pa), mean speed `u_m` (m/s), `η0` (Pa·s), `α` (1/Pa).
pub fn nijenbanning_central_film(load: f64, rx: f64, ry: f64, e_prime: f64, speed: f64, eta0: f64, alpha: f64) -> f64 {
    let (m, l, u_sum) = point_moes_groups(load, rx, e_prime, speed, eta0, alpha);
    nijenbanning_central(m, l, rx / ry) * rx * u_sum.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moes_tends_to_its_asymptotes() {
        // Rigid-isoviscous: M → 0, L = 0: H = 3/M (Martin's central film 3 U/W·R... in Moes units).
        let h = moes_central(1e-3, 0.0);
        assert!((h / 3e3 - 1.0).abs() < 1e-3, "{h}");
        // Elastic-piezoviscous: large M and L: H → 1.311 M^−1/8 L^3/4.
        let (m, l) = (1e5, 20.0);
        let h = moes_central(m, l);
        let ep = 1.311 * m.powf(-0.125) * l.powf(0.75);
        assert!((h / ep - 1.0).abs() < 0.02, "{h} vs {ep}");
    }

    #[test]
    fn groups_by_hand() {
        // w' = 1e5 N/m, R = 0.01 m, E' = 2.2e11 Pa, u = 2 m/s, η0 = 0.04 Pa·s, α = 2e-8 1/Pa:
        // W = 4.545e-5, U = 3.636e-11, G = 4400; U_Σ = 7.273e-11: M = 5.3300, L = 12.8493.
        let g = Groups::new(1e5, 0.01, 2.2e11, 2.0, 0.04, 2e-8);
        assert!((g.load / 4.5454545e-5 - 1.0).abs() < 1e-6);
        assert!((g.speed / 3.6363636e-11 - 1.0).abs() < 1e-6);
        assert!((g.moes_m / 5.32999 - 1.0).abs() < 1e-5, "{}", g.moes_m);
        assert!((g.moes_l / 12.84923 - 1.0).abs() < 1e-5, "{}", g.moes_l);
    }
}
