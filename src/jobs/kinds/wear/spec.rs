use super::*;

/// Wear model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum WearModel {
    /// Archard wear over the cam cycle with worn-profile evolution.
    #[default]
    Archard,
    /// Seed 004's empirical method (multi-arc cam, spherical tappet, eq. 15).
    Irgashev,
}

/// A wear coefficient: either the dimensional `k` or the dimensionless `K` with the hardness `H`
/// of the wearing body (`k = K/H`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct WearCoefficientSpec {
    /// Dimensional wear coefficient k, m³/(N·m) (= 1/Pa): worn volume per unit load and sliding
    /// distance. Typical lubricated steel cams: 1e-18 … 1e-16.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimensional: Option<f64>,
    /// Dimensionless Archard coefficient K (with `hardness`). Typical lubricated steel: 1e-9 … 1e-6.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimensionless: Option<f64>,
    /// Hardness H of the wearing body, Pa (Vickers HV × 9.807e6; 60 HRC ≈ 7e9 Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hardness: Option<f64>,
}

impl WearCoefficientSpec {
    /// k in 1/Pa.
    pub fn k(&self) -> f64 {
        match (self.dimensional, self.dimensionless, self.hardness) {
            (Some(k), _, _) => k,
            (None, Some(kk), Some(h)) => kk / h,
            _ => 0.0,
        }
    }
    pub(super) fn validate(&self, path: &str, v: &mut Validation) {
        match (self.dimensional, self.dimensionless, self.hardness) {
            (Some(k), None, None) => {
                v.in_range(&format!("{path}/dimensional"), k, 0.0, 1e-9);
            }
            (None, Some(kk), Some(h)) => {
                v.in_range(&format!("{path}/dimensionless"), kk, 0.0, 1.0);
                v.in_range(&format!("{path}/hardness"), h, 1e6, 1e11);
            }
            _ => {
                v.error(path, "give either `dimensional` (k, m³/(N·m)) or `dimensionless` (K) with `hardness` (Pa)");
            }
        }
    }
}

/// Which part of the contact load wears the surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum LoadShareSpec {
    /// Only the asperity-carried share (Greenwood–Tripp, from the cycle's film): needs a
    /// lubricant and rough surfaces.
    #[default]
    Asperity,
    /// The whole contact load (dry or boundary contact; or a k measured under the same
    /// lubrication).
    Full,
}

/// Which contact widths (eq. 2) and areas (eq. 3) seed 004's method uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum WidthReadingSpec {
    /// Eq. 2–3 at the cam material's Young's modulus, unrounded (the consistent reading).
    #[default]
    Material,
    /// The paper's tables: eq. 2 at E = 215 GPa (the modulus with which eq. 2 gives every width of
    /// Table 3 to its printed 0.001 mm; 210 GPa leaves them 0.8 % wide and eq. 15 2.4 % low),
    /// rounded to 0.001 mm as Table 5 feeds them into eq. 15; eq. 3 at the cam's modulus rounded
    /// to 0.001 mm². Reproduces Table 5's rows from its printed inputs.
    Paper,
}

impl From<WidthReadingSpec> for irgashev::WidthReading {
    fn from(w: WidthReadingSpec) -> Self {
        match w {
            WidthReadingSpec::Material => irgashev::WidthReading::Material,
            WidthReadingSpec::Paper => irgashev::WidthReading::Paper,
        }
    }
}

pub(super) fn default_steps() -> usize {
    9
}

pub(super) fn default_theta() -> f64 {
    4.23e-12
}

pub(super) fn default_yield() -> f64 {
    1.3e9
}

pub(super) fn default_c() -> f64 {
    3.0
}

pub(super) fn default_np() -> f64 {
    24.0
}

/// Inputs of seed 004's method besides the pair (defaults: the paper's values listed after
/// eq. 15).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct IrgashevSpec {
    /// Slip δ per arc (Table 4: 0.0111, 0.1211, 0.2360, 0.2360, 0.1285, 0.113), dimensionless.
    pub slip: Vec<f64>,
    /// Follower lift at the nose, m (the paper's 10 mm: 440 N over 44 N/mm).
    pub nose_lift: f64,
    /// Rows per flank arc, each a step of equal angle and equal lift increment. Default 9.
    #[serde(default = "default_steps")]
    pub flank_steps: usize,
    /// Elasticity constant θ, 1/Pa. Default 4.23e-12 (the paper's 4.23e-6 1/MPa).
    #[serde(default = "default_theta")]
    pub elasticity_constant: f64,
    /// Yield strength σ_t of the cam, Pa. Default 1.3e9.
    #[serde(default = "default_yield")]
    pub yield_strength: f64,
    /// Deformation coefficient c. Default 3.
    #[serde(default = "default_c")]
    pub deformation_coefficient: f64,
    /// Loadings that fail the deformed volume, n_p. Default 24.
    #[serde(default = "default_np")]
    pub cycles_to_failure: f64,
    /// Contact widths and areas: `material` (default: eq. 2–3 at the cam's modulus) or `paper`
    /// (Table 3's reading: eq. 2 at 215 GPa, rounded to 0.001 mm; reproduces Table 5).
    #[serde(default)]
    pub width_reading: WidthReadingSpec,
}

pub(super) fn default_snapshots() -> usize {
    10
}

/// Spec of a `wear` job. The cam–follower pair is exactly `cam_cycle`'s (steady running only).
/// SI units; angles in degrees where the name says so.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct WearSpec {
    /// The cam–follower pair and its running, as a `cam_cycle` spec: steady running only; the
    /// wear model decides what each cycle computes, so `outputs`, `profile_angles_deg` and
    /// `thermal` stay out. Its `fidelity` is the film model of every cycle (archard): `fast`
    /// (closed forms: Hertz pressure, Greenwood–Tripp share at the central film; default),
    /// `accurate` (the numerical line-contact EHL solver at every angle of every cycle: the
    /// wearing pressure is the EHL pressure, or with `load_share: asperity` the Greenwood–Tripp
    /// asperity pressure at the local film, which peaks at the exit constriction; spherical
    /// tappets keep the closed form), `auto` (per angle the closed form where its estimated error
    /// is within `ehl.auto_tolerance`, the numerical solver elsewhere; each angle wears with the
    /// model that ran there). `accurate` and `auto` need a lubricant, and their work — angles ×
    /// (2 × planned updates + 1) × `ehl.nodes` — counted in cycles of 720 angles × 192 nodes, must
    /// stay within the server's evaluation limit; a run takes at most twice its planned updates
    /// (stability cuts included). Its `angles` are also the resolution of the wear profile. A
    /// lubricant is required for the asperity load share and for roller followers (slip); without
    /// one the contact is dry.
    pub cycle: CamCycleSpec,
    /// `archard` (default) or `irgashev`.
    #[serde(default)]
    pub model: WearModel,
    /// Running time, h (give `hours` or `cycles`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hours: Option<f64>,
    /// Running time in camshaft revolutions (give `hours` or `cycles`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycles: Option<f64>,
    /// Archard: running time between profile updates, h. Default: a tenth of the running time.
    /// Updates that would wear more than 0.1·ρ·Δθ² somewhere (ρ the cam's radius of curvature,
    /// Δθ the angle step) are shortened automatically: larger steps make the explicit update
    /// unstable.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub update_interval_hours: Option<f64>,
    /// Wear coefficient of the cam (required by `archard`; with `irgashev` it adds an Archard
    /// column to the rows).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wear_coefficient: Option<WearCoefficientSpec>,
    /// Wear coefficient of the follower. Default: the cam's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub follower_wear_coefficient: Option<WearCoefficientSpec>,
    /// `asperity` (default) or `full`.
    #[serde(default)]
    pub load_share: LoadShareSpec,
    /// Cam wear depth that ends the run, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wear_limit: Option<f64>,
    /// Archard: wear-depth profiles kept over time (evenly spaced). Default 10; 0 for none.
    #[serde(default = "default_snapshots")]
    pub snapshots: usize,
    /// Required by `model: irgashev`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub irgashev: Option<IrgashevSpec>,
}

impl WearSpec {
    pub(super) fn is_roller(&self) -> bool {
        matches!(self.cycle.follower, FollowerSpec::Roller { .. })
    }

    /// The pair as a `cam_cycle` spec computing what the wear model needs.
    pub fn cycle_spec(&self) -> CamCycleSpec {
        let mut outputs = match self.model {
            WearModel::Archard => vec![CamOutput::Kinematics, CamOutput::Loads, CamOutput::Contact],
            WearModel::Irgashev => vec![CamOutput::Kinematics],
        };
        if self.model == WearModel::Archard {
            // Accurate/auto: the film's pressure wears, whatever the load share.
            let film_pressure = self.cycle.fidelity != Fidelity::Fast;
            if self.cycle.lubricant.is_some() && (self.load_share == LoadShareSpec::Asperity || self.is_roller() || film_pressure) {
                outputs.push(CamOutput::Film);
            }
            if self.is_roller() {
                outputs.push(CamOutput::Slip);
            }
        }
        CamCycleSpec { outputs, ..self.cycle.clone() }
    }

    pub(super) fn omega(&self) -> f64 {
        crate::physics::units::rpm_to_rad_per_s(self.cycle.operation.speed_rpm)
    }

    /// Running time, h.
    pub fn running_hours(&self) -> f64 {
        match (self.hours, self.cycles) {
            (Some(h), _) => h,
            (None, Some(c)) => crate::physics::units::hours_for_revolutions(c, self.cycle.operation.speed_rpm),
            _ => 0.0,
        }
    }

    pub(super) fn update_hours(&self) -> f64 {
        self.update_interval_hours.unwrap_or(self.running_hours() / 10.0)
    }

    /// Profile updates the running time and interval ask for (0 when either is not usable).
    pub(super) fn planned_updates(&self) -> usize {
        let (hours, u) = (self.running_hours(), self.update_hours());
        if hours > 0.0 && u > 0.0 && u.is_finite() { (hours / u).ceil().min(1e15) as usize } else { 0 }
    }

    /// Most profile updates of a run (see [`NUMERICAL_UPDATE_FACTOR`]).
    pub(super) fn max_updates(&self) -> usize {
        match self.cycle.fidelity {
            Fidelity::Fast => MAX_UPDATES,
            _ => self.planned_updates().max(1).saturating_mul(NUMERICAL_UPDATE_FACTOR),
        }
    }

    pub(super) fn composite_sigma(&self) -> f64 {
        let rq = match &self.cycle.follower {
            FollowerSpec::FlatFaced { roughness_rq, .. }
            | FollowerSpec::Roller { roughness_rq, .. }
            | FollowerSpec::Spherical { roughness_rq, .. } => *roughness_rq,
        };
        composite_sigma(self.cycle.cam.roughness_rq, rq)
    }
}
