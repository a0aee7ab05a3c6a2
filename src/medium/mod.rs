//! medium (see docs/architecture.md).
