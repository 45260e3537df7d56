//! `auto` with `ehl.geometry: finite` ([`AutoFinite`]): the 2-D model where
//! [`super::finite::ends_matter`], the line-contact `auto` choice elsewhere; with `ehl.thermal`
//! the thermal 2-D model ([`super::ThermalFinite`]) and the thermal line model.

use super::finite::{ends_matter, Finite};
use super::thermal_finite::ThermalFinite;
use super::{ContactInput, FilmModel, FilmSolution};
use crate::ehl::twod::Fields2d;
use crate::SolveError;

/// `auto` with `ehl.geometry: finite`: the 2-D model where [`ends_matter`], elsewhere the 1-D
/// `auto` choice (closed form or numerical line contact, [`super::Auto`]).
pub struct AutoFinite {
    pub auto: super::Auto,
    pub finite: Finite,
    /// The thermal 2-D model in place of `finite` (`ehl.thermal`).
    pub thermal: Option<ThermalFinite>,
}

impl FilmModel for AutoFinite {
    fn entrainment_tolerance(&self) -> f64 {
        self.auto.entrainment_tolerance()
    }

    fn solve(&self, input: &ContactInput, previous: Option<&FilmSolution>) -> Result<FilmSolution, SolveError> {
        if input.entrainment_velocity != 0.0 && ends_matter(self.finite.crown.as_ref(), input, self.auto.tolerance) {
            match &self.thermal {
                Some(t) => t.solve(input, previous),
                None => self.finite.solve(input, previous),
            }
        } else {
            self.auto.solve(input, previous)
        }
    }

    /// The isothermal 2-D model's fields; none for a thermal film ([`super::ThermalFinite`]
    /// keeps no re-entrant state per angle).
    fn fields(&self, film: &FilmSolution, input: &ContactInput) -> Result<Option<Fields2d>, SolveError> {
        if film.finite.as_deref().is_some_and(|f| f.temperatures.is_some()) {
            return Ok(None);
        }
        self.finite.fields(film, input)
    }

    fn traction_local(&self, film: &FilmSolution, input: &ContactInput, sliding: f64) -> (super::Traction, (f64, f64)) {
        if film.finite.is_some() {
            self.finite.traction_local(film, input, sliding)
        } else {
            self.auto.traction_local(film, input, sliding)
        }
    }
}
