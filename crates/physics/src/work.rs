//! Work counters of the film models inside a cam cycle (development aid, issue 16: where the
//! finite-length cycle's time goes). Process-wide relaxed atomics, incremented a few times per
//! film solve or per roller step and once per 2-D traction evaluation; they never change a
//! result. `benches/ehl2d.rs -- cycle` resets and prints them around one run (a concurrent run in
//! the same process would add to them). Counted by the film models, the 2-D solver's Newton
//! steps and the roller march, so they live below all three (also reachable as `film::work`).

use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

macro_rules! counters {
    ($($(#[$doc:meta])* $name:ident),* $(,)?) => {
        $($(#[$doc])* pub static $name: AtomicU64 = AtomicU64::new(0);)*
        /// Every counter as `(name, value)`.
        pub fn snapshot() -> Vec<(&'static str, u64)> {
            vec![$((stringify!($name), $name.load(Relaxed))),*]
        }
        /// Set every counter to zero.
        pub fn reset() {
            $($name.store(0, Relaxed);)*
        }
    };
}

counters! {
    /// 2-D Newton solves ([`crate::film::Finite`]): warm-started or cold.
    FINITE_SOLVES,
    /// Of those, the cold nested iteration (no usable warm start, or the warm start failed).
    FINITE_COLD,
    /// Newton steps of those solves (as reported, incl. the resolution check's are not counted).
    FINITE_NEWTON_STEPS,
    /// Numeric factorisations of the 2-D Newton preconditioner (near-field sparse LU) and GMRES
    /// iterations, over every 2-D solve (also outside a cam cycle), resolution checks included.
    FINITE_FACTORISATIONS,
    FINITE_GMRES_ITERATIONS,
    /// 2-D films taken from a neighbouring solution by the entrainment rescale instead of a solve.
    FINITE_RESCALED,
    /// Traction evaluations over a 2-D film's nodes, and the nodes summed by them.
    FINITE_TRACTION_EVALUATIONS,
    FINITE_TRACTION_NODES,
    /// Roller march: film requests at an angle without a cached film within the entrainment
    /// tolerance (a new angle, or a later cycle whose predicted entrainment moved).
    MARCH_FILM_NEW,
    /// Roller march: films re-solved because the converged entrainment moved by more than the
    /// model's tolerance from the film's (the passes of `step`).
    MARCH_FILM_PASS,
    /// Roller march: a dwell's previous-angle film reused as it is.
    MARCH_FILM_DWELL,
    /// Roller march: steps (angles marched, over all cycles) and slip solves.
    MARCH_STEPS,
    MARCH_SLIP_SOLVES,
    /// Thermal finite-line model ([`crate::ehl::thermal_finite`]): energy passes over the rows
    /// (coupling, final and traction probes), the rows' energy solves in them and their sweeps.
    THERMAL_2D_PASSES,
    THERMAL_2D_ROW_SOLVES,
    THERMAL_2D_SWEEPS,
    /// Of the passes: the traction probes at another slip ([`crate::film::ThermalFinite`]).
    THERMAL_2D_PROBES,
}

/// Add `n` to `counter`.
pub fn add(counter: &AtomicU64, n: u64) {
    counter.fetch_add(n, Relaxed);
}
