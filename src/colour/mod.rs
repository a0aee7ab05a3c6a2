//! colour (see docs/architecture.md).
