//! The per-field form of records: a dict from column name to an `int64` array of shape
//! `(N, lanes)`, values as numbers (signed columns sign-extended), lane order the vector
//! files' (lane 0 in the low bits). Packing checks every value against its column's format, so
//! a value out of range is an error naming the column, record and lane, never masked.

use gbump::capi::{GbumpConfig, Target};
use gbump::vectors::layout::{Column, Record};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The range of a lane value of `c`: two's complement for signed formats, else unsigned.
fn lane_range(c: &Column) -> (i64, i64) {
    let lw = c.width / c.lanes;
    if c.signed() {
        (-(1i64 << (lw - 1)), (1i64 << (lw - 1)) - 1)
    } else {
        (0, ((1u64 << lw) - 1) as i64)
    }
}

/// `v` as an `int64` array of `(n, lanes)` values (a 1-D array of n values for a one-lane
/// column): integers only, so a float is never truncated into a code.
fn column_values(v: &Bound<'_, PyAny>, c: &Column) -> PyResult<(usize, Vec<i64>)> {
    let np = v.py().import("numpy")?;
    let a = np.call_method1("asarray", (v,))?;
    let kind: String = a.getattr("dtype")?.getattr("kind")?.extract()?;
    if !"iub".contains(kind.as_str()) || kind.is_empty() {
        return Err(crate::fail(format!(
            "column `{}`: dtype kind `{kind}`, not integers\n  fix: pass integer codes (format {})",
            c.name, c.format
        )));
    }
    // An unsigned value past int64 would wrap to a negative code in the cast below: refused
    // as what it is instead.
    if kind == "u" && a.getattr("size")?.extract::<usize>()? > 0 {
        let max: u64 = np.call_method1("max", (&a,))?.extract()?;
        if max > i64::MAX as u64 {
            return Err(crate::fail(format!(
                "column `{}`: {max} is outside format {} (and past int64)\n  fix: give codes of the column's format",
                c.name, c.format
            )));
        }
    }
    let a = a.call_method1("astype", ("int64",))?;
    let arr: PyReadonlyArrayDyn<'_, i64> = a.extract()?;
    let shape = arr.shape().to_vec();
    let n = match shape.as_slice() {
        [n] if c.lanes == 1 => *n,
        [n, l] if *l == c.lanes as usize => *n,
        _ => {
            return Err(crate::fail(format!(
                "column `{}`: shape {shape:?}, but it has {} lane(s)\n  fix: pass shape (N, {}){}",
                c.name,
                c.lanes,
                c.lanes,
                if c.lanes == 1 { " or (N,)" } else { "" }
            )))
        }
    };
    let mut vals = crate::arrays::with_room(n * c.lanes as usize, &format!("column `{}`", c.name))?;
    vals.extend(arr.as_array().iter().copied());
    Ok((n, vals))
}

/// Pack `fields` into `t`'s records: every stimulus column must be given, expected columns
/// may be (zero otherwise), and no other name is accepted.
pub fn pack(h: &GbumpConfig, t: &Target, fields: &Bound<'_, PyDict>) -> PyResult<(usize, Vec<u32>)> {
    let cols = &t.layout.columns;
    for k in fields.keys() {
        let k: String = k.extract()?;
        if !cols.iter().any(|c| c.name == k) {
            let names: Vec<&str> = cols.iter().map(|c| c.name.as_str()).collect();
            return Err(crate::fail(format!(
                "field `{k}`: not a column of `{}` records\n  fix: use the columns {}",
                t.name,
                names.join(", ")
            )));
        }
    }
    let mut given = Vec::new();
    let mut count: Option<usize> = None;
    for c in cols {
        let Some(v) = fields.get_item(&c.name)? else {
            if c.role == gbump::vectors::layout::Role::Stimulus {
                return Err(crate::fail(format!(
                    "field `{}` of `{}` records: missing\n  fix: give every stimulus column ({} lane(s), format {})",
                    c.name, t.name, c.lanes, c.format
                )));
            }
            continue;
        };
        // Planned once the count is known, before the first column is copied.
        if count.is_none() {
            let n = v
                .py()
                .import("numpy")?
                .call_method1("shape", (&v,))?
                .get_item(0)
                .and_then(|n| n.extract::<u64>())
                .unwrap_or(0);
            crate::arrays::plan(h, t, "pack", n, crate::arrays::fields_bytes(t) + crate::arrays::words_bytes(t))?;
        }
        let (n, vals) = column_values(&v, c)?;
        match count {
            Some(m) if m != n => {
                return Err(crate::fail(format!(
                    "field `{}`: {n} records, but the fields before it have {m}\n  fix: give every column the same number of records",
                    c.name
                )))
            }
            _ => count = Some(n),
        }
        given.push((c, vals));
    }
    let n = count.unwrap_or(0);
    crate::arrays::check_batch("pack: records", n as u64)?;
    let w = t.layout.words32();
    let mut out = crate::arrays::zeros(n * w, "pack")?;
    for (i, rec) in out.chunks_mut(w).enumerate() {
        let mut r = Record::new(&t.layout);
        for (c, vals) in &given {
            let (lo, hi) = lane_range(c);
            for lane in 0..c.lanes {
                let v = vals[i * c.lanes as usize + lane as usize];
                if v < lo || v > hi {
                    return Err(crate::fail(format!(
                        "field `{}`, record {i}, lane {lane}: {v} is outside format {} ({lo}..={hi})\n  fix: give codes of the column's format",
                        c.name, c.format
                    )));
                }
                r.set_lane(c, lane, v);
            }
        }
        rec.copy_from_slice(&r.to_words32(w));
    }
    Ok((n, out))
}

/// Every column of `count` records of `t` as `int64` arrays `(N, lanes)`: each column's
/// array reserved whole first (`arrays::with_room`: a `GbumpError`, not an abort), then
/// filled a record at a time.
pub fn unpack<'py>(py: Python<'py>, t: &Target, words: &[u32], count: usize) -> PyResult<Bound<'py, PyDict>> {
    let w = t.layout.words32();
    let mut cols: Vec<Vec<i64>> = Vec::with_capacity(t.layout.columns.len());
    for c in &t.layout.columns {
        cols.push(crate::arrays::with_room(
            count * c.lanes as usize,
            &format!("unpack: column `{}`", c.name),
        )?);
    }
    for chunk in words.chunks(w) {
        let r = Record::from_words32(chunk);
        for (c, v) in t.layout.columns.iter().zip(&mut cols) {
            v.extend((0..c.lanes).map(|l| r.lane_value(c, l)));
        }
    }
    let d = PyDict::new(py);
    for (c, vals) in t.layout.columns.iter().zip(cols) {
        let a = Array2::from_shape_vec((count, c.lanes as usize), vals).map_err(|e| crate::fail(format!("column `{}`: {e}", c.name)))?;
        d.set_item(&c.name, a.into_pyarray(py))?;
    }
    Ok(d)
}
