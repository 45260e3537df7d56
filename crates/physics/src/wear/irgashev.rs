//! Seed 004's wear method (Irgashev, Mirzaev, Kurbonov): a multi-arc cam against a spherical
//! tappet, contact width and area from the spring force, slip per arc, and the wear rate of
//! eq. 15 — reproduced as printed, in the paper's units (N, mm, MPa, h), next to the chain of
//! eq. 6–14 it claims to simplify and a Hertz/Archard estimate for the same contact.
//!
//! # The paper's procedure
//! * Six arcs (base, flank, nose, nose, flank, base; Tables 1–2), reduced radius against the 42 mm
//!   tappet sphere `ρ = r r_t/(r + r_t)` (Table 1), arc length by eq. 1 as printed `2αr/360`.
//! * Spring force `P = z_n h` (eq. 2's `z_n h`): the base arcs carry the preload; each flank arc is
//!   cut into `m` (= 9) steps of equal angle whose lifts rise in equal steps of `h_max/(m + 1)`
//!   (Tables 3–5: 264 N, 308 … 660 N, 704 N at the nose, i.e. 44 N/mm × 1 mm steps, 10 mm lift).
//! * Contact width `B` (eq. 2) and area `F` (eq. 3) of [`crate::cam::seed004`].
//! * Slip per arc δ (Table 4), given.
//! * Wear rate, eq. 15: `γ = 6.376 P² θ (1 + δ) n_k / (B³ σ_t c n_p)` mm/h with `θ` in 1/MPa,
//!   `σ_t` in MPa, `n_k` in 1/s, `P` in N, `B` in mm (the inputs listed after eq. 15).
//!
//! # What the paper does not say, or says inconsistently (reproduced, documented)
//! * Eq. 1 writes the arc length `2αr/360`: a factor π short of `παr/180`; Tables 2 and 5 use it
//!   (13.856 mm for 116° of a 21.5 mm arc, whose true length is 43.53 mm).
//! * Eq. 15 is not what eq. 6 becomes with eq. 7–14 substituted. The chain
//!   `γ = F·S·M·n·η/(F_cm n_p)` with eq. 8 (`F = 0.65 P²θ/(B² c σ_t)`), eq. 9 (`S = δ l`), eq. 10
//!   (`M = B c σ_t E/(14.275 p² ρ)`), eq. 13 (`η = 0.0389 p² ρ/(B c σ_t E)`) collapses to
//!   `6.376 P² θ δ l n/(B² c σ_t F_cm n_p)` mm/h — its constant 0.65·0.0389/14.275·3600 = 6.3766 is
//!   eq. 15's, which identifies the ×3600 s/h of eq. 15 (so eq. 15 is in mm/h with `n_k` in 1/s,
//!   as labelled), but eq. 15 replaces `δ l/F_cm` by `(1 + δ)/B`: the sliding path per pass
//!   becomes `(1 + δ) B` instead of `δ l` (and `F_cm ≈ B²`, eq. 3 being ≈ 0.9955 B²). The profile
//!   length `L_k = 135.028 mm` listed among eq. 15's inputs appears in neither. Both are reported.
//! * The text's references in the derivation are off (`F` "from (29)", `S` "from (10)", `M` "from
//!   (11)", …); eq. 5 reads `(L_ci − L_ci)/L_ci` = 0; eq. 11 reuses `F_kc` for the contact area.
//! * Table 4's "deformation in height" is the spring's length, not its deflection: the forces are
//!   `44 N/mm × (52 mm − H)`; the part-5 heights (37, 39, 40 … 46) skip 38 and the part-6 height
//!   (48) should be 46 for the forces listed. Part 6's slip 0.113 is ten times part 1's 0.0111.
//! * Table 1 prints 14.20 mm for `21.5·42/63.5 = 14.22 mm`; Table 2 prints 53.440 for
//!   `2·62.75·153.3/360 = 53.442` (Table 5 has 53.442) and 0.218 for 0.21875.
//! * Exhaust cam: Table 2's part-2 length 42.752 mm does not follow from 65° and 117 mm (42.25);
//!   its nose length 0.272 mm and Table 3's nose width follow from a 31.5 mm nose, not the
//!   56.18 mm listed.
//! * Eq. 3 is called the area of a circular spot but equals ≈ B², not πB²/4.
//! * The six arcs of Tables 1–2 do not close as tangent arcs
//!   ([`crate::cam::MultiArc::new`] refuses them), and the spring force ignores the
//!   valve train's inertia and the pressure angle.
//! * The wear rates are huge for a cam (µm per hour; the fatigue-cycle count `n_p = 24` is tiny).
//! * Table 3's widths do not follow eq. 2 at E = 2.1e5 MPa: all eleven are 0.80 % (±0.05 %,
//!   their rounding) narrower, a constant factor whatever the force and radius — so not the
//!   exponent 0.67 (against 2/3), nor the rounded radii of Table 1, but the modulus: eq. 2 with
//!   **E = 2.15e5 MPa** (a common handbook value for steel) gives every printed width to the
//!   printed 0.001 mm, and only moduli within 214 950–215 050 MPa do (scan in 50 MPa steps, μ = 0.3).
//!   Cubed in eq. 15, the 0.8 % became the ~2.4 % by which the rates computed at 2.1e5 MPa missed
//!   eq. 15 on Table 5's printed inputs; the residual ≤ 0.17 % is Table 5 feeding its rounded
//!   (0.001 mm) widths into eq. 15. [`WidthReading::Paper`] reads eq. 2 that way: 2.15e5 MPa,
//!   widths rounded to 0.001 mm, so eq. 15 gives Table 5's rows from its printed force, width
//!   and the slip of Table 4 exactly (to rounding of the arithmetic).
//! * Table 3's areas follow no single modulus that way: at 2.1e5 MPa eq. 3 is within
//!   −0.6…+0.4 % of them, at 2.15e5 MPa 1–2 % below. The paper reading keeps eq. 3 at the cam's
//!   modulus, rounded to Table 3's 0.001 mm² (only the eq. 6–14 chain uses the area).

use crate::cam::seed004;
use crate::contact::hertz_point;
use crate::{ensure_finite, SolveError};
use std::f64::consts::PI;

/// Eq. 15's constant (the paper's value).
pub const EQ15_CONSTANT: f64 = 6.376;
/// The constant of the eq. 6–14 chain: eq. 8 × eq. 10⁻¹ × eq. 13 × 3600 s/h.
pub const CHAIN_CONSTANT: f64 = 0.65 * 0.0389 / 14.275 * 3600.0;

/// Which contact widths (eq. 2) and areas (eq. 3) feed eq. 15 and the eq. 6–14 chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WidthReading {
    /// Eq. 2–3 at the cam material's modulus, unrounded (the physically consistent reading).
    #[default]
    Material,
    /// The paper's tables: eq. 2 at [`PAPER_WIDTH_MODULUS_MPA`] rounded to Table 3's 0.001 mm,
    /// eq. 3 at the material's modulus rounded to 0.001 mm² — what Table 5 feeds into eq. 15.
    Paper,
}

/// The modulus (MPa) with which eq. 2 gives all eleven widths of Table 3 to the printed digit
/// (found by a scan: only 214 950–215 050 MPa do, with μ = 0.3).
pub const PAPER_WIDTH_MODULUS_MPA: f64 = 2.15e5;

/// Rounds `x` to `digits` decimals (the paper's printed precision).
fn round_to(x: f64, digits: i32) -> f64 {
    let f = 10f64.powi(digits);
    (x * f).round() / f
}

/// Eq. 2 width (mm) and eq. 3 area (mm²) of a row under `reading`.
pub fn width_and_area(force: f64, rho: f64, i: &IrgashevInput) -> (f64, f64) {
    match i.width_reading {
        WidthReading::Material => {
            (seed004::contact_width_mm(force, rho, i.youngs, i.poisson), seed004::contact_area_mm2(force, rho, i.youngs, i.poisson))
        }
        WidthReading::Paper => (
            round_to(seed004::contact_width_mm(force, rho, PAPER_WIDTH_MODULUS_MPA, i.poisson), 3),
            round_to(seed004::contact_area_mm2(force, rho, i.youngs, i.poisson), 3),
        ),
    }
}

/// What a part of the profile is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcRole {
    /// Base circle: the spring preload.
    Base,
    /// Flank: stepped spring forces, rising towards the nose or falling from it.
    Flank { rising: bool },
    /// Nose: the full lift.
    Nose,
}

/// The method's inputs, in the paper's units.
#[derive(Debug, Clone, PartialEq)]
pub struct IrgashevInput {
    /// Arcs `(radius mm, central angle °)` in profile order: base, flank(s), nose, nose,
    /// flank(s), base (an even number ≥ 6).
    pub arcs: Vec<(f64, f64)>,
    /// Tappet sphere radius, mm.
    pub tappet_radius: f64,
    /// Young's modulus, MPa, and Poisson's ratio (eq. 2–3).
    pub youngs: f64,
    pub poisson: f64,
    /// Spring force at zero lift, N, and spring rate z_n, N/mm.
    pub preload: f64,
    pub spring_rate: f64,
    /// Lift at the nose, mm.
    pub nose_lift: f64,
    /// Slip δ per arc (Table 4).
    pub slip: Vec<f64>,
    /// Rows per flank arc (9 in the paper).
    pub flank_steps: usize,
    /// Elasticity constant θ, 1/MPa.
    pub elasticity_constant: f64,
    /// Yield strength σ_t, MPa.
    pub yield_strength: f64,
    /// Deformation coefficient c.
    pub deformation_coefficient: f64,
    /// Loadings to failure n_p.
    pub cycles_to_failure: f64,
    /// Cam speed n_k, rev/s.
    pub speed: f64,
    /// For the Archard column: wear coefficient k (1/Pa) and contact modulus E* (Pa).
    pub archard: Option<(f64, f64)>,
    /// Widths and areas: the material's eq. 2–3 or the paper's tables.
    pub width_reading: WidthReading,
}

/// One row of Tables 3–5.
#[derive(Debug, Clone, PartialEq)]
pub struct IrgashevRow {
    /// Part (arc) number, from 1.
    pub part: usize,
    /// Step within a flank arc (1..=m), 0 for base and nose arcs.
    pub step: usize,
    pub role: ArcRole,
    /// Start and end of the row along the profile (arcs laid end to end from 0), °.
    pub position_start_deg: f64,
    pub position_end_deg: f64,
    /// Table 5's "current deflection angle", °.
    pub angle_deg: f64,
    /// Arc radius and reduced radius with the tappet sphere (Table 1), mm.
    pub radius: f64,
    pub reduced_radius: f64,
    /// Lift (mm), spring deflection z (mm) and spring force (N).
    pub lift: f64,
    pub spring_deflection: f64,
    pub spring_force: f64,
    /// Arc length by eq. 1 as printed (Table 2), and the true length `παr/180`, mm.
    pub length_as_printed: f64,
    pub length: f64,
    /// Eq. 2 contact width (mm) and eq. 3 area (mm²) (Table 3).
    pub contact_width: f64,
    pub contact_area: f64,
    /// Slip δ (Table 4).
    pub slip: f64,
    /// Eq. 15, mm/h (Table 5's withheld column).
    pub wear_rate: f64,
    /// The eq. 6–14 chain, mm/h.
    pub wear_rate_chain: f64,
    /// Hertz width 2a along the rolling direction (sphere r_t on the arc), mm.
    pub hertz_width: f64,
    /// Hertz peak pressure, MPa.
    pub hertz_pressure: f64,
    /// Archard: `k δ (π/2) p0 a` per pass × passes per hour, mm/h.
    pub archard_wear_rate: Option<f64>,
}

/// Eq. 15 (mm/h): `P` N, `B` mm, θ 1/MPa, σ_t MPa, `n` 1/s.
pub fn eq15(force: f64, width: f64, slip: f64, i: &IrgashevInput) -> f64 {
    EQ15_CONSTANT * force * force * i.elasticity_constant * (1.0 + slip) * i.speed
        / (width.powi(3) * i.yield_strength * i.deformation_coefficient * i.cycles_to_failure)
}

/// Eq. 6 with eq. 7–14 substituted (mm/h): `6.3766 P² θ δ l n/(B² c σ_t F n_p)`.
pub fn eq6_chain(force: f64, width: f64, area: f64, slip: f64, length: f64, i: &IrgashevInput) -> f64 {
    CHAIN_CONSTANT * force * force * i.elasticity_constant * slip * length * i.speed
        / (width * width * i.deformation_coefficient * i.yield_strength * area * i.cycles_to_failure)
}

/// Role of arc `k` of `n`.
pub fn role(k: usize, n: usize) -> ArcRole {
    let half = n / 2;
    if k == 0 || k + 1 == n {
        ArcRole::Base
    } else if k + 1 == half || k == half {
        ArcRole::Nose
    } else {
        ArcRole::Flank { rising: k < half }
    }
}

/// Tables 1–5 row by row.
pub fn rows(i: &IrgashevInput) -> Result<Vec<IrgashevRow>, SolveError> {
    let n = i.arcs.len();
    if n < 6 || n % 2 == 1 {
        return Err(SolveError::invalid("IrgashevInput.arcs", "the seed 004 method needs an even number (≥ 6) of arcs"));
    }
    if i.slip.len() != n {
        return Err(SolveError::invalid("IrgashevInput.slip", "needs one slip value per arc"));
    }
    let m = i.flank_steps.max(1);
    let flanks_per_side = n / 2 - 2;
    let steps = (flanks_per_side * m + 1) as f64;
    let force_at = |lift: f64| i.preload + i.spring_rate * lift;
    let mut out = Vec::new();
    let mut position = 0.0;
    for (k, &(r, alpha)) in i.arcs.iter().enumerate() {
        let rho = seed004::reduced_radius(r, i.tappet_radius);
        let role = role(k, n);
        // (step, lift, current angle, start and end within the arc)
        let parts: Vec<(usize, f64, f64, f64, f64)> = match role {
            ArcRole::Base => vec![(0, 0.0, alpha, 0.0, alpha)],
            ArcRole::Nose => vec![(0, i.nose_lift, alpha, 0.0, alpha)],
            ArcRole::Flank { rising } => {
                // Index of this arc among its side's flanks, counted from the base.
                let from_base = if rising { k - 1 } else { n - 2 - k };
                (1..=m)
                    .map(|j| {
                        let sub = alpha / m as f64;
                        let (a0, a1) = ((j - 1) as f64 * sub, j as f64 * sub);
                        let (level, current) = if rising {
                            (from_base * m + j, j as f64 * sub)
                        } else {
                            (from_base * m + (m + 1 - j), (m + 1 - j) as f64 * sub)
                        };
                        (j, i.nose_lift * level as f64 / steps, current, a0, a1)
                    })
                    .collect()
            }
        };
        for (step, lift, current, a0, a1) in parts {
            let p = force_at(lift);
            let (width, area) = width_and_area(p, rho, i);
            let slip = i.slip[k];
            let length_as_printed = seed004::arc_length_as_printed(alpha, r);
            let es = i.archard.map_or(i.youngs * 1e6 / (2.0 * (1.0 - i.poisson * i.poisson)), |a| a.1);
            let hz = hertz_point(p, rho * 1e-3, i.tappet_radius * 1e-3, es)?;
            let a_roll = if rho <= i.tappet_radius { hz.semi_minor } else { hz.semi_major };
            let archard_wear_rate = i.archard.map(|(kw, _)| kw * slip.abs() * 0.5 * PI * hz.max_pressure * a_roll * i.speed * 3600.0 * 1e3);
            out.push(IrgashevRow {
                part: k + 1,
                step,
                role,
                position_start_deg: position + a0,
                position_end_deg: position + a1,
                angle_deg: current,
                radius: r,
                reduced_radius: rho,
                lift,
                spring_deflection: p / i.spring_rate,
                spring_force: p,
                length_as_printed,
                length: alpha.to_radians() * r,
                contact_width: width,
                contact_area: area,
                slip,
                wear_rate: eq15(p, width, slip, i),
                wear_rate_chain: eq6_chain(p, width, area, slip, length_as_printed, i),
                hertz_width: 2.0 * a_roll * 1e3,
                hertz_pressure: hz.max_pressure * 1e-6,
                archard_wear_rate,
            });
        }
        position += alpha;
    }
    for r in &out {
        ensure_finite(
            "seed 004 rows",
            [&r.contact_width, &r.contact_area, &r.wear_rate, &r.wear_rate_chain, &r.hertz_width].into_iter().chain(r.archard_wear_rate.as_ref()),
        )?;
    }
    Ok(out)
}

/// The paper's intake cam (Tables 1, 2, 4 and the inputs after eq. 15) with `flank_steps = 9`.
pub fn paper_intake() -> IrgashevInput {
    IrgashevInput {
        arcs: vec![(21.5, 116.0), (153.3, 62.75), (31.5, 1.25), (31.5, 1.25), (153.3, 62.75), (21.5, 116.0)],
        tappet_radius: 42.0,
        youngs: 2.1e5,
        poisson: 0.3,
        preload: 264.0,
        spring_rate: 44.0,
        nose_lift: 10.0,
        slip: vec![0.0111, 0.1211, 0.2360, 0.2360, 0.1285, 0.113],
        flank_steps: 9,
        elasticity_constant: 4.23e-6,
        yield_strength: 1300.0,
        deformation_coefficient: 3.0,
        cycles_to_failure: 24.0,
        speed: 20.0,
        archard: None,
        width_reading: WidthReading::Paper,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chain_constant_is_eq15s() {
        assert!((CHAIN_CONSTANT - EQ15_CONSTANT).abs() < 1e-3, "{CHAIN_CONSTANT}");
    }

    /// Table 3's widths (intake), to the printed 0.001 mm, by eq. 2 at 215 GPa; 210 GPa misses
    /// every one by 0.8 %.
    #[test]
    fn paper_reading_gives_table_3_widths_to_the_digit() {
        let printed = [0.508, 0.709, 0.741, 0.771, 0.799, 0.825, 0.849, 0.872, 0.894, 0.915, 0.764];
        let rows = rows(&paper_intake()).unwrap();
        for (k, b) in printed.iter().enumerate() {
            assert!((rows[k].contact_width - b).abs() < 1e-12, "row {k}: {} vs {b}", rows[k].contact_width);
            let m = seed004::contact_width_mm(rows[k].spring_force, rows[k].reduced_radius, 2.1e5, 0.3);
            assert!((b / m - 1.0 + 0.0080).abs() < 0.0008, "row {k}: {m} vs {b}");
        }
    }

    #[test]
    fn paper_rows_follow_table_3_and_5_layout() {
        let rows = rows(&paper_intake()).unwrap();
        assert_eq!(rows.len(), 22);
        let forces: Vec<f64> = rows.iter().map(|r| r.spring_force).collect();
        let expect = [264.0, 308.0, 352.0, 396.0, 440.0, 484.0, 528.0, 572.0, 616.0, 660.0, 704.0, 704.0, 660.0, 616.0, 572.0, 528.0, 484.0, 440.0, 396.0, 352.0, 308.0, 264.0];
        for (f, e) in forces.iter().zip(expect) {
            assert!((f - e).abs() < 1e-9, "{f} vs {e}");
        }
        // Table 5's current angles: 6.97° steps up part 2, down part 5.
        assert!((rows[1].angle_deg - 6.972).abs() < 1e-3 && (rows[9].angle_deg - 62.75).abs() < 1e-9);
        assert!((rows[12].angle_deg - 62.75).abs() < 1e-9 && (rows[20].angle_deg - 6.972).abs() < 1e-3);
        // Profile positions tile 360°.
        assert!((rows.last().unwrap().position_end_deg - 360.0).abs() < 1e-9);
        for w in rows.windows(2) {
            assert!((w[1].position_start_deg - w[0].position_end_deg).abs() < 1e-9);
        }
    }
}

/// Seed 004's inputs in SI (what the job layer holds): converted to the paper's units by
/// [`IrgashevSi::paper_units`].
#[derive(Debug, Clone, PartialEq)]
pub struct IrgashevSi {
    /// Arcs `(radius m, central angle °)` in profile order.
    pub arcs: Vec<(f64, f64)>,
    /// Tappet sphere radius, m.
    pub tappet_radius: f64,
    /// The cam's elastic constants.
    pub cam: crate::contact::Elastic,
    /// Spring force at zero lift, N, and spring rate, N/m.
    pub preload: f64,
    pub spring_rate: f64,
    /// Lift at the nose, m.
    pub nose_lift: f64,
    pub slip: Vec<f64>,
    pub flank_steps: usize,
    /// Elasticity constant θ, 1/Pa.
    pub elasticity_constant: f64,
    /// Yield strength σ_t, Pa.
    pub yield_strength: f64,
    pub deformation_coefficient: f64,
    pub cycles_to_failure: f64,
    /// Cam speed, rev/s.
    pub speed: f64,
    /// Wear coefficient k (1/Pa) and contact modulus E* (Pa) for the Archard column.
    pub archard: Option<(f64, f64)>,
    pub width_reading: WidthReading,
}

impl IrgashevSi {
    /// The same inputs in the paper's units (mm, MPa, N/mm, 1/MPa).
    pub fn paper_units(&self) -> IrgashevInput {
        IrgashevInput {
            arcs: self.arcs.iter().map(|(r, a)| (r * 1e3, *a)).collect(),
            tappet_radius: self.tappet_radius * 1e3,
            youngs: self.cam.youngs_modulus * 1e-6,
            poisson: self.cam.poisson_ratio,
            preload: self.preload,
            spring_rate: self.spring_rate * 1e-3,
            nose_lift: self.nose_lift * 1e3,
            slip: self.slip.clone(),
            flank_steps: self.flank_steps,
            elasticity_constant: self.elasticity_constant * 1e6,
            yield_strength: self.yield_strength * 1e-6,
            deformation_coefficient: self.deformation_coefficient,
            cycles_to_failure: self.cycles_to_failure,
            speed: self.speed,
            archard: self.archard,
            width_reading: self.width_reading,
        }
    }
}

/// The cam's wear over running time from the rows' eq. 15 rates (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct CamWear {
    /// Cam angle of each point (uniform over the revolution), °.
    pub angle_deg: Vec<f64>,
    /// Wear rate, m/s, and depth after `hours`, m.
    pub rate: Vec<f64>,
    pub depth: Vec<f64>,
    /// Running time reached, h (the limit's time when it comes first).
    pub hours: f64,
    /// The wear limit was reached within the requested time.
    pub reached_limit: bool,
    /// Time at which the deepest point reaches the limit, h (with a limit).
    pub hours_to_limit: Option<f64>,
}

/// Spreads the rows' rates (mm/h) over `angles` uniform cam angles and integrates them over
/// `hours`, stopping at `limit` (m) when the deepest point reaches it first. Each angle takes the
/// rate of the row whose profile position it falls in (rates are constant in time: eq. 15 does
/// not change with wear).
pub fn cam_wear(rows: &[IrgashevRow], angles: usize, hours: f64, limit: Option<f64>) -> CamWear {
    const MM_PER_H_TO_M_PER_S: f64 = 1e-3 / 3600.0;
    let mut angle_deg = Vec::with_capacity(angles);
    let mut rate = Vec::with_capacity(angles);
    for k in 0..angles {
        let a = 360.0 * k as f64 / angles as f64;
        let row = rows.iter().find(|r| a >= r.position_start_deg && a < r.position_end_deg).or(rows.last());
        angle_deg.push(a);
        rate.push(row.map_or(0.0, |r| r.wear_rate * MM_PER_H_TO_M_PER_S));
    }
    let max_rate = rate.iter().copied().fold(0.0, f64::max);
    let hours_to_limit = limit.filter(|_| max_rate > 0.0).map(|l| l / max_rate / 3600.0);
    let reached_limit = hours_to_limit.is_some_and(|t| t <= hours);
    let hours = if reached_limit { hours_to_limit.unwrap_or(hours) } else { hours };
    let depth = rate.iter().map(|r| r * hours * 3600.0).collect();
    CamWear { angle_deg, rate, depth, hours, reached_limit, hours_to_limit }
}
