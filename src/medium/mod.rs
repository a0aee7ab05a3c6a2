//! Participating media: spectral media (coefficients at density 1 times a density field,
//! `density`), phase functions (a closed set, `phase`), fog from droplet sizes by Lorenz–Mie
//! theory (`droplets`), the spectral channel mixture used to sample distances, the camera-side
//! multi-sphere walk (docs: method note 2-4) and forward (light-side) free flights. Walks and
//! flights run in optical depth at density 1 (`density::Along`, docs/media.md).
//!
//! Everything here is allocation-free and works on one segment at a time, so the render engine
//! can call it from its per-ray loops.

mod build;
mod coefficients;
pub mod density;
pub mod droplets;
mod error;
mod forward;
mod mixture;
mod phase;
mod spectral;
pub mod tracking;
mod walk;

pub use build::{
    BuiltMedium, CoefficientKeys, KeyedError, MediumParts, Visibility, build as build_medium,
    check as check_medium,
};
pub use coefficients::Medium;
pub use density::{Along, Density, DensityDesc};
pub use error::MediumError;
pub use forward::{FlightEnd, ForwardFlight};
pub use mixture::{
    ChannelPick, DEFAULT_FLOOR, MIN_FLOOR, MixEval, Mixture, channel_probabilities,
    relative_extinction, sample_scatter,
};
pub use phase::{
    Draine, HenyeyGreenstein, HgDraine, Phase, PhaseCsv, PhaseDesc, PhaseSample, PhaseTable,
    Rayleigh, TwoTermHg, hg_draine_fit, intern as phase_intern,
};
pub use spectral::power_law;
pub use tracking::{Majorant, Tracker, Tracking, TrackingError};
pub use walk::{MultiSphereWalk, WalkEnd, sample_extinction};
