//! The backtracking line search of the damped Newton iterations: a step is tried at a first
//! length and halved until a trial is accepted or the halvings run out. [`armijo_backtrack`]
//! accepts on Armijo's sufficient decrease of a merit function (the 1-D and 2-D EHL Newton
//! solvers, `crate::ehl::newton` and `crate::ehl::twod::solver`); [`backtrack`] is the halving
//! loop itself with the caller's acceptance (the journal bearing's load balance and attitude
//! search, which accept on a plain decrease).
//!
//! Only the trial lengths are computed here (`α0`, `α0/2`, `α0/4`, …, each halving exact); the
//! caller's closure evaluates the trial point, so the callers' floating-point operations are
//! their own.

/// Armijo's sufficient-decrease fraction: a trial of length `α` is accepted when its merit is at
/// most `(1 − ARMIJO·α) m0`.
pub const ARMIJO: f64 = 1e-4;

/// Try the step lengths `alpha0`, `alpha0/2`, … (at most `max_halvings` trials) until `trial`
/// accepts one: `trial(α)` evaluates the point at length `α` and returns `Some` (what the caller
/// keeps of it) to accept, `None` to halve. Returns the accepted trial's value, `None` when every
/// trial was rejected; an error of `trial` ends the search.
pub fn backtrack<T, E>(alpha0: f64, max_halvings: u32, mut trial: impl FnMut(f64) -> Result<Option<T>, E>) -> Result<Option<T>, E> {
    let mut alpha = alpha0;
    for _ in 0..max_halvings {
        if let Some(kept) = trial(alpha)? {
            return Ok(Some(kept));
        }
        alpha *= 0.5;
    }
    Ok(None)
}

/// Armijo backtracking from the merit `m0` of the current point: `trial(α)` evaluates the point
/// at step length `α` (the caller keeps it, e.g. in a trial buffer) and returns its merit, or
/// `None` where it cannot be evaluated (a rejected trial). A merit `m` is accepted when
/// `m ≤ (1 − ARMIJO·α) m0` (a NaN merit never is). Returns the accepted length — the last point
/// `trial` evaluated — or `None` after `max_halvings` rejected trials; an error of `trial` (a
/// cancellation check, say) ends the search.
pub fn armijo_backtrack<E>(alpha0: f64, max_halvings: u32, m0: f64, mut trial: impl FnMut(f64) -> Result<Option<f64>, E>) -> Result<Option<f64>, E> {
    backtrack(alpha0, max_halvings, |alpha| {
        let merit = trial(alpha)?;
        Ok(merit.filter(|&m| m <= (1.0 - ARMIJO * alpha) * m0).map(|_| alpha))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::convert::Infallible;

    /// The merit `f(x)²` of a 1-D Newton step on `f`, from `x` along `dx`.
    fn merit_along(f: impl Fn(f64) -> f64, x: f64, dx: f64) -> impl FnMut(f64) -> Result<Option<f64>, Infallible> {
        move |alpha| Ok(Some(f(x + alpha * dx).powi(2)))
    }

    /// A quadratic's Newton step lands on its minimum's neighbourhood: the full step is accepted.
    #[test]
    fn a_quadratic_accepts_the_full_step() {
        // f(x) = x² − 4 from x = 3: dx = −f/f' = −5/6; f(3 − 5/6) = 0.694…, well below 25.
        let f = |x: f64| x * x - 4.0;
        let Ok(alpha) = armijo_backtrack(1.0, 30, f(3.0).powi(2), merit_along(f, 3.0, -5.0 / 6.0));
        assert_eq!(alpha, Some(1.0));
    }

    /// An overshooting step is halved until the merit falls enough, and the trials are the halved
    /// lengths in order.
    #[test]
    fn an_overshooting_step_is_halved() {
        // f(x) = atan(x) from x = 2: the Newton step −f/f' = −5 atan 2 overshoots to x ≈ −3.5,
        // where |f| is larger; half of it lands at ≈ −0.77 (|f| 0.66 < 1.11).
        let f = |x: f64| x.atan();
        let dx = -(2.0f64.atan()) * 5.0;
        let mut tried = Vec::new();
        let mut merit = merit_along(f, 2.0, dx);
        let Ok(alpha) = armijo_backtrack(1.0, 30, f(2.0).powi(2), |a| {
            tried.push(a);
            merit(a)
        });
        assert_eq!(alpha, Some(0.5));
        assert_eq!(tried, vec![1.0, 0.5]);
    }

    /// A direction that never decreases the merit: every halving is tried, none accepted.
    #[test]
    fn an_ascent_direction_is_rejected() {
        let f = |x: f64| x * x + 1.0;
        let mut trials = 0;
        let mut merit = merit_along(f, 1.0, 1.0);
        let Ok(alpha) = armijo_backtrack(1.0, 12, f(1.0).powi(2), |a| {
            trials += 1;
            merit(a)
        });
        assert_eq!(alpha, None);
        assert_eq!(trials, 12);
    }

    /// A point that cannot be evaluated is a rejected trial; a NaN merit is never accepted.
    #[test]
    fn unevaluable_and_nan_trials_are_rejected() {
        let Ok(alpha) = armijo_backtrack(1.0, 5, 1.0, |a: f64| Ok::<_, Infallible>(if a > 0.3 { None } else { Some(0.0) }));
        assert_eq!(alpha, Some(0.25));
        let Ok(alpha) = armijo_backtrack(1.0, 5, 1.0, |_| Ok::<_, Infallible>(Some(f64::NAN)));
        assert_eq!(alpha, None);
    }

    /// An error of the trial ends the search at once.
    #[test]
    fn an_error_ends_the_search() {
        let mut trials = 0;
        let out = armijo_backtrack(1.0, 10, 1.0, |_| {
            trials += 1;
            if trials == 3 { Err("cancelled") } else { Ok(Some(2.0)) }
        });
        assert_eq!(out, Err("cancelled"));
        assert_eq!(trials, 3);
    }

    /// The plain halving loop hands back what the accepting trial kept.
    #[test]
    fn backtrack_returns_the_kept_value() {
        let out = backtrack(1.0, 10, |a| Ok::<_, Infallible>((a < 0.2).then_some(a * 8.0)));
        assert_eq!(out, Ok(Some(1.0)));
    }
}
