//! The lubricated contact that the cam kinds share: lubricant, asperities, traction law, film
//! formula, fidelity and numerical EHL options. `cam_cycle` and `cam_point` carry the same block
//! in their specs (`wear` through its `cycle`), so it is validated here once and turned into one
//! film model here once (`film_model`: fidelity → closed form, 1-D or 2-D numerical, `auto`).
//!
//! A trait rather than one flattened struct: the specs reject unknown fields
//! (`deny_unknown_fields`), which serde cannot combine with `#[serde(flatten)]`, and the
//! lubricant is optional in a cycle (kinematics alone need none) but required at a point.

use super::common::{AsperitySpec, EhlSpec, FilmSpec, LubricantSpec, TractionSpec};
use crate::jobs::kind::{Limits, Validation};
use crate::physics::film::{model_for, AccurateSettings, Fidelity, FilmModel};

pub trait LubricatedContact {
    /// The lubricant (absent from a cycle that asks for no film).
    fn lubricant(&self) -> Option<&LubricantSpec>;
    fn asperities(&self) -> &AsperitySpec;
    fn traction(&self) -> &TractionSpec;
    fn film(&self) -> &FilmSpec;
    fn fidelity(&self) -> Fidelity;
    fn ehl(&self) -> &EhlSpec;

    /// The block's own rules, at its spec paths (`/lubricant`, `/asperities`, `/traction`,
    /// `/film`, `/ehl`), and the models each fidelity can run.
    fn validate_lubrication(&self, limits: &Limits, v: &mut Validation) {
        if let Some(l) = self.lubricant() {
            l.validate("/lubricant", v);
        }
        self.asperities().validate("/asperities", v);
        self.traction().validate("/traction", v);
        self.film().validate("/film", v);
        let ehl = self.ehl();
        ehl.validate("/ehl", limits, v);
        let numerical = self.fidelity() != Fidelity::Fast;
        if ehl.thermal.is_some() {
            v.check(numerical, "/ehl/thermal", "the thermal model runs with fidelity accurate or auto");
        }
        if !ehl.geometry.is_line() {
            v.check(numerical, "/ehl/geometry", "finite is a model of the accurate and auto fidelities (fast keeps the closed form)");
        }
    }

    /// The film model the fidelity selects, with the kind's numerical settings (its thermal
    /// bodies, crown or point grid already set): `physics::film::model_for`.
    fn film_model(&self, settings: AccurateSettings) -> Box<dyn FilmModel> {
        model_for(self.fidelity(), self.film().to_physics(), settings)
    }
}
