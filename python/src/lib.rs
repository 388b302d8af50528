use pyo3::prelude::*;

#[pyfunction]
fn config_hash() -> String {
    gbump::PipelineConfig::default().hash()
}

#[pymodule]
#[pyo3(name = "gbump")]
fn gbump_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(config_hash, m)?)?;
    Ok(())
}
