#pragma once
// numpy arrays at the module's boundary.
//
// In: vertex positions V (#V×3, any real dtype, any memory layout) and triangles F (#F×3,
// any integer dtype), checked for shape and type (InputError naming the argument: Python sees
// a ValueError) and converted to the library's Eigen types (one copy; F narrows to 32-bit
// indices, checked).
//
// Out without a copy: a result matrix is moved to the heap and owned by a capsule, and every
// array handed to Python is a view of it with the capsule as its base, so the matrix lives
// as long as any of the arrays. Eigen matrices are column-major: one column is a contiguous
// 1-D array, several columns an (n, k) array in Fortran order (strides 8 and 8n bytes).

#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace bemshape::python {

namespace py = pybind11;

/// V: an array-like of shape (n, 3) of real numbers [model units].
Eigen::MatrixX3d positions_from_array(const py::handle& object, const char* name);

/// F: an array-like of shape (m, 3) of integers in [0, 2³¹) (0-based vertex indices; the
/// range against #V is checked by the library).
Eigen::MatrixX3i indices_from_array(const py::handle& object, const char* name);

/// `value` moved to the heap and a capsule that deletes it: the base of views into it.
template <class T>
std::pair<const T*, py::capsule> owned(T value) {
  auto* held = new T(std::move(value));
  return {held, py::capsule(held, [](void* p) { delete static_cast<T*>(p); })};
}

/// Columns first … first+count−1 of `matrix` (owned by `owner`) as an (n, count) float64
/// view. A template over the plain Eigen types (MatrixXd, MatrixX3d, VectorXd) so that no
/// conversion can slip a temporary copy in between the owner and the view.
template <class Matrix>
inline constexpr bool kViewable = std::is_base_of_v<Eigen::PlainObjectBase<Matrix>, Matrix> &&
                                  std::is_same_v<typename Matrix::Scalar, double> &&
                                  !Matrix::IsRowMajor;

template <class Matrix>
py::array columns_view(const Matrix& matrix, Eigen::Index first, Eigen::Index count,
                       const py::capsule& owner) {
  static_assert(kViewable<Matrix>, "a view needs a plain column-major double matrix");
  const auto rows = py::ssize_t(matrix.rows());
  const auto item = py::ssize_t(sizeof(double));
  return py::array(py::dtype::of<double>(), {rows, py::ssize_t(count)}, {item, item * rows},
                   matrix.data() + first * matrix.rows(), owner);
}

/// Column `column` of `matrix` (owned by `owner`) as a 1-D float64 view.
template <class Matrix>
py::array column_view(const Matrix& matrix, Eigen::Index column, const py::capsule& owner) {
  static_assert(kViewable<Matrix>, "a view needs a plain column-major double matrix");
  return py::array(py::dtype::of<double>(), {py::ssize_t(matrix.rows())},
                   {py::ssize_t(sizeof(double))}, matrix.data() + column * matrix.rows(), owner);
}

/// A 1-D bool view of 0/1 flags (owned by `owner`).
py::array flags_view(const std::vector<char>& flags, const py::capsule& owner);

/// F as an (m, 3) int64 array (a copy: the library's indices are 32-bit).
py::array_t<std::int64_t> indices_array(const Eigen::MatrixX3i& faces);

/// 32-bit indices as a 1-D int64 array (a copy).
py::array_t<std::int64_t> index_list(const std::vector<int>& indices);

}  // namespace bemshape::python
