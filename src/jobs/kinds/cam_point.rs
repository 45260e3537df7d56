//! `cam_point`: the cam–roller contact at a fixed operating point (seed 001 Table 2) — roller slip
//! against roller–pin friction, the cam–roller friction needed to drive the roller and the
//! gross-sliding threshold. A point analysis has no cycle, so it is its own kind rather than a
//! `cam_cycle` option. Physics: `physics::roller::point`.

use super::common::{composite_sigma, AsperitySpec, Material, EhlSpec, FilmSpec, LubricantSpec, TractionSpec};
use crate::jobs::cost::{self, Cost};
use crate::jobs::quantity as Q;
use crate::jobs::kind::{Kind, Limits, Validation};
use crate::physics::contact::{contact_modulus, hertz_line};
use super::contact::LubricatedContact;
use crate::physics::film::{ContactInput, ContactShape, Fidelity, FilmModelId};
use crate::physics::friction::SlipRegime;
use crate::physics::roller::PointCase;
use crate::physics::{ensure_finite, Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;

pub struct CamPoint;

/// One body of the contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PointBody {
    /// Elastic constants. Default: steel.
    #[serde(default)]
    pub material: Material,
    /// RMS roughness Rq, m. Default 0.
    #[serde(default)]
    pub roughness_rq: f64,
}

impl Default for PointBody {
    fn default() -> Self {
        PointBody { material: Material::default(), roughness_rq: 0.0 }
    }
}

/// The roller.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PointRoller {
    /// Outer radius R_f, m.
    pub radius: f64,
    /// Pin radius, m.
    pub pin_radius: f64,
    /// Moment of inertia, kg·m². Default 0.
    #[serde(default)]
    pub inertia: f64,
    /// Roller angular acceleration ω̇_r, rad/s². Default 0 (the inertia torque is I ω̇_r).
    #[serde(default)]
    pub angular_acceleration: f64,
    /// Crowned roller profile over `contact_length` (seed 000 Table 1), used by the 2-D model
    /// (`ehl.geometry: finite`). Absent: a straight roller of `contact_length`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crown: Option<super::cam_cycle::CrownSpec>,
}

/// Optional outputs of a `cam_point` job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum PointOutput {
    /// The film and asperity shear stresses along the rolling direction at every roller–pin
    /// friction value (seed 001 Fig. 8b; `fidelity: accurate`, line model).
    TractionAlong,
}

/// Spec of a `cam_point` job (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CamPointSpec {
    /// Normal contact load F, N.
    #[schema(example = 12500.0)]
    pub load: f64,
    /// Reduced radius of curvature of the cam–roller contact, m.
    #[schema(example = 0.0105)]
    pub reduced_radius: f64,
    /// Cam surface velocity u_c, m/s.
    #[schema(example = 3.98)]
    pub cam_surface_velocity: f64,
    /// Axial contact length, m.
    pub contact_length: f64,
    pub roller: PointRoller,
    /// Roller–pin friction coefficients μ_rp to evaluate.
    pub pin_friction: Vec<f64>,
    #[serde(default)]
    pub cam: PointBody,
    #[serde(default)]
    pub follower: PointBody,
    pub lubricant: LubricantSpec,
    #[serde(default)]
    pub asperities: AsperitySpec,
    #[serde(default)]
    pub traction: TractionSpec,
    #[serde(default)]
    pub film: FilmSpec,
    /// Film model: `fast` (closed form, default), `accurate` (numerical line-contact EHL, steady),
    /// `auto` (the closed form where its estimated error is within `ehl.auto_tolerance`).
    #[serde(default)]
    #[schema(value_type = crate::jobs::schemas::FidelityDoc)]
    pub fidelity: Fidelity,
    /// Numerical EHL options (`accurate`, `auto`).
    #[serde(default)]
    pub ehl: EhlSpec,
    /// Optional outputs: `traction_along`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outputs: Vec<PointOutput>,
}

impl LubricatedContact for CamPointSpec {
    fn lubricant(&self) -> Option<&LubricantSpec> {
        Some(&self.lubricant)
    }
    fn asperities(&self) -> &AsperitySpec {
        &self.asperities
    }
    fn traction(&self) -> &TractionSpec {
        &self.traction
    }
    fn film(&self) -> &FilmSpec {
        &self.film
    }
    fn fidelity(&self) -> Fidelity {
        self.fidelity
    }
    fn ehl(&self) -> &EhlSpec {
        &self.ehl
    }
}

/// The balance at one roller–pin friction coefficient.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct PointRow {
    /// Roller–pin friction coefficient μ_rp.
    pub pin_friction: f64,
    /// Slide-to-roll ratio 2(u_c − u_r)/(u_c + u_r).
    pub slide_roll_ratio: f64,
    /// u_c − u_r, m/s.
    pub sliding_velocity: f64,
    /// Roller surface velocity u_r, m/s.
    pub roller_surface_velocity: f64,
    /// Cam–roller friction coefficient μ_cr = F_t/F.
    pub cam_roller_friction: f64,
    /// Film (viscous) part of the traction, N.
    pub viscous_traction: f64,
    /// Asperity part of the traction, N.
    pub asperity_traction: f64,
    /// Central film, m.
    pub film_central: f64,
    /// Minimum film, m.
    pub film_min: f64,
    /// 1 when the asperities stick (pure rolling), else 0.
    pub sticking: f64,
    /// `rolling` (the asperities stick, or a full film below 1 % SRR), `micro_slip` (partial
    /// slip of the asperity contact), `gross_sliding` (the asperities slide, or a full film at
    /// ≥ 1 % SRR).
    #[schema(value_type = crate::jobs::schemas::SlipRegimeDoc)]
    pub slip_regime: SlipRegime,
    /// Film model that ran for this row.
    #[schema(value_type = crate::jobs::schemas::FilmModelIdDoc)]
    pub model: FilmModelId,
}

/// Flat summary numbers.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct PointSummary {
    /// Pa.
    pub hertz_max_pressure: f64,
    /// m.
    pub hertz_half_width: f64,
    /// Central film at pure rolling, m.
    pub film_central: f64,
    /// Minimum film at pure rolling, m.
    pub film_min: f64,
    /// Exit-constriction film at pure rolling, m (the closed forms' minimum film).
    pub exit_film: f64,
    /// Exit pressure spike at pure rolling, Pa, when the numerical model resolved one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_spike: Option<f64>,
    /// Its position, m from the contact centre (positive downstream).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_spike_position: Option<f64>,
    /// Peak pressure at pure rolling, Pa (the Hertz p0 for closed forms).
    pub max_pressure: f64,
    /// h_min/σ at pure rolling (rough surfaces).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f64>,
    /// Share of the load on the asperities at pure rolling, inside the load balance of the film
    /// solution (mixed lubrication; the fluid carries the rest).
    pub asperity_load_fraction: f64,
    /// The film's traction at zero sliding: its rolling (Poiseuille) resistance, N on each
    /// surface, negative: against the entrainment (seed 001 eq. 24–25: `−(h/2) dp/dx` at the
    /// numerical film's nodes through the traction law; Goksem–Hargreaves for closed forms).
    /// Part of `viscous_traction`; the roller must overcome it as it overcomes the pin.
    pub rolling_resistance: f64,
    /// Minimum cam–roller friction coefficient that still drives the roller (Coulomb asperities:
    /// μ_b W_a/F; the partial-slip laws `carter` and `micro_slip`: 0 — their traction vanishes
    /// with the sliding; seed 001's sweep procedure is `first_sliding_cam_roller_friction`).
    pub min_cam_roller_friction: f64,
    /// Roller–pin friction coefficient where the asperity traction saturates (absent without asperity load; 0 when the film's rolling resistance alone exceeds the asperities' stick capacity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gross_sliding_pin_friction: Option<f64>,
    /// `ehl.geometry: finite`: the edge pressure peak at pure rolling, Pa — the largest
    /// off-centre maximum along the roller of `max_x p` above the centre value (absent when the
    /// pressure falls monotonically from the centre, or with the line model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_pressure_peak: Option<f64>,
    /// Its axial position, m from the roller centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_pressure_peak_position: Option<f64>,
    /// `ehl.geometry: finite`: where the minimum film sits along the roller axis, m from the
    /// centre (0: on the centre line).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_axial_position: Option<f64>,
    /// Seed 001's procedure on the requested list: the first roller–pin friction coefficient μ_rp with SRR > 0 …
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_sliding_pin_friction: Option<f64>,
    /// … and the cam–roller friction coefficient μ_cr there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_sliding_cam_roller_friction: Option<f64>,
}

/// The traction along the contact at one roller–pin friction value (seed 001 Fig. 8b): per node
/// of the numerical film, from the inlet to the outlet.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct TractionAlongContact {
    /// Roller–pin friction coefficient μ_rp of the row.
    pub pin_friction: f64,
    /// Sliding velocity u_c − u_r of the row, m/s.
    pub sliding_velocity: f64,
    /// Position along the rolling direction, m (0 at the contact centre, positive downstream).
    pub x: Vec<f64>,
    /// Film thickness, m.
    pub film: Vec<f64>,
    /// Fluid pressure, Pa.
    pub fluid_pressure: Vec<f64>,
    /// Asperity pressure p_a, Pa.
    pub asperity_pressure: Vec<f64>,
    /// Film shear stress on the surfaces, Pa (sign of the sliding; the rolling Poiseuille part included).
    pub viscous_shear: Vec<f64>,
    /// Asperity shear stress τ_a, Pa (sign of the sliding).
    pub asperity_shear: Vec<f64>,
    /// Its bound μ_b p_a, Pa: a node whose |τ_a| reaches it slides grossly.
    pub asperity_shear_limit: Vec<f64>,
}

/// Result of a `cam_point` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct CamPointResult {
    #[schema(value_type = crate::jobs::schemas::FidelityDoc)]
    pub fidelity_used: Fidelity,
    #[schema(value_type = crate::jobs::schemas::FilmModelIdDoc)]
    pub film_model: FilmModelId,
    /// The numerical line model's settings as they ran (fidelity `accurate` or `auto`, line
    /// geometry; see `cam_cycle`'s `ehl_settings`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ehl_settings: Option<super::accuracy::EhlSettingsUsed>,
    /// E*, Pa.
    pub contact_modulus: f64,
    pub rows: Vec<PointRow>,
    pub summary: PointSummary,
    /// `outputs: ["traction_along"]`: the traction along the contact at each row.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traction_along: Option<Vec<TractionAlongContact>>,
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

impl Kind for CamPoint {
    const NAME: &'static str = "cam_point";
    const SOLVER_VERSION: &'static str = "cam_point-16";
    const DESCRIPTION: &'static str = "Cam–roller contact at a fixed operating point: roller slip against \
        roller–pin friction, minimum cam–roller friction to drive the roller, gross-sliding threshold (seed 001).";
    const TABLES: &'static [&'static str] = &["rows"];
    const KEY_FIGURES: &'static [&'static str] = &["/summary/film_min", "/summary/film_central", "/summary/max_pressure", "/summary/pressure_spike", "/summary/lambda", "/summary/min_cam_roller_friction", "/summary/first_sliding_pin_friction"];
    type Spec = CamPointSpec;
    type Output = CamPointResult;

    fn example() -> Value {
        json!({
            "load": 12500.0, "reduced_radius": 0.0105, "cam_surface_velocity": 3.98, "contact_length": 0.021,
            "roller": {"radius": 0.018, "pin_radius": 0.0091},
            "pin_friction": [0.002, 0.005, 0.01, 0.02],
            "cam": {"material": {"youngs_modulus": 200e9}, "roughness_rq": 0.169e-6},
            "follower": {"material": {"youngs_modulus": 200e9}, "roughness_rq": 0.119e-6},
            "lubricant": {"viscosity": 0.013, "pressure_viscosity": 1.84e-8},
            "asperities": {"boundary_friction": 0.12}
        })
    }

    fn bound_examples() -> Vec<Value> {
        // Asperities from a measured surface (`rough_contact`'s curve and micro-slip map).
        let (film, pressure) = (json!([1e-7, 2e-7]), json!([2e8, 1e8]));
        vec![crate::jobs::kind::example_with::<Self>(json!({"asperities": {"plastic_limit": 6e9, "model": "micro_slip",
            "pressure_gap_curve": {"film": film, "pressure": pressure},
            "micro_slip_map": {"film": film, "gross_sliding_displacement": [1e-7, 2e-7], "exponent": [3.0, 3.0]}}}))]
    }

    fn outputs() -> &'static [crate::jobs::kind::OutputInfo] {
        &[crate::jobs::kind::OutputInfo { name: "traction_along", description: "film and asperity shear stresses along the rolling direction at each roller–pin friction value (fidelity accurate, line model)" }]
    }

    fn validate(spec: &CamPointSpec, limits: &Limits, v: &mut Validation) {
        v.quantity("/load", spec.load, Q::FORCE);
        if spec.outputs.contains(&PointOutput::TractionAlong) {
            v.check(spec.fidelity == Fidelity::Accurate && spec.ehl.geometry.is_line(), "/outputs", "traction_along needs fidelity accurate with the line model (a solved 1-D film)");
        }
        v.quantity("/reduced_radius", spec.reduced_radius, Q::RADIUS);
        v.quantity("/cam_surface_velocity", spec.cam_surface_velocity, Q::VELOCITY.from(1e-6));
        v.quantity("/contact_length", spec.contact_length, Q::LENGTH);
        v.quantity("/roller/radius", spec.roller.radius, Q::RADIUS);
        v.check(spec.roller.pin_radius > 0.0 && spec.roller.pin_radius < spec.roller.radius, "/roller/pin_radius", "must be > 0 and smaller than the roller radius");
        v.quantity("/roller/inertia", spec.roller.inertia, Q::INERTIA);
        v.check(spec.roller.angular_acceleration.is_finite(), "/roller/angular_acceleration", "must be finite");
        v.items("/pin_friction", spec.pin_friction.len(), 1, None);
        v.limit("/pin_friction", spec.pin_friction.len(), limits.max_angles, "the number of pin friction values");
        for (i, m) in spec.pin_friction.iter().enumerate() {
            v.in_range(&format!("/pin_friction/{i}"), *m, 0.0, 1.0);
        }
        for (name, b) in [("cam", spec.cam), ("follower", spec.follower)] {
            b.material.validate(&format!("/{name}/material"), v);
            v.in_range(&format!("/{name}/roughness_rq"), b.roughness_rq, 0.0, 1e-4);
        }
        spec.validate_lubrication(limits, v);
        v.check(!spec.film.squeeze, "/film/squeeze", "a point analysis is steady: no squeeze");
        if let Some(c) = spec.roller.crown {
            v.check(c.middle_length > 0.0 && c.middle_length <= spec.contact_length, "/roller/crown/middle_length", "must be in (0, contact_length]");
            v.in_range("/roller/crown/crown_height", c.crown_height, 0.0, 1e-3);
            v.quantity("/roller/crown/end_radius", c.end_radius, Q::RADIUS);
            v.check(!spec.ehl.geometry.is_line(), "/roller/crown", "the crown is a profile of the 2-D model: set ehl.geometry to finite");
        }
    }

    fn cost(spec: &CamPointSpec) -> Cost {
        // One film solve at rolling, then a torque balance per pin friction value: each
        // evaluates the traction at trial slips (the thermal model's traction table solves the
        // energy equation at a few slips per balance).
        let film = super::film_cost::film_cost(spec.fidelity, &spec.ehl.for_point(), super::film_cost::ContactKind::Line(super::accuracy::LineFamily::Roller));
        // 0.5 ms a balance (the seed 001 points: 30 balances in 15 ms); the numerical mixed
        // film's Greenwood–Tripp traction over its nodes 7 ms (seed001_mixed_nose).
        let rough = spec.cam.roughness_rq > 0.0 || spec.follower.roughness_rq > 0.0;
        let mixed = rough && spec.fidelity != Fidelity::Fast && spec.asperities.pressure_gap_curve.is_none();
        let per_balance = match &spec.ehl.thermal {
            Some(_) if spec.fidelity != Fidelity::Fast => 0.5 * film.cold,
            _ if mixed => 7e-3,
            _ => 5e-4,
        };
        let n = spec.pin_friction.len();
        let seconds = cost::JOB_OVERHEAD_S + film.cold + n as f64 * per_balance;
        Cost::new(seconds, cost::CAM_BASE_BYTES + film.bytes)
            .work_at(if per_balance > film.cold / n.max(1) as f64 { "/pin_friction" } else { film.path }, format!("{} and {n} torque balances", film.what))
            .memory_at(film.path, film.what)
    }

    fn solve(spec: &CamPointSpec, observer: &dyn Observer) -> Result<CamPointResult, SolveError> {
        solve_point(spec, observer).map_err(|e| e.in_spec(super::common::cam_spec_path))
    }
}

fn solve_point(spec: &CamPointSpec, observer: &dyn Observer) -> Result<CamPointResult, SolveError> {
    let es = contact_modulus(
        spec.cam.material.elastic(),
        spec.follower.material.elastic(),
    );
    let mut settings = spec.ehl.for_point().to_physics(super::accuracy::LineFamily::Roller);
    // A point analysis has no heat properties of its own: steel cam and follower (seed 000).
    let steel = crate::physics::thermal::ThermalSolid::STEEL;
    settings.thermal = spec.ehl.thermal_settings(steel, steel);
    if let (Some(f), Some(c)) = (settings.finite.as_mut(), spec.roller.crown) {
        f.crown = Some(crate::physics::geometry::Crown { length: spec.contact_length, middle_length: c.middle_length, crown_height: c.crown_height, end_radius: c.end_radius, profile: c.profile.into() });
    }
    let model = spec.film_model(settings);
    let lub = spec.lubricant.to_physics();
    let rough = spec.asperities.roughness(composite_sigma(spec.cam.roughness_rq, spec.follower.roughness_rq));
    let law = spec.traction.to_physics();
    let asp = spec.asperities.friction();
    let input = ContactInput {
        load: spec.load,
        shape: ContactShape::Line { reduced_radius: spec.reduced_radius, length: spec.contact_length },
        entrainment_velocity: spec.cam_surface_velocity,
        sliding_velocity: 0.0,
        time: 0.0,
        time_step: 0.0,
        contact_modulus: es,
        temperature: spec.lubricant.inlet_temperature(),
        lubricant: &lub,
        roughness: &rough,
        traction_law: &law,
        asperity_friction: &asp,
        interrupts: crate::physics::Interrupts(observer),
    };
    let rolling = model.solve(&input, None)?;
    let case = PointCase {
        model: model.as_ref(),
        input,
        cam_surface_velocity: spec.cam_surface_velocity,
        roller_radius: spec.roller.radius,
        pin_radius: spec.roller.pin_radius,
        inertia_torque: spec.roller.inertia * spec.roller.angular_acceleration,
        rolling: Some(&rolling),
    };
    let mut rows = Vec::with_capacity(spec.pin_friction.len());
    let want_along = spec.outputs.contains(&PointOutput::TractionAlong);
    let mut along = Vec::new();
    let mut first = None;
    for (i, &mu) in spec.pin_friction.iter().enumerate() {
        observer.check()?;
        observer.progress(i as f64 / spec.pin_friction.len() as f64, "torque balance");
        let b = case.balance(mu)?;
        let asperity = b.traction.force - b.traction.viscous;
        if want_along {
            if let Some(t) = crate::physics::film::traction_along(&b.film, &input, b.sliding_velocity) {
                ensure_finite("traction along the contact", t.viscous_shear.iter().chain(&t.asperity_shear).chain(&t.fluid_pressure))?;
                along.push(TractionAlongContact {
                    pin_friction: mu,
                    sliding_velocity: b.sliding_velocity,
                    x: t.x,
                    film: t.film,
                    fluid_pressure: t.fluid_pressure,
                    asperity_pressure: t.asperity_pressure,
                    viscous_shear: t.viscous_shear,
                    asperity_shear: t.asperity_shear,
                    asperity_shear_limit: t.asperity_shear_limit,
                });
            }
        }
        if first.is_none() && b.slide_roll_ratio > 0.0 {
            first = Some((mu, b.cam_roller_friction));
        }
        rows.push(PointRow {
            pin_friction: mu,
            slide_roll_ratio: b.slide_roll_ratio,
            sliding_velocity: b.sliding_velocity,
            roller_surface_velocity: spec.cam_surface_velocity - b.sliding_velocity,
            cam_roller_friction: b.cam_roller_friction,
            viscous_traction: b.traction.viscous,
            asperity_traction: asperity,
            film_central: b.film.central_film,
            film_min: b.film.min_film,
            sticking: if b.sticking { 1.0 } else { 0.0 },
            slip_regime: b.regime,
            model: b.film.model,
        });
    }
    let hz = hertz_line(spec.load / spec.contact_length, spec.reduced_radius, es);
    let summary = PointSummary {
        hertz_max_pressure: hz.max_pressure,
        hertz_half_width: hz.half_width,
        film_central: rolling.central_film,
        film_min: rolling.min_film,
        exit_film: rolling.exit_film.unwrap_or(rolling.min_film),
        pressure_spike: rolling.pressure_spike,
        pressure_spike_position: rolling.pressure_spike_position,
        max_pressure: rolling.max_pressure,
        lambda: rolling.lambda,
        asperity_load_fraction: rolling.asperity.load / spec.load,
        rolling_resistance: model.traction(&rolling, &input, 0.0).viscous,
        min_cam_roller_friction: case.min_cam_roller_friction()?,
        gross_sliding_pin_friction: case.gross_sliding_pin_friction()?,
        edge_pressure_peak: rolling.finite.as_ref().and_then(|f| f.edge_pressure_peak).map(|e| e.0),
        edge_pressure_peak_position: rolling.finite.as_ref().and_then(|f| f.edge_pressure_peak).map(|e| e.1),
        min_film_axial_position: rolling.finite.as_ref().map(|f| f.min_film_position.1),
        first_sliding_pin_friction: first.map(|f| f.0),
        first_sliding_cam_roller_friction: first.map(|f| f.1),
    };
    ensure_finite("cam point rows", rows.iter().flat_map(|r| [&r.slide_roll_ratio, &r.cam_roller_friction, &r.film_central]))?;
    Ok(CamPointResult {
        fidelity_used: spec.fidelity,
        film_model: rolling.model,
        ehl_settings: (spec.fidelity != Fidelity::Fast && spec.ehl.geometry.is_line()).then(|| spec.ehl.for_point().settings_used(super::accuracy::LineFamily::Roller)),
        contact_modulus: es,
        rows,
        summary,
        traction_along: (want_along && !along.is_empty()).then_some(along),
        convergence: Convergence::closed_form(),
    })
}
