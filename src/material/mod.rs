//! material (see docs/architecture.md).
