//! Estimated error of the closed-form line-contact films — Moes' central film and Pan–Hamrock's
//! minimum film ([`super::formulas`]) — for a contact state, from maps *measured* with the
//! numerical solver. The `auto` fidelity runs the closed form where
//! [`estimate_closed_form_error`] is within the requested tolerance and the numerical solver
//! elsewhere.
//!
//! # The model
//! The relative error of a closed-form film against the numerical (isothermal, Roelands,
//! Dowson–Higginson, squeeze) solution is split into
//! * a **steady** part `e_s(M, L, α)`: the signed error of the formula against the
//!   grid-converged steady solution, tabulated over Moes' `M` and `L` and the pressure–viscosity
//!   coefficient `α` ([`STEADY_M`], [`STEADY_L`], [`STEADY_ALPHA`], [`STEADY_CENTRAL`],
//!   [`STEADY_MINIMUM`]) and interpolated linearly in `(ln M, ln L, ln α)`. `α` is the third
//!   axis because with Roelands' law `M` and `L` fix `α p_h` but not `p_h/p_r`: at the same
//!   `M`, `L` a smaller `α` means higher pressures, more Roelands saturation and a thinner film
//!   (measured: up to 10 points of error between `α` = 1.2e-8 and 2e-8 1/Pa);
//! * a **transient** part `e_t(ξ)`: the largest measured departure of the squeeze (transient)
//!   solution from the steady solution at the same instant, as a function of the squeeze number
//!   `ξ` ([`squeeze_number`]) ([`SQUEEZE_XI`], [`SQUEEZE_CENTRAL`], [`SQUEEZE_MINIMUM`]).
//!
//! The estimate is the worst case of the two, `s + e_t (1 + s)` with `s = |e_s| + δ`, where `δ`
//! ([`RHEOLOGY_SPREAD_CENTRAL`], [`RHEOLOGY_SPREAD_MINIMUM`]) is the measured spread of the steady
//! error over the ambient viscosity at the same `M`, `L`, `α` (`η0` 0.0118–0.38 Pa·s, Roelands
//! `Z` 0.45–0.75 at `α` = 2e-8): the map is measured at one `η0`. For a Barus or incompressible lubricant the map was not
//! measured (Moes' formula fits Barus solutions, so the estimate is then pessimistic for the
//! central film). Outside the measured
//! maps — `M`, `L` or `α` beyond the tables, `p_h` beyond [`MAX_PH`], `ξ` beyond the last
//! squeeze bin, zero entrainment — the estimate is `f64::INFINITY`: nothing was measured there, so
//! the caller must run the numerical solver. Proximity to zero entrainment shows up twice: `M`
//! grows like `|u_m|^(−1/2)` and `ξ` like `1/|u_m|`.
//!
//! The slide-to-roll ratio is part of [`ContactState`] but does not enter the estimate: the
//! numerical model is isothermal and its Reynolds equation Newtonian, so sliding changes the
//! traction and not the film (checked by a test). With shear heating (not modelled, see
//! [`super`]) the film would thin with sliding and this estimate would be optimistic there.
//!
//! # How the tables were generated
//! `cargo bench --bench ehl -- error-map` (release) prints both tables as Rust source:
//! * steady: [`measure_steady`] at every `(M, L, α)` cell with `p_h ≤ MAX_PH`, by Richardson
//!   extrapolation of 511 and 256 nodes (tolerance 1e-9), for the reference contact of
//!   [`reference_contact`] (steel, `R` = 10 mm, `η0` = 0.04 Pa·s, Roelands and
//!   Dowson–Higginson at the reference temperature); the spread by [`measure_steady_for`] at
//!   every other `(M, L)` cell at `α` = 2e-8 with `η0` = 0.38 and 0.0118 Pa·s;
//! * transient: [`measure_squeeze`] over the benchmark cam-like cycle ([`cycle_input`]) at cycle
//!   periods of 4, 2, 1, ½ and ¼ times 63.2 ms (950 rpm), Richardson 97 + 193 nodes; each angle gives
//!   `(ξ, e_t)`; the table holds the largest `|e_t|` per `ξ` bin, made non-decreasing in `ξ`.
//!
//! A validation test regenerates a few cells at smaller grids and checks them against the tables.

use super::formulas::{moes_central_film, pan_hamrock_minimum_film, Groups};
use super::{EhlInput, EhlOptions, Extrapolation, Rheology, TransientSolver};
use crate::physics::lubricant::Lubricant;
use crate::physics::{Observer, SolveError};

/// A contact state as the `auto` fidelity sees it (dimensionless; compute `M`, `L` with
/// [`Groups`] and `ξ` with [`squeeze_number`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Moes load parameter `M` (sum-velocity convention, [`Groups::moes_m`]).
    pub moes_m: f64,
    /// Moes material parameter `L` ([`Groups::moes_l`]).
    pub moes_l: f64,
    /// Pressure–viscosity coefficient `α` of the (Roelands) lubricant, 1/Pa: its low-pressure
    /// slope, [`Lubricant::pressure_viscosity`].
    pub pressure_viscosity: f64,
    /// Slide-to-roll ratio `u_s/u_m` (does not enter the estimate: see the module docs).
    pub slide_roll_ratio: f64,
    /// Squeeze number `ξ` ([`squeeze_number`]); 0 in steady running.
    pub squeeze_number: f64,
}

impl ContactState {
    /// The state of a contact with groups `g`, pressure–viscosity coefficient `α` (1/Pa),
    /// slide-to-roll ratio and squeeze number.
    pub fn new(g: &Groups, pressure_viscosity: f64, slide_roll_ratio: f64, squeeze_number: f64) -> Self {
        ContactState { moes_m: g.moes_m, moes_l: g.moes_l, pressure_viscosity, slide_roll_ratio, squeeze_number }
    }
}

/// Squeeze number `ξ = (b/|u_m|) |d ln h/dt|`: the time the lubricant takes to cross the
/// Hertzian half-width `b` (m) at the entrainment speed `u_m` (m/s), over the time scale on which
/// the (closed-form, quasi-steady) film `h` changes; `film_rate = d ln h/dt` (1/s), e.g. by
/// differencing the closed-form film over neighbouring cam angles. `ξ ≪ 1`: quasi-steady; `ξ`
/// of order 0.1 and more: the film lags behind (squeeze, entrainment reversal). Infinite at
/// zero entrainment.
pub fn squeeze_number(half_width: f64, entrainment_velocity: f64, film_rate: f64) -> f64 {
    let u = entrainment_velocity.abs();
    if u == 0.0 {
        return f64::INFINITY;
    }
    half_width / u * film_rate.abs()
}

/// Estimated relative errors (magnitudes) of the closed-form films.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedFormError {
    /// Moes' central film.
    pub central: f64,
    /// Pan–Hamrock's minimum film.
    pub minimum: f64,
}

/// Estimated relative errors of Moes' central and Pan–Hamrock's minimum film for `state`
/// (`f64::INFINITY` outside the measured maps).
pub fn closed_form_errors(state: &ContactState) -> ClosedFormError {
    let steady = steady_errors(state.moes_m, state.moes_l, state.pressure_viscosity);
    let squeeze = squeeze_errors(state.squeeze_number);
    let combine = |s: Option<f64>, spread: f64, t: Option<f64>| match (s, t) {
        (Some(s), Some(t)) => {
            let s = s.abs() + spread;
            s + t * (1.0 + s)
        }
        _ => f64::INFINITY,
    };
    ClosedFormError {
        central: combine(steady.map(|s| s.0), RHEOLOGY_SPREAD_CENTRAL, squeeze.map(|t| t.0)),
        minimum: combine(steady.map(|s| s.1), RHEOLOGY_SPREAD_MINIMUM, squeeze.map(|t| t.1)),
    }
}

/// The larger of the estimated relative errors of the closed-form central and minimum films
/// for `state` (`f64::INFINITY` where nothing was measured): compare with the tolerance of the
/// `auto` fidelity.
pub fn estimate_closed_form_error(state: &ContactState) -> f64 {
    let e = closed_form_errors(state);
    e.central.max(e.minimum)
}

/// Largest Hertzian pressure of the steady map, Pa (`p_h = L sqrt(M/2π)/α`).
pub const MAX_PH: f64 = 3.5e9;

/// `M` of the steady map's rows.
pub const STEADY_M: [f64; NM] = [0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 20.0, 30.0, 50.0, 100.0, 200.0, 300.0, 500.0, 1000.0];
/// `L` of the steady map's columns.
pub const STEADY_L: [f64; NL] = [2.5, 5.0, 7.5, 10.0, 12.5, 15.0, 20.0];
/// Rows and columns of the steady map.
pub const NM: usize = 15;
pub const NL: usize = 7;
pub const NA: usize = 4;
/// `α` (1/Pa) of the steady map's layers.
pub const STEADY_ALPHA: [f64; NA] = [1.0e-8, 1.6e-8, 2.4e-8, 3.5e-8];

/// Signed relative error `h_Moes/h_c − 1` of Moes' central film against the numerical steady
/// solution, by `[α][M][L]` (columns `L` = 2.5, 5, 7.5, 10, 12.5, 15, 20); `None` where `p_h > MAX_PH` (or the solve failed). Generated by
/// `cargo bench --bench ehl -- error-map` (see the module docs).
#[rustfmt::skip]
pub const STEADY_CENTRAL: [[[Option<f64>; NL]; NM]; NA] = [
    [ // α = 1e-8
        [Some(0.2039), Some(0.1819), Some(0.1695), Some(0.1641), Some(0.1637), Some(0.1669), Some(0.1801)], // M = 0.3
        [Some(0.1829), Some(0.1696), Some(0.1738), Some(0.1867), Some(0.2034), Some(0.2213), Some(0.2561)], // M = 0.5
        [Some(0.1256), Some(0.1534), Some(0.1873), Some(0.2175), Some(0.2426), Some(0.2633), Some(0.2946)], // M = 1
        [Some(0.0096), Some(0.0553), Some(0.0924), Some(0.1225), Some(0.1483), Some(0.1709), Some(0.2090)], // M = 2
        [Some(-0.0111), Some(0.0519), Some(0.1041), Some(0.1456), Some(0.1784), Some(0.2045), Some(0.2428)], // M = 3
        [Some(0.0365), Some(0.1114), Some(0.1632), Some(0.2007), Some(0.2289), Some(0.2509), Some(0.2829)], // M = 5
        [Some(0.0887), Some(0.1678), Some(0.2185), Some(0.2533), Some(0.2785), Some(0.2975), Some(0.3242)], // M = 10
        [Some(0.1329), Some(0.2156), Some(0.2650), Some(0.2972), Some(0.3199), Some(0.3365), None], // M = 20
        [Some(0.1583), Some(0.2424), Some(0.2906), Some(0.3214), Some(0.3426), Some(0.3580), None], // M = 30
        [Some(0.1899), Some(0.2742), Some(0.3207), Some(0.3498), None, None, None], // M = 50
        [Some(0.2311), Some(0.3140), Some(0.3576), None, None, None, None], // M = 100
        [Some(0.2695), Some(0.3492), None, None, None, None, None], // M = 200
        [Some(0.2903), Some(0.3676), None, None, None, None, None], // M = 300
        [Some(0.3143), None, None, None, None, None, None], // M = 500
        [Some(0.3427), None, None, None, None, None, None], // M = 1000
    ],
    [ // α = 1.6e-8
        [Some(0.2053), Some(0.1840), Some(0.1718), Some(0.1661), Some(0.1651), Some(0.1674), Some(0.1780)], // M = 0.3
        [Some(0.1847), Some(0.1712), Some(0.1739), Some(0.1838), Some(0.1966), Some(0.2098), Some(0.2334)], // M = 0.5
        [Some(0.1249), Some(0.1447), Some(0.1664), Some(0.1826), Some(0.1932), Some(0.1999), Some(0.2077)], // M = 1
        [Some(-0.0070), Some(0.0112), Some(0.0251), Some(0.0436), Some(0.0666), Some(0.0878), Some(0.1204)], // M = 2
        [Some(-0.0373), Some(0.0033), Some(0.0435), Some(0.0740), Some(0.0972), Some(0.1162), Some(0.1457)], // M = 3
        [Some(0.0041), Some(0.0532), Some(0.0888), Some(0.1158), Some(0.1370), Some(0.1541), Some(0.1803)], // M = 5
        [Some(0.0457), Some(0.0991), Some(0.1354), Some(0.1616), Some(0.1813), Some(0.1967), Some(0.2192)], // M = 10
        [Some(0.0817), Some(0.1407), Some(0.1777), Some(0.2028), Some(0.2208), Some(0.2344), Some(0.2534)], // M = 20
        [Some(0.1034), Some(0.1653), Some(0.2021), Some(0.2262), Some(0.2431), Some(0.2555), Some(0.2726)], // M = 30
        [Some(0.1314), Some(0.1957), Some(0.2317), Some(0.2543), Some(0.2698), Some(0.2808), None], // M = 50
        [Some(0.1700), Some(0.2351), Some(0.2687), Some(0.2889), Some(0.3022), None, None], // M = 100
        [Some(0.2081), Some(0.2711), Some(0.3015), None, None, None, None], // M = 200
        [Some(0.2295), Some(0.2902), Some(0.3187), None, None, None, None], // M = 300
        [Some(0.2549), Some(0.3123), None, None, None, None, None], // M = 500
        [Some(0.2855), None, None, None, None, None, None], // M = 1000
    ],
    [ // α = 2.4e-8
        [Some(0.2061), Some(0.1852), Some(0.1731), Some(0.1673), Some(0.1660), Some(0.1678), Some(0.1768)], // M = 0.3
        [Some(0.1857), Some(0.1722), Some(0.1738), Some(0.1821), Some(0.1925), Some(0.2027), Some(0.2189)], // M = 0.5
        [Some(0.1245), Some(0.1395), Some(0.1536), Some(0.1606), Some(0.1615), Some(0.1594), Some(0.1580)], // M = 1
        [Some(-0.0174), Some(-0.0185), Some(-0.0188), Some(-0.0008), Some(0.0188), Some(0.0346), Some(0.0602)], // M = 2
        [Some(-0.0543), Some(-0.0276), Some(0.0023), Some(0.0232), Some(0.0405), Some(0.0554), Some(0.0801)], // M = 3
        [Some(-0.0172), Some(0.0135), Some(0.0375), Some(0.0572), Some(0.0738), Some(0.0881), Some(0.1114)], // M = 5
        [Some(0.0166), Some(0.0508), Some(0.0769), Some(0.0975), Some(0.1142), Some(0.1280), Some(0.1496)], // M = 10
        [Some(0.0456), Some(0.0865), Some(0.1153), Some(0.1366), Some(0.1529), Some(0.1658), Some(0.1850)], // M = 20
        [Some(0.0636), Some(0.1087), Some(0.1386), Some(0.1597), Some(0.1755), Some(0.1876), Some(0.2053)], // M = 30
        [Some(0.0876), Some(0.1372), Some(0.1677), Some(0.1884), Some(0.2032), Some(0.2142), Some(0.2298)], // M = 50
        [Some(0.1224), Some(0.1759), Some(0.2056), Some(0.2245), Some(0.2375), Some(0.2471), Some(0.2600)], // M = 100
        [Some(0.1586), Some(0.2128), Some(0.2404), Some(0.2570), Some(0.2681), None, None], // M = 200
        [Some(0.1799), Some(0.2331), Some(0.2589), Some(0.2741), None, None, None], // M = 300
        [Some(0.2059), Some(0.2569), Some(0.2802), None, None, None, None], // M = 500
        [Some(0.2386), Some(0.2846), None, None, None, None, None], // M = 1000
    ],
    [ // α = 3.5e-8
        [Some(0.2066), Some(0.1860), Some(0.1740), Some(0.1681), Some(0.1666), Some(0.1681), Some(0.1761)], // M = 0.3
        [Some(0.1864), Some(0.1728), Some(0.1739), Some(0.1810), Some(0.1898), Some(0.1980), Some(0.2091)], // M = 0.5
        [Some(0.1243), Some(0.1361), Some(0.1451), Some(0.1455), Some(0.1394), Some(0.1323), Some(0.1283)], // M = 1
        [Some(-0.0245), Some(-0.0401), Some(-0.0482), Some(-0.0314), Some(-0.0179), Some(-0.0061), Some(0.0148)], // M = 2
        [Some(-0.0661), Some(-0.0488), Some(-0.0287), Some(-0.0148), Some(-0.0023), Some(0.0093), Some(0.0301)], // M = 3
        [Some(-0.0320), Some(-0.0153), Some(-0.0006), Some(0.0130), Some(0.0256), Some(0.0373), Some(0.0578)], // M = 5
        [Some(-0.0043), Some(0.0147), Some(0.0321), Some(0.0478), Some(0.0616), Some(0.0738), Some(0.0943)], // M = 10
        [Some(0.0189), Some(0.0445), Some(0.0660), Some(0.0837), Some(0.0984), Some(0.1108), Some(0.1305)], // M = 20
        [Some(0.0335), Some(0.0640), Some(0.0876), Some(0.1060), Some(0.1209), Some(0.1331), Some(0.1518)], // M = 30
        [Some(0.0536), Some(0.0898), Some(0.1155), Some(0.1346), Some(0.1493), Some(0.1609), Some(0.1781)], // M = 50
        [Some(0.0837), Some(0.1265), Some(0.1534), Some(0.1720), Some(0.1856), Some(0.1961), Some(0.2111)], // M = 100
        [Some(0.1166), Some(0.1634), Some(0.1898), Some(0.2069), Some(0.2189), Some(0.2279), Some(0.2404)], // M = 200
        [Some(0.1368), Some(0.1844), Some(0.2097), Some(0.2256), Some(0.2365), Some(0.2446), None], // M = 300
        [Some(0.1624), Some(0.2098), Some(0.2330), Some(0.2471), Some(0.2567), None, None], // M = 500
        [Some(0.1961), Some(0.2402), Some(0.2606), None, None, None, None], // M = 1000
    ],
];
/// Signed relative error `h_PH/h_min − 1` of Pan–Hamrock's minimum film, as [`STEADY_CENTRAL`].
#[rustfmt::skip]
pub const STEADY_MINIMUM: [[[Option<f64>; NL]; NM]; NA] = [
    [ // α = 1e-8
        [Some(-0.6663), Some(-0.5383), Some(-0.4491), Some(-0.3809), Some(-0.3265), Some(-0.2818), Some(-0.2131)], // M = 0.3
        [Some(-0.5191), Some(-0.3559), Some(-0.2535), Some(-0.1826), Some(-0.1311), Some(-0.0927), Some(-0.0412)], // M = 0.5
        [Some(-0.3119), Some(-0.1387), Some(-0.0539), Some(-0.0081), Some(0.0174), Some(0.0314), Some(0.0411)], // M = 1
        [Some(-0.1974), Some(-0.0587), Some(-0.0061), Some(0.0167), Some(0.0264), Some(0.0296), Some(0.0261)], // M = 2
        [Some(-0.1684), Some(-0.0423), Some(0.0036), Some(0.0214), Some(0.0268), Some(0.0265), Some(0.0174)], // M = 3
        [Some(-0.1364), Some(-0.0231), Some(0.0129), Some(0.0238), Some(0.0242), Some(0.0196), Some(0.0051)], // M = 5
        [Some(-0.1038), Some(-0.0053), Some(0.0203), Some(0.0237), Some(0.0186), Some(0.0098), Some(-0.0101)], // M = 10
        [Some(-0.0774), Some(0.0089), Some(0.0262), Some(0.0237), Some(0.0142), Some(0.0020), None], // M = 20
        [Some(-0.0633), Some(0.0168), Some(0.0298), Some(0.0244), Some(0.0126), Some(-0.0010), None], // M = 30
        [Some(-0.0461), Some(0.0266), Some(0.0348), Some(0.0261), None, None, None], // M = 50
        [Some(-0.0235), Some(0.0403), Some(0.0424), None, None, None, None], // M = 100
        [Some(-0.0007), Some(0.0544), None, None, None, None, None], // M = 200
        [Some(0.0126), Some(0.0629), None, None, None, None, None], // M = 300
        [Some(0.0292), None, None, None, None, None, None], // M = 500
        [Some(0.0517), None, None, None, None, None, None], // M = 1000
    ],
    [ // α = 1.6e-8
        [Some(-0.6583), Some(-0.5269), Some(-0.4354), Some(-0.3657), Some(-0.3103), Some(-0.2651), Some(-0.1966)], // M = 0.3
        [Some(-0.5074), Some(-0.3402), Some(-0.2363), Some(-0.1658), Some(-0.1162), Some(-0.0806), Some(-0.0370)], // M = 0.5
        [Some(-0.2957), Some(-0.1240), Some(-0.0473), Some(-0.0123), Some(0.0014), Some(0.0041), Some(-0.0041)], // M = 1
        [Some(-0.1843), Some(-0.0612), Some(-0.0245), Some(-0.0132), Some(-0.0119), Some(-0.0157), Some(-0.0287)], // M = 2
        [Some(-0.1592), Some(-0.0500), Some(-0.0198), Some(-0.0139), Some(-0.0173), Some(-0.0241), Some(-0.0408)], // M = 3
        [Some(-0.1300), Some(-0.0362), Some(-0.0167), Some(-0.0175), Some(-0.0251), Some(-0.0351), Some(-0.0559)], // M = 5
        [Some(-0.1007), Some(-0.0243), Some(-0.0155), Some(-0.0235), Some(-0.0363), Some(-0.0502), Some(-0.0729)], // M = 10
        [Some(-0.0769), Some(-0.0149), Some(-0.0145), Some(-0.0279), Some(-0.0444), Some(-0.0608), Some(-0.0910)], // M = 20
        [Some(-0.0644), Some(-0.0093), Some(-0.0134), Some(-0.0295), Some(-0.0477), Some(-0.0651), Some(-0.0970)], // M = 30
        [Some(-0.0493), Some(-0.0027), Some(-0.0114), Some(-0.0302), Some(-0.0501), Some(-0.0691), None], // M = 50
        [Some(-0.0292), Some(0.0071), Some(-0.0075), Some(-0.0299), Some(-0.0517), None, None], // M = 100
        [Some(-0.0093), Some(0.0174), Some(-0.0022), None, None, None, None], // M = 200
        [Some(0.0024), Some(0.0237), Some(0.0014), None, None, None, None], // M = 300
        [Some(0.0170), Some(0.0321), None, None, None, None, None], // M = 500
        [Some(0.0365), None, None, None, None, None, None], // M = 1000
    ],
    [ // α = 2.4e-8
        [Some(-0.6513), Some(-0.5171), Some(-0.4237), Some(-0.3526), Some(-0.2962), Some(-0.2504), Some(-0.1816)], // M = 0.3
        [Some(-0.4972), Some(-0.3266), Some(-0.2213), Some(-0.1506), Some(-0.1019), Some(-0.0681), Some(-0.0296)], // M = 0.5
        [Some(-0.2815), Some(-0.1099), Some(-0.0381), Some(-0.0107), Some(-0.0055), Some(-0.0104), Some(-0.0255)], // M = 1
        [Some(-0.1715), Some(-0.0583), Some(-0.0309), Some(-0.0261), Some(-0.0299), Some(-0.0371), Some(-0.0543)], // M = 2
        [Some(-0.1489), Some(-0.0501), Some(-0.0297), Some(-0.0305), Some(-0.0381), Some(-0.0478), Some(-0.0682)], // M = 3
        [Some(-0.1214), Some(-0.0400), Some(-0.0301), Some(-0.0371), Some(-0.0487), Some(-0.0605), Some(-0.0837)], // M = 5
        [Some(-0.0941), Some(-0.0317), Some(-0.0326), Some(-0.0463), Some(-0.0623), Some(-0.0781), Some(-0.1016)], // M = 10
        [Some(-0.0720), Some(-0.0248), Some(-0.0341), Some(-0.0526), Some(-0.0717), Some(-0.0895), Some(-0.1210)], // M = 20
        [Some(-0.0605), Some(-0.0209), Some(-0.0341), Some(-0.0548), Some(-0.0755), Some(-0.0943), Some(-0.1271)], // M = 30
        [Some(-0.0465), Some(-0.0158), Some(-0.0334), Some(-0.0565), Some(-0.0789), Some(-0.0986), Some(-0.1334)], // M = 50
        [Some(-0.0280), Some(-0.0083), Some(-0.0311), Some(-0.0575), Some(-0.0814), Some(-0.1024), Some(-0.1381)], // M = 100
        [Some(-0.0097), Some(0.0001), Some(-0.0276), Some(-0.0558), Some(-0.0817), None, None], // M = 200
        [Some(0.0011), Some(0.0051), Some(-0.0245), Some(-0.0545), None, None, None], // M = 300
        [Some(0.0146), Some(0.0120), Some(-0.0206), None, None, None, None], // M = 500
        [Some(0.0323), Some(0.0212), None, None, None, None, None], // M = 1000
    ],
    [ // α = 3.5e-8
        [Some(-0.6448), Some(-0.5079), Some(-0.4127), Some(-0.3403), Some(-0.2829), Some(-0.2365), Some(-0.1671)], // M = 0.3
        [Some(-0.4877), Some(-0.3139), Some(-0.2070), Some(-0.1359), Some(-0.0875), Some(-0.0547), Some(-0.0199)], // M = 0.5
        [Some(-0.2681), Some(-0.0957), Some(-0.0272), Some(-0.0055), Some(-0.0069), Some(-0.0162), Some(-0.0338)], // M = 1
        [Some(-0.1586), Some(-0.0520), Some(-0.0305), Some(-0.0302), Some(-0.0372), Some(-0.0465), Some(-0.0663)], // M = 2
        [Some(-0.1376), Some(-0.0457), Some(-0.0319), Some(-0.0373), Some(-0.0476), Some(-0.0591), Some(-0.0819)], // M = 3
        [Some(-0.1112), Some(-0.0383), Some(-0.0348), Some(-0.0458), Some(-0.0598), Some(-0.0727), Some(-0.0984)], // M = 5
        [Some(-0.0851), Some(-0.0323), Some(-0.0396), Some(-0.0570), Some(-0.0751), Some(-0.0921), Some(-0.1173)], // M = 10
        [Some(-0.0643), Some(-0.0274), Some(-0.0426), Some(-0.0643), Some(-0.0852), Some(-0.1041), Some(-0.1366)], // M = 20
        [Some(-0.0533), Some(-0.0244), Some(-0.0434), Some(-0.0670), Some(-0.0891), Some(-0.1094), Some(-0.1423)], // M = 30
        [Some(-0.0402), Some(-0.0205), Some(-0.0436), Some(-0.0695), Some(-0.0931), Some(-0.1139), Some(-0.1484)], // M = 50
        [Some(-0.0227), Some(-0.0141), Some(-0.0423), Some(-0.0707), Some(-0.0959), Some(-0.1186), Some(-0.1551)], // M = 100
        [Some(-0.0053), Some(-0.0071), Some(-0.0394), Some(-0.0704), Some(-0.0968), Some(-0.1198), Some(-0.1584)], // M = 200
        [Some(0.0049), Some(-0.0026), Some(-0.0372), Some(-0.0689), Some(-0.0965), Some(-0.1200), None], // M = 300
        [Some(0.0175), Some(0.0034), Some(-0.0335), Some(-0.0674), Some(-0.0953), None, None], // M = 500
        [Some(0.0341), Some(0.0114), Some(-0.0284), None, None, None, None], // M = 1000
    ],
];

/// Largest measured change of the steady error of the central film when the ambient viscosity of
/// the reference contact changes at the same `M`, `L`, `α`: `η0` 0.38 or 0.0118 Pa·s instead of
/// 0.04 (Roelands `Z` 0.45 or 0.75 instead of 0.61 at `α` = 2e-8), at every other `(M, L)` cell
/// (`-- error-map`). Added to `|e_s|`.
pub const RHEOLOGY_SPREAD_CENTRAL: f64 = 0.0263;
/// The same for the minimum film.
pub const RHEOLOGY_SPREAD_MINIMUM: f64 = 0.0205;

/// Upper ends of the squeeze-number bins (the first bin starts at 0).
pub const SQUEEZE_XI: [f64; 8] = [0.001, 0.003, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0];
/// Largest measured `|h_transient/h_steady − 1|` of the central film per bin of
/// [`SQUEEZE_XI`], non-decreasing; `None`: no sample in or beyond the bin.
pub const SQUEEZE_CENTRAL: [Option<f64>; 8] = [Some(0.0031), Some(0.0055), Some(0.0163), Some(0.0467), Some(0.1432), Some(0.4105), Some(0.8473), Some(1.4410)];
/// The same for the minimum film.
pub const SQUEEZE_MINIMUM: [Option<f64>; 8] = [Some(0.0035), Some(0.0071), Some(0.0201), Some(0.0612), Some(0.2362), Some(0.3918), Some(0.4486), Some(0.6367)];

/// Linear interpolation of the steady map in `(ln M, ln L, ln α)`; `None` outside it or inside a
/// cell with an unmeasured corner.
fn steady_errors(m: f64, l: f64, alpha: f64) -> Option<(f64, f64)> {
    if !(m.is_finite() && l.is_finite() && alpha.is_finite() && m > 0.0 && l > 0.0 && alpha > 0.0) {
        return None;
    }
    if l * (m / (2.0 * std::f64::consts::PI)).sqrt() / alpha > MAX_PH {
        return None;
    }
    let bracket = |v: f64, axis: &[f64]| -> Option<(usize, f64)> {
        if v < axis[0] || v > axis[axis.len() - 1] {
            return None;
        }
        let i = axis.partition_point(|&a| a <= v).clamp(1, axis.len() - 1);
        let t = (v.ln() - axis[i - 1].ln()) / (axis[i].ln() - axis[i - 1].ln());
        Some((i, t))
    };
    let (i, s) = bracket(m, &STEADY_M)?;
    let (j, t) = bracket(l, &STEADY_L)?;
    let (k, u) = bracket(alpha, &STEADY_ALPHA)?;
    // Corners of zero weight (on a grid line) may be unmeasured.
    let lerp = |table: &[[[Option<f64>; NL]; NM]; NA]| -> Option<f64> {
        let mut sum = 0.0;
        for (kk, wk) in [(k - 1, 1.0 - u), (k, u)] {
            for (ii, wi) in [(i - 1, 1.0 - s), (i, s)] {
                for (jj, wj) in [(j - 1, 1.0 - t), (j, t)] {
                    let w = wk * wi * wj;
                    if w > 0.0 {
                        sum += w * table[kk][ii][jj]?;
                    }
                }
            }
        }
        Some(sum)
    };
    Some((lerp(&STEADY_CENTRAL)?, lerp(&STEADY_MINIMUM)?))
}

/// The transient part for squeeze number `xi`; `None` beyond the measured bins.
fn squeeze_errors(xi: f64) -> Option<(f64, f64)> {
    if !(xi >= 0.0) {
        return None;
    }
    let k = SQUEEZE_XI.iter().position(|&top| xi <= top)?;
    Some((SQUEEZE_CENTRAL[k]?, SQUEEZE_MINIMUM[k]?))
}

/// The steel contact the steady map is measured on, at Moes `M`, `L`: `E'` = 2.2e11 Pa,
/// `R` = 10 mm, `η0` = 0.04 Pa·s, `α` = 2e-8 1/Pa (other `α`: [`reference_contact_with`]), Roelands and Dowson–Higginson at 303 K.
/// `w' = M (L/G)² E' R`, `u_m = (L/G)⁴ E' R/(2 η0)` with `G = α E'`.
pub fn reference_contact(m: f64, l: f64) -> EhlInput<'static> {
    reference_contact_with(m, l, 0.04, 2e-8)
}

/// Hertzian pressure of the reference contact at `M`, `L`, `α`: `p_h = L sqrt(M/2π)/α`, Pa.
pub fn reference_pressure(m: f64, l: f64, alpha: f64) -> f64 {
    l * (m / (2.0 * std::f64::consts::PI)).sqrt() / alpha
}

/// [`reference_contact`] with another ambient viscosity `η0` (Pa·s) and pressure–viscosity
/// coefficient `α` (1/Pa): the same `M`, `L`, another Roelands index `Z = α p_r/(ln η0 + 9.67)`
/// and another `p_h/p_r`.
pub fn reference_contact_with(m: f64, l: f64, eta0: f64, alpha: f64) -> EhlInput<'static> {
    let (e_prime, r) = (2.2e11, 0.01);
    let lubricant = Lubricant { viscosity: eta0, pressure_viscosity: alpha, ..Lubricant::SEED000 };
    let g = alpha * e_prime;
    let u_sum = (l / g).powi(4);
    EhlInput {
        load_per_length: m * u_sum.sqrt() * e_prime * r,
        reduced_radius: r,
        effective_modulus: e_prime,
        entrainment_velocity: 0.5 * u_sum * e_prime * r / eta0,
        sliding_velocity: 0.0,
        lubricant,
        temperature: lubricant.reference_temperature,
        rheology: Rheology::default(),
        transient: None,
        warm_start: None,
    }
}

/// Measure one steady cell: the signed errors `(h_Moes/h_c − 1, h_PH/h_min − 1)` of the
/// closed forms against Richardson extrapolation of `nodes` and `(nodes − 1)/2 + 1` nodes, for
/// the reference contact at `M`, `L` and `α` (1/Pa).
pub fn measure_steady(m: f64, l: f64, alpha: f64, nodes: usize, observer: &dyn Observer) -> Result<(f64, f64), SolveError> {
    measure_steady_for(&reference_contact_with(m, l, 0.04, alpha), nodes, observer)
}

/// [`measure_steady`] for any steady input.
pub fn measure_steady_for(input: &EhlInput, nodes: usize, observer: &dyn Observer) -> Result<(f64, f64), SolveError> {
    let input = *input;
    let options = EhlOptions { nodes, tolerance: 1e-9, max_iterations: 80, ..EhlOptions::default() };
    let mut solver = TransientSolver::new(options, Extrapolation::Richardson);
    let s = solver.step(&input, None, observer)?;
    let r = input.reduced_radius;
    let g = Groups::of(input.load_per_length, r, input.effective_modulus, input.entrainment_velocity, &input.lubricant, input.temperature);
    Ok((moes_central_film(&g, r) / s.central_film - 1.0, pan_hamrock_minimum_film(&g, r) / s.min_film - 1.0))
}

/// The benchmark cam-like cycle at angle index `k` of `steps`: load 2.25–12.5 kN over 21 mm,
/// radius 15.2–10.5 mm, entrainment `u_m = 4 cos θ + 1.5` m/s (reverses twice), slide 1 %,
/// oil η0 = 0.013 Pa·s, α = 1.84e-8 1/Pa (Roelands, Dowson–Higginson), steel (`E'` = 219.8 GPa).
/// The velocities do not depend on the cycle period: a shorter period is a faster load change
/// at the same entrainment, a larger squeeze number.
pub fn cycle_input(k: usize, steps: usize) -> EhlInput<'static> {
    let th = 2.0 * std::f64::consts::PI * k as f64 / steps as f64;
    let f = 2250.0 + (12500.0 - 2250.0) * (0.5 - 0.5 * th.cos()).powi(2);
    let r = 0.0152 - 0.0047 * (0.5 - 0.5 * th.cos());
    let u = 4.0 * th.cos() + 1.5;
    let lubricant = Lubricant { viscosity: 0.013, pressure_viscosity: 1.84e-8, ..Lubricant::SEED000 };
    EhlInput {
        load_per_length: f / 0.021,
        reduced_radius: r,
        effective_modulus: 2.0 / (2.0 * 0.91 / 200e9),
        entrainment_velocity: u,
        sliding_velocity: 0.01 * u,
        lubricant,
        temperature: lubricant.reference_temperature,
        rheology: Rheology { eyring_stress: Some(5e6), ..Rheology::default() },
        transient: None,
        warm_start: None,
    }
}

/// One sample of the transient map: squeeze number and the departures
/// `h_transient/h_steady − 1` of the central and minimum film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqueezeSample {
    pub angle_index: usize,
    pub xi: f64,
    pub central: f64,
    pub minimum: f64,
}

/// Measure the transient map over the second of two revolutions of [`cycle_input`] (the first
/// sets up the squeeze history) with `steps` angles per revolution of `period` s: at each angle
/// the squeeze solution against the steady solution at the same instant (both Richardson of
/// `nodes` and `(nodes − 1)/2 + 1`), and `ξ` from Moes' central film differenced over the
/// neighbouring angles. Angles where the steady problem has no solution (zero entrainment)
/// are skipped.
pub fn measure_squeeze(period: f64, steps: usize, nodes: usize, tolerance: f64, observer: &dyn Observer) -> Result<Vec<SqueezeSample>, SolveError> {
    let options = EhlOptions { nodes, tolerance, ..EhlOptions::default() };
    let mut transient = TransientSolver::new(options, Extrapolation::Richardson);
    let mut steady = TransientSolver::new(options, Extrapolation::Richardson);
    let dt = period / steps as f64;
    let moes = |k: usize| {
        let i = cycle_input(k % steps, steps);
        let g = Groups::of(i.load_per_length, i.reduced_radius, i.effective_modulus, i.entrainment_velocity, &i.lubricant, i.temperature);
        moes_central_film(&g, i.reduced_radius)
    };
    let mut out = Vec::new();
    for k in 0..2 * steps {
        let input = cycle_input(k % steps, steps);
        let t = transient.step(&input, Some(dt), observer)?;
        if k < steps {
            continue;
        }
        let s = match steady.step(&input, None, observer) {
            Ok(s) => s,
            Err(SolveError::Physical { .. }) | Err(SolveError::NotConverged { .. }) => {
                steady.reset();
                continue;
            }
            Err(e) => return Err(e),
        };
        let (a, b) = (moes(k + steps - 1), moes(k + 1));
        let rate = if a > 0.0 && b > 0.0 { (b.ln() - a.ln()) / (2.0 * dt) } else { f64::INFINITY };
        out.push(SqueezeSample {
            angle_index: k - steps,
            xi: squeeze_number(t.hertz_half_width, input.entrainment_velocity, rate),
            central: t.central_film / s.central_film - 1.0,
            minimum: t.min_film / s.min_film - 1.0,
        });
    }
    Ok(out)
}

/// The squeeze table from samples: the largest `|e_t|` per bin of [`SQUEEZE_XI`], made
/// non-decreasing; bins beyond the last sample stay `None`.
pub fn squeeze_table(samples: &[SqueezeSample]) -> ([Option<f64>; 8], [Option<f64>; 8]) {
    let mut c = [None::<f64>; 8];
    let mut m = [None::<f64>; 8];
    for s in samples {
        if let Some(k) = SQUEEZE_XI.iter().position(|&top| s.xi <= top) {
            c[k] = Some(c[k].unwrap_or(0.0).max(s.central.abs()));
            m[k] = Some(m[k].unwrap_or(0.0).max(s.minimum.abs()));
        }
    }
    let last = c.iter().rposition(|v| v.is_some());
    let (mut rc, mut rm) = (0.0f64, 0.0f64);
    for k in 0..8 {
        if last.is_some_and(|l| k <= l) {
            rc = rc.max(c[k].unwrap_or(0.0));
            rm = rm.max(m[k].unwrap_or(0.0));
            c[k] = Some(rc);
            m[k] = Some(rm);
        }
    }
    (c, m)
}
