//! The `brume._brume` extension module: a thin layer over the brume library for the `brume`
//! Python package (python/brume). Loading, building, rendering, merging and writing are the
//! library's own functions, the ones the command line calls; this crate only converts values
//! and errors between Rust and Python, and runs a render beside the interpreter so that
//! Ctrl-C and progress reach Python.

mod convert;
mod render;
mod result;
mod scene;

use std::path::PathBuf;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use brume::colour::Observer;
use brume::colour::describe::{self, SpectrumRequest};

create_exception!(
    _brume,
    BrumeError,
    PyException,
    "Base class of brume's errors."
);
create_exception!(
    _brume,
    SceneError,
    BrumeError,
    "A scene that cannot be used: the message names file:line:column and key, as the CLI's."
);
create_exception!(
    _brume,
    FilmError,
    BrumeError,
    "A film file that cannot be read, written or merged."
);
create_exception!(
    _brume,
    RenderError,
    BrumeError,
    "A render that cannot run or cannot go on (another render running, memory budget)."
);

/// The colour of a spectrum as `brume spectrum --json` prints it (JSON text).
#[pyfunction]
#[pyo3(signature = (spectrum, lines, illuminant=None, observer="1931", bins=32, lambda_min=380.0, lambda_max=780.0))]
fn spectrum_json(
    spectrum: String,
    lines: Vec<(f64, f64)>,
    illuminant: Option<String>,
    observer: &str,
    bins: usize,
    lambda_min: f64,
    lambda_max: f64,
) -> PyResult<String> {
    let observer = match observer {
        "1931" => Observer::Cie1931,
        "1964" => Observer::Cie1964,
        o => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "observer {o:?}: expected \"1931\" or \"1964\""
            )));
        }
    };
    let err = |e: brume::colour::ColourError| BrumeError::new_err(e.to_string());
    let wavelengths: Vec<f64> = lines.iter().map(|l| l.0).collect();
    let grid = describe::check_grid(bins, lambda_min, lambda_max, &wavelengths).map_err(err)?;
    let request = SpectrumRequest {
        spectrum,
        lines,
        column: None,
        illuminant,
        observer,
        grid,
        cat: brume::colour::Cat::Bradford,
    };
    Ok(describe::spectrum_colour(&request).map_err(err)?.to_json())
}

/// A film file (`.brume`) as a result.
#[pyfunction]
fn read_film(path: PathBuf) -> PyResult<result::RenderResult> {
    result::RenderResult::read(&path)
}

#[pymodule]
fn _brume(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("BrumeError", py.get_type::<BrumeError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("FilmError", py.get_type::<FilmError>())?;
    m.add("RenderError", py.get_type::<RenderError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<result::RenderResult>()?;
    m.add_function(wrap_pyfunction!(scene::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(result::merge, m)?)?;
    m.add_function(wrap_pyfunction!(read_film, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum_json, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
