//! `brume study`: renders variants of a scene (a cartesian product of `--set` overrides) for
//! equal time (wall clock or process CPU time), several independent runs each, and measures
//! their error against a reference image after every pass: brume's own (spectral, with the
//! medium / surface split) or any renderer's EXR (RGB, optionally scale-fitted). The measured
//! answer to "which integration volume and which q give the least noise for the time" (paper
//! section 2.3; method note section 7).

mod best;
mod clock;
mod csv;
mod measure;
mod metrics;
mod plot;
mod reference;
mod run;
mod summary;
mod ticks;
mod variants;

pub use best::{Best, Estimate, Measure};
pub use clock::{Budget, Clock, Elapsed, PassEnd, process_cpu_seconds};
pub use csv::{CSV_HEADER, write_csv};
pub use measure::Checkpoint;
pub use metrics::{
    LayerErrors, ScaleFit, efficiency, fit_scale, layer_errors, mean_error, mean_noise, mse,
    rel_mse, rmse,
};
pub use plot::write_plots;
pub use reference::{Layers, REFERENCE_MAGIC, Reference, ReferenceOptions, Values, space_name};
pub use run::{
    Event, InvalidVariants, Row, StudyConfig, check_variants, render_for, render_reference,
    run_study,
};
pub use summary::{Summary, VariantSummary, summarise, summarise_variants};
pub use ticks::{Ticks, format_sig, labels, linear_ticks, log_ticks};
pub use variants::{Variant, Vary, expand, parse_vary};

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    #[error("--vary {0:?}: expected KEY=V1,V2,... with at least one value")]
    Vary(String),
    #[error("{0}")]
    Budget(String),
    #[error("{0}")]
    Scene(#[from] crate::scene::SceneError),
    #[error("{path}: {message}")]
    Io { path: PathBuf, message: String },
    #[error("{path}: {message}")]
    Reference { path: PathBuf, message: String },
    #[error("reference is {got}, the study renders {want} (same size and values needed)")]
    Mismatch { got: String, want: String },
    #[error("plot {path}: {message}")]
    Plot { path: PathBuf, message: String },
    #[error("no valid variant to study: {0}")]
    NoVariant(String),
}

pub(crate) fn io_err(path: &std::path::Path, e: impl std::fmt::Display) -> StudyError {
    StudyError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}
