//! camera (see docs/architecture.md).
