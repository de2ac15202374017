// The HTML report writer (apps/output/html_report.hpp): the embedded arrays, decoded from
// base64 independently here, must equal the input in float32/uint32; the JSON holds the small
// fields; no text of the report can end its script element; bad input leaves no file. The
// page itself (three.js, clicks, rendering) is tested in headless Chromium by
// html_report_browser.mjs.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "apps/output/html_report.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

/// RFC 4648 base64 decoding, written apart from the encoder it checks.
std::vector<unsigned char> decode_base64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=')
      break;
    const std::size_t value = alphabet.find(c);
    REQUIRE(value != std::string::npos);
    buffer = (buffer << 6) | static_cast<std::uint32_t>(value);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  return out;
}

/// The text of <script ... id="bemshape-<name>">…</script>, or "" if absent.
std::string element_text(const std::string& page, const std::string& name) {
  const std::string id = "id=\"bemshape-" + name + "\">";
  const std::size_t at = page.find(id);
  if (at == std::string::npos)
    return "";
  const std::size_t begin = at + id.size();
  return page.substr(begin, page.find("</script>", begin) - begin);
}

template <typename T>
std::vector<T> little_endian_array(const std::string& page, const std::string& name) {
  const std::vector<unsigned char> bytes = decode_base64(element_text(page, name));
  REQUIRE(bytes.size() % 4 == 0);
  std::vector<T> out(bytes.size() / 4);
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::uint32_t bits = 0;
    for (int k = 0; k < 4; ++k)
      bits |= std::uint32_t(bytes[4 * i + k]) << (8 * k);
    std::memcpy(&out[i], &bits, 4);
  }
  return out;
}

output::HtmlReport box_report() {
  const geometry::SurfaceMesh mesh =
      geometry::make_box(Eigen::Vector3d(100, -2, 7), Eigen::Vector3d(103, 2, 8), 0.9);
  output::HtmlReport r;
  r.title = "box </script><!-- <script> & \"quotes\"";
  r.units = "mm";
  r.vertices = mesh.vertices();
  r.faces = mesh.faces();
  r.vertex_values = mesh.vertices().col(0).array() - 100.0;
  r.vertex_values(1) = std::numeric_limits<double>::quiet_NaN();
  r.face_values = mesh.face_centroids().col(2);
  r.colour_minimum = 0.0;
  r.colour_maximum = 3.0;
  r.min_thickness = 0.5;
  output::HtmlRegion a, b;
  a.faces = {0, 1, 2};
  a.extreme = 0.1;
  b.faces = {5, 7};
  b.kind = "thick";
  r.regions = {a, b};
  r.histogram = {{0.0, 1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}, 0.5};
  r.parameters = {{"h0", "1"}, {"measure", "h_p"}};
  r.verdict = "FAIL";
  r.verdict_text = "2 regions";
  return r;
}

}  // namespace

TEST_CASE("HTML report: base64 follows the RFC 4648 test vectors") {
  for (const auto& [plain, encoded] : std::vector<std::pair<std::string, std::string>>{
           {"", ""},
           {"f", "Zg=="},
           {"fo", "Zm8="},
           {"foo", "Zm9v"},
           {"foob", "Zm9vYg=="},
           {"fooba", "Zm9vYmE="},
           {"foobar", "Zm9vYmFy"}})
    CHECK(output::base64(plain.data(), plain.size()) == encoded);
}

TEST_CASE("HTML report: arrays read back as float32 and uint32, positions about the box centre") {
  const output::HtmlReport r = box_report();
  const std::string path = scratch("report.html");
  output::write_html_report(path, r);
  const std::string page = slurp(path);

  const nlohmann::json meta = nlohmann::json::parse(element_text(page, "report"));
  CHECK(meta["title"] == r.title);
  CHECK(meta["vertices"] == r.vertices.rows());
  CHECK(meta["faces"] == r.faces.rows());
  const Eigen::Vector3d origin(101.5, 0.0, 7.5);  // the centre of the box's bounding box
  for (int k = 0; k < 3; ++k)
    CHECK(meta["origin"][k].get<double>() == origin(k));

  const auto positions = little_endian_array<float>(page, "positions");
  REQUIRE(positions.size() == std::size_t(3 * r.vertices.rows()));
  for (Eigen::Index v = 0; v < r.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k)
      CHECK(positions[3 * v + k] == static_cast<float>(r.vertices(v, k) - origin(k)));
  const auto indices = little_endian_array<std::uint32_t>(page, "indices");
  REQUIRE(indices.size() == std::size_t(3 * r.faces.rows()));
  for (Eigen::Index f = 0; f < r.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      CHECK(indices[3 * f + k] == std::uint32_t(r.faces(f, k)));
  const auto vertex_values = little_endian_array<float>(page, "vertex-values");
  REQUIRE(vertex_values.size() == std::size_t(r.vertices.rows()));
  CHECK(std::isnan(vertex_values[1]));
  CHECK(vertex_values[0] == static_cast<float>(r.vertex_values(0)));
  CHECK(little_endian_array<float>(page, "face-values").size() == std::size_t(r.faces.rows()));
  CHECK(little_endian_array<std::uint32_t>(page, "region-faces") ==
        std::vector<std::uint32_t>{0, 1, 2, 5, 7});
  CHECK(meta["regions"][1]["kind"] == "thick");
  CHECK(meta["regions"][1]["face_offset"] == 3);
  CHECK(meta["regions"][1]["face_count"] == 2);
  CHECK(meta["histogram"]["area"] == std::vector<double>{4.0, 5.0, 6.0});
  CHECK(meta["min_thickness"] == 0.5);
  CHECK(meta["max_thickness"].is_null());
}

TEST_CASE("HTML report: no text of the report can end or hide the page's script elements") {
  const std::string path = scratch("escaped.html");
  output::write_html_report(path, box_report());
  const std::string page = slurp(path);
  // The data come after the template's head; from there on every "<" belongs to the
  // elements the writer made.
  const std::string json = element_text(page, "report");
  CHECK(json.find('<') == std::string::npos);
  CHECK(page.find("box </script>") == std::string::npos);
  CHECK(page.find("<!-- <script>") == std::string::npos);
  CHECK(page.find("<!DOCTYPE html>") == 0);
  CHECK(page.rfind("</html>") != std::string::npos);
}

TEST_CASE("HTML report: inconsistent input is refused and leaves no file") {
  const std::string path = scratch("refused.html");
  const auto refused = [&](const output::HtmlReport& r) {
    CHECK_THROWS_AS(output::write_html_report(path, r), InternalError);
    CHECK_FALSE(fs::exists(path));
  };
  output::HtmlReport r = box_report();
  r.faces(3, 1) = int(r.vertices.rows());
  refused(r);
  r = box_report();
  r.vertex_values.resize(2);
  refused(r);
  r = box_report();
  r.vertex_values.resize(0);
  r.face_values.resize(0);
  refused(r);
  r = box_report();
  r.regions[0].faces.push_back(int(r.faces.rows()));
  refused(r);
  r = box_report();
  r.histogram.edges.pop_back();
  refused(r);
  r = box_report();
  r.colour_maximum = -1.0;
  refused(r);
}
