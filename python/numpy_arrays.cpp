#include "python/numpy_arrays.hpp"

#include <cstddef>
#include <limits>
#include <string>

#include "core/errors.hpp"

namespace bemshape::python {
namespace {

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d)
    text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

/// `object` as a 2-D numpy array with 3 columns whose dtype kind is one of `kinds`.
py::array checked_array(const py::handle& object, const char* name, const char* kinds,
                        const char* what) {
  py::array array = py::array::ensure(object);
  if (!array)
    throw InputError(std::string(name) + " must be a numpy array (or array-like) of shape (n, 3) of " +
                     what + ", got a " + std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  const char kind = array.dtype().kind();
  if (std::string(kinds).find(kind) == std::string::npos)
    throw InputError(std::string(name) + " must hold " + what + ", got dtype " +
                     std::string(py::str(array.dtype())));
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw InputError(std::string(name) + " must have shape (n, 3), got shape " + shape_text(array));
  return array;
}

}  // namespace

Eigen::MatrixX3d positions_from_array(const py::handle& object, const char* name) {
  const py::array array = checked_array(object, name, "fiu", "real numbers (positions)");
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(values.data(), values.shape(0), 3);
}

Eigen::MatrixX3i indices_from_array(const py::handle& object, const char* name) {
  const py::array array =
      checked_array(object, name, "iu", "integers (0-based vertex indices)");
  const auto values =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  using RowMajor = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor>;
  const Eigen::Map<const RowMajor> indices(values.data(), values.shape(0), 3);
  if (indices.size() > 0 && (indices.minCoeff() < 0 ||
                             indices.maxCoeff() > std::numeric_limits<int>::max()))
    throw InputError(std::string(name) + ": vertex indices must lie in [0, 2^31), got " +
                     std::to_string(indices.minCoeff() < 0 ? indices.minCoeff()
                                                           : indices.maxCoeff()));
  return indices.cast<int>();
}

py::array flags_view(const std::vector<char>& flags, const py::capsule& owner) {
  static_assert(sizeof(char) == sizeof(bool), "numpy's bool is one byte holding 0 or 1");
  return py::array(py::dtype::of<bool>(), {py::ssize_t(flags.size())}, {py::ssize_t(1)},
                   flags.data(), owner);
}

py::array_t<std::int64_t> indices_array(const Eigen::MatrixX3i& faces) {
  py::array_t<std::int64_t> array({py::ssize_t(faces.rows()), py::ssize_t(3)});
  auto out = array.mutable_unchecked<2>();
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      out(f, k) = faces(f, k);
  return array;
}

py::array_t<std::int64_t> index_list(const std::vector<int>& indices) {
  py::array_t<std::int64_t> array(py::ssize_t(indices.size()));
  auto out = array.mutable_unchecked<1>();
  for (std::size_t i = 0; i < indices.size(); ++i)
    out(py::ssize_t(i)) = indices[i];
  return array;
}

}  // namespace bemshape::python
