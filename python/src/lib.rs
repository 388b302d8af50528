//! gbump's golden model as a Python module (`import gbump`), built by maturin from this crate.
//! Everything is the library's: the configuration handle of the C ABI (`capi::GbumpConfig`,
//! with its record layouts and power table), the vector sources, the ROM builders and the
//! interface JSON. Nothing here states a width or a layout; records are the vector files'
//! records as rows of 32-bit words, LSB first (the C ABI's and DPI-C's layout).

use pyo3::prelude::*;

mod arrays;
mod config;
mod fields;
mod vectors;

pyo3::create_exception!(
    gbump,
    GbumpError,
    pyo3::exceptions::PyValueError,
    "A gbump error: the library's message, naming the input, the place and the fix."
);

/// `f` with the GIL released, on the library's pool (`gbump::thread_pool`, made again in a
/// process `os.fork()` started, where the parent's pool has no threads).
pub(crate) fn detach<R: Send>(py: Python<'_>, f: impl FnOnce() -> R + Send) -> R {
    py.detach(|| gbump::thread_pool::install(f))
}

/// The library's error as a Python exception, with its message unchanged.
pub(crate) fn err(e: gbump::Error) -> PyErr {
    GbumpError::new_err(e.to_string())
}

/// A Python integer argument `name` as a u64 in `lo..=hi` (`limit` names the bound), or a
/// `GbumpError` naming the argument: a negative or huge value would otherwise surface as
/// pyo3's OverflowError, which names neither.
pub(crate) fn arg(name: &str, v: i128, lo: u64, hi: u64, limit: &str) -> PyResult<u64> {
    if v < 0 {
        return Err(fail(format!("{name}: {v} is negative\n  fix: use {lo}..={hi}")));
    }
    let v = u64::try_from(v).map_err(|_| fail(format!("{name}: {v} does not fit 64 bits\n  fix: use {lo}..={hi}")))?;
    gbump::limits::check_count(name, v, lo, hi, limit).map_err(err)?;
    Ok(v)
}

/// A Python integer argument, refusing a bool: `True` is 1 to Python, but no count, seed or
/// shininess of gbump is a flag, so a bool there is a mistake (pyo3 names the argument).
pub(crate) struct Int(pub i128);

impl<'a, 'py> FromPyObject<'a, 'py> for Int {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if obj.is_instance_of::<pyo3::types::PyBool>() {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "a bool, where an integer is wanted\n  fix: pass an int",
            ));
        }
        Ok(Int(obj.extract::<i128>()?))
    }
}

/// A message of this module's own as a `GbumpError`.
pub(crate) fn fail(msg: String) -> PyErr {
    GbumpError::new_err(msg)
}

#[pymodule]
#[pyo3(name = "gbump")]
fn gbump_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", gbump::TOOL.trim_start_matches("gbump "))?;
    m.add("TOOL", gbump::TOOL)?;
    // The sources the module was built from: `gbump --version` prints the same hash for the
    // same sources (python/tests/check_module.py compares them).
    m.add("__source__", gbump::SOURCE_HASH)?;
    m.add("GbumpError", m.py().get_type::<GbumpError>())?;
    m.add_class::<config::Config>()?;
    m.add_class::<vectors::Stimulus>()?;
    Ok(())
}
