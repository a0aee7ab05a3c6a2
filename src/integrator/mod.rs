//! integrator (see docs/architecture.md).
pub mod volume;
