//! integrator (see docs/architecture.md).
