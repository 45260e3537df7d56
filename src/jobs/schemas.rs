//! OpenAPI schemas of the physics types that specs and results carry as they are (a lift law, a
//! film formula, a convergence report): the transport description lives here, with the spec and
//! result types, so that the physics crate knows nothing of `utoipa`. Each is a documented mirror
//! deriving `ToSchema` under the physics type's name, named at each field that carries the physics
//! type (`#[schema(value_type = FidelityDoc)]`); an exhaustive match keeps its variants (fields)
//! those of the physics type, and a test that they serialise alike.

use crate::physics::cam::LiftLaw;
use crate::physics::film::{Fidelity, FilmFormula, FilmModelId};
use crate::physics::friction::SlipRegime;
use crate::physics::lubricant::{DensityModel, ViscosityModel};
use crate::physics::{Convergence, Termination};

/// A unit enum's mirror: the same variants (checked by an exhaustive match) and serde names.
macro_rules! enum_mirror {
    ($(#[$doc:meta])* $mirror:ident as $name:ident for $phys:ident { $($(#[$vattr:meta])* $variant:ident),* $(,)? }) => {
        $(#[$doc])*
        #[derive(utoipa::ToSchema, serde::Serialize)]
        #[schema(as = $name)]
        #[serde(rename_all = "snake_case")]
        #[allow(dead_code)]
        pub(crate) enum $mirror {
            $($(#[$vattr])* $variant),*
        }
        impl From<$phys> for $mirror {
            fn from(x: $phys) -> Self {
                match x {
                    $($phys::$variant => $mirror::$variant),*
                }
            }
        }
        impl $mirror {
            fn agrees() -> bool {
                [$($phys::$variant),*].into_iter().all(|x| serde_json::to_value(x).ok() == serde_json::to_value($mirror::from(x)).ok())
            }
        }
    };
}

enum_mirror! {
    /// Why a solver stopped.
    TerminationDoc as Termination for Termination { ClosedForm, Converged, Stalled }
}

enum_mirror! {
    /// Model fidelity requested by a spec.
    FidelityDoc as Fidelity for Fidelity { Fast, Accurate, Auto }
}

enum_mirror! {
    /// Film formula of a line contact (point contacts always use Hamrock–Dowson).
    FilmFormulaDoc as FilmFormula for FilmFormula { PanHamrock, DowsonHigginson, Seed003 }
}

enum_mirror! {
    /// Which model produced a film solution. The `*_mixed` variants are the same models with rough
    /// surfaces sharing the load inside the solution ([`mixed`]): their asperity load is part of the
    /// load balance (numerical: of the elastic deflection too), not evaluated afterwards.
    FilmModelIdDoc as FilmModelId for FilmModelId {
        PanHamrock, DowsonHigginson, Seed003, HamrockDowson, Numerical, Thermal, ThermalCarried, PanHamrockMixed,
        DowsonHigginsonMixed, Seed003Mixed, HamrockDowsonMixed, NumericalMixed, Finite, ThermalFinite,
    }
}

enum_mirror! {
    /// A normalised rise law.
    LiftLawDoc as LiftLaw for LiftLaw {
        Cycloidal,
        #[serde(rename = "polynomial_345")]
        Polynomial345,
        #[serde(rename = "polynomial_4567")]
        Polynomial4567,
        SimpleHarmonic,
    }
}

enum_mirror! {
    /// Pressure–viscosity law.
    ViscosityModelDoc as ViscosityModel for ViscosityModel { Barus, Roelands }
}

enum_mirror! {
    /// Density law.
    DensityModelDoc as DensityModel for DensityModel { Incompressible, DowsonHigginson }
}

enum_mirror! {
    /// How the roller runs on the cam at one instant (seed 001 §"Tangential contact", eq. 15–23).
    SlipRegimeDoc as SlipRegime for SlipRegime { Rolling, MicroSlip, GrossSliding }
}

/// How a solver reached its answer.
#[derive(utoipa::ToSchema)]
#[schema(as = Convergence)]
#[allow(dead_code)]
pub(crate) struct ConvergenceDoc {
    /// Iterations (or sweeps, or Newton steps: the solver's own unit) performed.
    iterations: u32,
    /// Final residual, in the solver's own (documented, usually relative) norm.
    residual: f64,
    /// Tolerance the residual was compared against.
    tolerance: f64,
    /// Why the solver stopped.
    termination: TerminationDoc,
}

impl From<Convergence> for ConvergenceDoc {
    fn from(c: Convergence) -> Self {
        // Exhaustive: a new field of the physics type must be documented here.
        let Convergence { iterations, residual, tolerance, termination } = c;
        ConvergenceDoc { iterations, residual, tolerance, termination: termination.into() }
    }
}

/// Whether every mirror serialises as its physics type (the test `service_units::schemas`).
#[doc(hidden)]
pub fn mirrors_agree() -> bool {
    let _ = ConvergenceDoc::from(Convergence::closed_form());
    TerminationDoc::agrees()
        && FidelityDoc::agrees()
        && FilmFormulaDoc::agrees()
        && FilmModelIdDoc::agrees()
        && LiftLawDoc::agrees()
        && ViscosityModelDoc::agrees()
        && DensityModelDoc::agrees()
        && SlipRegimeDoc::agrees()
}
