//! Shared vocabulary of every solver: convergence reports, termination reasons, typed errors and the
//! observer through which a solver reports progress and learns that it should stop
//! (argmin's observer / termination-reason split, without its generics).

use serde::{Deserialize, Serialize};

/// Why a solver stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// A closed-form evaluation: no iteration was needed.
    ClosedForm,
    /// The residual fell below the tolerance.
    Converged,
    /// The residual stopped decreasing but is within a relaxed acceptance bound; the result is
    /// usable and the report says how far it is from the tolerance.
    Stalled,
}

/// How a solver reached its answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Convergence {
    /// Iterations (or sweeps, or Newton steps: the solver's own unit) performed.
    pub iterations: u32,
    /// Final residual, in the solver's own (documented, usually relative) norm.
    pub residual: f64,
    /// Tolerance the residual was compared against.
    pub tolerance: f64,
    /// Why the solver stopped.
    pub termination: Termination,
}

impl Convergence {
    /// The report of a closed-form evaluation.
    pub fn closed_form() -> Self {
        Self { iterations: 0, residual: 0.0, tolerance: 0.0, termination: Termination::ClosedForm }
    }
}

/// Why a solver was asked to stop before it finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Interrupt {
    /// A user canceled the job.
    Canceled,
    /// The job ran past its time limit.
    TimedOut,
    /// The service is shutting down; the job will be queued again.
    Shutdown,
}

/// Progress and cancellation channel between a running solver and whoever runs it.
///
/// Solvers call [`Observer::check`] once per outer iteration (one sweep, one cam angle, one load
/// balance step) and return `Err(SolveError::Interrupted(..))` when it fails. Progress reports are
/// cheap to call often: implementations throttle them.
pub trait Observer: Sync {
    /// Report the fraction done (0..=1) of the whole job and the current stage.
    fn progress(&self, _fraction: f64, _stage: &str) {}
    /// `Err` when the solver should stop now.
    fn check(&self) -> Result<(), Interrupt> {
        Ok(())
    }
}

/// An observer that ignores progress and never interrupts (tests, benchmarks, nested solves).
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;
impl Observer for Silent {}

/// One stage of a solve whose length is not known in advance (a Newton solve on one grid of a
/// nested iteration): it forwards `check` to the run's observer and reports a progress fraction
/// that moves from `lo` towards `hi` with every check (`lo + (hi − lo)(1 − e^(−k/scale))` after `k`
/// checks), so a long stage still shows progress.
pub struct Stage<'a> {
    outer: &'a dyn Observer,
    lo: f64,
    hi: f64,
    scale: f64,
    name: &'a str,
    checks: std::sync::atomic::AtomicU32,
}

impl<'a> Stage<'a> {
    /// A stage from `lo` to `hi` of the run's progress, named `name`, expected to last about
    /// `scale` checks.
    pub fn new(outer: &'a dyn Observer, lo: f64, hi: f64, scale: f64, name: &'a str) -> Self {
        outer.progress(lo, name);
        Stage { outer, lo, hi, scale: scale.max(1.0), name, checks: std::sync::atomic::AtomicU32::new(0) }
    }
}

impl Observer for Stage<'_> {
    fn progress(&self, fraction: f64, stage: &str) {
        self.outer.progress(self.lo + (self.hi - self.lo) * fraction.clamp(0.0, 1.0), stage);
    }
    fn check(&self) -> Result<(), Interrupt> {
        let k = self.checks.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        self.outer.progress(self.lo + (self.hi - self.lo) * (1.0 - (-(k as f64) / self.scale).exp()), self.name);
        self.outer.check()
    }
}

/// A borrowed observer inside a plain (`Copy`, `Debug`) solver input, e.g. the
/// [`ContactInput`](crate::film::ContactInput) of a film model: the job's cancel, time
/// limit and shutdown reach a film solve through it. Its progress reports are not forwarded (the
/// caller reports the progress of the run as a whole).
#[derive(Clone, Copy)]
pub struct Interrupts<'a>(pub &'a dyn Observer);

impl Interrupts<'static> {
    /// Never interrupts (tests, benchmarks, nested solves).
    pub const NONE: Interrupts<'static> = Interrupts(&Silent);
}

impl Observer for Interrupts<'_> {
    fn check(&self) -> Result<(), Interrupt> {
        self.0.check()
    }
}

impl std::fmt::Debug for Interrupts<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Interrupts")
    }
}

/// Why the physics has no solution for an input: each a stable snake_case problem code
/// ([`PhysicalFailure::code`]), mapped to the HTTP problem in one place (`crate::problem`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PhysicalFailure {
    /// The cam profile does not close over one revolution.
    CamNotClosed,
    /// The cam surface velocity reverses where the model needs one direction.
    CamSurfaceReversal,
    /// The cam is undercut: its pitch curve's radius of curvature turns negative.
    CamUndercut,
    /// The contact point runs off the follower's face.
    ContactOffFace,
    /// The bearing film closes (zero or negative thickness).
    FilmClosed,
    /// The converged EHL film is not positive.
    FilmCollapse,
    /// The follower leaves the cam (the contact load turns negative).
    FollowerSeparation,
    /// The contact carries no positive load.
    NoContactLoad,
    /// There is no entrainment velocity to build a film.
    NoEntrainment,
    /// No attitude angle balances the bearing load.
    NoEquilibriumAttitude,
    /// No journal position balances the bearing load.
    NoEquilibriumPosition,
    /// The design carries no load.
    NoLoad,
    /// The roller torque balance has no root.
    RollerSpeedUnbounded,
    /// A wear run would need more profile updates than allowed for a stable update.
    UpdateLimit,
}

impl PhysicalFailure {
    /// The problem code clients see (`code` of the stored problem).
    pub fn code(self) -> &'static str {
        match self {
            PhysicalFailure::CamNotClosed => "cam_not_closed",
            PhysicalFailure::CamSurfaceReversal => "cam_surface_reversal",
            PhysicalFailure::CamUndercut => "cam_undercut",
            PhysicalFailure::ContactOffFace => "contact_off_face",
            PhysicalFailure::FilmClosed => "film_closed",
            PhysicalFailure::FilmCollapse => "film_collapse",
            PhysicalFailure::FollowerSeparation => "follower_separation",
            PhysicalFailure::NoContactLoad => "no_contact_load",
            PhysicalFailure::NoEntrainment => "no_entrainment",
            PhysicalFailure::NoEquilibriumAttitude => "no_equilibrium_attitude",
            PhysicalFailure::NoEquilibriumPosition => "no_equilibrium_position",
            PhysicalFailure::NoLoad => "no_load",
            PhysicalFailure::RollerSpeedUnbounded => "roller_speed_unbounded",
            PhysicalFailure::UpdateLimit => "update_limit",
        }
    }
}

impl std::fmt::Display for PhysicalFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.code())
    }
}

/// A solver failure. The job layer maps each variant to one problem code.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// An input the validator could not rule out is unusable for this solver (for example a
    /// combination of fields). `field` names the solver input's field (`EhlOptions.nodes`,
    /// `MultiArc.arcs[2]`); the job layer replaces it by the spec's JSON pointer
    /// (`SolveError::in_spec`), which starts with `/`.
    #[error("invalid input {field}: {message}")]
    InvalidInput { field: String, message: String },
    /// The iteration cap was reached before the tolerance.
    #[error("{solver} did not converge: residual {residual:.3e} > tolerance {tolerance:.3e} after {iterations} iterations")]
    NotConverged {
        solver: &'static str,
        iterations: u32,
        residual: f64,
        tolerance: f64,
        /// Residual after each outer iteration (possibly thinned to the last entries).
        history: Vec<f64>,
    },
    /// The physics has no solution for this input (film closed, follower separation, undercut
    /// cam, load beyond capacity...).
    #[error("{message}")]
    Physical { code: PhysicalFailure, message: String },
    /// A NaN or infinity was produced; a bug or an input far outside a model's range.
    #[error("non-finite value in {quantity}")]
    NonFinite { quantity: String },
    /// The solver was asked to stop.
    #[error("interrupted: {0:?}")]
    Interrupted(Interrupt),
}

impl From<Interrupt> for SolveError {
    fn from(i: Interrupt) -> Self {
        SolveError::Interrupted(i)
    }
}

impl SolveError {
    /// Shorthand for [`SolveError::InvalidInput`].
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> Self {
        SolveError::InvalidInput { field: field.into(), message: message.into() }
    }
    /// An input error named in the job spec's terms: `spec_path` maps a solver input field to
    /// the spec's JSON pointer (`None`: the field keeps its solver name). Other errors pass.
    pub fn in_spec(self, spec_path: impl Fn(&str) -> Option<String>) -> Self {
        match self {
            SolveError::InvalidInput { field, message } if !field.starts_with('/') => {
                SolveError::InvalidInput { field: spec_path(&field).unwrap_or(field), message }
            }
            other => other,
        }
    }
    /// Shorthand for [`SolveError::Physical`].
    pub fn physical(code: PhysicalFailure, message: impl Into<String>) -> Self {
        SolveError::Physical { code, message: message.into() }
    }
}

/// NaN quarantine at a chokepoint: `Err(NonFinite)` naming `quantity` unless every value is finite.
pub fn ensure_finite<'a>(
    quantity: &str,
    values: impl IntoIterator<Item = &'a f64>,
) -> Result<(), SolveError> {
    if values.into_iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SolveError::NonFinite { quantity: quantity.to_string() })
    }
}
