//! Scenes: the TOML file format (`desc`), loading with `--set` overrides and exact error
//! positions (`load`), validation (`validate`), and building the runtime scene (`build`).
//!
//! The camera and each kind of light, shape and material keep their keys, defaults, checks and
//! runtime construction together (`camera.rs`, `lights/`, `shapes/`, `materials/`); `tagged.rs`
//! reads tables whose `type` key picks the kind.

mod array;
mod build;
mod builder;
mod camera;
mod check;
pub mod density_report;
pub mod desc;
mod enclosed;
mod error;
mod gltf;
pub mod identity;
mod import_report;
pub mod info;
mod lights;
mod lines;
mod load;
mod loaded;
mod materials;
mod media;
mod path;
mod sensors;
mod shapes;
mod source;
mod spectra;
mod spectrum_desc;
pub mod summary;
mod tagged;
mod validate;

pub use crate::world::Scene;
pub use build::{LARGE_RADIUS, build, build_integrator, build_with_warnings, film_extras};
pub use camera::{MAX_PIXELS, MAX_SIDE};
pub use check::{MAX_TEXTURE_PIXELS, MAX_TEXTURE_SIDE};
pub use desc::ImportDesc;
pub use error::{Origin, SceneError, SceneWarning};
pub use import_report::GltfReport;
pub use lights::{MAX_IRRADIANCE, MAX_POWER};
pub use load::{load, load_str};
pub use loaded::LoadedScene;
pub use shapes::MAX_RADIANCE;
pub use source::Source;
