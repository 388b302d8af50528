//! Records between NumPy and the library. A record array is `uint32`, shape `(N, words)`, or
//! `(words,)` for one record; each row is one record of the vector files, 32-bit words LSB
//! first. Other dtypes are refused rather than cast, since a cast can drop bits silently.

use gbump::capi::{GbumpConfig, Target};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// Records read from Python: the words back to back, how many records, and whether the caller
/// gave one record as a 1-D array (so the answer is 1-D too).
pub struct Records {
    pub words: Vec<u32>,
    pub count: usize,
    pub single: bool,
}

/// The records of `a`, each `words` words of a `target` record.
/// `per_record` is what the caller will hold per record while it runs, its copy of the input
/// among it ([`plan`]).
pub fn records_in(a: &Bound<'_, PyAny>, h: &GbumpConfig, t: &Target, per_record: u64) -> PyResult<Records> {
    let (words, target) = (t.layout.words32(), t.name);
    let arr: PyReadonlyArrayDyn<'_, u32> = a.extract().map_err(|_| {
        // What was given, as numpy names it (a list, a float or int64 array, a uint32 array
        // in the other byte order all land here): a GbumpError like every other bad input.
        let kind = a.get_type().name().map_or("value".into(), |n| n.to_string());
        // A numpy scalar has a dtype too, but is no array (an ndarray subclass is one).
        let scalar = a
            .py()
            .import("numpy")
            .and_then(|np| np.getattr("generic"))
            .and_then(|g| a.is_instance(&g))
            .unwrap_or(false);
        let given = match a.getattr("dtype").and_then(|d| d.str()) {
            Ok(d) if scalar => format!("a numpy scalar ({kind}, dtype {d})"),
            Ok(d) => format!("dtype {d}"),
            Err(_) => format!("a {kind}"),
        };
        crate::fail(format!(
            "records: {given}, not a numpy uint32 array in this machine's byte order\n  fix: pass numpy.asarray(records, dtype=numpy.uint32), shape (N, {words}) for `{target}` records"
        ))
    })?;
    let shape = arr.shape().to_vec();
    let (count, single) = match shape.as_slice() {
        [w] if *w == words => (1, true),
        [n, w] if *w == words => (*n, false),
        _ => {
            return Err(crate::fail(format!(
                "records: shape {shape:?}, but a `{target}` record of this configuration is {words} words\n  fix: pass shape (N, {words}) or ({words},) (Config.record_words(\"{target}\"))"
            )))
        }
    };
    check_batch("records", count as u64)?;
    plan(h, t, "records", count as u64, per_record)?;
    let mut words = with_room(count * words, "records")?;
    words.extend(arr.as_array().iter().copied());
    Ok(Records { words, count, single })
}

/// Records as a NumPy array: 1-D for a single record the caller gave as 1-D, else `(N, words)`.
pub fn records_out(py: Python<'_>, words: Vec<u32>, per: usize, single: bool) -> PyResult<Bound<'_, PyAny>> {
    if single {
        return Ok(Array1::from_vec(words).into_pyarray(py).into_any());
    }
    let n = words.len() / per;
    let a = Array2::from_shape_vec((n, per), words).map_err(|e| crate::fail(format!("records: {e}")))?;
    Ok(a.into_pyarray(py).into_any())
}

/// Refuse to build more than `MAX_BATCH_RECORDS` records in one array.
pub fn check_batch(what: &str, n: u64) -> PyResult<()> {
    check_records(what, n, 0)
}

/// Refuse a count of records outside `lo..=MAX_BATCH_RECORDS`.
pub fn check_records(what: &str, n: u64, lo: u64) -> PyResult<()> {
    use gbump::limits::{check_count, MAX_BATCH_RECORDS};
    check_count(what, n, lo, MAX_BATCH_RECORDS, "MAX_BATCH_RECORDS").map_err(crate::err)
}

/// Refuse `count` records of `t` holding `per_record` bytes each that would not fit in memory
/// (`GbumpConfig::plan_batch`): an allocation that fails aborts the Python process, where
/// this raises a `GbumpError`.
pub fn plan(h: &GbumpConfig, t: &Target, what: &str, count: u64, per_record: u64) -> PyResult<()> {
    h.plan_batch(t, count, per_record, what).map_err(crate::err)
}

/// Bytes of one record of `t` as 32-bit words (a copy in or out of the library).
pub fn words_bytes(t: &Target) -> u64 {
    4 * t.layout.words32() as u64
}

/// Bytes of one record of `t` in the per-field form: every lane an int64.
pub fn fields_bytes(t: &Target) -> u64 {
    8 * t.layout.columns.iter().map(|c| c.lanes as u64).sum::<u64>()
}

/// An empty vector with room for `n` values, or a `GbumpError` where the room cannot be had
/// (an infallible allocation that fails aborts the Python process).
pub fn with_room<T>(n: usize, what: &str) -> PyResult<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| {
        crate::fail(format!(
            "{what}: no memory for {n} values\n  fix: pass fewer records per call (split the batch), or free memory"
        ))
    })?;
    Ok(v)
}

/// `n` zeros, as [`with_room`].
pub fn zeros(n: usize, what: &str) -> PyResult<Vec<u32>> {
    let mut v = with_room(n, what)?;
    v.resize(n, 0);
    Ok(v)
}
