#pragma once
// The HTML report of `bemshape thickness --html FILE`: the thickness on the solver mesh (the
// values the statistics and regions are computed from), its thin regions and the specks set
// aside, the histogram of area per thickness range, the parameters, the verdict and the
// warnings, gathered into the writer's plain input (apps/output/html_report.hpp).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "apps/output/html_report.hpp"
#include "analysis/thickness_statistics.hpp"
#include "geometry/defect_zones.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::apps {

/// Bins of the report's histogram of area per thickness range (at most; round widths).
constexpr int kHtmlHistogramBins = 12;

struct ThicknessHtmlInput {
  std::string title;    ///< the input file's name
  std::string measure;  ///< "h_p" or "h_f"
  const geometry::SurfaceMesh* mesh = nullptr;  ///< the solver mesh
  Eigen::VectorXd vertex_thickness;             ///< #V of *mesh [model units]
  Eigen::VectorXd face_thickness;               ///< #F of *mesh [model units]
  double unmeasurable_from = 0.0;  ///< values at or above it have no thickness (drawn grey)
  analysis::ThicknessStatistics statistics;
  std::vector<analysis::ThinRegion> thin_regions;  ///< with their face lists, most severe first
  analysis::ThinCheck check;             ///< the verdict and the specks set aside
  std::optional<double> min_thickness;   ///< --min-thickness
  std::vector<std::pair<std::string, std::string>> parameters;
  /// Regions where the input crosses itself, measured as given, and the solver faces within
  /// h0 of them (#F of *mesh, or empty): drawn in the defect colour and listed.
  std::vector<geometry::DefectZone> defects;
  std::vector<char> defect_faces;
  std::vector<std::string> warnings;     ///< one line each (the units check)
};

output::HtmlReport thickness_html_report(const ThicknessHtmlInput& input);

}  // namespace bemshape::apps
