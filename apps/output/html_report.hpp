#pragma once
// A self-contained HTML page of a thickness result: the surface coloured by thickness (viridis,
// colour_map.hpp) with a colour bar, orbit/zoom, the thin (and thick) regions listed and
// clickable (the camera flies to the region, a marker sits on its extreme value, its faces are
// highlighted and outlined), the histogram of area per thickness range, the parameters and the
// verdict of the check. One file: three.js and the page's script (viewer/) are compiled into
// the program, and the data are embedded, so the page opens from file:// with no network.
//
// The input is a plain struct, independent of the solver. Lengths are in `units` (the input
// file's units), areas in units².
//
// File layout (docs/usage.md, "HTML report"): the page template; one <script
// type="application/json" id="bemshape-report"> with every small field; the arrays as base64
// of little-endian binary in <script type="text/plain" id="bemshape-<name>"> elements:
//   positions      float32 #V×3, vertex − origin (origin in the JSON: the bounding box centre,
//                  so that float32 keeps the precision relative to the part's size)
//   indices        uint32 #F×3, counter-clockwise seen from outside
//   vertex-values  float32 #V (NaN: no value, drawn grey)         (if vertex_values is given)
//   face-values    float32 #F (NaN: no value)                      (if face_values is given)
//   region-faces   uint32, the regions' face lists one after the other (offsets in the JSON)
//   defect-faces   uint32, the faces near a defect region, drawn kDefectColour
//                  (colour_map.hpp)                                (if defect_faces is given)
// Payload: about (4/3)·(16·#V + 16·#F) bytes with both value arrays, 28 MB at 10⁶ faces.
// Written atomically (atomic_file.hpp).

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace bemshape::output {

/// A connected set of faces beyond a threshold: thinner than the minimum ("thin") or thicker
/// than the maximum ("thick").
struct HtmlRegion {
  std::string kind = "thin";  ///< "thin", "thick" or "speck" (thin, smaller than the speck area)
  int rank = 1;               ///< 1 = most severe of its kind
  double area = 0.0;          ///< [units²]
  double extreme = 0.0;       ///< the thinnest value for "thin", the thickest for "thick" [units]
  Eigen::Vector3d extreme_location = Eigen::Vector3d::Zero();  ///< where `extreme` is [units]
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();          ///< area-weighted [units]
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();           ///< bounding box of its faces
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  std::vector<int> faces;  ///< indices into HtmlReport::faces
};

/// A region where the surface crosses itself and was measured as given (geometry's
/// DefectZone): listed in a warning beside the verdict.
struct HtmlDefect {
  std::string text;  ///< what and why, one sentence
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< [units]
  double size = 0.0;  ///< bounding-box diagonal [units]
};

/// Area of the surface per thickness range: bin k is [edges[k], edges[k + 1]).
struct HtmlHistogram {
  std::vector<double> edges;  ///< n + 1 increasing edges [units]
  std::vector<double> area;   ///< n areas [units²]
  double other_area = 0.0;    ///< area not in any bin (no measurable value) [units²]
};

struct HtmlReport {
  std::string title;                 ///< page title and heading, e.g. the input file's name
  std::string units = "input file units";  ///< the unit of every length shown
  std::string quantity = "thickness";      ///< what the colours show, e.g. "thickness (h_p)"
  Eigen::MatrixX3d vertices;         ///< #V×3 [units]
  Eigen::MatrixX3i faces;            ///< #F×3 vertex indices
  Eigen::VectorXd vertex_values;     ///< #V, or empty; NaN where there is no value [units]
  Eigen::VectorXd face_values;       ///< #F, or empty; at least one of the two is given
  double colour_minimum = 0.0;       ///< darkest colour [units]
  double colour_maximum = 1.0;       ///< brightest colour [units]
  std::optional<double> min_thickness;  ///< threshold of the thin regions, marked on the bar
  std::optional<double> max_thickness;  ///< threshold of the thick regions
  std::vector<HtmlRegion> regions;   ///< listed in this order
  HtmlHistogram histogram;           ///< may be empty
  /// (name, value) lines of the parameters table, in order
  std::vector<std::pair<std::string, std::string>> parameters;
  std::string verdict;       ///< "PASS", "FAIL" or empty (no check)
  std::string verdict_text;  ///< one sentence, e.g. "3 regions thinner than 10"
  /// Defect regions, and the faces near them (indices into faces), drawn in the defect
  /// colour over the thickness: the values there are measured on a surface that crosses
  /// itself.
  std::vector<HtmlDefect> defects;
  std::vector<int> defect_faces;
  std::vector<std::string> warnings;  ///< one line each, shown under the verdict
};

/// Writes `report` to `path` atomically. Throws InputError on an I/O error, InternalError if
/// the arrays' sizes do not match (a face index out of range, a value array of the wrong
/// length, neither value array given, colour_maximum < colour_minimum).
void write_html_report(const std::filesystem::path& path, const HtmlReport& report);

/// The base64 text (RFC 4648, with '=' padding) of `bytes`.
std::string base64(const void* bytes, std::size_t size);

}  // namespace bemshape::output
