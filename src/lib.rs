//! brume: a spectral renderer for light in participating media, built on bidirectional
//! Monte-Carlo ray tracing with reverse photon mapping (integration spheres, multiple stochastic
//! spheres with control parameter q, and integration cylinders; Ershov, Zhdanov, Voloboy 2019).
//!
//! Data flows in one direction: `scene` (file -> validated description -> runtime scene),
//! camera pass -> gather structure -> light pass (`integrator`), `film` accumulation, and the
//! colour pipeline (`spectrum` -> `colour`) at output time only.

pub mod camera;
pub mod colour;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod light;
pub mod material;
pub mod medium;
pub mod scene;
pub mod spectrum;
pub mod study;
pub mod world;

/// Running means, standard errors and quadrature for the Monte-Carlo unit tests; the same file
/// serves the integration tests in tests/.
#[cfg(test)]
#[path = "../tests/estimator_stats.rs"]
pub(crate) mod test_stats;
