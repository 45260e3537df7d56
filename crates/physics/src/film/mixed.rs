//! Mixed lubrication: the asperities share the load with the fluid inside the solution (seed 001
//! eq. 1, 7, 12), in both fidelities.
//!
//! * `accurate` ([`super::Numerical`]): the numerical EHL solver adds the mean asperity pressure
//!   of the local film, `p_a(h(x))`, to the fluid pressure in the load balance and in the elastic
//!   deflection ([`crate::ehl::EhlInput::asperity`]); the relation `p_a(h)` is
//!   [`LoadSharingLaw`] ([`Roughness::load_sharing_pressure`]: Greenwood–Tripp at the
//!   separation that conserves the film's volume, or a tabulated curve, with the plastic cap).
//! * `fast` ([`super::ClosedForm`]): the load-sharing closed form of Johnson, Greenwood & Poon
//!   (Wear 19, 1972) in the form of Gelinck & Schipper (Tribol. Int. 33, 2000): the fluid carries
//!   `W_h = (1 − f_a) W` as a smooth EHL contact whose modulus is scaled alike (`E'(1 − f_a)`, so
//!   that both parts see the same deformation), the asperities carry `W_a = f_a W` at the mean
//!   pressure `p_a(h_c)` over the nominal Hertz area `A` of the full load; [`share_load`] solves
//!   `f_a W = A p_a(h_c(f_a))` for `f_a`, a monotone scalar equation with one root in `[0, 1)`.

use crate::ehl::AsperityPressure;
use crate::friction::Roughness;
use crate::SolveError;

/// The mean asperity pressure of [`Roughness::load_sharing_pressure`] as the EHL solver's
/// load-sharing law. `contact_modulus` is Johnson's `E*` (Greenwood's convention, see
/// [`crate::friction::greenwood_tripp`]).
#[derive(Debug, Clone)]
pub struct LoadSharingLaw {
    pub roughness: Roughness,
    pub contact_modulus: f64,
}

impl AsperityPressure for LoadSharingLaw {
    fn pressure(&self, film: f64) -> (f64, f64) {
        self.roughness.load_sharing_pressure(film, self.contact_modulus)
    }
}

/// The load-sharing fixed point of the closed form: `films(s)` returns the central film (m) of
/// the fluid part carrying the fraction `s` of the load (with the modulus scaled by `s`),
/// `pressure(h)` the mean asperity pressure (Pa) at film `h`, `area` the nominal contact area
/// (m²). Returns the asperity fraction `f_a ∈ [0, 1)` with `|f_a W − A p_a(h_c(1 − f_a))| ≤
/// 1e-9 W` (bisection: `f_a W` grows and `p_a(h_c)` falls as `f_a` grows).
pub fn share_load(load: f64, area: f64, films: impl Fn(f64) -> f64, pressure: impl Fn(f64) -> f64) -> Result<f64, SolveError> {
    let residual = |fa: f64| fa - area * pressure(films(1.0 - fa)) / load;
    let r0 = residual(0.0);
    if !r0.is_finite() {
        return Err(SolveError::invalid("ContactInput.roughness", "the asperity pressure is not finite"));
    }
    if r0 >= 0.0 {
        return Ok(0.0);
    }
    let (mut lo, mut hi) = (0.0_f64, 1.0 - 1e-9);
    if residual(hi) < 0.0 {
        // The asperities carry (almost) everything: a dry contact.
        return Ok(hi);
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        let r = residual(mid);
        if !r.is_finite() {
            return Err(SolveError::invalid("ContactInput.roughness", "the asperity pressure is not finite"));
        }
        if r < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-12 {
            break;
        }
    }
    Ok(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn share_load_closes_the_balance_and_has_the_smooth_limit() {
        // A film growing like s^-0.126 (Pan–Hamrock with W and E' both scaled by s) and an
        // exponential asperity law.
        let films = |s: f64| 0.3e-6 * s.powf(-0.126);
        let p = |h: f64| 5e7 * (-(h / 0.1e-6)).exp();
        let (w, a) = (1e4, 2e-5);
        let fa = share_load(w, a, films, p).unwrap();
        assert!(fa > 0.0 && fa < 1.0);
        assert!((fa * w - a * p(films(1.0 - fa))).abs() < 1e-8 * w, "{fa}");
        assert_eq!(share_load(w, a, films, |_| 0.0).unwrap(), 0.0);
    }
}
