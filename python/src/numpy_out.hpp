// Output arrays of the bindings: a new numpy array, or the caller's `out=`
// array written in place (no allocation per call in a Python control loop).
// Vectors are 1-D float64; matrices are 2-D float64 in Fortran (column-major)
// order, Eigen's layout, so that the C++ code writes straight into them.
#pragma once

#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <Eigen/Core>

namespace wbi::python {

namespace py = pybind11;

using Array = py::array_t<double>;
using ColumnMajorArray = py::array_t<double, py::array::f_style>;

// `out` when it is a writable float64 vector of `size`, a new vector when it is None.
// Throws ValueError naming `what` otherwise.
inline Array vector_out(const py::object& out, Eigen::Index size, const char* what) {
  if (out.is_none()) {
    return Array(size);
  }
  if (!py::isinstance<Array>(out)) {
    throw py::value_error(std::string(what) + ": out must be a numpy float64 array");
  }
  auto array = py::reinterpret_borrow<Array>(out);
  if (array.ndim() != 1 || array.shape(0) != size || array.strides(0) != sizeof(double) ||
      !array.writeable()) {
    throw py::value_error(std::string(what) + ": out must be a writable contiguous vector of " +
                          std::to_string(size) + " float64");
  }
  return array;
}

// `out` when it is a writable Fortran-ordered float64 matrix rows × cols, a new one when None.
inline ColumnMajorArray matrix_out(const py::object& out, Eigen::Index rows, Eigen::Index cols,
                                   const char* what) {
  if (out.is_none()) {
    return ColumnMajorArray({rows, cols});
  }
  if (!py::isinstance<Array>(out)) {
    throw py::value_error(std::string(what) + ": out must be a numpy float64 array");
  }
  auto array = py::reinterpret_borrow<py::array>(out);
  const bool fortran = (array.flags() & py::array::f_style) != 0;
  if (array.ndim() != 2 || array.shape(0) != rows || array.shape(1) != cols || !fortran ||
      !array.writeable()) {
    throw py::value_error(std::string(what) + ": out must be a writable Fortran-ordered " +
                          std::to_string(rows) + "x" + std::to_string(cols) +
                          " float64 matrix (numpy.zeros(shape, order='F'))");
  }
  return py::reinterpret_borrow<ColumnMajorArray>(out);
}

inline Eigen::Map<Eigen::VectorXd> as_vector(Array& array) {
  return {array.mutable_data(), array.shape(0)};
}

inline Eigen::Map<Eigen::MatrixXd> as_matrix(ColumnMajorArray& array) {
  return {array.mutable_data(), array.shape(0), array.shape(1)};
}

}  // namespace wbi::python
