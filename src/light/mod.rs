//! light (see docs/architecture.md).
