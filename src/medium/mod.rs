//! Participating media: homogeneous spectral media, the Henyey–Greenstein phase function, the
//! spectral channel mixture used to sample distances, the camera-side multi-sphere walk
//! (docs: method note 2-4) and forward (light-side) free flights.
//!
//! Everything here is allocation-free and works on one segment at a time, so the render engine
//! can call it from its per-ray loops.

mod error;
mod forward;
mod homogeneous;
mod mixture;
mod phase;
mod spectral;
mod walk;

pub use error::MediumError;
pub use forward::{FlightEnd, ForwardFlight};
pub use homogeneous::HomogeneousMedium;
pub use mixture::{ChannelPick, DEFAULT_FLOOR, MIN_FLOOR, MixEval, Mixture, relative_extinction};
pub use phase::HenyeyGreenstein;
pub use spectral::power_law;
pub use walk::{MultiSphereWalk, WalkEnd, sample_extinction};
