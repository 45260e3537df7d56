//! Hertz contact at every angle of the cycle: the contact shapes the film models take, and the
//! contact series (pressure, half-width, load per length, sub-surface shear).

use super::*;

/// The Hertz contact at every angle, column by column.
struct HertzColumns {
    shapes: Vec<ContactShape>,
    max_pressure: Vec<f64>,
    /// Half-width (point contact: the semi-axis along the rolling direction), m.
    half_width: Vec<f64>,
    /// Line contacts only.
    load_per_length: Option<Vec<f64>>,
    /// Crowned rollers only.
    effective_length: Option<Vec<f64>>,
    /// Line contacts only.
    max_shear_stress: Option<Vec<f64>>,
    /// Line contacts only.
    max_shear_depth: Option<Vec<f64>>,
    /// Straight line contacts only (seed 003 eq. 6).
    deflection: Option<Vec<f64>>,
}

impl HertzColumns {
    fn with_capacity(n: usize) -> Self {
        HertzColumns {
            shapes: Vec::with_capacity(n),
            max_pressure: Vec::with_capacity(n),
            half_width: Vec::with_capacity(n),
            load_per_length: None,
            effective_length: None,
            max_shear_stress: None,
            max_shear_depth: None,
            deflection: None,
        }
    }
}

/// Hertz contact at every angle: writes the contact series and returns the contact shapes.
pub(super) fn hertz_contact(spec: &CycleSpec, kin: &[KinematicState], loads: &[FollowerLoad], series: &mut CycleSeries) -> Result<Vec<ContactShape>, SolveError> {
    let es = spec.contact_modulus;
    let unit_line = hertz_line(1.0, 1.0, 1.0);
    let stress = line_stress_maxima(&unit_line, spec.poisson_ratio);
    // Maximum shear stress per unit maximum pressure, its depth per unit half-width.
    let factors = (stress.max_shear.value / unit_line.max_pressure, stress.max_shear.depth / unit_line.half_width);
    let c = match &spec.follower {
        FollowerKind::Flat { contact_length } | FollowerKind::Roller { contact_length, crown: None, .. } => {
            line_columns(kin, loads, *contact_length, es, factors)
        }
        FollowerKind::Roller { crown: Some(crown), .. } => crowned_columns(kin, loads, crown, es, factors),
        FollowerKind::Spherical { face_radius } => point_columns(kin, loads, *face_radius, es)?,
    };
    ensure_finite("hertz contact", c.max_pressure.iter().chain(&c.half_width).chain(c.deflection.iter().flatten()))?;
    series.hertz_max_pressure = Some(c.max_pressure);
    series.hertz_half_width = Some(c.half_width);
    series.load_per_length = c.load_per_length;
    series.effective_length = c.effective_length;
    series.max_shear_stress = c.max_shear_stress;
    series.max_shear_depth = c.max_shear_depth;
    series.contact_deflection = c.deflection;
    Ok(c.shapes)
}

/// Straight line contact of `contact_length` (flat faces, straight rollers).
fn line_columns(kin: &[KinematicState], loads: &[FollowerLoad], contact_length: f64, es: f64, (tau_factor, depth_factor): (f64, f64)) -> HertzColumns {
    let n = kin.len();
    let mut c = HertzColumns::with_capacity(n);
    let (mut w_v, mut t_v, mut d_v) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
    let mut defl = Vec::with_capacity(n);
    for (k, l) in kin.iter().zip(loads) {
        let w = l.contact / contact_length;
        let hz = hertz_line(w, k.reduced_radius, es);
        defl.push(line_contact_deflection(w, contact_length, k.reduced_radius, es));
        c.shapes.push(ContactShape::Line { reduced_radius: k.reduced_radius, length: contact_length });
        c.max_pressure.push(hz.max_pressure);
        c.half_width.push(hz.half_width);
        w_v.push(w);
        t_v.push(tau_factor * hz.max_pressure);
        d_v.push(depth_factor * hz.half_width);
    }
    (c.load_per_length, c.max_shear_stress, c.max_shear_depth) = (Some(w_v), Some(t_v), Some(d_v));
    c.deflection = Some(defl);
    c
}

/// Crowned roller: the load distributed along the crown, the peak load per length taken as the
/// line contact's.
fn crowned_columns(kin: &[KinematicState], loads: &[FollowerLoad], crown: &Crown, es: f64, (tau_factor, depth_factor): (f64, f64)) -> HertzColumns {
    let mut c = HertzColumns::with_capacity(kin.len());
    let (mut w_v, mut e_v, mut t_v, mut d_v) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    // Consecutive angles with the same load and radius (the base circle) reuse the
    // distribution: the same inputs give the same result.
    let mut last: Option<((f64, f64), (crate::geometry::CrownedContact, crate::contact::LineContact))> = None;
    let mut hint = [f64::NAN; 3];
    for (k, l) in kin.iter().zip(loads) {
        let key = (l.contact, k.reduced_radius);
        let (cc, hz) = match last {
            Some((lk, v)) if lk == key => v,
            _ => {
                let cc = crown.distribute_warm(l.contact, k.reduced_radius, es, &mut hint);
                let v = (cc, hertz_line(cc.peak_load_per_length, k.reduced_radius, es));
                last = Some((key, v));
                v
            }
        };
        c.shapes.push(ContactShape::Line { reduced_radius: k.reduced_radius, length: cc.equivalent_length });
        c.max_pressure.push(hz.max_pressure);
        c.half_width.push(hz.half_width);
        w_v.push(cc.peak_load_per_length);
        e_v.push(cc.effective_length);
        t_v.push(tau_factor * hz.max_pressure);
        d_v.push(depth_factor * hz.half_width);
    }
    (c.load_per_length, c.effective_length, c.max_shear_stress, c.max_shear_depth) = (Some(w_v), Some(e_v), Some(t_v), Some(d_v));
    c
}

/// Spherical face of radius `face_radius`: point contact.
fn point_columns(kin: &[KinematicState], loads: &[FollowerLoad], face_radius: f64, es: f64) -> Result<HertzColumns, SolveError> {
    let mut c = HertzColumns::with_capacity(kin.len());
    for (k, l) in kin.iter().zip(loads) {
        let hz = hertz_point(l.contact, k.reduced_radius, face_radius, es)?;
        let ax = if k.reduced_radius <= face_radius { hz.semi_minor } else { hz.semi_major };
        c.shapes.push(ContactShape::Point { rx: k.reduced_radius, ry: face_radius });
        c.max_pressure.push(hz.max_pressure);
        c.half_width.push(ax);
    }
    Ok(c)
}
