//! Loads on the follower per cam angle.
//!
//! * Valve train (seed 003 eq. 21, quasi-static): the axial force the cam must supply is
//!   `F_ax = F_preload + k s + m a + F_ext(θ)` (spring preload and rate, moving mass reduced to
//!   the follower, optional external/gas force table). The normal contact force is
//!   `F = F_ax / cos φ` (φ the pressure angle); the friction force's axial component and guide
//!   friction are neglected.
//! * Dynamic: the axial force of the valve-train dynamics (`physics::valvetrain`, seed 003
//!   §4 with compliances), computed over the cycle's angles before the cycle runs.
//! * Spectrum: a measured contact-load table versus cam angle (seed 000 Fig. 4), plus an optional
//!   constant offset (seed 000's "modified load" w1).
//!
//! Tables are periodic in the cam angle and interpolated linearly (no overshoot on steep
//! measured rises). A negative axial force means the follower would leave the cam
//! (separation): the cycle reports it, and refuses contact analyses that would need a load.

use super::kinematics::KinematicState;
use crate::SolveError;
use std::f64::consts::TAU;

/// A periodic table `value(θ)`, linear between points.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicTable {
    angles: Vec<f64>,
    values: Vec<f64>,
}

impl PeriodicTable {
    /// Angles in radians (any order within one revolution after wrapping, distinct), values.
    pub fn new(angles: &[f64], values: &[f64]) -> Result<Self, SolveError> {
        if angles.len() != values.len() || angles.is_empty() {
            return Err(SolveError::invalid("", "a table needs equal-length, non-empty angle and value arrays"));
        }
        let mut pairs: Vec<(f64, f64)> = angles.iter().map(|a| a.rem_euclid(TAU)).zip(values.iter().copied()).collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in pairs.windows(2) {
            if w[1].0 - w[0].0 <= 0.0 {
                return Err(SolveError::invalid("", "table angles must be distinct within one revolution"));
            }
        }
        Ok(PeriodicTable { angles: pairs.iter().map(|p| p.0).collect(), values: pairs.iter().map(|p| p.1).collect() })
    }

    /// Value at `theta` (rad, any real).
    pub fn at(&self, theta: f64) -> f64 {
        let n = self.angles.len();
        if n == 1 {
            return self.values[0];
        }
        let t = theta.rem_euclid(TAU);
        let i = self.angles.partition_point(|&a| a <= t); // first index with angle > t
        let (i0, i1) = if i == 0 { (n - 1, 0) } else if i == n { (n - 1, 0) } else { (i - 1, i) };
        let a0 = self.angles[i0];
        let mut a1 = self.angles[i1];
        let mut tt = t;
        if a1 <= a0 {
            a1 += TAU;
            if tt < a0 {
                tt += TAU;
            }
        }
        let u = (tt - a0) / (a1 - a0);
        self.values[i0] + u * (self.values[i1] - self.values[i0])
    }
}

/// How the follower is loaded.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadModel {
    ValveTrain {
        /// Spring preload at zero lift, N.
        preload: f64,
        /// Spring rate, N/m.
        stiffness: f64,
        /// Moving mass reduced to the follower, kg.
        mass: f64,
        /// External (e.g. gas) force on the follower along its axis, N (positive pushes it onto the
        /// cam).
        external: Option<PeriodicTable>,
    },
    Spectrum {
        /// Normal contact load versus cam angle, N.
        table: PeriodicTable,
        /// Constant added to the table, N.
        offset: f64,
    },
    /// The axial contact force of the valve-train dynamics (`physics::valvetrain`), sampled at
    /// the cycle's angles (the table returns them exactly there).
    Dynamic {
        /// Force along the follower axis versus cam angle, N (0 while separated).
        axial: PeriodicTable,
    },
}

/// Loads at one cam angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowerLoad {
    /// Force along the follower axis, N (negative: separation).
    pub axial: f64,
    /// Normal contact force, N (negative: separation).
    pub contact: f64,
}

impl LoadModel {
    pub fn at(&self, k: &KinematicState) -> FollowerLoad {
        match self {
            LoadModel::ValveTrain { preload, stiffness, mass, external } => {
                let ext = external.as_ref().map_or(0.0, |t| t.at(k.theta));
                let axial = preload + stiffness * k.lift.v + mass * k.acceleration + ext;
                FollowerLoad { axial, contact: axial / k.axial_cosine }
            }
            LoadModel::Dynamic { axial } => {
                let axial = axial.at(k.theta);
                FollowerLoad { axial, contact: axial / k.axial_cosine }
            }
            LoadModel::Spectrum { table, offset } => {
                let contact = table.at(k.theta) + offset;
                FollowerLoad { axial: contact * k.axial_cosine, contact }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_linear_table() {
        let t = PeriodicTable::new(&[0.0, 1.0, 3.0], &[10.0, 20.0, 0.0]).unwrap();
        assert_eq!(t.at(0.5), 15.0);
        assert_eq!(t.at(2.0), 10.0);
        // Wrap from 3.0 back to 2π: value 0 → 10 over 2π − 3.
        let mid = 3.0 + 0.5 * (TAU - 3.0);
        assert!((t.at(mid) - 5.0).abs() < 1e-12);
        assert!((t.at(mid - TAU) - 5.0).abs() < 1e-12);
        assert_eq!(t.at(1.0), 20.0);
        assert!(PeriodicTable::new(&[0.0, TAU], &[1.0, 1.0]).is_err());
    }
}
