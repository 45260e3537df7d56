//! `bearing`: one finite-length hydrodynamic journal bearing (seed 002): Reynolds equation with
//! Reynolds (Swift–Stieber) cavitation, optional shaft misalignment and axial edge profile, fixed
//! position or load balance; dimensionless figures and, with dimensions, SI values.
//!
//! Conventions (also in the OpenAPI field docs):
//! - Angles: measured around the bearing from the *unloaded side* (the point opposite the
//!   direction of the applied load), positive in the direction of journal rotation. The attitude
//!   angle is the angle from the load line to the line of centres of the mid-plane, positive in
//!   the direction of rotation; the mid-plane's largest film is at `attitude`, its smallest film
//!   at `attitude + 180°`.
//! - `P = p (c/R)²/(6ηω)` (seed 002), `H = h/c`, `Z = z/L`, `W̄ = w (c/R)²/(6ηωRL)`,
//!   Sommerfeld number `S = (R/c)² μN/P_avg = 1/(6πW̄)` with `P_avg = w/(LD)`.
//! - Friction: `friction_variable` is Raimondi & Boyd's `(R/c) f` of the journal: Couette shear
//!   over the whole circumference (the clearance taken as full of oil) plus the pressure-gradient
//!   term — it reproduces their tables. `friction_variable_seed002` reads seed 002 eq. (9)
//!   (Lund & Thomsen's power loss) with the cavitated zone filled by streamers: there only the
//!   fraction `h_c/h` of the gap is sheared, `h_c` being the film at the rupture line; it
//!   reproduces the paper's aligned f = 2.2178 (Table 2) within 0.4 %.
//! - Dynamic coefficients (`outputs: ["dynamic_coefficients"]`): x along the applied load, y
//!   perpendicular to it, 90° ahead in the direction of rotation; `K_ij = −∂F_i/∂x_j`,
//!   `C_ij = −∂F_i/∂ẋ_j` (F: film force on the journal), N/m and N·s/m; dimensionless
//!   `K̄ = K c/W`, `C̄ = C c ω/W` (W the film load, Lund's convention). From the Reynolds equation
//!   linearised about the equilibrium with its cavitation set (the rupture boundary's motion has
//!   no first-order effect); a supply groove stays where the equilibrium put it.
//! - Force and moment coefficients (`outputs: ["moment_coefficients"]`): the 4×4 stiffness and
//!   damping of the coordinates `(x, y, tilt_x, tilt_y)` — the mid-plane centre and the slopes
//!   `dx/dz`, `dy/dz` of the journal axis — against `(F_x, F_y, M_x, M_y)`, the film force and
//!   its moments about the mid-plane `M = ∫ (z − L/2) dF`; the same linearisation with a tilt as
//!   a translation varying as `z − L/2`, twice the linear solves of `dynamic_coefficients`.
//! - Heat balance (`thermal`): bulk model of ISO 7902-1 / DIN 31652-2, temperatures in K
//!   (`physics::journal::heat`); `checks` (with `limits`) compare the minimum film, the specific
//!   load and the maximum bulk temperature with configurable limits.

//!
//! Files: `spec.rs` (the request), `result.rs` (the answer), `validate.rs` (the spec's checks),
//! `solve.rs` (spec → `physics::journal::case` → result), `cost.rs` (the work model); this
//! file is the kind.

mod cost;
mod result;
mod solve;
mod spec;
mod validate;

pub use cost::bearing_cost;
pub use result::*;
pub use solve::{aligned_reference, bearing_spec_path, resolve_load, resolve_load_in, solve_spec, to_result};
use solve::solve_bearing;
pub use spec::*;
pub use validate::validate_bearing;

use crate::jobs::cost::Cost;
use crate::jobs::kind::{Kind, Limits, OutputInfo, Validation};
use crate::physics::{Observer, SolveError};
use serde_json::{json, Value};

pub use crate::physics::journal::Dimensions;

pub struct BearingKind;

impl Kind for BearingKind {
    const NAME: &'static str = "bearing";
    const SOLVER_VERSION: &'static str = "bearing-10";
    const DESCRIPTION: &'static str = "Finite-length hydrodynamic journal bearing (seed 002): Reynolds \
        equation with Reynolds cavitation solved as a complementarity problem (active set + multigrid), \
        misalignment, axial edge profiles, load balance; Raimondi–Boyd figures and SI values; optional \
        heat balance (effective temperature, ISO VG/Walther viscosity), operating-limit checks and \
        stiffness/damping coefficients (linearised Reynolds) with the rigid-rotor stability threshold.";
    const TABLES: &'static [&'static str] = &["field"];
    const KEY_FIGURES: &'static [&'static str] = &["/eccentricity_ratio", "/attitude_angle_deg", "/min_film", "/max_pressure", "/thermal/effective_temperature", "/power_loss", "/friction_coefficient", "/side_flow", "/checks/pass"];
    type Spec = BearingSpec;
    type Output = BearingResult;

    fn example() -> Value {
        json!({
            "geometry": {"length_to_diameter": 1.25},
            "operating": {"speed_rpm": 3000, "viscosity": 0.0293},
            "load": {"aligned_eccentricity_ratio": 0.6},
            "misalignment": {"vertical": 0.56, "horizontal": 0.56},
            "profile": {"order": 2, "height": 0.4, "length_fraction": 0.2},
            "grid": {"circumferential": 361, "axial": 181}
        })
    }

    fn bound_examples() -> Vec<Value> {
        // The heat balance with a two-point viscosity curve (examples/bearing_thermal.json's case).
        let curve = json!([{"temperature": 313.15, "viscosity": 0.04}, {"temperature": 373.15, "viscosity": 0.007}]);
        vec![json!({"geometry": {"radius": 0.05, "length": 0.04, "radial_clearance": 6e-5}, "operating": {"speed_rpm": 3000}, "load": {"force": 8000},
            "thermal": {"supply_temperature": 313.15, "lubricant": {"viscosity_curve": curve}}, "grid": {"circumferential": 121, "axial": 41}})]
    }

    fn outputs() -> &'static [OutputInfo] {
        &[
            OutputInfo { name: "pressure_field", description: "dimensionless pressure at the grid nodes (table `field`, downsampled by `field_stride`)" },
            OutputInfo { name: "film_field", description: "dimensionless film at the grid nodes (table `field`, downsampled by `field_stride`)" },
            OutputInfo { name: "dynamic_coefficients", description: "stiffness and damping coefficients at the equilibrium (linearised Reynolds; x along the load, y 90° ahead in rotation), dimensionless and SI, rigid-rotor stability threshold" },
            OutputInfo { name: "moment_coefficients", description: "4×4 stiffness and damping of the journal's translations and tilts against the film force and its moments about the mid-plane (linearised Reynolds), dimensionless and SI" },
        ]
    }

    fn validate(spec: &BearingSpec, limits: &Limits, v: &mut Validation) {
        validate_bearing(spec, limits, v, true, "");
    }

    fn cost(spec: &BearingSpec) -> Cost {
        bearing_cost(spec)
    }

    fn solve(spec: &BearingSpec, observer: &dyn Observer) -> Result<BearingResult, SolveError> {
        solve_bearing(spec, observer).map_err(|e: SolveError| e.in_spec(bearing_spec_path))
    }
}
