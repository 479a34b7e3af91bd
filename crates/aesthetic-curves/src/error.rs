//! The library's one error type.
//!
//! Every fallible operation returns [`Error`]. Its [`Error::kind`] is the `snake_case` error
//! kind of the JSON protocol (`docs/protocol.md`), so the CLI and the editor
//! map library errors to protocol errors without a table of their own.

/// What went wrong, in terms a user can act on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter is missing, not finite, out of its range or of the wrong size.
    #[error("invalid input: {field}: {message}")]
    InvalidInput {
        /// The offending parameter, as named in the API or protocol.
        field: String,
        /// What is wrong with it and what is allowed.
        message: String,
    },
    /// The geometry is degenerate: coincident or collinear control points, zero-length
    /// tangents, cusps. Curvature (or the requested construction) is undefined.
    #[error("degenerate: {0}")]
    Degenerate(String),
    /// No curve of the requested family fits the input; the message gives the admissible range.
    #[error("no segment: {0}")]
    NoSegment(String),
    /// A solver gave up before reaching its tolerance; the message says which.
    #[error("no convergence: {0}")]
    NoConvergence(String),
    /// The work ran past the deadline its caller set ([`crate::deadline`]) and was stopped.
    #[error("timeout: {0}")]
    Timeout(String),
}

impl Error {
    /// The protocol's error kind: `invalid_input`, `degenerate`, `no_segment`,
    /// `no_convergence` or `timeout`.
    pub fn kind(&self) -> &'static str {
        match self {
            Error::InvalidInput { .. } => "invalid_input",
            Error::Degenerate(_) => "degenerate",
            Error::NoSegment(_) => "no_segment",
            Error::NoConvergence(_) => "no_convergence",
            Error::Timeout(_) => "timeout",
        }
    }

    /// The message without the kind in front (what the protocol sends beside its `kind`,
    /// so a client that shows both does not say "degenerate: degenerate: ...").
    pub fn message(&self) -> String {
        match self {
            Error::InvalidInput { field, message } => format!("{field}: {message}"),
            Error::Degenerate(m)
            | Error::NoSegment(m)
            | Error::NoConvergence(m)
            | Error::Timeout(m) => m.clone(),
        }
    }

    /// Shorthand for [`Error::InvalidInput`].
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::InvalidInput {
            field: field.into(),
            message: message.into(),
        }
    }

    /// `Ok` for a finite `value > 0`, else [`Error::InvalidInput`] naming `field` (a
    /// tolerance, an accuracy).
    pub fn check_positive(field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(Error::invalid(field, "must be a positive number"))
        }
    }
}

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
