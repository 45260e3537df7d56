//! Progressive (variable-pitch) valve springs: the coils grouped by pitch, each group going
//! solid at its own deflection, so that the rate rises as the closely pitched coils close — the
//! standard model of a variable-pitch helical spring (Wahl, *Mechanical Springs*, 2nd ed. 1963,
//! ch. "Springs with variable pitch"; SAE HS-795, *Manual on Design and Application of Helical
//! and Spiral Springs*): the groups are in series and carry the same force; a group of `n_g`
//! coils of pitch `p_g` (wire `d`) closes when its coils touch, at the deflection
//! `n_g (p_g − d)`, i.e. at the force `F_g = K (p_g − d)` with the coil constant
//! `K = G d⁴/(8 D³)` (Shigley eq. 10-9 per coil, independent of the group's coil count). With
//! `n_open` coils still open the rate is `K/n_open`, the active mass and the surge frequency
//! those of `n_open` coils (Shigley eq. 10-24, 10-25).

use super::model::HelicalSpring;

/// A group of coils of one pitch (free spring).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoilGroup {
    /// Active coils of the group.
    pub coils: f64,
    /// Pitch (axial distance of successive coils' centres in the free spring), m (> wire d).
    pub pitch: f64,
}

/// The spring's state at a deflection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProgressiveState {
    /// Force, N.
    pub force: f64,
    /// Tangent rate, N/m (with every group closed: the last open rate; the spring is solid).
    pub rate: f64,
    /// Coils still open (0: every group closed).
    pub active_coils: f64,
}

/// The coil constant `K = G d⁴/(8 D³)`, N/m per coil (a spring of `n` coils has rate `K/n`).
pub fn coil_constant(coil: &HelicalSpring) -> f64 {
    coil.shear_modulus * coil.wire_diameter.powi(4) / (8.0 * coil.mean_diameter.powi(3))
}

/// The groups' closing forces `K (p − d)` (N) with their coils, in the order they close
/// (lowest force first).
pub fn closing_forces(coil: &HelicalSpring, groups: &[CoilGroup]) -> Vec<(f64, f64)> {
    let k = coil_constant(coil);
    let mut out: Vec<(f64, f64)> = groups.iter().map(|g| (k * (g.pitch - coil.wire_diameter), g.coils)).collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// Force, rate and open coils at the deflection `delta` from the free length (m, ≥ 0). With no
/// groups, the uniform spring of `coil.active_coils` (Hooke's law, Shigley eq. 10-9).
pub fn state_at(coil: &HelicalSpring, groups: &[CoilGroup], delta: f64) -> ProgressiveState {
    let k = coil_constant(coil);
    if groups.is_empty() {
        return ProgressiveState { force: coil.rate() * delta, rate: coil.rate(), active_coils: coil.active_coils };
    }
    let mut open: f64 = groups.iter().map(|g| g.coils).sum();
    let (mut f, mut at) = (0.0, 0.0);
    for (fc, coils) in closing_forces(coil, groups) {
        let rate = k / open;
        // Deflection where this group's coils touch: the open coils deflect (F − f)/rate more.
        let closes = at + (fc - f) / rate;
        if delta <= closes {
            return ProgressiveState { force: f + rate * (delta - at), rate, active_coils: open };
        }
        (f, at) = (fc, closes);
        open = (open - coils).max(0.0);
    }
    // Every group closed: solid (the force stays at the last closing force).
    let last = groups.iter().map(|g| g.coils).fold(f64::MAX, f64::min);
    ProgressiveState { force: f, rate: k / last, active_coils: 0.0 }
}

/// Deflection (m) at which every group is closed: `Σ n_g (p_g − d)`.
pub fn closed_deflection(coil: &HelicalSpring, groups: &[CoilGroup]) -> f64 {
    groups.iter().map(|g| g.coils * (g.pitch - coil.wire_diameter)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand calculation: d = 4 mm, D = 24 mm, G = 79.3 GPa: K = G d⁴/(8 D³) = 79.3e9 × 2.56e-10
    /// / (8 × 1.3824e-5) = 183 564 N/m per coil. Two coils of pitch 5 mm (gap 1 mm) and four of
    /// 7.5 mm (gap 3.5 mm): the first group closes at F₁ = K × 1 mm = 183.56 N after
    /// δ₁ = 2 × 1 + 4 × 1 = 6 mm (rate K/6 = 30 594 N/m), then the rate is K/4 = 45 891 N/m up
    /// to F₂ = K × 3.5 mm = 642.5 N at δ₂ = 6 + 4 × 2.5 = 16 mm = Σ n (p − d).
    #[test]
    fn two_pitch_groups_by_hand() {
        let coil = HelicalSpring { wire_diameter: 4e-3, mean_diameter: 24e-3, active_coils: 6.0, shear_modulus: 79.3e9, density: 7850.0 };
        let groups = [CoilGroup { coils: 2.0, pitch: 5e-3 }, CoilGroup { coils: 4.0, pitch: 7.5e-3 }];
        let k = coil_constant(&coil);
        assert!((k - 183_564.0).abs() < 1.0, "{k}");
        let s = state_at(&coil, &groups, 3e-3);
        assert!((s.rate - 30_594.0).abs() < 1.0 && s.active_coils == 6.0);
        assert!((s.force - 91.78).abs() < 0.01, "{}", s.force);
        let s = state_at(&coil, &groups, 6e-3);
        assert!((s.force - 183.56).abs() < 0.01);
        let s = state_at(&coil, &groups, 10e-3);
        assert!((s.rate - 45_891.0).abs() < 1.0 && s.active_coils == 4.0);
        assert!((s.force - (183.564 + 45_891.0 * 4e-3)).abs() < 0.01, "{}", s.force);
        assert!((closed_deflection(&coil, &groups) - 16e-3).abs() < 1e-12);
        let s = state_at(&coil, &groups, 16e-3);
        assert!((s.force - 642.47).abs() < 0.01, "{}", s.force);
        // Uniform pitch: the linear spring.
        let one = [CoilGroup { coils: 6.0, pitch: 7e-3 }];
        let s = state_at(&coil, &one, 5e-3);
        assert!((s.force - coil.rate() * 5e-3).abs() < 1e-9 && (s.rate - coil.rate()).abs() < 1e-9);
    }
}
