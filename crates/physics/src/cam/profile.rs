//! Cam profiles and the follower lift they produce.
//!
//! Conventions (all of `physics::cam`): the cam angle `θ` (rad) is the angle the cam has turned in
//! its running direction; profiles are described in the order the follower meets them, so the
//! running direction only matters for an offset follower (the kinematics mirror the offset for
//! clockwise running). In the cam frame a contact normal is labelled by its *contact angle* `γ`,
//! the cam angle at which a flat-faced follower touches that normal: `n(γ) = (sin γ, cos γ)`,
//! `γ = 0` pointing at the follower at `θ = 0`.
//!
//! * [`CamProfile::Program`] ([`LiftProgram`]): a rise–dwell–return–dwell law defines the follower lift directly.
//! * [`CamProfile::Synthesised`]: a lift law synthesised from lift, duration, ramps and dwell
//!   ([`super::synthesis`]).
//! * [`CamProfile::Tabulated`]: a measured follower lift table, interpolated by a periodic cubic spline.
//! * [`MultiArc`]: a cam built of tangent circular arcs (seed 004 Tables 1–2); the lift follows
//!   from the geometry and depends on the follower (flat face: support function; roller or
//!   spherical face: the pitch curve, arcs of radius `r_i + R_f` on the same centres).

use super::jet::Jet;
use super::lift::LiftProgram;
use super::spline::PeriodicSpline;
use super::synthesis::SynthesisedLift;
use crate::SolveError;
use std::f64::consts::TAU;
#[cfg(test)]
use std::f64::consts::PI;

/// How the follower touches the cam, as far as the lift is concerned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FollowerShape {
    /// Flat face perpendicular to the follower axis.
    Flat,
    /// A circular face of `radius` (roller, or spherical tappet in its plane of motion) centred on
    /// the follower axis, which is offset by `offset` (m) from the cam centre.
    Curved { radius: f64, offset: f64 },
}

/// One circular arc of a multi-arc cam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Radius of curvature, m (> 0, convex).
    pub radius: f64,
    /// Contact angle where the arc starts, rad.
    pub start: f64,
    /// Angle the normal turns along the arc (its central angle), rad.
    pub span: f64,
    /// Centre in the cam frame, m.
    pub centre: (f64, f64),
}

impl Arc {
    /// True arc length `r·Δγ`, m. (Seed 004 eq. 1 prints `2αr/360`, a factor π short.)
    pub fn length(&self) -> f64 {
        self.radius * self.span
    }
}

/// A closed convex cam made of tangent circular arcs.
#[derive(Debug, Clone, PartialEq)]
pub struct MultiArc {
    pub arcs: Vec<Arc>,
}

fn normal(gamma: f64) -> (f64, f64) {
    let (s, c) = gamma.sin_cos();
    (s, c)
}

impl MultiArc {
    /// Arcs `(radius, central angle)` in the order the follower meets them. The first arc is the
    /// base circle: centred on the rotation axis and centred on `θ = 0`. Consecutive arcs are
    /// tangent. The angles must add up to 2π and the chain must close on itself (gap below
    /// 1e-6 of the base radius), otherwise `cam_not_closed` with the gap.
    pub fn new(arcs: &[(f64, f64)]) -> Result<Self, SolveError> {
        if arcs.len() < 2 {
            return Err(SolveError::invalid("MultiArc.arcs", "a multi-arc cam needs at least 2 arcs"));
        }
        for (i, &(r, a)) in arcs.iter().enumerate() {
            if !(r > 0.0 && r.is_finite() && a > 0.0 && a.is_finite()) {
                return Err(SolveError::invalid(
                    format!("MultiArc.arcs[{i}]"),
                    "radius and angle must be finite and > 0",
                ));
            }
        }
        let total: f64 = arcs.iter().map(|a| a.1).sum();
        if (total - TAU).abs() > 1e-9 {
            return Err(SolveError::physical(
                crate::PhysicalFailure::CamNotClosed,
                format!("the arc angles add up to {:.6}°, not 360°", total.to_degrees()),
            ));
        }
        let mut out = Vec::with_capacity(arcs.len());
        let mut centre = (0.0, 0.0);
        let mut start = -0.5 * arcs[0].1;
        for (i, &(r, span)) in arcs.iter().enumerate() {
            if i > 0 {
                let (nx, ny) = normal(start);
                let dr = arcs[i - 1].0 - r;
                centre = (centre.0 + dr * nx, centre.1 + dr * ny);
            }
            out.push(Arc { radius: r, start, span, centre });
            start += span;
        }
        // Closing: from the last arc back to the base circle.
        let (nx, ny) = normal(start);
        let dr = arcs[arcs.len() - 1].0 - arcs[0].0;
        let end = (centre.0 + dr * nx, centre.1 + dr * ny);
        let gap = end.0.hypot(end.1);
        if gap > 1e-6 * arcs[0].0 {
            return Err(SolveError::physical(
                crate::PhysicalFailure::CamNotClosed,
                format!(
                    "the arcs do not close: the chain of centres misses the cam centre by {:.4} mm \
                     (tangent arcs with these radii and angles do not form a closed cam)",
                    gap * 1e3
                ),
            ));
        }
        Ok(MultiArc { arcs: out })
    }

    /// A cam symmetric about its nose (at `θ = 180°`): base circle `base_radius` over
    /// `base_angle`, then the flank arcs `(radius, angle)` from the base circle towards the nose;
    /// the nose arc's radius is whatever closes the cam, and the other flank mirrors the first.
    pub fn symmetric(base_radius: f64, base_angle: f64, flanks: &[(f64, f64)]) -> Result<Self, SolveError> {
        let mut gamma = 0.5 * base_angle;
        let mut centre = (0.0, 0.0);
        let mut prev_r = base_radius;
        for &(r, span) in flanks {
            let (nx, ny) = normal(gamma);
            centre = (centre.0 + (prev_r - r) * nx, centre.1 + (prev_r - r) * ny);
            prev_r = r;
            gamma += span;
        }
        let nose_span = TAU - 2.0 * gamma;
        if !(nose_span > 0.0) {
            return Err(SolveError::physical(
                crate::PhysicalFailure::CamNotClosed,
                format!("base and flank angles add up to {:.4}° > 360°", (2.0 * gamma).to_degrees()),
            ));
        }
        // Nose centre on the symmetry axis (x = 0): c_x + (r_prev − r_nose) sin γ = 0.
        let s = gamma.sin();
        let nose_r = if s.abs() < 1e-12 { f64::NAN } else { prev_r + centre.0 / s };
        if !(nose_r > 0.0 && nose_r.is_finite()) {
            return Err(SolveError::physical(
                crate::PhysicalFailure::CamNotClosed,
                format!(
                    "no convex nose arc closes this cam (the closing radius would be {:.3} mm): \
                     reduce the flank angles or radii",
                    nose_r * 1e3
                ),
            ));
        }
        let mut arcs = vec![(base_radius, base_angle)];
        arcs.extend_from_slice(flanks);
        arcs.push((nose_r, nose_span));
        arcs.extend(flanks.iter().rev());
        // Rounding may leave the angle sum a few ulps off 2π; it is exact by construction.
        let total: f64 = arcs.iter().map(|a| a.1).sum();
        arcs[0].1 += TAU - total;
        MultiArc::new(&arcs)
    }

    /// Base circle radius (the first arc).
    pub fn base_radius(&self) -> f64 {
        self.arcs[0].radius
    }

    /// Index of the arc holding contact angle `gamma`.
    fn arc_at(&self, gamma: f64) -> usize {
        let g0 = self.arcs[0].start;
        let g = g0 + (gamma - g0).rem_euclid(TAU);
        self.arcs.iter().rposition(|a| a.start <= g).unwrap_or(0)
    }

    /// Lift and derivatives for a flat follower: support function minus base radius.
    fn flat_lift(&self, theta: f64) -> Jet {
        let arc = &self.arcs[self.arc_at(theta)];
        let t = Jet::variable(theta);
        // h(θ) = c · n(θ) + r with n = (sin θ, cos θ).
        t.sin() * arc.centre.0 + t.cos() * arc.centre.1 + (arc.radius - self.base_radius())
    }

    /// Lift for a curved follower of radius `rf` on an axis offset by `e`: the roller centre on
    /// the pitch arc (radius `r_i + rf`) of the active arc.
    fn curved_lift(&self, theta: f64, rf: f64, e: f64) -> Jet {
        let y0 = ((self.base_radius() + rf).powi(2) - e * e).sqrt();
        let t = Jet::variable(theta);
        let (st, ct) = (t.sin(), t.cos());
        let candidate = |arc: &Arc| -> Option<(Jet, f64)> {
            let (cx, cy) = arc.centre;
            let gx = ct * cx - st * cy;
            let gy = st * cx + ct * cy;
            let rho = arc.radius + rf;
            let dx = (gx - e).scale(-1.0); // e − c_gx
            let q2 = rho * rho - dx.v * dx.v;
            if q2 <= 0.0 {
                return None;
            }
            let q = (Jet::constant(rho * rho) - dx * dx).sqrt();
            let y = gy + q;
            // Contact angle of this solution: γ = θ + atan2(N_x, N_y), N = (C − c_g)/ρ.
            let gamma = theta + (dx.v).atan2(q.v);
            let rel = (gamma - arc.start).rem_euclid(TAU);
            // Distance outside the arc's span (0 inside).
            let outside = if rel <= arc.span { 0.0 } else { (rel - arc.span).min(TAU - rel) };
            Some((y - y0, outside))
        };
        let mut best: Option<(Jet, f64)> = None;
        for arc in &self.arcs {
            if let Some((s, out)) = candidate(arc) {
                if out == 0.0 {
                    return s;
                }
                if best.as_ref().map_or(true, |b| out < b.1) {
                    best = Some((s, out));
                }
            }
        }
        best.map(|b| b.0).unwrap_or(Jet::constant(f64::NAN))
    }
}

/// The cam, as far as the follower motion is concerned.
#[derive(Debug, Clone, PartialEq)]
pub enum CamProfile {
    /// A lift program on a base circle of `base_radius` (m).
    Program { base_radius: f64, program: LiftProgram },
    /// A synthesised lift law ([`SynthesisedLift`]: ramps, main rise, dwell, return) on a base
    /// circle of `base_radius` (m).
    Synthesised { base_radius: f64, law: SynthesisedLift },
    /// A measured lift table on a base circle of `base_radius` (m).
    Tabulated { base_radius: f64, spline: PeriodicSpline },
    /// Circular arcs.
    MultiArc(MultiArc),
    /// A profile worn by `wear`: the follower lift of `original` minus the lift drop `wear(θ)`
    /// (m, a periodic spline over the cam angle), same base radius. The wear kind rebuilds the
    /// profile this way after every update, so the original stays exact and only the (smooth)
    /// wear correction is interpolated.
    Worn { original: Box<CamProfile>, wear: PeriodicSpline },
}

impl CamProfile {
    pub fn base_radius(&self) -> f64 {
        match self {
            CamProfile::Program { base_radius, .. }
            | CamProfile::Synthesised { base_radius, .. }
            | CamProfile::Tabulated { base_radius, .. } => *base_radius,
            CamProfile::MultiArc(m) => m.base_radius(),
            CamProfile::Worn { original, .. } => original.base_radius(),
        }
    }

    /// Follower lift `s(θ)` with exact derivatives (rad⁻ᵏ), for this follower shape.
    pub fn lift(&self, theta: f64, follower: FollowerShape) -> Jet {
        match self {
            CamProfile::Program { program, .. } => program.lift(theta),
            CamProfile::Synthesised { law, .. } => law.lift(theta),
            CamProfile::Tabulated { spline, .. } => spline.eval(theta),
            CamProfile::MultiArc(m) => match follower {
                FollowerShape::Flat => m.flat_lift(theta),
                FollowerShape::Curved { radius, offset } => m.curved_lift(theta, radius, offset),
            },
            CamProfile::Worn { original, wear } => original.lift(theta, follower) - wear.eval(theta),
        }
    }

    /// Cam angle of the maximum lift (the nose), rad, by sampling at 0.1°.
    pub fn nose_angle(&self, follower: FollowerShape) -> f64 {
        let n = 3600;
        (0..n)
            .map(|i| TAU * i as f64 / n as f64)
            .fold((0.0, f64::NEG_INFINITY), |(ba, bv), a| {
                let v = self.lift(a, follower).v;
                if v > bv { (a, v) } else { (ba, bv) }
            })
            .0
    }
}

/// Degrees to radians, wrapped into `[0, 2π)`.
pub fn wrap(angle: f64) -> f64 {
    angle.rem_euclid(TAU)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eccentric_three_arc() -> MultiArc {
        MultiArc::symmetric(0.0215, 232f64.to_radians(), &[(0.1533, 7.2f64.to_radians())]).unwrap()
    }

    #[test]
    fn symmetric_cam_closes_and_has_the_expected_nose() {
        let cam = eccentric_three_arc();
        assert_eq!(cam.arcs.len(), 4);
        let nose = cam.arcs[2];
        // Nose centre on the axis, nose in the middle at γ = 180°.
        assert!(nose.centre.0.abs() < 1e-12);
        assert!(((nose.start + 0.5 * nose.span) - PI).abs() < 1e-12);
        // Flat-follower lift at the nose = −c_y + r_n − r_b (support function at n = (0, −1)).
        let lift = cam.flat_lift(PI).v;
        assert!((lift - (-nose.centre.1 + nose.radius - 0.0215)).abs() < 1e-12);
        assert!(lift > 0.009 && lift < 0.011, "lift {lift}");
    }

    #[test]
    fn seed004_arcs_do_not_close() {
        // Seed 004 Tables 1–2: 116°, 62.75°, 1.25°, 1.25°, 62.75°, 116° with radii 21.5, 153.3,
        // 31.5, 31.5, 153.3, 21.5 mm: tangent arcs with these values leave a gap (documented).
        let arcs: Vec<(f64, f64)> = [(21.5, 116.0), (153.3, 62.75), (31.5, 1.25), (31.5, 1.25), (153.3, 62.75), (21.5, 116.0)]
            .iter()
            .map(|&(r, a): &(f64, f64)| (r * 1e-3, a.to_radians()))
            .collect();
        // The first and last arcs are both the base circle: merge them (116° + 116° centred on 0).
        let merged: Vec<(f64, f64)> = std::iter::once((arcs[0].0, arcs[0].1 + arcs[5].1)).chain(arcs[1..5].iter().copied()).collect();
        match MultiArc::new(&merged) {
            Err(SolveError::Physical { code, .. }) => assert_eq!(code, crate::PhysicalFailure::CamNotClosed),
            other => panic!("expected cam_not_closed, got {other:?}"),
        }
    }

    #[test]
    fn flat_follower_curvature_radius_is_the_arc_radius() {
        // r_b + s + s'' equals the radius of the arc in contact (support-function identity).
        let cam = eccentric_three_arc();
        // Base ±116°, flanks 116°–123.2° and 236.8°–244°, nose between.
        for (theta, arc) in [(0.3, 0), (4.5, 0), (2.07, 1), (PI, 2), (4.19, 3)] {
            let j = cam.flat_lift(theta);
            assert_eq!(cam.arc_at(theta), arc, "θ = {theta}");
            let rho = 0.0215 + j.v + j.d2;
            assert!((rho - cam.arcs[arc].radius).abs() < 1e-12, "θ = {theta}: {rho}");
        }
    }

    #[test]
    fn roller_on_base_circle_and_nose() {
        let cam = eccentric_three_arc();
        let rf = 0.01;
        let base = cam.curved_lift(0.2, rf, 0.0);
        assert!(base.v.abs() < 1e-15 && base.d1.abs() < 1e-15);
        // At the nose the roller centre sits at |c_n| + r_n + rf from the cam centre.
        let nose = cam.arcs[2];
        let top = cam.curved_lift(PI, rf, 0.0);
        let expect = -nose.centre.1 + nose.radius + rf - (0.0215 + rf);
        assert!((top.v - expect).abs() < 1e-12, "{} vs {}", top.v, expect);
        // Lift is continuous across arc junctions (tangent arcs): sample finely.
        let dt = TAU / 3600.0;
        let mut prev = cam.curved_lift(0.0, rf, 0.0);
        for i in 1..=3600 {
            let j = cam.curved_lift(dt * i as f64, rf, 0.0);
            // Taylor step from the previous angle: a jump would show far above O(dθ²).
            let predicted = prev.v + prev.d1 * dt + 0.5 * prev.d2 * dt * dt;
            assert!((j.v - predicted).abs() < 1e-7, "jump at step {i}");
            prev = j;
        }
    }

    #[test]
    fn arc_length_is_radius_times_angle() {
        // Seed 004 Table 2 prints l = 2αr/360 (13.856 mm for 116°, 21.5 mm): the true length is
        // π times that.
        let a = Arc { radius: 21.5, start: 0.0, span: 116f64.to_radians(), centre: (0.0, 0.0) };
        assert!((a.length() / (2.0 * 116.0 * 21.5 / 360.0) - PI).abs() < 1e-12);
    }
}
