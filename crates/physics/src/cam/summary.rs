//! The figures of one cam cycle an engineer reads first: extremes with the cam angle where they
//! occur, and time averages over the revolution (SI, angles in rad). Plain functions of a
//! [`CycleOutput`]; the job layer only renames and converts angles to degrees.

use super::cycle::{CycleOutput, CycleSeries};

/// Extremes and means of a cycle. Per-angle quantities that were not computed leave their
/// figures `None`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CycleSummary {
    pub max_lift: f64,
    pub max_velocity: f64,
    pub max_acceleration: f64,
    pub min_acceleration: f64,
    pub max_abs_jerk: f64,
    /// rad.
    pub max_abs_pressure_angle: f64,
    /// `None` where the cam is nowhere convex.
    pub min_cam_radius_of_curvature: Option<f64>,
    pub min_reduced_radius: f64,
    pub zero_entrainment_count: usize,
    pub min_axial_load: Option<f64>,
    pub max_contact_load: Option<f64>,
    /// `(value, cam angle rad)` pairs.
    pub max_hertz_pressure: Option<(f64, f64)>,
    pub max_subsurface_shear: Option<f64>,
    pub min_film: Option<(f64, f64)>,
    pub min_central_film: Option<f64>,
    pub min_exit_film: Option<f64>,
    pub max_pressure_spike: Option<(f64, f64)>,
    /// Newton steps of the numerical film over the cycle.
    pub newton_steps: Option<f64>,
    pub min_lambda: Option<(f64, f64)>,
    pub max_asperity_load_fraction: Option<f64>,
    pub max_friction_coefficient: Option<f64>,
    /// Time mean of |μ|.
    pub mean_friction_coefficient: Option<f64>,
    pub mean_friction_torque: Option<f64>,
    pub mean_power_loss: Option<f64>,
    /// J over the revolution (the simulated one for a startup).
    pub energy_loss: Option<f64>,
    /// `(|SRR|, angle)` at the largest magnitude.
    pub max_abs_slide_roll_ratio: Option<(f64, f64)>,
    pub mean_slide_roll_ratio: Option<f64>,
    pub max_flash_temperature: Option<(f64, f64)>,
}

/// Index and value of the extreme of `v` by `better` (the first one on ties).
pub fn extreme(v: &[f64], better: impl Fn(f64, f64) -> bool) -> (usize, f64) {
    let mut best = (0, v[0]);
    for (i, &x) in v.iter().enumerate() {
        if better(x, best.1) {
            best = (i, x);
        }
    }
    best
}

/// Time-average of `v` over the revolution: trapezoid in time with the wrap for steady running;
/// for a startup, the value at the end of each step over that step (what the implicit step
/// computes), so that the instant of rest at t = 0 carries no weight.
pub fn time_mean(v: &[f64], time: &[f64], duration: f64, periodic: bool) -> f64 {
    let n = v.len();
    if n == 1 {
        return v[0];
    }
    let mut integral = 0.0;
    if periodic {
        for i in 0..n - 1 {
            integral += 0.5 * (v[i] + v[i + 1]) * (time[i + 1] - time[i]);
        }
        integral += 0.5 * (v[n - 1] + v[0]) * (duration - time[n - 1]);
        integral / duration
    } else {
        for i in 1..n {
            integral += v[i] * (time[i] - time[i - 1]);
        }
        integral / (time[n - 1] - time[0])
    }
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}
fn min(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

/// The summary of a cycle; `periodic` for steady running (a startup is not periodic).
pub fn summarise(out: &CycleOutput, periodic: bool) -> CycleSummary {
    let s: &CycleSeries = &out.series;
    let at = |(i, v): (usize, f64)| (v, s.angle[i]);
    let mean = |v: &[f64]| time_mean(v, &s.time, out.duration, periodic);
    let span = if periodic { out.duration } else { s.time[s.time.len() - 1] - s.time[0] };
    let abs = |v: &[f64]| v.iter().map(|x| x.abs()).collect::<Vec<f64>>();
    CycleSummary {
        max_lift: max(&s.lift),
        max_velocity: max(&s.velocity),
        max_acceleration: max(&s.acceleration),
        min_acceleration: min(&s.acceleration),
        max_abs_jerk: s.jerk.iter().map(|x| x.abs()).fold(0.0, f64::max),
        max_abs_pressure_angle: s.pressure_angle.iter().map(|x| x.abs()).fold(0.0, f64::max),
        min_cam_radius_of_curvature: {
            let k = s.cam_curvature.iter().copied().fold(0.0, f64::max);
            (k > 0.0).then(|| 1.0 / k)
        },
        min_reduced_radius: min(&s.reduced_radius),
        zero_entrainment_count: out.events.zero_entrainment.len(),
        min_axial_load: out.events.min_axial_load,
        max_contact_load: s.contact_load.as_deref().map(max),
        max_hertz_pressure: s.hertz_max_pressure.as_deref().map(|v| at(extreme(v, |a, b| a > b))),
        max_subsurface_shear: s.max_shear_stress.as_deref().map(|v| v.iter().copied().fold(0.0, f64::max)),
        min_film: s.film_min.as_deref().map(|v| at(extreme(v, |a, b| a < b))),
        min_central_film: s.film_central.as_deref().map(min),
        min_exit_film: s.exit_film.as_deref().map(min),
        max_pressure_spike: s.pressure_spike.as_ref().and_then(|v| {
            v.iter()
                .enumerate()
                .filter_map(|(i, x)| x.map(|(p, _)| (i, p)))
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .map(at)
        }),
        newton_steps: s.newton_steps.as_ref().map(|v| v.iter().map(|&k| f64::from(k)).sum()),
        min_lambda: s.lambda.as_deref().map(|v| at(extreme(v, |a, b| a < b))),
        max_asperity_load_fraction: s.asperity_load_fraction.as_deref().map(|v| v.iter().copied().fold(0.0, f64::max)),
        max_friction_coefficient: s.friction_coefficient.as_deref().map(|v| v.iter().map(|x| x.abs()).fold(0.0, f64::max)),
        mean_friction_coefficient: s.friction_coefficient.as_deref().map(|v| mean(&abs(v))),
        mean_friction_torque: s.friction_torque.as_deref().map(mean),
        mean_power_loss: s.power_loss.as_deref().map(mean),
        energy_loss: s.power_loss.as_deref().map(|v| mean(v) * span),
        max_abs_slide_roll_ratio: s.slide_roll_ratio.as_deref().map(|v| {
            let (i, _) = extreme(v, |a, b| a.abs() > b.abs());
            (v[i].abs(), s.angle[i])
        }),
        mean_slide_roll_ratio: s.slide_roll_ratio.as_deref().map(mean),
        max_flash_temperature: s.flash_temperature.as_deref().map(|v| at(extreme(v, |a, b| a > b))),
    }
}

/// A flat follower face of finite radius: where its centre sits across the contact (the
/// follower axis, offset from the cam centre line) and its radius, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatFace {
    pub centre: f64,
    pub radius: f64,
}

/// `Err(ContactOffFace)` when the contact leaves the face at some angle.
pub fn check_contact_on_face(series: &CycleSeries, face: FlatFace) -> Result<(), crate::SolveError> {
    let off = series.contact_offset.iter().map(|x| x - face.centre).enumerate().find(|(_, x)| x.abs() > face.radius);
    match off {
        None => Ok(()),
        Some((i, x)) => Err(crate::SolveError::physical(
            crate::PhysicalFailure::ContactOffFace,
            format!(
                "the contact runs off the follower face at {:.2}° ({:.3} mm from its centre, face radius {:.3} mm)",
                series.angle[i].to_degrees(),
                x * 1e3,
                face.radius * 1e3
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_mean_of_a_constant_and_of_a_full_sine() {
        let n = 360;
        let duration = 0.02;
        let time: Vec<f64> = (0..n).map(|i| duration * i as f64 / n as f64).collect();
        assert!((time_mean(&vec![3.5; n], &time, duration, true) - 3.5).abs() < 1e-12);
        let sine: Vec<f64> = time.iter().map(|t| (std::f64::consts::TAU * t / duration).sin()).collect();
        assert!(time_mean(&sine, &time, duration, true).abs() < 1e-12);
        // Startup: the first instant carries no weight.
        let mut v = vec![1.0; n];
        v[0] = 1e6;
        assert!((time_mean(&v, &time, duration, false) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn extreme_takes_the_first_of_equal_values() {
        assert_eq!(extreme(&[1.0, 3.0, 3.0, 2.0], |a, b| a > b), (1, 3.0));
        assert_eq!(extreme(&[1.0, -3.0, 2.0], |a, b| a.abs() > b.abs()), (1, -3.0));
    }
}
