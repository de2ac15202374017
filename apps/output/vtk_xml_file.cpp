#include "apps/output/vtk_xml_file.hpp"

#include <algorithm>
#include <bit>
#include <charconv>

#include "apps/output/atomic_file.hpp"
#include "apps/output/number_text.hpp"

namespace bemshape::output {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the VTK XML files declare byte_order=LittleEndian and are written from memory");

/// Numbers per text line of an ASCII array: readable in a text editor.
constexpr std::uint64_t kNumbersPerLine = 6;
/// Values converted per write of the appended block: 1 MiB of doubles, so no array is ever
/// copied whole (a 10⁶-face .vtp holds 7·10⁶ doubles of cell data).
constexpr std::uint64_t kValuesPerChunk = std::uint64_t{1} << 17;

const char* type_name(VtkScalarType type) {
  switch (type) {
    case VtkScalarType::int64:
      return "Int64";
    case VtkScalarType::float32:
      return "Float32";
    case VtkScalarType::float64:
      return "Float64";
  }
  return "";
}

std::uint64_t type_bytes(VtkScalarType type) {
  return type == VtkScalarType::float32 ? 4 : 8;
}

std::uint64_t value_count(const VtkDataArray& array) {
  return static_cast<std::uint64_t>(array.tuples) * static_cast<std::uint64_t>(array.components);
}

/// The i-th value of the array in file order (tuple after tuple).
double value_at(const VtkDataArray& array, std::uint64_t i) {
  const auto c = static_cast<std::uint64_t>(array.components);
  return array.value(static_cast<Eigen::Index>(i / c), static_cast<int>(i % c));
}

void append_text(std::string& text, VtkScalarType type, double x) {
  char buffer[32];
  std::to_chars_result result{};
  switch (type) {
    case VtkScalarType::int64:
      result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<std::int64_t>(x));
      break;
    case VtkScalarType::float32:
      result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(x));
      break;
    case VtkScalarType::float64:
      append_number(text, x);
      return;
  }
  text.append(buffer, result.ptr);
}

/// Writes the array's entry of the appended block: its byte count, then its values as T.
template <class T>
void write_block(AtomicFileWriter& out, const VtkDataArray& array) {
  const std::uint64_t count = value_count(array), bytes = count * sizeof(T);
  out.write(&bytes, sizeof bytes);
  std::vector<T> chunk;
  chunk.reserve(static_cast<std::size_t>(std::min(count, kValuesPerChunk)));
  for (std::uint64_t start = 0; start < count; start += kValuesPerChunk) {
    chunk.clear();
    const std::uint64_t end = std::min(count, start + kValuesPerChunk);
    for (std::uint64_t i = start; i < end; ++i)
      chunk.push_back(static_cast<T>(value_at(array, i)));
    out.write(chunk.data(), chunk.size() * sizeof(T));
  }
}

}  // namespace

VtkDataArray vtk_array(std::string name, VtkScalarType type, const Eigen::MatrixXd& values,
                       int components) {
  const auto value = [m = &values](Eigen::Index tuple, int component) {
    return component < m->cols() ? (*m)(tuple, component) : 0.0;
  };
  return {std::move(name), type, values.rows(), components, value};
}

VtkXmlFile::VtkXmlFile(const std::string& dataset_type, VtkEncoding encoding)
    : encoding_(encoding) {
  xml_ = "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + dataset_type +
         "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
}

void VtkXmlFile::data_array(VtkDataArray array, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  xml_ += pad + "<DataArray type=\"" + type_name(array.type) + '"';
  if (!array.name.empty())
    xml_ += " Name=\"" + array.name + '"';
  xml_ += " NumberOfComponents=\"" + std::to_string(array.components) + '"';
  if (encoding_ == VtkEncoding::binary) {
    xml_ += " format=\"appended\" offset=\"" + std::to_string(appended_bytes_) + "\"/>\n";
    appended_bytes_ += sizeof(std::uint64_t) + value_count(array) * type_bytes(array.type);
    appended_.push_back(std::move(array));
    return;
  }
  xml_ += " format=\"ascii\">\n";
  const std::uint64_t count = value_count(array);
  for (std::uint64_t i = 0; i < count; ++i) {
    xml_ += i % kNumbersPerLine == 0 ? pad + "  " : " ";
    append_text(xml_, array.type, value_at(array, i));
    if ((i + 1) % kNumbersPerLine == 0 || i + 1 == count)
      xml_ += '\n';
  }
  xml_ += pad + "</DataArray>\n";
}

void VtkXmlFile::write(const std::filesystem::path& path) {
  AtomicFileWriter out(path);
  if (encoding_ == VtkEncoding::binary) {
    xml_ += "  <AppendedData encoding=\"raw\">\n   _";
    out.write(xml_);
    for (const VtkDataArray& array : appended_) {
      switch (array.type) {
        case VtkScalarType::int64:
          write_block<std::int64_t>(out, array);
          break;
        case VtkScalarType::float32:
          write_block<float>(out, array);
          break;
        case VtkScalarType::float64:
          write_block<double>(out, array);
          break;
      }
    }
    xml_ = "\n  </AppendedData>\n";
  }
  xml_ += "</VTKFile>\n";
  out.write(xml_);
  out.commit();
}

}  // namespace bemshape::output
