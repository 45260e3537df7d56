//! Lubricant film and traction at one contact point — the seam between the cam-cycle job and
//! the models that can resolve a lubricated contact.
//!
//! # The seam: [`FilmModel`]
//!
//! A cam cycle visits one contact point per cam angle. At each it builds a [`ContactInput`]
//! (load, geometry, entrainment and sliding velocities, time and time step, lubricant, moduli,
//! roughness, traction laws) and asks a [`FilmModel`] for a [`FilmSolution`]: central and minimum
//! film, peak pressure and contact size, the pressure spike when the model resolves it, the
//! asperity load share, validity indicators, and which model ran. The roller torque balance then
//! calls [`FilmModel::traction`] many times per angle (inside its root finder) with trial sliding
//! velocities, so traction is evaluated from the stored solution without re-solving the film:
//! the solution carries [`TractionNode`]s (area, pressure, viscosity, film) over which the default
//! implementation integrates the shear law.
//!
//! Implementations:
//! * [`ClosedForm`] — fidelity `fast`: Hertz pressure + a regression film formula (Pan–Hamrock,
//!   Dowson–Higginson, seed 003 eq. 17 with squeeze; Hamrock–Dowson for point contacts) +
//!   Greenwood–Tripp load sharing. Microseconds per point.
//! * [`Numerical`] — fidelity `accurate`: the numerical line-contact EHL solver
//!   ([`crate::ehl`]) at every point. It reads `input.time_step` and `previous` (the
//!   solution at the previous angle, whose [`FilmProfile`] holds the converged fields) for the
//!   squeeze term ∂(ρh)/∂t and a warm start, fills `pressure_spike`, `exit_film` and `profile`,
//!   and returns its grid nodes with positive pressure as traction nodes. Point contacts (the
//!   spherical tappet) keep the closed form: the solver is one-dimensional.
//! * [`Finite`] — fidelity `accurate` with `ehl.geometry: finite`: the 2-D finite-length / point
//!   EHL solver ([`crate::ehl::twod`]) at every point with entrainment, warm-started
//!   from the previous point's 2-D solution ([`finite`]); [`AutoFinite`] with `auto`: the 2-D
//!   model where [`finite::ends_matter`], the line-contact [`Auto`] elsewhere
//!   ([`auto_finite`]).
//! * [`ThermalFinite`] — `ehl.thermal` with `ehl.geometry: finite`: the thermal 2-D model
//!   ([`crate::ehl::thermal_finite`]) at every point, quasi-steady, warm from the previous
//!   point; the traction nodes' viscosity calibrated to the whole-contact thermal traction at the
//!   solved slip ([`thermal_finite`]).
//! * [`Auto`] — fidelity `auto`: per point, the closed form where [`closed_form_error`] (the one
//!   place the decision is made; measured rules in [`auto`]) is within the tolerance, else
//!   [`Numerical`]. After closed-form points the numerical model has no history: its first point
//!   is a steady solve (no squeeze), which the squeeze rule keeps to points where the squeeze is
//!   still small.
//!
//! Every implementation is deterministic, returns finite numbers or a typed [`SolveError`], and
//! sets `model`.
//!
//! Units: SI. The moduli are passed as `E*` (Johnson); formulas needing `E' = 2E*` convert.

pub mod auto;
pub mod auto_finite;
pub mod closed_form;
pub mod finite;
/// The closed-form film formulas live with the EHL solvers they are checked against.
pub use crate::ehl::formulas;
pub mod mixed;
pub mod numerical;
pub mod thermal;
pub mod thermal_finite;
pub mod traction_table;
pub mod traction_along;
/// Work counters (shared with the EHL solvers; `crate::work`).
pub use crate::work;

pub use auto::{closed_form_error, Auto, ClosedFormError, ErrorRule};
pub use closed_form::{ClosedForm, FilmFormula};
pub use auto_finite::AutoFinite;
pub use finite::{Finite, FiniteFilm};
pub use numerical::Numerical;
pub use thermal::{FilmThermal, ThermalFilmSettings, ThermalNumerical};
pub use traction_along::{traction_along, TractionAlong};
pub use thermal_finite::ThermalFinite;

use crate::friction::{
    viscous_traction_local, AsperityContact, AsperityFriction, AsperityNode, Roughness, TractionLaw, TractionNode,
};
use crate::lubricant::{Lubricant, ViscosityLaw};
use crate::SolveError;
use serde::{Deserialize, Serialize};

/// Geometry of the contact at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactShape {
    /// Line contact: reduced radius in the rolling direction (m) and the length carrying the load
    /// at the given load per length (m). A crowned roller passes its equivalent length
    /// `F / w'_max` so that `load/length` is the peak load per length of its central slice.
    Line { reduced_radius: f64, length: f64 },
    /// Point contact with reduced radii along the rolling direction `rx` and across it `ry` (m).
    Point { rx: f64, ry: f64 },
}

/// Everything a film/traction model may use at one contact point.
#[derive(Debug, Clone, Copy)]
pub struct ContactInput<'a> {
    /// Normal load, N (> 0).
    pub load: f64,
    pub shape: ContactShape,
    /// Mean entrainment velocity `(u1 + u2)/2`, m/s (signed; reversal flips the inlet).
    pub entrainment_velocity: f64,
    /// Sliding velocity `u1 − u2`, m/s (the cam's surface minus the follower's).
    pub sliding_velocity: f64,
    /// Time since the start of the run, s.
    pub time: f64,
    /// Time since the previous contact point of the same run, s (0 when there is none).
    pub time_step: f64,
    /// Contact modulus `E* = 1/Σ(1 − ν²)/E`, Pa.
    pub contact_modulus: f64,
    /// Inlet (bulk oil) temperature, K.
    pub temperature: f64,
    pub lubricant: &'a Lubricant,
    pub roughness: &'a Roughness,
    pub traction_law: &'a TractionLaw,
    pub asperity_friction: &'a AsperityFriction,
    /// The run's cancel, time limit and shutdown: the numerical models poll it inside their
    /// iterations (`Interrupts::NONE` outside a job).
    pub interrupts: crate::Interrupts<'a>,
}

/// The settings of a smooth contact with seed 000's oil and steels that the film models' tests
/// and benches share: no roughness (σ = 0), a Newtonian traction law, Coulomb asperity friction
/// 0.1, E* = 1.911e11/(2(1 − 0.3²)) Pa, the oil at its 313 K reference. `input` builds the
/// contact point in pure rolling, steady.
#[derive(Debug, Clone)]
pub struct SmoothContact {
    pub lubricant: Lubricant,
    pub roughness: Roughness,
    pub traction_law: TractionLaw,
    pub asperity_friction: AsperityFriction,
    pub contact_modulus: f64,
}

impl SmoothContact {
    /// Seed 000 Table 1's oil and steels (cam and roller E = 191.1 GPa, ν = 0.3).
    pub fn seed000() -> Self {
        use crate::friction::{AsperityModel, Rheology};
        SmoothContact {
            lubricant: Lubricant::SEED000,
            roughness: Roughness { sigma: 0.0, eta_beta_sigma: 0.04, sigma_over_beta: 0.001, plastic_limit: f64::INFINITY, curve: None },
            traction_law: TractionLaw { rheology: Rheology::Newtonian, limiting_shear_coefficient: None },
            asperity_friction: AsperityFriction { coefficient: 0.1, model: AsperityModel::Coulomb, map: None },
            contact_modulus: 1.911e11 / (2.0 * 0.91),
        }
    }

    /// The contact point at `load` (N) on `shape`, entrained at `u` (m/s), no sliding, steady.
    pub fn input(&self, load: f64, shape: ContactShape, u: f64) -> ContactInput<'_> {
        ContactInput {
            load,
            shape,
            entrainment_velocity: u,
            sliding_velocity: 0.0,
            time: 0.0,
            time_step: 0.0,
            contact_modulus: self.contact_modulus,
            temperature: self.lubricant.reference_temperature,
            lubricant: &self.lubricant,
            roughness: &self.roughness,
            traction_law: &self.traction_law,
            asperity_friction: &self.asperity_friction,
            interrupts: crate::Interrupts::NONE,
        }
    }
}

/// Which model produced a film solution. The `*_mixed` variants are the same models with rough
/// surfaces sharing the load inside the solution ([`mixed`]): their asperity load is part of the
/// load balance (numerical: of the elastic deflection too), not evaluated afterwards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilmModelId {
    PanHamrock,
    DowsonHigginson,
    Seed003,
    HamrockDowson,
    /// The numerical line-contact EHL solver (`physics::ehl`).
    Numerical,
    /// The thermal numerical line-contact EHL model (`physics::ehl::thermal`).
    Thermal,
    /// The thermal model's factors carried from a key point onto the closed form's change
    /// (`ehl.thermal.carry_tolerance`; `physics::film::thermal`).
    ThermalCarried,
    /// Pan–Hamrock in the Johnson–Greenwood–Poon load sharing.
    PanHamrockMixed,
    /// Dowson–Higginson in the Johnson–Greenwood–Poon load sharing.
    DowsonHigginsonMixed,
    /// Seed 003's formula in the Johnson–Greenwood–Poon load sharing.
    Seed003Mixed,
    /// Hamrock–Dowson (point contacts) in the Johnson–Greenwood–Poon load sharing.
    HamrockDowsonMixed,
    /// The numerical EHL solver with the asperity pressure in its load balance and deflection.
    NumericalMixed,
    /// The finite-length / point 2-D EHL solver (`physics::ehl::twod`, `ehl.geometry: finite`).
    Finite,
    /// The thermal finite-length / point 2-D EHL model (`physics::ehl::thermal_finite`,
    /// `ehl.thermal` with `ehl.geometry: finite`).
    ThermalFinite,
}

impl FilmModelId {
    /// The snake_case name used in results.
    pub fn name(self) -> &'static str {
        match self {
            FilmModelId::PanHamrock => "pan_hamrock",
            FilmModelId::DowsonHigginson => "dowson_higginson",
            FilmModelId::Seed003 => "seed003",
            FilmModelId::HamrockDowson => "hamrock_dowson",
            FilmModelId::Numerical => "numerical",
            FilmModelId::Thermal => "thermal",
            FilmModelId::ThermalCarried => "thermal_carried",
            FilmModelId::PanHamrockMixed => "pan_hamrock_mixed",
            FilmModelId::DowsonHigginsonMixed => "dowson_higginson_mixed",
            FilmModelId::Seed003Mixed => "seed003_mixed",
            FilmModelId::HamrockDowsonMixed => "hamrock_dowson_mixed",
            FilmModelId::NumericalMixed => "numerical_mixed",
            FilmModelId::Finite => "finite",
            FilmModelId::ThermalFinite => "thermal_finite",
        }
    }

    /// The same model with the asperities sharing the load inside the solution.
    pub fn mixed(self) -> Self {
        match self {
            FilmModelId::PanHamrock => FilmModelId::PanHamrockMixed,
            FilmModelId::DowsonHigginson => FilmModelId::DowsonHigginsonMixed,
            FilmModelId::Seed003 => FilmModelId::Seed003Mixed,
            FilmModelId::HamrockDowson => FilmModelId::HamrockDowsonMixed,
            FilmModelId::Numerical => FilmModelId::NumericalMixed,
            other => other,
        }
    }
}

/// Johnson's regime parameters of a line contact (see [`formulas`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Regime {
    pub viscous: f64,
    pub elastic: f64,
}

/// Pressure and film along the rolling direction through the contact centre (numerical models).
#[derive(Debug, Clone, PartialEq)]
pub struct FilmProfile {
    /// Position along the rolling direction, m (0 at the contact centre).
    pub x: Vec<f64>,
    /// Pressure, Pa.
    pub pressure: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
    /// Density ratio `ρ/ρ0` (the squeeze term of the next time step needs `ρh`).
    pub density_ratio: Vec<f64>,
    /// The coarse grid's state of a Richardson-extrapolated solve (its squeeze history).
    pub coarse: Option<crate::ehl::EhlState>,
    /// Asperity part of `pressure`, Pa (mixed lubrication; empty for smooth surfaces): `pressure`
    /// is the total pressure, the fluid's is the difference.
    pub asperity_pressure: Vec<f64>,
}

/// The lubricated contact at one point.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmSolution {
    pub model: FilmModelId,
    /// Central film thickness, m.
    pub central_film: f64,
    /// Minimum film thickness, m.
    pub min_film: f64,
    /// Central film without transient (squeeze) effects, m: lets the next point estimate `ḣ`.
    pub steady_central_film: f64,
    /// Peak pressure, Pa (the Hertz `p0` for the closed forms).
    pub max_pressure: f64,
    /// Height of the exit pressure spike, Pa, when the model resolves it.
    pub pressure_spike: Option<f64>,
    /// Position of the spike, m from the contact centre along the rolling direction (positive in
    /// the direction of positive entrainment).
    pub pressure_spike_position: Option<f64>,
    /// Smallest film downstream of the centre (exit constriction), m, when the model resolves it
    /// (closed forms: their minimum film is that estimate).
    pub exit_film: Option<f64>,
    /// Semi-width of the pressure zone along the rolling direction, m.
    pub half_width: f64,
    /// Nominal contact area, m².
    pub contact_area: f64,
    /// The asperity-borne part of the load.
    pub asperity: AsperityContact,
    /// The solved asperity pressure node by node, for the local micro-slip map (numerical mixed
    /// films with `AsperityModel::MicroSlip`; empty otherwise: the asperity traction then takes
    /// a semi-elliptic pressure, [`crate::friction::micro_slip_share`]).
    pub asperity_nodes: Vec<AsperityNode>,
    /// Film parameter λ = h_min/σ (absent for smooth surfaces).
    pub lambda: Option<f64>,
    /// Validity indicators of closed forms (line contacts).
    pub regime: Option<Regime>,
    /// Quadrature nodes for the traction integral.
    pub nodes: Vec<TractionNode>,
    /// The film's rolling (Poiseuille, seed 001 eq. 24) force on the follower that `nodes` do not
    /// carry, N along the positive sense of the surface velocities: closed forms' integrated
    /// Goksem–Hargreaves force (line contacts); 0 for the numerical models, whose nodes carry
    /// their own Poiseuille stresses.
    pub rolling_force: f64,
    /// The viscosity law (lubricant at the film's temperature) the nodes' viscosities were
    /// evaluated with, when one law holds for all of them (closed forms): lets the next point
    /// reuse viscosities at identical node pressures.
    pub viscosity_law: Option<ViscosityLaw>,
    /// Pressure and film profiles (numerical models only).
    pub profile: Option<Box<FilmProfile>>,
    /// Newton steps of a numerical model (absent for closed forms); coupling iterations of the
    /// thermal model.
    pub iterations: Option<u32>,
    /// Temperatures, factors and the traction table of the thermal model.
    pub thermal: Option<Box<FilmThermal>>,
    /// Edge pressure peak, where the minimum film sits and the warm start of the finite-length /
    /// point 2-D model ([`Finite`]).
    pub finite: Option<Box<FiniteFilm>>,
}

impl FilmSolution {
    /// A transient film that has stopped changing on a stretch of unchanging conditions
    /// ([`FiniteFilm::settled`]): a further step at the same load, shape and entrainment would
    /// return it within the model's settling tolerance, so the roller march reuses it on a dwell
    /// as it reuses a history-free model's film.
    pub fn settled(&self) -> bool {
        self.finite.as_deref().is_some_and(|f| f.settled)
    }
}

/// Traction at one contact point for one sliding velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traction {
    /// Total tangential force on the follower surface, N, same sign as the sliding velocity
    /// (it drags the slower surface along).
    pub force: f64,
    /// d(force)/d(sliding velocity), N·s/m.
    pub slope: f64,
    /// Half-height of a traction jump at zero sliding (stuck asperities), N.
    pub stick_limit: f64,
    /// Viscous (film) part of `force`, N.
    pub viscous: f64,
}

/// A film and traction model at one contact point. See the module docs.
pub trait FilmModel: Send + Sync {
    /// Solve the film at `input`. `previous` is this run's solution at the previous point (for
    /// squeeze terms and warm starts), `None` at the first point or in a point analysis.
    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError>;

    /// Relative change of the entrainment velocity within which a film solved at one entrainment
    /// may stand for the film at another (the roller torque balance re-solves the film beyond
    /// it). Default 1e-6: far below a closed form's error. Numerical models return a value whose
    /// film change (`∝ u^0.7`) stays well below their discretisation error.
    fn entrainment_tolerance(&self) -> f64 {
        1e-6
    }

    /// Whether a solution depends on its input's load, shape and entrainment alone (besides the
    /// run's fixed settings) — not on time, time step, sliding velocity or the previous point's
    /// solution. A history-free model's film solved at one point then stands for another point
    /// with the same load and shape and an entrainment within [`Self::entrainment_tolerance`]
    /// (the roller march uses this on a dwell). Default: false.
    fn history_free(&self) -> bool {
        false
    }

    /// The 2-D pressure and film fields of `film` (which this model solved at `input`), for the
    /// cycle's `profiles` output at chosen angles: a finite-length/point model re-enters its
    /// converged solution (no Newton step moves it) and returns the fields it does not keep.
    /// `None` for models without a 2-D field (the default).
    fn fields(&self, _film: &FilmSolution, _input: &ContactInput) -> Result<Option<crate::ehl::twod::Fields2d>, SolveError> {
        Ok(None)
    }

    /// Traction for sliding velocity `sliding` with the film of `film` (which was solved at
    /// `input`, possibly with a different sliding velocity): [`Self::traction_local`] without
    /// the curvature.
    fn traction(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> Traction {
        self.traction_local(film, input, sliding).0
    }

    /// Traction and what bounds its second derivative nearby: within `reach` of `sliding` the
    /// traction is twice differentiable with `|d²F_t/du_s²| ≤ bound` (`(bound, reach)`; the root
    /// finder of the roller balance uses it to accept a Newton step without another
    /// evaluation). Default: film shear over `film.nodes` plus the asperity friction of
    /// `film.asperity`.
    fn traction_local(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> (Traction, (f64, f64)) {
        nodal_traction_local(film, input, sliding, self.stick_limit(film, input))
    }

    /// Half-height of the traction jump at zero sliding ([`Traction::stick_limit`]) without
    /// evaluating the film shear. Default: the asperity friction's stick limit.
    fn stick_limit(&self, film: &FilmSolution, input: &ContactInput) -> f64 {
        input.asperity_friction.stick_limit(&film.asperity)
    }
}

/// The default [`FilmModel::traction_local`]: film shear over `film.nodes` plus the asperity
/// friction of `film.asperity`, with the model's `stick_limit`.
pub fn nodal_traction_local(film: &FilmSolution, input: &ContactInput, sliding: f64, stick_limit: f64) -> (Traction, (f64, f64)) {
    let v = viscous_traction_local(&film.nodes, input.traction_law, sliding);
    let (asp, aslope, (acurv, areach)) =
        input.asperity_friction.traction_local(&film.asperity, &film.asperity_nodes, sliding, input.entrainment_velocity);
    let traction = Traction {
        force: v.force + film.rolling_force + asp,
        slope: v.slope + aslope,
        stick_limit,
        viscous: v.force + film.rolling_force,
    };
    (traction, (1.5 * v.curvature + acurv, v.smooth_reach.min(areach)))
}

/// Model fidelity requested by a spec.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fidelity {
    /// Closed forms at every point.
    #[default]
    Fast,
    /// The numerical EHL solver at every point (issue 5).
    Accurate,
    /// The closed form where its estimated error is within tolerance, the numerical solver
    /// elsewhere (issue 5).
    Auto,
}

/// Settings of the numerical model and of the `auto` choice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccurateSettings {
    /// Resolution, tolerance and iteration cap of the numerical EHL solver.
    pub options: crate::ehl::EhlOptions,
    /// `auto`: the largest estimated relative error of the closed-form film accepted (see
    /// [`closed_form_error`]).
    pub auto_tolerance: f64,
    /// Grid extrapolation of the numerical solver.
    pub extrapolation: crate::ehl::Extrapolation,
    /// The thermal model (`accurate` only): `None` is isothermal.
    pub thermal: Option<ThermalFilmSettings>,
    /// The finite-length / point 2-D model instead of the line contact (`ehl.geometry: finite`;
    /// with `thermal` the thermal 2-D model, [`ThermalFinite`]): its grid and options, and the
    /// roller's crown.
    pub finite: Option<FiniteSettings>,
}

/// Settings of the finite-length / point 2-D model ([`Finite`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiniteSettings {
    pub options: crate::ehl::twod::Ehl2dOptions,
    /// The roller's axial profile (`None`: a straight roller of the contact length, or a point
    /// contact).
    pub crown: Option<crate::geometry::Crown>,
    /// The squeeze term along a cycle ([`Finite::squeeze`]).
    pub squeeze: bool,
}

/// The film model for a fidelity: `fast` the closed form; `accurate` the numerical EHL solver on
/// line contacts ([`Numerical`]; point contacts keep the closed form); `auto` the closed form
/// where [`closed_form_error`] is within `settings.auto_tolerance`, the numerical solver elsewhere
/// ([`Auto`]).
///
/// With `settings.finite` (`ehl.geometry: finite`): `accurate` runs the 2-D model ([`Finite`];
/// with `settings.thermal` the thermal one, [`ThermalFinite`]) at every point with entrainment,
/// `auto` where [`finite::ends_matter`] and the 1-D `auto` choice (thermal with
/// `settings.thermal`) elsewhere ([`AutoFinite`]).
pub fn model_for(fidelity: Fidelity, fast: ClosedForm, settings: AccurateSettings) -> Box<dyn FilmModel> {
    let numerical = Numerical::new(settings.options, fast).with_extrapolation(settings.extrapolation);
    if let Some(f) = settings.finite {
        let finite = Finite::new(f.options, f.crown, fast).check_first_only().with_squeeze(f.squeeze);
        let thermal = settings.thermal.map(|t| ThermalFinite::new(f.options, f.crown, t, fast));
        match (fidelity, thermal) {
            (Fidelity::Fast, _) => {}
            (Fidelity::Accurate, Some(t)) => return Box::new(t),
            (Fidelity::Accurate, None) => return Box::new(finite),
            (Fidelity::Auto, thermal) => {
                let line_thermal = settings.thermal.map(|t| ThermalNumerical::new(settings.options, t, fast));
                let auto = Auto { fast, numerical, tolerance: settings.auto_tolerance, thermal: line_thermal };
                return Box::new(AutoFinite { auto, finite, thermal });
            }
        }
    }
    match fidelity {
        Fidelity::Fast => Box::new(fast),
        Fidelity::Accurate => match settings.thermal {
            Some(t) => Box::new(ThermalNumerical::new(settings.options, t, fast)),
            None => Box::new(numerical),
        },
        Fidelity::Auto => Box::new(Auto {
            fast,
            numerical,
            tolerance: settings.auto_tolerance,
            thermal: settings.thermal.map(|t| ThermalNumerical::new(settings.options, t, fast)),
        }),
    }
}
