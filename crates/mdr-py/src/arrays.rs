//! numpy in and out: any array-like (a float, a list, an array of any shape) is read as `float64`
//! values, and results go back in the same shape (a float for a scalar).

use crate::errors::invalid;
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Values of an array-like argument, with the shape to give the results.
pub struct Values {
    /// The values in C order.
    pub data: Vec<f64>,
    shape: Vec<usize>,
    scalar: bool,
}

impl Values {
    /// Read `obj` (named `argument` in errors) as float64 values.
    pub fn read(py: Python<'_>, argument: &str, obj: &Bound<'_, PyAny>) -> PyResult<Values> {
        let numpy = py.import("numpy")?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("dtype", "float64")?;
        let array = numpy
            .call_method("asarray", (obj,), Some(&kwargs))
            .map_err(|e| invalid(argument, format!("not an array of numbers ({e})")))?;
        // ascontiguousarray makes a 0-d array 1-d: remember whether a scalar came in.
        let scalar = array.getattr("ndim")?.extract::<usize>()? == 0;
        let array = numpy.call_method1("ascontiguousarray", (array,))?;
        let array = array
            .cast_into::<PyArrayDyn<f64>>()
            .map_err(|e| invalid(argument, e))?;
        let readonly = array.readonly();
        Ok(Values {
            data: readonly.as_array().iter().copied().collect(),
            shape: readonly.shape().to_vec(),
            scalar,
        })
    }

    /// Like [`Values::read`], then check every value is finite and > 0.
    pub fn read_positive(
        py: Python<'_>,
        argument: &str,
        obj: &Bound<'_, PyAny>,
    ) -> PyResult<Values> {
        let values = Self::read(py, argument, obj)?;
        if let Some(bad) = values.data.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            return Err(invalid(argument, format!("{bad} (must be finite and > 0)")));
        }
        Ok(values)
    }

    /// `results` (one per value) in the input's shape: a float for a scalar input.
    pub fn shaped(&self, py: Python<'_>, results: Vec<f64>) -> PyResult<Py<PyAny>> {
        if self.scalar {
            return Ok(results[0].into_pyobject(py)?.into_any().unbind());
        }
        let flat = PyArray1::from_vec(py, results);
        Ok(flat.reshape(self.shape.clone())?.into_any().unbind())
    }
}

/// A 1-D float64 array.
pub fn array1(py: Python<'_>, values: Vec<f64>) -> Py<PyAny> {
    PyArray1::from_vec(py, values).into_any().unbind()
}
