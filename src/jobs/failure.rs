//! Solver failures as problems: the one mapping of [`SolveError`] to the stored problem of a
//! failed job (the problem type itself, `crate::problem`, knows nothing of the solvers).

use crate::physics::{Interrupt, SolveError};
use crate::problem::{ErrorCode, FieldError, Problem};

impl Problem {
    /// The problem a failed solve stores with its job.
    pub fn from_solve_error(err: &SolveError) -> Self {
        match err {
            // A spec path (the kind mapped the solver's field) becomes the field error's path;
            // an unmapped solver field is named in the detail.
            SolveError::InvalidInput { field, message } if field.starts_with('/') => Problem::new(
                ErrorCode::InvalidSpec,
                format!("the solver rejected the spec: {message}"),
            )
            .with_errors(vec![FieldError::new(field.clone(), message.clone())]),
            SolveError::InvalidInput { field, message } => Problem::new(
                ErrorCode::InvalidSpec,
                if field.is_empty() {
                    format!("the solver rejected the spec: {message}")
                } else {
                    format!("the solver rejected the spec (its input {field}): {message}")
                },
            ),
            SolveError::NotConverged { .. } => Problem::new(ErrorCode::NotConverged, err.to_string()),
            SolveError::Physical { code, message } => {
                let (status, title) = ErrorCode::NonPhysical.describe();
                Problem::with_code(code.code(), status, title, message.clone())
            }
            SolveError::NonFinite { .. } => Problem::new(ErrorCode::InternalError, err.to_string()),
            SolveError::Interrupted(Interrupt::TimedOut) => {
                Problem::new(ErrorCode::Timeout, "the job ran past its time limit and was stopped")
            }
            SolveError::Interrupted(i) => {
                Problem::new(ErrorCode::Interrupted, format!("the job was interrupted ({i:?})"))
            }
        }
    }
}
