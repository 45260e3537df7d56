use super::*;

/// Why the run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum WearStopReason {
    /// The requested running time was reached.
    Completed,
    /// The cam wear depth reached `wear_limit`.
    WearLimit,
    /// The next worn profile would undercut the cam (cusp).
    CamUndercut,
    /// On the next worn profile the follower would leave the cam.
    FollowerSeparation,
    /// On the next worn profile the contact would run off the flat face.
    ContactOffFace,
    /// Another typed failure of the cycle on the next worn profile (see `code`).
    ProfileFailure,
    /// Stable updates would need more than the most updates a run may take (`update_limit`).
    UpdateLimit,
}

/// How the run ended. A run that ends on a failed profile still returns everything up to the
/// last valid profile.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearTermination {
    pub reason: WearStopReason,
    /// The cycle's error code when the profile failed (`cam_undercut`, `follower_separation`, …).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code: Option<String>,
    /// Its message.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
    /// Running time of the profile update that failed, h.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_hours: Option<f64>,
}

/// Per cam angle, columnar, SI. Archard: at the end of the run; `angle_deg` is the cam angle at
/// which that cam point meets the follower. Irgashev: `angle_deg` is the position along the
/// profile (the arcs laid end to end from the start of arc 1).
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct WearSeries {
    /// Degrees.
    pub angle_deg: Vec<f64>,
    /// Cam wear depth along the surface normal, m.
    pub wear_depth: Vec<f64>,
    /// Cam wear rate at the end of the run, m/s.
    pub wear_rate: Vec<f64>,
    /// Drop of the follower lift at this cam angle (wear/cos φ), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lift_loss: Option<Vec<f64>>,
    /// Arc length along the cam surface from the point of 0°, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_position: Option<Vec<f64>>,
    /// Follower lift of the original profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_lift: Option<Vec<f64>>,
    /// Follower lift of the worn profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_lift: Option<Vec<f64>>,
    /// Share of the contact load that wears (asperity share or 1), end of the run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worn_load_share: Option<Vec<f64>>,
    /// Sliding velocity u_c − u_f at the end of the run, m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sliding_velocity: Option<Vec<f64>>,
    /// Hertz peak pressure on the original and on the worn profile, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_hertz_pressure: Option<Vec<f64>>,
    /// Hertz peak pressure on the worn profile, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_hertz_pressure: Option<Vec<f64>>,
    /// Minimum film on the original and on the worn profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_film_min: Option<Vec<f64>>,
    /// Minimum film on the worn profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_film_min: Option<Vec<f64>>,
    /// Film model that ran at each angle on the worn profile (fidelity accurate/auto).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<crate::jobs::schemas::FilmModelIdDoc>>)]
    pub film_model: Option<Vec<FilmModelId>>,
}

/// One row of seed 004's Tables 1–5 (SI, except where the name says otherwise).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearRow {
    /// Profile part (arc) number, from 1.
    pub part: usize,
    /// Step within a flank arc, from 1; 0 for base and nose arcs.
    pub step: usize,
    /// `base`, `flank_rising`, `nose` or `flank_falling`.
    pub role: String,
    /// Start and end of the row along the profile, degrees.
    pub position_start_deg: f64,
    pub position_end_deg: f64,
    /// Table 5's "current deflection angle" of the part, degrees.
    pub angle_deg: f64,
    /// Arc radius, m.
    pub radius: f64,
    /// Reduced radius with the tappet sphere (Table 1), m.
    pub reduced_radius: f64,
    /// Follower lift of the row, m.
    pub lift: f64,
    /// Spring force (Tables 3–5), N.
    pub spring_force: f64,
    /// Arc length by eq. 1 as printed, 2αr/360 (Tables 2 and 5), m.
    pub profile_length_as_printed: f64,
    /// True arc length παr/180, m.
    pub profile_length: f64,
    /// Contact width by eq. 2 (Table 3), m.
    pub contact_width: f64,
    /// Contact area by eq. 3 (Table 3), m².
    pub contact_area: f64,
    /// Slip δ (Table 4), dimensionless.
    pub slip: f64,
    /// Wear rate by eq. 15 as printed (Table 5's withheld column), mm/h.
    pub wear_rate_mm_per_h: f64,
    /// Wear rate by eq. 6 with eq. 7–14 substituted (what eq. 15 claims to simplify), mm/h.
    pub chain_wear_rate_mm_per_h: f64,
    /// Hertz contact width 2a along the rolling direction (sphere on the arc), m.
    pub hertz_contact_width: f64,
    /// Hertz peak pressure, Pa.
    pub hertz_pressure: f64,
    /// Archard: k δ (π/2) p0 a per pass × passes per hour (when `wear_coefficient` is given), mm/h.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub archard_wear_rate_mm_per_h: Option<f64>,
}

/// The state after each profile update (and at the start).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearHistoryRow {
    /// Running time, h.
    pub hours: f64,
    /// Camshaft revolutions.
    pub cycles: f64,
    /// Largest cam wear depth, m.
    pub max_wear_depth: f64,
    /// Its cam angle, degrees.
    pub max_wear_angle_deg: f64,
    /// Largest cam wear rate on this profile, m/s.
    pub max_wear_rate: f64,
    /// Cam volume worn so far, m³.
    pub worn_volume: f64,
    /// Follower volume worn so far, m³.
    pub follower_worn_volume: f64,
    /// Drop of the peak follower lift, m.
    pub valve_lift_loss: f64,
    /// Smallest minimum film over the revolution, m (when a film is computed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film: Option<f64>,
    /// Largest Hertz pressure over the revolution, Pa.
    pub max_pressure: f64,
    /// Largest pressure of the numerical EHL film over the revolution (exit spike included), Pa
    /// (fidelity accurate/auto, where the numerical model ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_film_pressure: Option<f64>,
}

/// Flat follower face wear, columnar.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FaceWear {
    /// Position on the face, m, measured like the cycle's `contact_offset`: from the cam centre
    /// line (the follower axis when `offset` is 0).
    pub position: Vec<f64>,
    /// Face wear depth, m.
    pub wear_depth: Vec<f64>,
}

/// The cam wear depth at one time.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearSnapshot {
    /// h.
    pub hours: f64,
    /// Per cam angle (the series' `angle_deg`), m.
    pub wear_depth: Vec<f64>,
}

/// Flat numbers.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct WearSummary {
    /// Largest cam wear depth, m.
    pub max_wear_depth: f64,
    /// Where, degrees (cam angle; irgashev: profile position).
    pub max_wear_angle_deg: f64,
    /// Largest cam wear rate at the end, m/s.
    pub max_wear_rate: f64,
    /// Running time at which the cam wear reached `wear_limit`, h (absent when not reached).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hours_to_limit: Option<f64>,
    /// When the limit was not reached: the time it would be at the final wear rates, h.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hours_to_limit_extrapolated: Option<f64>,
    /// Cam volume worn, m³ (`k ∫ F_worn |v_s| dt`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worn_volume: Option<f64>,
    /// Follower volume worn, m³.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub follower_worn_volume: Option<f64>,
    /// Flat face: largest face wear depth, m, and its position from the axis, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_follower_wear_depth: Option<f64>,
    /// Position of the largest face wear depth from the follower axis, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_follower_wear_position: Option<f64>,
    /// Roller: wear depth spread evenly over its circumference, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roller_wear_depth: Option<f64>,
    /// Loss of peak valve lift with mechanical lash (drop of the peak follower lift), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_lift_loss: Option<f64>,
    /// Loss of peak valve lift with a lash adjuster (drop of the peak lift over the base circle's
    /// mean lift, the base circle being where the original lift is lowest), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valve_lift_loss_lash_adjusted: Option<f64>,
    /// Smallest minimum film on the original and on the final profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_min_film: Option<f64>,
    /// Smallest minimum film on the final profile, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_min_film: Option<f64>,
    /// Largest Hertz pressure on the original and on the final profile, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_max_pressure: Option<f64>,
    /// Largest Hertz pressure on the final profile, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_max_pressure: Option<f64>,
    /// Largest numerical EHL film pressure (exit spike included) on the original and on the final
    /// profile, Pa (fidelity accurate/auto, where the numerical model ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_max_film_pressure: Option<f64>,
    /// Largest numerical EHL film pressure on the final profile, Pa (fidelity accurate/auto).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_max_film_pressure: Option<f64>,
    /// Fidelity accurate/auto: angles at which each film model ran (`numerical`, `pan_hamrock`,
    /// …), summed over every cycle of the run (the unworn profile and each update).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fidelity_used: Option<BTreeMap<String, usize>>,
}

/// Result of a `wear` job.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct WearResult {
    pub model: WearModel,
    /// Fidelity requested (per-model counts: `summary.fidelity_used`).
    #[schema(value_type = crate::jobs::schemas::FidelityDoc)]
    pub fidelity_used: Fidelity,
    /// Film model of the cycles (when a film was computed and one model ran at every angle;
    /// absent when `auto` mixed models or a point contact kept the closed form).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<crate::jobs::schemas::FilmModelIdDoc>)]
    pub film_model: Option<FilmModelId>,
    /// Cam wear coefficient used, m³/(N·m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wear_coefficient: Option<f64>,
    pub termination: WearTermination,
    /// Running time reached, h.
    pub hours: f64,
    /// Camshaft revolutions run.
    pub cycles: f64,
    /// Profile updates performed (archard).
    pub updates: usize,
    /// Angles per revolution.
    pub angles: usize,
    pub series: WearSeries,
    /// Seed 004's Tables 1–5, one row per spring force (irgashev).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rows: Option<Vec<WearRow>>,
    /// After each update (archard).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub history: Option<Vec<WearHistoryRow>>,
    /// Flat follower face wear (archard, flat-faced follower).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub follower_face: Option<FaceWear>,
    /// Cam wear-depth profiles over time (archard).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<Vec<WearSnapshot>>,
    pub summary: WearSummary,
    /// Archard: the profile updates (a fixed-step march: no tolerance); irgashev: closed form.
    #[schema(value_type = crate::jobs::schemas::ConvergenceDoc)]
    pub convergence: Convergence,
}
