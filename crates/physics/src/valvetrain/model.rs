//! The lumped valve train and its equations of motion: a direct-acting follower, or a lever
//! (rocker arm, optionally driven through a pushrod; end-pivot finger follower) between the cam
//! and the valve.
//!
//! Degrees of freedom along the cam's line of action, positive in the opening direction,
//! measured from the static position with the cam on its base circle (where every element
//! carries the spring preload `P`):
//!
//! * the follower (tappet; in seed 003 the retainer the cam touches, Table 2 "curve to curve"),
//!   mass `m_f`;
//! * with a pushrod, the lever's cam-side end (the rocker's inertia `I/l_c²` plus half the
//!   pushrod; the other half is on the tappet);
//! * the valve with retainer and keepers, mass `m_v` (merged with the body before it when the
//!   train is rigid);
//! * the valve spring as a chain of `N` interior masses (see [`SpringChain`]).
//!
//! Elements (each a preloaded linear spring–damper carrying compression `P + k Δ + c Δ̇`):
//! cam–follower contact (unilateral: no tension), pushrod, the lever–valve (or follower–valve)
//! train link, spring segments, and the valve seat (unilateral stop, no preload). With the
//! follower's displacement `x_f`, cam lift `s(θ)`, the contact compression is
//! `P + k_c (s − x_f) + c_c (ṡ − ẋ_f)`, cut to zero when the penetration `P/k_c + s − x_f` or the
//! force itself would be negative (separation).
//! Each mass obeys Newton's law `m ẍ = Σ forces` — seed 003 eq. (21)–(22), the valve's
//! Lagrange equation with the spring force, here with the train's compliances (the seed's model
//! is rigid apart from the contact, eq. (32)) — written as the first-order system
//! `y = (x, ẋ, W)`, `W` the work done by the cam on the train (`Ẇ = F_c ṡ`, for the energy
//! balance).
//!
//! **A lever** of ratio `r = l_v/l_c` (see [`Lever`]) is taken with a constant ratio: the valve
//! side moves `r` times the cam side and carries `1/r` of its force. Lagrange's equations of the
//! lever with the valve-side coordinate `x_v = r x_c` then hold in cam-side coordinates with every
//! valve-side mass and stiffness (and damping) multiplied by `r²`, forces and preloads by `r`,
//! lengths by `1/r`; the lever's rotation `φ = x_c/l_c` adds the mass `I/l_c²` (standard reduction,
//! Norton, *Cam Design and Manufacturing Handbook*, ch. 10). The assembly works in those cam-side
//! coordinates; [`Assembly`]'s valve outputs are converted back to the valve side. Kinetic and
//! elastic energies are invariant under the reduction.

pub use super::chain::SpringChain;
use super::chain::{attach, Element, Law, Parts};
use std::f64::consts::PI;

/// A linear spring–damper link, N/m and N·s/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    pub stiffness: f64,
    pub damping: f64,
}

/// A nested inner spring, in parallel with the outer one between the valve and the fixed end.
#[derive(Debug, Clone, PartialEq)]
pub struct NestedSpring {
    pub spring: SpringChain,
    /// Its share of the preload, N (the outer spring carries the rest of `ValveTrain::preload`).
    pub preload: f64,
}

/// A helical compression spring (round wire).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelicalSpring {
    /// Wire diameter d, m.
    pub wire_diameter: f64,
    /// Mean coil diameter D, m.
    pub mean_diameter: f64,
    /// Active coils n.
    pub active_coils: f64,
    /// Shear modulus G, Pa.
    pub shear_modulus: f64,
    /// Density ρ, kg/m³.
    pub density: f64,
}

impl HelicalSpring {
    /// Rate `k = G d⁴/(8 D³ n)`, N/m (Shigley, *Mechanical Engineering Design*, eq. 10-9).
    pub fn rate(&self) -> f64 {
        self.shear_modulus * self.wire_diameter.powi(4) / (8.0 * self.mean_diameter.powi(3) * self.active_coils)
    }
    /// Active mass `ρ (π d²/4) (π D n)`, kg (Shigley eq. 10-24's `W`).
    pub fn active_mass(&self) -> f64 {
        self.density * PI * self.wire_diameter.powi(2) / 4.0 * PI * self.mean_diameter * self.active_coils
    }
    /// First surge frequency with both ends fixed, `f = d/(2π n D²) √(G/(2ρ))`, Hz (Shigley
    /// eq. 10-25, = ½√(k/m)).
    pub fn surge_frequency(&self) -> f64 {
        self.wire_diameter / (2.0 * PI * self.active_coils * self.mean_diameter.powi(2))
            * (self.shear_modulus / (2.0 * self.density)).sqrt()
    }
}

/// Secant stiffness W/δ of a line contact of length `length` (m) between a cylinder of radius
/// `radius` (m) and a flat, at load `load` (N), contact modulus E* (Pa): seed 003 eq. (6) with
/// eq. (3)–(4), `δ = b₀ p₀ (1/E*) (ln(4b/b₀) + 0.5)` with `b₀ p₀ = 2W/(πL)` and the half-width
/// `b₀ = √(4WR/(πLE*))` (eq. (3) with D = 2R); the seed's `b` in the logarithm is read as the
/// half-length of the line, `L/2`.
pub fn line_contact_stiffness(load: f64, length: f64, radius: f64, contact_modulus: f64) -> f64 {
    let w = load.max(1e-3);
    let b0 = (4.0 * w * radius / (PI * length * contact_modulus)).sqrt();
    let log = (2.0 * length / b0).ln() + 0.5;
    PI * length * contact_modulus / (2.0 * log.max(0.5))
}

/// Damping coefficient `2ζ√(k m)` of a link of stiffness `k` on mass `m`, N·s/m.
pub fn damping_from_ratio(ratio: f64, stiffness: f64, mass: f64) -> f64 {
    2.0 * ratio * (stiffness * mass).sqrt()
}

/// A pushrod between the follower (tappet) and the lever's cam side (overhead-valve train): mass
/// `mass` (kg), lumped half on each end, and its axial stiffness and damping (N/m, N·s/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pushrod {
    pub mass: f64,
    pub link: Link,
}

/// A rigid lever between the cam and the valve, pivoted on the frame: a rocker arm (pivot between
/// the cam side and the valve side; the cam acts through a pushrod or directly on a pad or
/// roller on the arm) or an end-pivot finger follower (pivot at one end, valve pad at the other,
/// the cam's roller or slipper in between: `cam_arm < valve_arm`).
///
/// Kinematics to first order in the lever's angle: the ratio `r = l_v/l_c` is constant. For
/// straight arms perpendicular to both lines of action at mid-lift, both ends move `l sin φ` and
/// the ratio of the displacements is exact; the neglected terms are the arms' obliquity away from
/// mid-lift (`cos φ`, a relative error in the ratio of at most `1 − cos(φ_max/2) ≈ φ_max²/8`,
/// `φ_max = s_max/l_c`: 0.6 % for a 6.5 mm lift on a 30 mm arm) and the travel of the contact
/// points along pads of radius `ρ` (of order `ρ φ/l`; not modelled). The cam's lift is the
/// translating follower's: on a finger follower the roller moves on an arc of radius `l_c`
/// instead, a difference of the same order. Gravity and pivot friction are not modelled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lever {
    /// Pivot to the cam side's line of action l_c, m (> 0).
    pub cam_arm: f64,
    /// Pivot to the valve's line of action l_v, m (> 0).
    pub valve_arm: f64,
    /// Moment of inertia about the pivot, kg·m² (≥ 0).
    pub inertia: f64,
    /// Pushrod from the follower to the lever; `None`: the cam acts on the lever itself (its
    /// pad or roller; the follower mass is then what moves with the cam's lift outside `I`).
    pub pushrod: Option<Pushrod>,
}

impl Lever {
    /// The ratio r = l_v/l_c (valve motion per cam-side motion).
    pub fn ratio(&self) -> f64 {
        self.valve_arm / self.cam_arm
    }
    /// The lever's inertia reduced to its cam side, `I/l_c²`, kg.
    pub fn cam_side_mass(&self) -> f64 {
        self.inertia / (self.cam_arm * self.cam_arm)
    }
}

/// The valve train.
#[derive(Debug, Clone, PartialEq)]
pub struct ValveTrain {
    /// Follower mass m_f, kg (> 0).
    pub follower_mass: f64,
    /// Valve (+ retainer, keepers) mass m_v, kg (≥ 0; > 0 with an elastic train).
    pub valve_mass: f64,
    /// Follower–valve link; `None`: rigid (follower and valve one body).
    pub train: Option<Link>,
    pub spring: SpringChain,
    /// A nested inner spring (its own chain, in parallel). `None`: one spring.
    pub inner_spring: Option<NestedSpring>,
    /// Spring force at zero lift, N (> 0: the cam carries it on the base circle; with an inner
    /// spring the sum of both).
    pub preload: f64,
    /// Cam–follower contact (unilateral).
    pub contact: Link,
    /// Valve seat: a unilateral stop `gap` (m) below the closed position (the valve's place with
    /// the cam on its base circle); `None`: no seat.
    pub seat: Option<Seat>,
    /// Lever between cam and valve; `None`: direct-acting. With a lever, `follower_mass` is
    /// the part moving with the cam's lift outside the lever (tappet; ≥ 0), and `valve_mass`,
    /// `train` (the lever–valve link: arm bending, valve stem), `spring`, `preload` and `seat`
    /// are valve-side quantities.
    pub lever: Option<Lever>,
    /// Lash: `None`: none, the cam carries the preload on the base circle. See [`Lash`].
    pub lash: Option<Lash>,
}

/// Lash in the train.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lash {
    /// Mechanical lash: a clearance (m, cam side; a valve-side clearance `c_v` is `c_v/r` here)
    /// between the cam and the follower with the cam on its base circle (0: none). The valve
    /// rests on its seat (required; `gap` taken as 0), which carries the spring preload; the
    /// contact and the train's links carry no load until the cam's lift closes the gap on the
    /// opening ramp (Norton, *Cam Design and Manufacturing Handbook*, ch. 10: the ramps take up
    /// the lash at a constant velocity), and the contact opens again on the closing ramp.
    Mechanical(f64),
    /// A hydraulic lash adjuster between the follower and the valve (direct-acting bucket;
    /// takes the place of the `train` link).
    Hydraulic(HydraulicLashAdjuster),
}

/// A hydraulic lash adjuster, the standard lumped model (the plunger's high-pressure chamber as
/// a compressible oil column, laminar leak-down through the plunger clearance, a check valve
/// that refills the chamber from the supply — the form used throughout the valve-train dynamics
/// literature; its parts are textbook: the oil column's stiffness from the bulk modulus, and
/// leak-down as pressure-driven laminar flow through a narrow concentric annulus, i.e. between
/// parallel plates of width πD (e.g. White, *Viscous Fluid Flow*, Poiseuille flow in an
/// annulus of small gap):
///
/// * chamber pressure `p = p_s + k_h (δ − z)/A` (gauge), `δ` the approach of follower and valve,
///   `z` the plunger's leak-down (net oil volume lost over the plunger area `A = π D²/4`), oil
///   column stiffness `k_h = β A²/V` (bulk modulus β, chamber volume V);
/// * force `F = P_h + A p + c_h δ̇` (plunger spring preload `P_h`; on the base circle the cam
///   carries `P_h + A p_s`, the seat the rest of the valve-spring preload);
/// * `A ż = G_L p − G_C max(0, p_s − p)`: leak-down through the annular clearance, laminar,
///   `G_L = π D c³/(12 μ L)` (radial clearance c, leak length L, viscosity μ; narrow concentric
///   annulus), and refill through the check valve, open while `p < p_s`, conductance `G_C`.
///
/// Not modelled: aeration (lower β), the check valve's own dynamics and cracking pressure,
/// cavitation (the force is not cut at zero pressure).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HydraulicLashAdjuster {
    /// Plunger diameter D, m.
    pub plunger_diameter: f64,
    /// Radial clearance of the plunger c, m.
    pub clearance: f64,
    /// Leak length L, m.
    pub leak_length: f64,
    /// Oil viscosity μ, Pa·s.
    pub viscosity: f64,
    /// Oil bulk modulus β, Pa.
    pub bulk_modulus: f64,
    /// High-pressure chamber volume V, m³.
    pub chamber_volume: f64,
    /// Oil supply pressure p_s (gauge), Pa.
    pub supply_pressure: f64,
    /// Plunger spring preload P_h, N.
    pub spring_preload: f64,
    /// Check-valve conductance G_C, m³/(s·Pa).
    pub check_conductance: f64,
    /// Damping of the plunger's motion c_h, N·s/m.
    pub damping: f64,
}

impl HydraulicLashAdjuster {
    pub fn area(&self) -> f64 {
        PI * self.plunger_diameter * self.plunger_diameter / 4.0
    }
    /// Oil column stiffness `β A²/V`, N/m.
    pub fn stiffness(&self) -> f64 {
        self.bulk_modulus * self.area().powi(2) / self.chamber_volume
    }
    /// Leak conductance `π D c³/(12 μ L)`, m³/(s·Pa).
    pub fn leak_conductance(&self) -> f64 {
        PI * self.plunger_diameter * self.clearance.powi(3) / (12.0 * self.viscosity * self.leak_length)
    }
    /// Force on the base circle with the chamber at supply pressure, N.
    pub fn base_force(&self) -> f64 {
        self.spring_preload + self.area() * self.supply_pressure
    }
    /// Leak-down velocity under the force `f` with the check valve shut, m/s (the leak-down
    /// test: `G_L (F − P_h)/A²`).
    pub fn leak_down_velocity(&self, f: f64) -> f64 {
        self.leak_conductance() * (f - self.spring_preload) / self.area().powi(2)
    }
}

/// The adjuster in the assembly: between nodes `b` (follower) and `a` (valve).
#[derive(Debug, Clone, Copy)]
pub struct HlaElement {
    pub b: usize,
    pub a: usize,
    pub hla: HydraulicLashAdjuster,
    k: f64,
    leak: f64,
}

impl HlaElement {
    /// Chamber pressure (gauge), Pa, at displacements `x` and leak-down `z`.
    pub fn pressure(&self, x: &[f64], z: f64) -> f64 {
        self.hla.supply_pressure + self.k * (x[self.b] - x[self.a] - z) / self.hla.area()
    }
    /// Force between follower and valve (compression), N.
    pub fn force(&self, x: &[f64], v: &[f64], z: f64) -> f64 {
        self.hla.spring_preload + self.hla.area() * self.pressure(x, z) + self.hla.damping * (v[self.b] - v[self.a])
    }
    /// Whether the check valve is open.
    pub fn open(&self, x: &[f64], z: f64) -> bool {
        self.pressure(x, z) < self.hla.supply_pressure
    }
    /// `ż`, m/s.
    pub fn rate(&self, x: &[f64], z: f64) -> f64 {
        let p = self.pressure(x, z);
        let refill = if p < self.hla.supply_pressure { self.hla.check_conductance * (self.hla.supply_pressure - p) } else { 0.0 };
        (self.leak * p - refill) / self.hla.area()
    }
    /// `(∂ż/∂x_b, ∂ż/∂x_a, ∂ż/∂z)` with the check valve open or shut.
    pub fn rate_jacobian(&self, open: bool) -> (f64, f64, f64) {
        let g = self.leak + if open { self.hla.check_conductance } else { 0.0 };
        let d = g * self.k / self.hla.area().powi(2);
        (d, -d, -d)
    }
    /// Oil column stiffness, N/m.
    pub fn stiffness(&self) -> f64 {
        self.k
    }
}

impl ValveTrain {
    /// The lever ratio r (1 for a direct-acting follower).
    pub fn ratio(&self) -> f64 {
        self.lever.map_or(1.0, |l| l.ratio())
    }

    /// The rigid train's quasi-static load at the cam, `P_c + k_c s + m_c s̈`: every part rigid,
    /// the spring massless but for Rayleigh's third, reduced to the cam side — `(P_c, k_c, m_c)`
    /// = `(P, k, m_f + m_v + m_s/3)` direct-acting; with a lever of ratio r,
    /// `(r P, r² k, m_f + m_p + I/l_c² + r² (m_v + m_s/3))` (seed 003 eq. (21)–(22) with the
    /// rigid train; the lever's reduction as in the module docs).
    pub fn quasi_static_equivalent(&self) -> (f64, f64, f64) {
        let r = self.ratio();
        let inner = self.inner_spring.as_ref().map_or((0.0, 0.0), |n| (n.spring.rate, n.spring.mass));
        let valve_side = self.valve_mass + (self.spring.mass + inner.1) / 3.0;
        let cam_side = self.follower_mass
            + self.lever.map_or(0.0, |l| l.cam_side_mass() + l.pushrod.map_or(0.0, |p| p.mass));
        (r * self.preload, r * r * (self.spring.rate + inner.0), cam_side + r * r * valve_side)
    }

    /// The rigid train's separation ("jump") speed, rad/s: with every part rigid and the spring
    /// massless but for Rayleigh's third, the contact force is `P_c + k_c s + m_c ω² s''` (s'' per
    /// rad²; [`ValveTrain::quasi_static_equivalent`]), so contact is lost first at
    /// `ω_j = min over s'' < 0 of √((P_c + k_c s)/(m_c (−s'')))` (Norton, *Cam Design and
    /// Manufacturing Handbook*, ch. 10). `samples`: `(s, s'')` over the revolution. `None` when
    /// the lift never decelerates; 0 when the spring force is not positive where it does. A
    /// closed form: the dynamic train (compliance, surge, residual vibration) separates near it,
    /// usually below — a `sweep` over speed finds that one.
    pub fn rigid_jump_speed(&self, samples: impl IntoIterator<Item = (f64, f64)>) -> Option<f64> {
        let (p, k, m) = self.quasi_static_equivalent();
        samples
            .into_iter()
            .filter(|&(_, d2)| d2 < 0.0)
            .map(|(s, d2)| ((p + k * s).max(0.0) / (m * -d2)).sqrt())
            .fold(None, |best: Option<f64>, w| Some(best.map_or(w, |b| b.min(w))))
    }
}

/// The valve seat.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seat {
    pub link: Link,
    /// Distance below the closed position, m (≥ 0).
    pub gap: f64,
}

/// The assembled model: masses and elements.
#[derive(Debug, Clone)]
pub struct Assembly {
    pub masses: Vec<f64>,
    elements: Vec<Element>,
    /// Index of the follower and of the valve degree of freedom.
    pub follower: usize,
    pub valve: usize,
    /// Element indices of the springs' segments at the moving (valve) and fixed ends (outer
    /// spring first).
    spring_moving: Vec<usize>,
    spring_fixed: Vec<usize>,
    /// Piecewise-linear laws of progressive springs' elements, and the element of each.
    laws: Vec<Law>,
    law_elements: Vec<usize>,
    /// Per degree of freedom, its share of the valve's lift in the static state (1 for bodies).
    pub shares: Vec<f64>,
    contact: Link,
    /// The seat in cam-side coordinates.
    seat: Option<Seat>,
    /// Cam-side lash, m (0: none).
    pub lash: f64,
    /// The hydraulic lash adjuster (its leak-down `z` is a state of the system).
    pub hla: Option<HlaElement>,
    /// Preload of the contact (the spring preload; 0 with a lash) and of the seat (the spring
    /// preload with a lash, else 0), cam side.
    contact_preload: f64,
    seat_preload: f64,
    /// Lever ratio r: valve-side displacement per cam-side coordinate (1: direct-acting).
    pub ratio: f64,
}

impl ValveTrain {
    /// Masses and elements, in cam-side coordinates (with a lever: valve-side masses, stiffnesses
    /// and damping times r², the preload times r, the seat gap over r).
    pub fn assemble(&self) -> Assembly {
        let r = self.ratio();
        let r2 = r * r;
        let preload = r * self.preload;
        let lash = match self.lash {
            Some(Lash::Mechanical(c)) if c > 0.0 => c,
            _ => 0.0,
        };
        let hla = match self.lash {
            Some(Lash::Hydraulic(h)) => Some(h),
            _ => None,
        };
        // With a lash only the spring (and the seat) carry the preload on the base circle; with
        // an adjuster the train carries its base force.
        let link_preload = match hla {
            Some(h) => h.base_force(),
            None if lash > 0.0 => 0.0,
            None => preload,
        };
        let mut masses = vec![self.follower_mass];
        let mut elements = Vec::new();
        let follower = 0;
        // The body the valve side hangs on: the follower, or with a lever the lever itself (on
        // the follower without a pushrod, its own node with one).
        let mut lever_node = 0;
        if let Some(l) = self.lever {
            match l.pushrod {
                None => masses[0] += l.cam_side_mass(),
                Some(p) => {
                    masses[0] += 0.5 * p.mass;
                    masses.push(l.cam_side_mass() + 0.5 * p.mass);
                    lever_node = 1;
                    elements.push(Element { b: Some(0), a: Some(1), k: p.link.stiffness, c: p.link.damping, preload: link_preload, law: None });
                }
            }
        }
        let mut hla_element = None;
        let valve = match self.train {
            None if hla.is_some() => {
                masses.push(r2 * self.valve_mass);
                let v = masses.len() - 1;
                let h = hla.expect("checked");
                hla_element = Some(HlaElement { b: lever_node, a: v, hla: h, k: h.stiffness(), leak: h.leak_conductance() });
                v
            }
            None => {
                masses[lever_node] += r2 * self.valve_mass;
                lever_node
            }
            Some(link) => {
                masses.push(r2 * self.valve_mass);
                let v = masses.len() - 1;
                elements.push(Element { b: Some(lever_node), a: Some(v), k: r2 * link.stiffness, c: r2 * link.damping, preload: link_preload, law: None });
                v
            }
        };
        let mut shares = vec![1.0; masses.len()];
        let mut laws = Vec::new();
        let inner_preload = self.inner_spring.as_ref().map_or(0.0, |n| n.preload);
        let mut springs = vec![(&self.spring, self.preload - inner_preload)];
        springs.extend(self.inner_spring.as_ref().map(|n| (&n.spring, n.preload)));
        let (mut spring_moving, mut spring_fixed) = (Vec::new(), Vec::new());
        for (sp, pre) in springs {
            let parts = Parts { masses: &mut masses, shares: &mut shares, elements: &mut elements, laws: &mut laws };
            let (m, f) = attach(parts, valve, r, sp, pre);
            spring_moving.push(m);
            spring_fixed.push(f);
        }
        let law_elements: Vec<usize> = (0..laws.len()).map(|l| elements.iter().position(|e| e.law == Some(l)).expect("each law has its element")).collect();
        let gap = |g: f64| if lash > 0.0 { 0.0 } else { g / r };
        let seat = self.seat.map(|st| Seat { link: Link { stiffness: r2 * st.link.stiffness, damping: r2 * st.link.damping }, gap: gap(st.gap) });
        let (contact_preload, seat_preload) = match hla {
            Some(h) => (h.base_force(), preload - h.base_force()),
            None if lash > 0.0 => (0.0, preload),
            None => (preload, 0.0),
        };
        let gap = |st: Seat| if hla.is_some() { 0.0 } else { st.gap };
        let seat = seat.map(|st| Seat { gap: gap(st), ..st });
        Assembly { masses, elements, follower, valve, spring_moving, spring_fixed, laws, law_elements, shares, contact: self.contact, seat, ratio: r, lash, contact_preload, seat_preload, hla: hla_element }
    }
}

/// First regime bit of the progressive springs' stages (bits 0–2: contact, seat, the lash
/// adjuster's check valve).
pub const SPRING_REGIME_SHIFT: u32 = 3;

/// Contact and seat forces and whether each is closed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unilateral {
    /// Cam–follower contact force, N (≥ 0).
    pub contact: f64,
    pub contact_closed: bool,
    /// Event function: positive while the contact is loaded.
    pub contact_gap: f64,
    /// Seat force on the valve, N (≥ 0).
    pub seat: f64,
    pub seat_closed: bool,
    pub seat_gap: f64,
}

impl Assembly {
    pub fn dofs(&self) -> usize {
        self.masses.len()
    }

    pub fn has_seat(&self) -> bool {
        self.seat.is_some()
    }

    /// Where the valve (cam side) first touches its seat, m above the closed position: the
    /// preloaded seat's compression with a lash, 0 otherwise.
    pub fn seat_touch_height(&self) -> f64 {
        match self.seat {
            Some(st) if self.seat_preload > 0.0 => self.seat_preload / st.link.stiffness,
            _ => 0.0,
        }
    }

    /// Contact and seat forces at the state `(x, v)` with cam lift `s` and lift rate `sd` (cam-side
    /// coordinates: the seat force on the valve is `seat / ratio`).
    pub fn unilateral(&self, x: &[f64], v: &[f64], s: f64, sd: f64) -> Unilateral {
        let (kc, cc) = (self.contact.stiffness, self.contact.damping);
        let pen = self.contact_preload + kc * (s - self.lash - x[self.follower]);
        let raw = pen + cc * (sd - v[self.follower]);
        let contact_gap = pen.min(raw);
        let contact_closed = contact_gap > 0.0;
        let (mut seat, mut seat_closed, mut seat_gap) = (0.0, false, -1.0);
        if let Some(st) = self.seat {
            let (k, c) = (st.link.stiffness, st.link.damping);
            let pen = self.seat_preload + k * (-st.gap - x[self.valve]);
            let raw = pen - c * v[self.valve];
            seat_gap = pen.min(raw);
            seat_closed = seat_gap > 0.0;
            if seat_closed {
                seat = raw;
            }
        }
        Unilateral { contact: if contact_closed { raw } else { 0.0 }, contact_closed, contact_gap, seat, seat_closed, seat_gap }
    }

    fn compression(&self, e: &Element, x: &[f64], v: &[f64]) -> f64 {
        let xb = e.b.map_or(0.0, |i| x[i]);
        let xa = e.a.map_or(0.0, |i| x[i]);
        let vb = e.b.map_or(0.0, |i| v[i]);
        let va = e.a.map_or(0.0, |i| v[i]);
        match e.law {
            None => e.preload + e.k * (xb - xa) + e.c * (vb - va),
            Some(l) => {
                let law = &self.laws[l];
                let d = xb - xa;
                law.force(d) + law.beta * law.rate(law.stage(d)) * (vb - va)
            }
        }
    }

    /// Stiffness and damping of element `e` in `regime` (a progressive segment's stage from the
    /// regime's bits, [`Assembly::spring_regime`]).
    fn stiffness_in(&self, e: &Element, regime: u32) -> (f64, f64) {
        match e.law {
            None => (e.k, e.c),
            Some(l) => {
                let law = &self.laws[l];
                let shift = SPRING_REGIME_SHIFT + self.laws[..l].iter().map(|x| x.breaks().len() as u32).sum::<u32>();
                let width = law.breaks().len() as u32;
                let stage = ((regime >> shift) & ((1u32 << width) - 1)).count_ones() as usize;
                let k = law.rate(stage);
                (k, law.beta * k)
            }
        }
    }

    /// Regime bits of the progressive springs' elements (bit `SPRING_REGIME_SHIFT + l`: law `l`
    /// past its break) at the displacements `x`. Elements with more than one break (a massless
    /// progressive spring) use as many bits as breaks (one per break passed, in order).
    pub fn spring_regime(&self, x: &[f64]) -> u32 {
        let mut bits = 0u32;
        let mut shift = SPRING_REGIME_SHIFT;
        for (l, law) in self.laws.iter().enumerate() {
            let e = &self.elements[self.law_elements[l]];
            let d = e.b.map_or(0.0, |i| x[i]) - e.a.map_or(0.0, |i| x[i]);
            let stage = law.stage(d) as u32;
            // Thermometer code: `stage` ones.
            bits |= ((1u32 << stage) - 1) << shift;
            shift += law.breaks().len() as u32;
        }
        bits
    }

    /// Number of progressive-spring events (breaks of every law).
    pub fn spring_events(&self) -> usize {
        self.laws.iter().map(|l| l.breaks().len()).sum()
    }

    /// The progressive-spring event functions `Δ − break` (into `g`, [`Assembly::spring_events`]
    /// long).
    pub fn spring_event_values(&self, x: &[f64], g: &mut [f64]) {
        let mut i = 0;
        for (l, law) in self.laws.iter().enumerate() {
            let e = &self.elements[self.law_elements[l]];
            let d = e.b.map_or(0.0, |i| x[i]) - e.a.map_or(0.0, |i| x[i]);
            for b in law.breaks() {
                g[i] = d - b;
                i += 1;
            }
        }
    }

    /// Spring force at the moving (retainer) and the fixed end, N (compression positive; the
    /// valve side's own force, cam-side force over the ratio; nested springs summed).
    pub fn spring_forces(&self, x: &[f64], v: &[f64]) -> (f64, f64) {
        let r = self.ratio;
        let sum = |idx: &[usize]| idx.iter().map(|&i| self.compression(&self.elements[i], x, v)).sum::<f64>() / r;
        (sum(&self.spring_moving), sum(&self.spring_fixed))
    }

    /// Net force on each mass (`out`, length dofs) and the contact/seat state.
    pub fn forces(&self, x: &[f64], v: &[f64], s: f64, sd: f64, out: &mut [f64]) -> Unilateral {
        out.iter_mut().for_each(|f| *f = 0.0);
        for e in &self.elements {
            let q = self.compression(e, x, v);
            if let Some(b) = e.b {
                out[b] -= q;
            }
            if let Some(a) = e.a {
                out[a] += q;
            }
        }
        let u = self.unilateral(x, v, s, sd);
        out[self.follower] += u.contact;
        out[self.valve] += u.seat;
        u
    }

    /// Net force on degree of freedom `dof` alone (as [`Assembly::forces`] would give it).
    pub fn force_on(&self, dof: usize, x: &[f64], v: &[f64], u: &Unilateral) -> f64 {
        let mut f = 0.0;
        for e in &self.elements {
            if e.b == Some(dof) {
                f -= self.compression(e, x, v);
            }
            if e.a == Some(dof) {
                f += self.compression(e, x, v);
            }
        }
        if dof == self.follower {
            f += u.contact;
        }
        if dof == self.valve {
            f += u.seat;
        }
        f
    }

    /// `∂F/∂x` and `∂F/∂v` (row-major dofs × dofs) in `regime` (bit 0 the contact closed, bit
    /// 1 the seat, the progressive springs' stages from bit [`SPRING_REGIME_SHIFT`]).
    pub fn force_jacobian(&self, regime: u32, kx: &mut [f64], cv: &mut [f64]) {
        let (contact, seat) = (regime & 1 != 0, regime & 2 != 0);
        let n = self.dofs();
        kx.iter_mut().for_each(|v| *v = 0.0);
        cv.iter_mut().for_each(|v| *v = 0.0);
        let mut add = |i: usize, j: usize, k: f64, c: f64| {
            kx[i * n + j] += k;
            cv[i * n + j] += c;
        };
        for e in &self.elements {
            let (k, c) = self.stiffness_in(e, regime);
            // Force on b: −(k (x_b − x_a) + …); on a: +(…).
            if let Some(b) = e.b {
                add(b, b, -k, -c);
                if let Some(a) = e.a {
                    add(b, a, k, c);
                }
            }
            if let Some(a) = e.a {
                add(a, a, -k, -c);
                if let Some(b) = e.b {
                    add(a, b, k, c);
                }
            }
        }
        if contact {
            add(self.follower, self.follower, -self.contact.stiffness, -self.contact.damping);
        }
        if seat {
            if let Some(st) = self.seat {
                add(self.valve, self.valve, -st.link.stiffness, -st.link.damping);
            }
        }
    }

    /// Kinetic plus stored elastic energy, J (the preloaded elements store `q²/(2k)` at
    /// compression `q`, the spring part of it).
    pub fn energy(&self, x: &[f64], v: &[f64], s: f64) -> f64 {
        let mut e: f64 = self.masses.iter().zip(v).map(|(m, v)| 0.5 * m * v * v).sum();
        for el in &self.elements {
            if let Some(l) = el.law {
                e += self.laws[l].energy(el.b.map_or(0.0, |i| x[i]) - el.a.map_or(0.0, |i| x[i]));
            } else if el.k > 0.0 {
                let q = el.preload + el.k * (el.b.map_or(0.0, |i| x[i]) - el.a.map_or(0.0, |i| x[i]));
                e += q * q / (2.0 * el.k);
            }
        }
        let kc = self.contact.stiffness;
        let q = (self.contact_preload + kc * (s - self.lash - x[self.follower])).max(0.0);
        e += q * q / (2.0 * kc);
        if let Some(st) = self.seat {
            let q = (self.seat_preload + st.link.stiffness * (-st.gap - x[self.valve])).max(0.0);
            e += q * q / (2.0 * st.link.stiffness);
        }
        e
    }

    /// Mass and stiffness matrices of the spring chain alone with both ends held (for its surge
    /// modes): diagonal masses and row-major stiffness of the interior nodes.
    pub fn spring_chain_matrices(&self) -> (Vec<f64>, Vec<f64>) {
        let first = self.valve.max(self.follower) + 1;
        let m: Vec<f64> = self.masses[first..].to_vec();
        let n = m.len();
        let total = self.dofs();
        let (mut kx, mut cv) = (vec![0.0; total * total], vec![0.0; total * total]);
        let rest = self.spring_regime(&vec![0.0; total]);
        self.force_jacobian(rest, &mut kx, &mut cv);
        let mut k = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                k[i * n + j] = -kx[(first + i) * total + first + j];
            }
        }
        (m, k)
    }

}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seed 003 eq. (6): W/δ is the secant stiffness the valve-train dynamics use (same reading
    /// of `b`), and δ grows with the load (Fig. 11b), less than linearly.
    #[test]
    fn line_contact_deflection_is_the_stiffness_of_the_dynamics() {
        let (len, r, es) = (0.012, 0.02, 1.15e11);
        let mut prev = 0.0;
        for load in [50.0, 200.0, 800.0, 3200.0] {
            let d = crate::contact::line_contact_deflection(load / len, len, r, es);
            let k = line_contact_stiffness(load, len, r, es);
            assert!((load / d - k).abs() <= 1e-9 * k, "{load} N: {} vs {k}", load / d);
            assert!(d > prev && (prev == 0.0 || d < 4.0 * prev), "{load} N: {d} after {prev}");
            prev = d;
        }
        assert_eq!(crate::contact::line_contact_deflection(0.0, len, r, es), 0.0);
    }
}
