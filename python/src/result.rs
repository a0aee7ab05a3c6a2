//! `brume.RenderResult`: a film (the exact sums of its passes) with the render's identity, its
//! image as numpy arrays, and the writers the command line uses.

use std::path::{Path, PathBuf};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::json;

use brume::colour::ColourSpace;
use brume::film::output::{self, OutputOptions};
use brume::film::{Film, FilmId, SpectralImage, checkpoint};
use brume::scene::identity::{is_film_path, output_options};

use crate::FilmError;
use crate::convert::json_to_py;

/// The result of a render, a merge or a film file.
#[pyclass(frozen, module = "brume")]
pub struct RenderResult {
    film: Film,
    id: FilmId,
    arrays: Py<PyDict>,
}

fn film_error(e: impl std::fmt::Display) -> PyErr {
    FilmError::new_err(e.to_string())
}

/// `data` (`shape`'s product of values) as a numpy array that owns it.
fn array<'py>(py: Python<'py>, data: Vec<f32>, shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
}

impl RenderResult {
    /// The result of `film`; `settings` says how its passes sampled (None: unknown, as for a
    /// film file).
    pub fn new(film: Film, id: FilmId, settings: Option<serde_json::Value>) -> PyResult<Self> {
        let opts = output_options(&id, &film).map_err(film_error)?;
        Python::attach(|py| {
            let img = py.detach(|| film.image());
            let arrays = arrays(py, img, &opts)?;
            let mut s = settings.unwrap_or_else(|| json!({}));
            s["seed"] = json!(id.seed);
            s["first_pass"] = json!(film.first);
            s["passes"] = json!(film.passes);
            s["dropped_samples"] = json!(film.dropped);
            // The choice the film keeps (a merge's and a film file's too), None without one.
            let auto = &film.auto_settings;
            s["auto"] = json!((!auto.is_empty()).then_some(auto));
            arrays.set_item("settings", json_to_py(py, &s.to_string())?)?;
            // Through a JSON value as the sensors' JSON file is written (f32 positions
            // widened to f64), so the readings compare equal to that file's.
            let sensors = serde_json::to_value(film.sensor_readings()).map_err(film_error)?;
            arrays.set_item("sensors", json_to_py(py, &sensors.to_string())?)?;
            Ok(Self {
                film,
                id,
                arrays: arrays.unbind(),
            })
        })
    }

    /// One of the arrays and values made once when the result was made.
    fn item<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        self.arrays
            .bind(py)
            .get_item(name)?
            .ok_or_else(|| PyValueError::new_err(format!("no {name}")))
    }

    pub fn read(path: &Path) -> PyResult<Self> {
        let f = Python::attach(|py| py.detach(|| checkpoint::read(path))).map_err(film_error)?;
        Self::new(f.film, f.id, None)
    }
}

/// The image's arrays: `spectral`, `rgb` (working space), `xyz`, `luminance` (cd/m²),
/// `stderr`, `layers`, `wavelengths`, `bin_edges`.
fn arrays<'py>(
    py: Python<'py>,
    img: SpectralImage,
    opts: &OutputOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let (h, w, n) = (img.height, img.width, img.grid.n);
    let d = PyDict::new(py);
    let flat = |v: Vec<[f32; 3]>| v.into_iter().flatten().collect::<Vec<f32>>();
    let rgb = output::to_rgb(&img, &img.data, opts.colour_space, opts).map_err(film_error)?;
    let xyz = output::to_rgb(&img, &img.data, ColourSpace::Xyz, opts).map_err(film_error)?;
    let per_y = brume::colour::photometry::luminance_scale(opts.observer).map_err(film_error)?;
    let lum: Vec<f32> = xyz.iter().map(|p| (p[1] as f64 * per_y) as f32).collect();
    d.set_item("rgb", array(py, flat(rgb), &[h, w, 3])?)?;
    d.set_item("xyz", array(py, flat(xyz), &[h, w, 3])?)?;
    d.set_item("luminance", array(py, lum, &[h, w])?)?;
    d.set_item("cd_per_unit_y", per_y)?;
    d.set_item(
        "colour_space",
        format!("{:?}", opts.colour_space).to_lowercase(),
    )?;
    let edges: Vec<f64> = (0..n)
        .map(|i| img.grid.edges(i).0)
        .chain([img.grid.edges(n - 1).1])
        .collect();
    d.set_item("wavelengths", PyArray1::from_vec(py, img.grid.centres()))?;
    d.set_item("bin_edges", PyArray1::from_vec(py, edges))?;
    let layers = PyDict::new(py);
    for (name, data) in img.layers {
        layers.set_item(name, array(py, data, &[h, w, n])?)?;
    }
    d.set_item("layers", layers)?;
    match img.noise {
        Some(noise) => d.set_item("stderr", array(py, noise, &[h, w, n])?)?,
        None => d.set_item("stderr", py.None())?,
    }
    d.set_item("spectral", array(py, img.data, &[h, w, n])?)?;
    Ok(d)
}

#[pymethods]
impl RenderResult {
    /// Writes `path` as `brume render -o PATH` (or `brume merge -o PATH`) writes it: `.exr`
    /// (scene-linear, the scene's [film] settings), `.png` (display sRGB) or `.brume` (the
    /// film file, for `merge` and `read_film`). Atomic: an existing file is replaced whole.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        if self.film.passes == 0 {
            return Err(PyValueError::new_err(
                "the film holds no passes: nothing to write",
            ));
        }
        if is_film_path(&path) {
            return py
                .detach(|| checkpoint::write(&path, &self.film, &self.id))
                .map_err(film_error);
        }
        output::format_of(&path).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let opts = output_options(&self.id, &self.film).map_err(film_error)?;
        py.detach(|| output::write(&path, &self.film.image(), &opts))
            .map_err(film_error)
    }

    /// RGB in the scene's working space (`film.colour_space`), shape (H, W, 3), float32: the EXR's RGB for radiometric films (cd/m² scale: multiply by `cd_per_unit_y`).
    #[getter]
    fn rgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "rgb")
    }

    /// CIE XYZ of each pixel (Y = 1 for a constant radiance of 1 W/(m² sr nm)), shape (H, W, 3).
    #[getter]
    fn xyz<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "xyz")
    }

    /// Luminance in cd/m², shape (H, W).
    #[getter]
    fn luminance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "luminance")
    }

    /// Bin-averaged spectral radiance, W/(m² sr nm), shape (H, W, N); bins in `wavelengths` and `bin_edges`.
    #[getter]
    fn spectral<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "spectral")
    }

    /// Centre of each bin (a line bin: its line), nm, shape (N,).
    #[getter]
    fn wavelengths<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "wavelengths")
    }

    /// The N + 1 bin edges, nm.
    #[getter]
    fn bin_edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "bin_edges")
    }

    /// Spectral component layers by name (`medium`, `surface`, one per light when `film.light_layers`), each (H, W, N).
    #[getter]
    fn layers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "layers")
    }

    /// Standard error of each pixel's mean per bin, (H, W, N); None below 2 passes.
    #[getter]
    fn stderr<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "stderr")
    }

    /// The `[[sensors]]` readings: dicts with name, type, value, std_error, ci95, unit, passes, spectrum (as the CLI's sensors CSV and JSON).
    #[getter]
    fn sensors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "sensors")
    }

    /// How the passes sampled: seed, first_pass, passes, the resolved q, forward_rays, camera_samples, radius, radius_indirect, and `auto` (what automatic settings chose, or None).
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "settings")
    }

    /// Luminance (cd/m²) per unit of `xyz`'s Y (683 lm/W over the observer's normalisation).
    #[getter]
    fn cd_per_unit_y<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "cd_per_unit_y")
    }

    /// The working space of `rgb`.
    #[getter]
    fn colour_space<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.item(py, "colour_space")
    }

    /// Passes in the film.
    #[getter]
    fn passes(&self) -> u64 {
        self.film.passes
    }

    /// The first pass of the seed's sequence the film holds (0 unless a part).
    #[getter]
    fn first_pass(&self) -> u64 {
        self.film.first
    }

    /// The seed of the render.
    #[getter]
    fn seed(&self) -> u64 {
        self.id.seed
    }

    fn __repr__(&self) -> String {
        format!(
            "<brume.RenderResult {} x {} pixels, {} bins, passes {}..{} of seed {}>",
            self.film.width,
            self.film.height,
            self.film.grid.n,
            self.film.first,
            self.film.end(),
            self.id.seed
        )
    }
}

/// A film to merge: a `RenderResult` or a film file's path, and its name in messages.
fn part(item: &Bound<'_, PyAny>, i: usize) -> PyResult<(String, Film, FilmId)> {
    if let Ok(r) = item.cast::<RenderResult>() {
        let r = r.get();
        return Ok((format!("films[{i}]"), r.film.clone(), r.id.clone()));
    }
    let path: PathBuf = item.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "films[{i}]: expected a RenderResult or a film file's path, got a {}",
            item.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let f = item
        .py()
        .detach(|| checkpoint::read(&path))
        .map_err(film_error)?;
    Ok((path.display().to_string(), f.film, f.id))
}

/// Merges films of one render (results or `.brume` paths, any order) into the film of all
/// their passes, bit-identical to one run: as `brume merge`.
#[pyfunction]
pub fn merge(films: &Bound<'_, PyList>) -> PyResult<RenderResult> {
    let mut parts = Vec::with_capacity(films.len());
    for (i, item) in films.iter().enumerate() {
        parts.push(part(&item, i)?);
    }
    if parts.is_empty() {
        return Err(PyValueError::new_err("merge: no films given"));
    }
    // Integer sums make the order irrelevant; sorting makes gaps and overlaps easy to name.
    parts.sort_by_key(|(_, f, _)| f.first);
    let mut parts = parts.into_iter();
    let Some((first_name, mut film, id)) = parts.next() else {
        return Err(PyValueError::new_err("merge: no films given"));
    };
    for (name, f, pid) in parts {
        // As `brume merge`: the merged film carries the first film's identity, so both films'
        // passes must be rendered alike under both descriptions.
        let passes = film.first.min(f.first)..(film.first + film.passes).max(f.first + f.passes);
        brume::scene::identity::same_render(&pid, &id, passes).map_err(|m| {
            film_error(format!(
                "{name} is not of the same render as {first_name}: {}",
                m.describe(&name, &first_name)
            ))
        })?;
        film.merge(&f)
            .map_err(|e| film_error(format!("{name}: cannot merge: {e}")))?;
    }
    RenderResult::new(film, id, None)
}
