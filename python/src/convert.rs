//! Values between Python and the library: `set={...}` values as TOML, JSON as Python objects.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// `KEY=VALUE` as `--set` takes it, from a Python key and value. `None` switches a medium off
/// (`--set media.fog=none`).
pub fn assignment(key: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let key: String = key.extract().map_err(|_| {
        PyTypeError::new_err("set: keys are dotted paths (str), e.g. \"media.fog.g\"")
    })?;
    if value.is_none() {
        return Ok(format!("{key}=none"));
    }
    let v = toml_value(&key, value)?;
    Ok(format!("{key}={v}"))
}

/// A Python value as TOML: bool, int, float, str, list/tuple and dict (inline table).
fn toml_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    // bool before int: Python's bool is an int.
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        let i: i64 = v.extract().map_err(|_| {
            PyTypeError::new_err(format!("set {key}: integer out of range (64-bit signed)"))
        })?;
        return Ok(toml::Value::Integer(i));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for item in v.try_iter()? {
            out.push(toml_value(key, &item?)?);
        }
        return Ok(toml::Value::Array(out));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, item) in d.iter() {
            let k: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("set {key}: table keys must be str")))?;
            let sub = format!("{key}.{k}");
            t.insert(k, toml_value(&sub, &item)?);
        }
        return Ok(toml::Value::Table(t));
    }
    // Numbers from numpy and the like: anything float() accepts.
    if let Ok(f) = v.call_method0("__float__").and_then(|f| f.extract::<f64>()) {
        return Ok(toml::Value::Float(f));
    }
    Err(PyTypeError::new_err(format!(
        "set {key}: a {} is not a scene value (bool, int, float, str, list or dict)",
        v.get_type().name()?
    )))
}

/// JSON text as Python objects (through the standard library's json module).
pub fn json_to_py<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}
