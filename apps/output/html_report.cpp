#include "apps/output/html_report.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <string_view>

#include "apps/output/atomic_file.hpp"
#include "apps/output/colour_map.hpp"
#include "apps/output/html_report_page.hpp"  // generated from viewer/ (apps/output/CMakeLists.txt)
#include "core/errors.hpp"

namespace bemshape::output {
namespace {

static_assert(std::numeric_limits<float>::is_iec559, "the page reads IEEE-754 float32");

/// Bytes of one base64 chunk handed to the file at a time: a multiple of 3, so chunks
/// concatenate to the base64 of the whole array without padding in between.
constexpr std::size_t kChunkBytes = 3 * 65536;

/// Little-endian bytes of a 32-bit value (float or uint32).
template <typename T>
void put_le(unsigned char* out, T value) {
  static_assert(sizeof(T) == 4);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, 4);
  for (int k = 0; k < 4; ++k)
    out[k] = static_cast<unsigned char>(bits >> (8 * k));
}

/// One <script type="text/plain"> element holding the base64 of `bytes`.
void write_blob(AtomicFileWriter& file, std::string_view name, const std::vector<unsigned char>& bytes) {
  file.write("<script type=\"text/plain\" id=\"bemshape-");
  file.write(name);
  file.write("\">");
  for (std::size_t begin = 0; begin < bytes.size(); begin += kChunkBytes) {
    const std::size_t size = std::min(kChunkBytes, bytes.size() - begin);
    file.write(base64(bytes.data() + begin, size));
  }
  file.write("</script>\n");
}

std::vector<unsigned char> float32_bytes(const Eigen::Ref<const Eigen::VectorXd>& values) {
  std::vector<unsigned char> bytes(4 * static_cast<std::size_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const double v = values(i);
    put_le(bytes.data() + 4 * i,
           std::isfinite(v) ? static_cast<float>(v) : std::numeric_limits<float>::quiet_NaN());
  }
  return bytes;
}

nlohmann::json point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

void check_sizes(const HtmlReport& r) {
  const Eigen::Index nv = r.vertices.rows(), nf = r.faces.rows();
  const auto fail = [](const std::string& what) {
    throw InternalError("write_html_report: " + what);
  };
  if (nf > 0 && (r.faces.minCoeff() < 0 || r.faces.maxCoeff() >= nv))
    fail("a face index is outside the " + std::to_string(nv) + " vertices");
  if (r.vertex_values.size() == 0 && r.face_values.size() == 0)
    fail("neither vertex_values nor face_values is given");
  if (r.vertex_values.size() != 0 && r.vertex_values.size() != nv)
    fail("vertex_values has " + std::to_string(r.vertex_values.size()) + " entries for " +
         std::to_string(nv) + " vertices");
  if (r.face_values.size() != 0 && r.face_values.size() != nf)
    fail("face_values has " + std::to_string(r.face_values.size()) + " entries for " +
         std::to_string(nf) + " faces");
  if (!(r.colour_minimum <= r.colour_maximum))
    fail("colour_maximum is below colour_minimum");
  for (const HtmlRegion& region : r.regions)
    for (const int f : region.faces)
      if (f < 0 || f >= nf)
        fail("region face " + std::to_string(f) + " is outside the " + std::to_string(nf) +
             " faces");
  for (const int f : r.defect_faces)
    if (f < 0 || f >= nf)
      fail("defect face " + std::to_string(f) + " is outside the " + std::to_string(nf) +
           " faces");
  if (!r.histogram.edges.empty() && r.histogram.edges.size() != r.histogram.area.size() + 1)
    fail("the histogram needs one more edge than bins");
}

/// Every small field of the report as JSON, with '<' escaped so that no text (a title with
/// "</script>") can end the element it sits in.
std::string metadata(const HtmlReport& r, const Eigen::Vector3d& origin) {
  nlohmann::json regions = nlohmann::json::array();
  std::size_t offset = 0;
  for (const HtmlRegion& region : r.regions) {
    regions.push_back({{"kind", region.kind},
                       {"rank", region.rank},
                       {"area", region.area},
                       {"extreme", region.extreme},
                       {"extreme_location", point(region.extreme_location)},
                       {"centroid", point(region.centroid)},
                       {"box_min", point(region.box_min)},
                       {"box_max", point(region.box_max)},
                       {"face_offset", offset},
                       {"face_count", region.faces.size()}});
    offset += region.faces.size();
  }
  nlohmann::json defects = nlohmann::json::array();
  for (const HtmlDefect& d : r.defects)
    defects.push_back({{"text", d.text}, {"centre", point(d.centre)}, {"size", d.size}});
  nlohmann::json parameters = nlohmann::json::array();
  for (const auto& [name, value] : r.parameters)
    parameters.push_back({name, value});
  const auto optional = [](const std::optional<double>& x) {
    return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
  };
  const nlohmann::json json = {
      {"format", "bemshape-html-report 1"},
      {"title", r.title},
      {"units", r.units},
      {"quantity", r.quantity},
      {"vertices", r.vertices.rows()},
      {"faces", r.faces.rows()},
      {"origin", point(origin)},
      {"has_vertex_values", r.vertex_values.size() != 0},
      {"has_face_values", r.face_values.size() != 0},
      {"colour_range", {r.colour_minimum, r.colour_maximum}},
      {"min_thickness", optional(r.min_thickness)},
      {"max_thickness", optional(r.max_thickness)},
      {"regions", regions},
      {"histogram",
       {{"edges", r.histogram.edges},
        {"area", r.histogram.area},
        {"other_area", r.histogram.other_area}}},
      {"parameters", parameters},
      {"verdict", r.verdict},
      {"verdict_text", r.verdict_text},
      {"defects", defects},
      {"defect_colour", {kDefectColour.r, kDefectColour.g, kDefectColour.b}},
      {"defect_face_count", r.defect_faces.size()},
      {"warnings", r.warnings}};
  std::string text = json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    if (c == '<')
      escaped += "\\u003c";  // only inside JSON strings: the one place '<' can appear
    else
      escaped += c;
  }
  return escaped;
}

}  // namespace

std::string base64(const void* data, std::size_t size) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v = (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8) | in[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (const std::size_t rest = size - i; rest > 0) {
    std::uint32_t v = std::uint32_t(in[i]) << 16;
    if (rest == 2)
      v |= std::uint32_t(in[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

void write_html_report(const std::filesystem::path& path, const HtmlReport& report) {
  check_sizes(report);
  const Eigen::Index nv = report.vertices.rows(), nf = report.faces.rows();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  if (nv > 0)
    origin = 0.5 * (report.vertices.colwise().minCoeff() + report.vertices.colwise().maxCoeff())
                       .transpose();
  const std::string json = metadata(report, origin);

  AtomicFileWriter file(path);
  for (const std::string_view piece : html_page::kBeforeData)
    file.write(piece);
  file.write("<script type=\"application/json\" id=\"bemshape-report\">");
  file.write(json);
  file.write("</script>\n");
  {
    std::vector<unsigned char> bytes(12 * static_cast<std::size_t>(nv));
    for (Eigen::Index v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k)
        put_le(bytes.data() + 4 * (3 * v + k), static_cast<float>(report.vertices(v, k) - origin(k)));
    write_blob(file, "positions", bytes);
  }
  {
    std::vector<unsigned char> bytes(12 * static_cast<std::size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k)
        put_le(bytes.data() + 4 * (3 * f + k), static_cast<std::uint32_t>(report.faces(f, k)));
    write_blob(file, "indices", bytes);
  }
  if (report.vertex_values.size() != 0)
    write_blob(file, "vertex-values", float32_bytes(report.vertex_values));
  if (report.face_values.size() != 0)
    write_blob(file, "face-values", float32_bytes(report.face_values));
  {
    std::vector<unsigned char> bytes;
    for (const HtmlRegion& region : report.regions)
      for (const int f : region.faces) {
        bytes.resize(bytes.size() + 4);
        put_le(bytes.data() + bytes.size() - 4, static_cast<std::uint32_t>(f));
      }
    write_blob(file, "region-faces", bytes);
  }
  if (!report.defect_faces.empty()) {
    std::vector<unsigned char> bytes(4 * report.defect_faces.size());
    for (std::size_t i = 0; i < report.defect_faces.size(); ++i)
      put_le(bytes.data() + 4 * i, static_cast<std::uint32_t>(report.defect_faces[i]));
    write_blob(file, "defect-faces", bytes);
  }
  for (const std::string_view piece : html_page::kAfterData)
    file.write(piece);
  file.commit();
}

}  // namespace bemshape::output
