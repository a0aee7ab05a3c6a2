//! Scenes: the TOML file format (`desc`), loading with `--set` overrides and exact error
//! positions (`load`), validation (`validate`), and building the runtime scene (`build`).

mod build;
pub mod desc;
mod error;
mod load;
mod path;
mod spectra;
pub mod summary;
pub mod validate;

pub use crate::world::Scene;
pub use build::{build, build_integrator};
pub use error::{Origin, SceneError};
pub use load::{LoadedScene, load, load_str};
