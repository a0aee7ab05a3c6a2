//! geometry (see docs/architecture.md).
