//! film (see docs/architecture.md).
