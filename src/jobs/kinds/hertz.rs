//! `hertz`: dry Hertzian contact of two elastic bodies — line or point — with the sub-surface
//! stress maxima. Closed forms only (`physics::contact`).

use crate::jobs::cost::{Cost, JOB_OVERHEAD_S};
use crate::jobs::quantity as Q;
use crate::jobs::kind::{Kind, Limits, OutputInfo, Validation};
use super::common::Material;
use crate::physics::contact::{
    circular_axis_stress, circular_max_shear, contact_modulus, hertz_line, hertz_point,
    line_stress, line_stress_maxima, reduced_radius, Elastic, StressMaximum,
};
use crate::physics::{ensure_finite, Convergence, Observer, SolveError};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;

pub struct Hertz;

/// Line (two parallel cylinders, or cylinder on plane) or point (elliptical footprint) contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ContactType {
    Line,
    Point,
}

/// Shape of one body near the contact. `x` is the direction across the contact width (rolling
/// direction), `y` the transverse direction (along a cylinder's axis).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    /// A plane: no radius.
    Flat,
    /// A cylinder with its axis along `y`: `radius` curves the `x` direction only.
    Cylinder,
    /// A sphere of `radius` (point contact only).
    Sphere,
    /// Principal radii `radius` (in x) and `transverse_radius` (in y) (point contact only).
    Ellipsoid,
}

/// One contacting body: shape and elastic constants.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Body {
    pub shape: Shape,
    /// Radius of curvature in the x direction, m. Positive convex, negative concave.
    /// Required unless `shape` is `flat`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 0.0255)]
    pub radius: Option<f64>,
    /// Radius of curvature in the y direction, m (`ellipsoid` only). Positive convex, negative concave.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transverse_radius: Option<f64>,
    /// Elastic constants. Default: steel.
    #[serde(default)]
    pub material: Material,
}

impl Body {
    fn elastic(&self) -> Elastic {
        self.material.elastic()
    }
    /// Signed radii `(x, y)`; `INFINITY` where flat.
    fn radii(&self) -> (f64, f64) {
        let r = self.radius.unwrap_or(f64::INFINITY);
        match self.shape {
            Shape::Flat => (f64::INFINITY, f64::INFINITY),
            Shape::Cylinder => (r, f64::INFINITY),
            Shape::Sphere => (r, r),
            Shape::Ellipsoid => (r, self.transverse_radius.unwrap_or(f64::INFINITY)),
        }
    }
}

/// Spec of a `hertz` job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"contact": "line", "load": 5000.0, "length": 0.014,
    "body_1": {"shape": "cylinder", "radius": 0.0255}, "body_2": {"shape": "cylinder", "radius": 0.02}}))]
pub struct HertzSpec {
    pub contact: ContactType,
    /// Total normal load, N.
    #[schema(example = 5000.0)]
    pub load: f64,
    /// Contact length, m (line contact only; the load is spread uniformly along it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    pub body_1: Body,
    pub body_2: Body,
    /// Optional outputs: `stress_profile` (stresses along the contact axis).
    #[serde(default)]
    pub outputs: Vec<HertzOutput>,
    /// Points of the stress profile (depth 0 to 3 half-widths). Default 61.
    #[serde(default = "default_profile_points")]
    pub profile_points: usize,
}

fn default_profile_points() -> usize {
    61
}

/// Optional outputs of a `hertz` job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum HertzOutput {
    StressProfile,
}

/// Stresses along the contact axis (x = 0) from the surface to three half-widths deep.
/// Compression negative. For a circular point contact `sigma_x = sigma_y = σr`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StressProfile {
    /// Depth below the surface, m.
    pub depth: Vec<f64>,
    /// Pa.
    pub sigma_x: Vec<f64>,
    /// Pa (plane strain for line contacts: ν(σx + σz)).
    pub sigma_y: Vec<f64>,
    /// Pa.
    pub sigma_z: Vec<f64>,
    /// Largest principal shear stress (Tresca), Pa.
    pub principal_shear: Vec<f64>,
    /// von Mises equivalent stress, Pa.
    pub von_mises: Vec<f64>,
}

/// A stress maximum below the surface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct StressPeak {
    /// Pa.
    pub value: f64,
    /// Depth below the surface, m.
    pub depth: f64,
    /// Distance from the contact centre in x, m.
    pub offset: f64,
    /// `value / max_pressure`.
    pub ratio_to_max_pressure: f64,
}

/// Result of a `hertz` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct HertzResult {
    pub contact: ContactType,
    /// `E* = 1/Σ(1−ν²)/E`, Pa (Johnson's convention; every formula here uses it).
    pub contact_modulus: f64,
    /// `E' = 2E*`, Pa (the EHL literature's reduced modulus).
    pub effective_modulus: f64,
    /// Reduced radius in x, m.
    pub reduced_radius: f64,
    /// Reduced radius in y, m (point contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reduced_radius_transverse: Option<f64>,
    /// Load per unit length, N/m (line contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_per_length: Option<f64>,
    /// Semi-width of the contact band, m (line contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_width: Option<f64>,
    /// Semi-axis of the footprint in x, m (point contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub semi_axis_x: Option<f64>,
    /// Semi-axis of the footprint in y, m (point contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub semi_axis_y: Option<f64>,
    /// Mutual approach of distant points, m (point contact; undefined for a line contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approach: Option<f64>,
    /// Peak pressure p0, Pa.
    pub max_pressure: f64,
    /// Mean pressure, Pa.
    pub mean_pressure: f64,
    /// Maximum principal shear stress below the surface (line: 0.300 p0 at 0.786 b; circular
    /// point: 0.31 p0 at 0.48 a for ν = 0.3). Absent for non-circular point contacts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_shear: Option<StressPeak>,
    /// Maximum orthogonal shear |τxz| (line contact: 0.250 p0 at x = ±0.87 b, z = 0.5 b).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_orthogonal_shear: Option<StressPeak>,
    /// Maximum von Mises stress (on the axis; uses the softer body's ν... see `poisson_ratio_used`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_von_mises: Option<StressPeak>,
    /// Poisson's ratio used for the stress field (body 1's: stresses are reported in body 1).
    pub poisson_ratio_used: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_profile: Option<StressProfile>,
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}

/// A body radius: negative for a concave surface, its magnitude a physical radius
/// (`jobs::quantity::RADIUS`).
fn radius_ok(r: f64) -> bool {
    r.is_finite() && (Q::RADIUS.min..=Q::RADIUS.max).contains(&r.abs())
}

const RADIUS_RULE: &str = "must be between 1e-5 m and 100 m in magnitude (negative for a concave surface)";

impl Kind for Hertz {
    const NAME: &'static str = "hertz";
    const SOLVER_VERSION: &'static str = "hertz-1";
    const DESCRIPTION: &'static str = "Dry Hertzian line or point contact: contact size, peak \
        pressure and sub-surface stress maxima (closed forms, Johnson's Contact Mechanics).";
    const TABLES: &'static [&'static str] = &["stress_profile"];
    const KEY_FIGURES: &'static [&'static str] = &["/max_pressure", "/half_width", "/mean_pressure", "/max_shear/value", "/max_shear/depth", "/max_von_mises/value", "/approach"];
    type Spec = HertzSpec;
    type Output = HertzResult;

    fn example() -> Value {
        json!({
            "contact": "line",
            "load": 5000.0,
            "length": 0.014,
            "body_1": {"shape": "cylinder", "radius": 0.0255},
            "body_2": {"shape": "cylinder", "radius": 0.02},
            "outputs": ["stress_profile"]
        })
    }

    fn outputs() -> &'static [OutputInfo] {
        &[OutputInfo {
            name: "stress_profile",
            description: "stresses along the contact axis from the surface to 3 half-widths deep",
        }]
    }

    fn validate(spec: &HertzSpec, _limits: &Limits, v: &mut Validation) {
        // Upper bounds far above any machine element, low enough that no intermediate overflows
        // (a load of 1e308 N used to end as an internal error instead of a 422).
        v.quantity("/load", spec.load, Q::FORCE);
        for (name, body) in [("/body_1", &spec.body_1), ("/body_2", &spec.body_2)] {
            body.material.validate(&format!("{name}/material"), v);
            let needs_radius = body.shape != Shape::Flat;
            for (field, r) in [("radius", body.radius), ("transverse_radius", body.transverse_radius)] {
                if let Some(r) = r.filter(|r| radius_ok(*r)) {
                    v.plausible(&format!("{name}/{field}"), r.abs(), Q::RADIUS);
                }
            }
            match body.radius {
                Some(r) => v.check(
                    needs_radius && radius_ok(r),
                    &format!("{name}/radius"),
                    if needs_radius { RADIUS_RULE } else { "a flat body has no radius" },
                ),
                None => v.check(!needs_radius, &format!("{name}/radius"), "is required for this shape"),
            };
            match body.transverse_radius {
                Some(r) => v.check(
                    body.shape == Shape::Ellipsoid && radius_ok(r),
                    &format!("{name}/transverse_radius"),
                    if body.shape == Shape::Ellipsoid { RADIUS_RULE } else { "only an ellipsoid has a transverse radius" },
                ),
                None => v.check(
                    body.shape != Shape::Ellipsoid,
                    &format!("{name}/transverse_radius"),
                    "is required for an ellipsoid",
                ),
            };
            if spec.contact == ContactType::Line {
                v.check(
                    matches!(body.shape, Shape::Flat | Shape::Cylinder),
                    &format!("{name}/shape"),
                    "a line contact needs flat or cylinder bodies",
                );
            }
        }
        match (spec.contact, spec.length) {
            (ContactType::Line, Some(l)) => {
                v.quantity("/length", l, Q::LENGTH);
            }
            (ContactType::Line, None) => {
                v.error("/length", "is required for a line contact");
            }
            (ContactType::Point, Some(_)) => {
                v.error("/length", "only a line contact has a length");
            }
            (ContactType::Point, None) => {}
        }
        v.count_in_range("/profile_points", spec.profile_points, 2, 10_000);
        if v.is_ok() {
            let (x1, y1) = spec.body_1.radii();
            let (x2, y2) = spec.body_2.radii();
            v.check(
                reduced_radius(x1, x2).is_some(),
                "/body_2/radius",
                "the bodies conform in x (1/r1 + 1/r2 <= 0): no Hertzian contact",
            );
            if spec.contact == ContactType::Point {
                v.check(
                    reduced_radius(y1, y2).is_some(),
                    "/body_2/shape",
                    "the bodies do not curve in y: a point contact needs curvature in both directions (use contact: line)",
                );
            }
        }
    }

    fn cost(_spec: &HertzSpec) -> Cost {
        // Closed forms; the sub-surface stress field (output `stress_field`) is a few thousand points.
        Cost::new(JOB_OVERHEAD_S, 1.0 * crate::jobs::cost::MIB)
    }

    fn solve(spec: &HertzSpec, _observer: &dyn Observer) -> Result<HertzResult, SolveError> {
        let es = contact_modulus(spec.body_1.elastic(), spec.body_2.elastic());
        let nu = spec.body_1.material.poisson_ratio;
        let (x1, y1) = spec.body_1.radii();
        let (x2, y2) = spec.body_2.radii();
        let rx = reduced_radius(x1, x2)
            .ok_or_else(|| SolveError::invalid("/body_2/radius", "conforming surfaces"))?;
        let want_profile = spec.outputs.contains(&HertzOutput::StressProfile);
        let peak = |m: StressMaximum, p0: f64| StressPeak {
            value: m.value,
            depth: m.depth,
            offset: m.offset,
            ratio_to_max_pressure: m.value / p0,
        };
        let depths = |scale: f64| -> Vec<f64> {
            let n = spec.profile_points;
            (0..n).map(|i| 3.0 * scale * i as f64 / (n - 1) as f64).collect()
        };
        let result = match spec.contact {
            ContactType::Line => {
                let length = spec.length.unwrap_or(1.0);
                let c = hertz_line(spec.load / length, rx, es);
                let maxima = line_stress_maxima(&c, nu);
                let stress_profile = want_profile.then(|| {
                    let depth = depths(c.half_width);
                    let s: Vec<_> = depth.iter().map(|&z| line_stress(0.0, z, &c, nu)).collect();
                    StressProfile {
                        sigma_x: s.iter().map(|s| s.sigma_x).collect(),
                        sigma_y: s.iter().map(|s| s.sigma_y).collect(),
                        sigma_z: s.iter().map(|s| s.sigma_z).collect(),
                        principal_shear: s.iter().map(|s| tresca(s.sigma_x, s.sigma_y, s.sigma_z)).collect(),
                        von_mises: s.iter().map(|s| s.von_mises()).collect(),
                        depth,
                    }
                });
                HertzResult {
                    contact: ContactType::Line,
                    contact_modulus: es,
                    effective_modulus: 2.0 * es,
                    reduced_radius: rx,
                    reduced_radius_transverse: None,
                    load_per_length: Some(c.load_per_length),
                    half_width: Some(c.half_width),
                    semi_axis_x: None,
                    semi_axis_y: None,
                    approach: None,
                    max_pressure: c.max_pressure,
                    mean_pressure: c.mean_pressure,
                    max_shear: Some(peak(maxima.max_shear, c.max_pressure)),
                    max_orthogonal_shear: Some(peak(maxima.max_orthogonal_shear, c.max_pressure)),
                    max_von_mises: Some(peak(maxima.max_von_mises, c.max_pressure)),
                    poisson_ratio_used: nu,
                    stress_profile,
                    convergence: Convergence::closed_form(),
                }
            }
            ContactType::Point => {
                let ry = reduced_radius(y1, y2)
                    .ok_or_else(|| SolveError::invalid("/body_2/shape", "no curvature in y"))?;
                let c = hertz_point(spec.load, rx, ry, es)?;
                // The larger semi-axis lies along the direction of the larger reduced radius.
                let (ax, ay) = if rx >= ry { (c.semi_major, c.semi_minor) } else { (c.semi_minor, c.semi_major) };
                let circular = (rx - ry).abs() <= 1e-12 * rx.max(ry);
                let a = c.semi_major;
                let (max_shear, max_von_mises, stress_profile) = if circular {
                    let s = circular_max_shear(a, c.max_pressure, nu);
                    // On the axis σr = σθ, so von Mises = |σr − σz| = 2 τ: same depth.
                    let vm = StressMaximum { value: 2.0 * s.value, ..s };
                    let profile = want_profile.then(|| {
                        let depth = depths(a);
                        let s: Vec<_> =
                            depth.iter().map(|&z| circular_axis_stress(z, a, c.max_pressure, nu)).collect();
                        StressProfile {
                            sigma_x: s.iter().map(|s| s.0).collect(),
                            sigma_y: s.iter().map(|s| s.0).collect(),
                            sigma_z: s.iter().map(|s| s.1).collect(),
                            principal_shear: s.iter().map(|s| 0.5 * (s.0 - s.1).abs()).collect(),
                            von_mises: s.iter().map(|s| (s.0 - s.1).abs()).collect(),
                            depth,
                        }
                    });
                    (Some(peak(s, c.max_pressure)), Some(peak(vm, c.max_pressure)), profile)
                } else {
                    (None, None, None)
                };
                HertzResult {
                    contact: ContactType::Point,
                    contact_modulus: es,
                    effective_modulus: 2.0 * es,
                    reduced_radius: rx,
                    reduced_radius_transverse: Some(ry),
                    load_per_length: None,
                    half_width: None,
                    semi_axis_x: Some(ax),
                    semi_axis_y: Some(ay),
                    approach: Some(c.approach),
                    max_pressure: c.max_pressure,
                    mean_pressure: c.mean_pressure,
                    max_shear,
                    max_orthogonal_shear: None,
                    max_von_mises,
                    poisson_ratio_used: nu,
                    stress_profile,
                    convergence: Convergence::closed_form(),
                }
            }
        };
        ensure_finite("hertz result", [&result.max_pressure, &result.reduced_radius, &result.mean_pressure])?;
        Ok(result)
    }
}

/// Largest principal shear `(σmax − σmin)/2` of three principal stresses.
fn tresca(a: f64, b: f64, c: f64) -> f64 {
    0.5 * (a.max(b).max(c) - a.min(b).min(c))
}
