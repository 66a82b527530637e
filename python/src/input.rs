//! numpy arrays (and lists of index lists) in: checked for type, shape, contiguity and
//! finiteness, with errors that name the argument, and the face or vertex.

use glam::DVec3;
use numpy::{
    PyArrayDescrMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PySequence, PyTuple};

/// The numpy array behind `obj`, or a `TypeError` naming `what`.
fn array<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Bound<'py, PyUntypedArray>> {
    obj.cast::<PyUntypedArray>().cloned().map_err(|_| {
        PyTypeError::new_err(format!(
            "{what} must be a numpy array, not {}",
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })
}

/// The array's dtype name, for messages.
fn dtype_name(a: &Bound<'_, PyUntypedArray>) -> String {
    a.dtype().to_string()
}

/// Checks a C-contiguous array of `ndim` dimensions whose last has length `columns` (any,
/// when `None`).
fn check_shape(
    a: &Bound<'_, PyUntypedArray>,
    what: &str,
    ndim: usize,
    columns: Option<usize>,
) -> PyResult<()> {
    let shape = a.shape();
    let expected = match (ndim, columns) {
        (1, _) => "(n,)".to_owned(),
        (_, Some(c)) => format!("(n, {c})"),
        _ => "(n, k)".to_owned(),
    };
    if shape.len() != ndim || columns.is_some_and(|c| shape[ndim - 1] != c) {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape {expected}, got {shape:?}"
        )));
    }
    if !a.is_c_contiguous() {
        return Err(PyValueError::new_err(format!(
            "{what} must be C-contiguous (numpy.ascontiguousarray makes a copy that is)"
        )));
    }
    Ok(())
}

/// A float array of shape `(n, columns)`, float64 (read in place) or float32 (widened).
pub fn floats2(obj: &Bound<'_, PyAny>, what: &str, columns: usize) -> PyResult<Vec<f64>> {
    let a = array(obj, what)?;
    check_shape(&a, what, 2, Some(columns))?;
    let values: Vec<f64> = if let Ok(r) = obj.extract::<PyReadonlyArray2<'_, f64>>() {
        r.as_slice()?.to_vec()
    } else if let Ok(r) = obj.extract::<PyReadonlyArray2<'_, f32>>() {
        r.as_slice()?.iter().map(|&v| f64::from(v)).collect()
    } else {
        return Err(PyTypeError::new_err(format!(
            "{what} must be float64 or float32, not {}",
            dtype_name(&a)
        )));
    };
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{what}[{}, {}] is {} (every coordinate must be finite)",
            k / columns,
            k % columns,
            values[k]
        )));
    }
    Ok(values)
}

/// Vertices: an `(n, 3)` float array.
pub fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<DVec3>> {
    Ok(floats2(obj, what, 3)?
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect())
}

/// A 1-D array of integers as `i64` (any integer dtype).
pub fn ints1(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<i64>> {
    let a = array(obj, what)?;
    check_shape(&a, what, 1, None)?;
    integers(obj, &a, what)
}

fn integers(
    obj: &Bound<'_, PyAny>,
    a: &Bound<'_, PyUntypedArray>,
    what: &str,
) -> PyResult<Vec<i64>> {
    macro_rules! try_dtype {
        ($($t:ty),*) => {$(
            if let Ok(r) = obj.extract::<numpy::PyReadonlyArrayDyn<'_, $t>>() {
                return r
                    .as_slice()?
                    .iter()
                    .map(|&v| i64::try_from(v).map_err(|_| PyValueError::new_err(format!("{what} holds {v}, too large for an index"))))
                    .collect();
            }
        )*};
    }
    try_dtype!(i64, i32, u32, u64, i16, u16, i8, u8);
    Err(PyTypeError::new_err(format!(
        "{what} must hold integers, not {}",
        dtype_name(a)
    )))
}

/// Faces: an `(m, k)` integer array (every face `k` corners) or a sequence of index
/// sequences (any number of corners each); each index in `0..vertex_count`, at least 3
/// corners a face.
pub fn faces(obj: &Bound<'_, PyAny>, vertex_count: usize) -> PyResult<Vec<Vec<u32>>> {
    let rows: Vec<Vec<i64>> = if let Ok(a) = obj.cast::<PyUntypedArray>() {
        if a.ndim() == 1 && a.dtype().kind() == b'O' {
            return faces(
                &PyList::new(obj.py(), obj.try_iter()?.collect::<PyResult<Vec<_>>>()?)?.into_any(),
                vertex_count,
            );
        }
        check_shape(a, "faces", 2, None)?;
        let k = a.shape()[1];
        let flat = integers(obj, a, "faces")?;
        flat.chunks(k.max(1)).map(<[i64]>::to_vec).collect()
    } else if obj.cast::<PySequence>().is_ok() && !obj.is_instance_of::<pyo3::types::PyString>() {
        let mut rows = Vec::new();
        for (n, face) in obj.try_iter()?.enumerate() {
            let face = face?;
            let row: Vec<i64> = if face.cast::<PyUntypedArray>().is_ok() {
                ints1(&face, &format!("faces[{n}]"))?
            } else if face.cast::<PyList>().is_ok() || face.cast::<PyTuple>().is_ok() {
                face.extract()
                    .map_err(|_| PyTypeError::new_err(format!("faces[{n}] must hold integers")))?
            } else {
                return Err(PyTypeError::new_err(format!(
                    "faces[{n}] must be a sequence of vertex indices"
                )));
            };
            rows.push(row);
        }
        rows
    } else {
        return Err(PyTypeError::new_err(
            "faces must be an (m, k) integer numpy array or a list of index lists",
        ));
    };
    rows.into_iter()
        .enumerate()
        .map(|(n, row)| {
            if row.len() < 3 {
                return Err(PyValueError::new_err(format!(
                    "face {n} has {} corners (at least 3 needed)",
                    row.len()
                )));
            }
            row.iter()
                .map(|&i| {
                    if i < 0 || i as u64 >= vertex_count as u64 {
                        Err(PyValueError::new_err(format!(
                            "face {n} names vertex {i}, outside 0..{vertex_count}"
                        )))
                    } else {
                        Ok(i as u32)
                    }
                })
                .collect()
        })
        .collect()
}

/// Per-face colours: `(m, 3)` or `(m, 4)`, uint8 (0–255) or float (0–1).
pub fn colours(obj: &Bound<'_, PyAny>, face_count: usize) -> PyResult<Vec<[u8; 4]>> {
    let a = array(obj, "colours")?;
    let columns = a.shape().get(1).copied().unwrap_or(0);
    if a.ndim() != 2 || !(columns == 3 || columns == 4) || a.shape()[0] != face_count {
        return Err(PyValueError::new_err(format!(
            "colours must have shape ({face_count}, 3) or ({face_count}, 4), got {:?}",
            a.shape()
        )));
    }
    let values: Vec<f64> = if let Ok(r) = obj.extract::<PyReadonlyArray2<'_, u8>>() {
        check_shape(&a, "colours", 2, Some(columns))?;
        r.as_slice()?
            .iter()
            .map(|&v| f64::from(v) / 255.0)
            .collect()
    } else {
        floats2(obj, "colours", columns)?
    };
    values
        .chunks_exact(columns)
        .enumerate()
        .map(|(n, c)| {
            if c.iter().any(|v| !(0.0..=1.0).contains(v)) {
                return Err(PyValueError::new_err(format!(
                    "colours[{n}] = {c:?} is outside 0..1"
                )));
            }
            let byte = |v: f64| (v * 255.0).round() as u8;
            Ok([
                byte(c[0]),
                byte(c[1]),
                byte(c[2]),
                if columns == 4 { byte(c[3]) } else { 255 },
            ])
        })
        .collect()
}

/// A boolean (or 0/1 integer) array of length `n`.
pub fn flags(obj: &Bound<'_, PyAny>, what: &str, n: usize) -> PyResult<Vec<bool>> {
    let a = array(obj, what)?;
    check_shape(&a, what, 1, None)?;
    if a.shape()[0] != n {
        return Err(PyValueError::new_err(format!(
            "{what} must have length {n}, got {}",
            a.shape()[0]
        )));
    }
    if let Ok(r) = obj.extract::<PyReadonlyArray1<'_, bool>>() {
        return Ok(r.as_slice()?.to_vec());
    }
    Ok(integers(obj, &a, what)?
        .into_iter()
        .map(|v| v != 0)
        .collect())
}
