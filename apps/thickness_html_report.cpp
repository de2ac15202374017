#include "apps/thickness_html_report.hpp"

#include <cmath>
#include <limits>

#include "analysis/area_histogram.hpp"
#include "apps/report_text.hpp"
#include "core/errors.hpp"

namespace bemshape::apps {
namespace {

/// The values with those at or above `unmeasurable_from` replaced by NaN (no colour).
Eigen::VectorXd without_unmeasurable(const Eigen::VectorXd& values, double unmeasurable_from) {
  Eigen::VectorXd out = values;
  for (Eigen::Index i = 0; i < out.size(); ++i)
    if (!(out(i) < unmeasurable_from))
      out(i) = std::numeric_limits<double>::quiet_NaN();
  return out;
}

output::HtmlRegion html_region(const geometry::SurfaceMesh& mesh,
                               const analysis::ThinRegion& region, const char* kind,
                               int rank) {
  output::HtmlRegion r;
  r.kind = kind;
  r.rank = rank;
  r.area = region.area;
  r.extreme = region.minimum;
  r.extreme_location = region.min_location;
  r.centroid = region.centroid;
  r.box_min.setConstant(std::numeric_limits<double>::infinity());
  r.box_max.setConstant(-std::numeric_limits<double>::infinity());
  for (const int f : region.face_indices)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.corner(f, k);
      r.box_min = r.box_min.cwiseMin(p);
      r.box_max = r.box_max.cwiseMax(p);
    }
  if (region.face_indices.empty())
    r.box_min = r.box_max = region.min_location;
  r.faces = region.face_indices;
  return r;
}

}  // namespace

output::HtmlReport thickness_html_report(const ThicknessHtmlInput& input) {
  if (input.mesh == nullptr)
    throw InternalError("thickness_html_report: no mesh");
  const geometry::SurfaceMesh& mesh = *input.mesh;
  output::HtmlReport report;
  report.title = input.title;
  report.units = "input file units";
  report.quantity = "thickness " + input.measure;
  report.vertices = mesh.vertices();
  report.faces = mesh.faces();
  report.vertex_values = without_unmeasurable(input.vertex_thickness, input.unmeasurable_from);
  report.face_values = without_unmeasurable(input.face_thickness, input.unmeasurable_from);
  report.colour_minimum = input.statistics.minimum;
  report.colour_maximum = input.statistics.maximum;
  report.min_thickness = input.min_thickness;
  for (std::size_t i = 0; i < input.thin_regions.size(); ++i)
    report.regions.push_back(
        html_region(mesh, input.thin_regions[i], "thin", static_cast<int>(i) + 1));
  for (std::size_t i = 0; i < input.check.specks.size(); ++i)
    report.regions.push_back(
        html_region(mesh, input.check.specks[i], "speck", static_cast<int>(i) + 1));
  report.warnings = input.warnings;
  const analysis::AreaHistogram h = analysis::area_histogram(
      input.face_thickness, mesh.face_areas(), kHtmlHistogramBins, input.unmeasurable_from);
  report.histogram = {h.edges, h.area, h.other_area};
  report.parameters = input.parameters;
  for (const geometry::DefectZone& zone : input.defects) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on chains of + here,
    // point_text's included.
    std::string text = zone.what;
    text += ", ";
    text += number_text(zone.size(), 6);
    text += " across around ";
    text += '(';
    for (int k = 0; k < 3; ++k) {
      text += number_text(zone.centre()(k), 6);
      text += k < 2 ? ", " : ")";
    }
    text += ", not repaired: ";
    text += zone.why;
    text += ". Measured on the surface as given there.";
    report.defects.push_back({std::move(text), zone.centre(), zone.size()});
  }
  for (std::size_t f = 0; f < input.defect_faces.size(); ++f)
    if (input.defect_faces[f] != 0)
      report.defect_faces.push_back(static_cast<int>(f));
  if (input.min_thickness) {
    const analysis::ThinCheck& check = input.check;
    const std::string threshold = number_text(*input.min_thickness, 6);
    const std::string speck_area = number_text(check.speck_area, 6);
    const std::size_t specks = check.specks.size();
    const std::string set_aside =
        std::to_string(specks) + " speck" + (specks == 1 ? "" : "s") + " (each smaller than " +
        speck_area + "), total area " + number_text(check.speck_total, 6);
    if (check.unmeasurable) {
      report.verdict = "FAIL";
      report.verdict_text = "no face has a measurable thickness at this h0, and the lengths "
                            "given do not fit the part's size (see the warning).";
    } else if (check.pass) {
      report.verdict = "PASS";
      report.verdict_text = "no wall thinner than " + threshold +
                            (specks == 0 ? "" : " over the speck area " + speck_area +
                                                    "; set aside: " + set_aside) +
                            ".";
    } else if (!input.thin_regions.empty()) {
      double area = 0.0;
      for (const analysis::ThinRegion& r : input.thin_regions)
        area += r.area;
      const std::size_t n = input.thin_regions.size();
      report.verdict = "FAIL";
      report.verdict_text = std::to_string(n) + " region" + (n == 1 ? "" : "s") +
                            " thinner than " + threshold + ", total area " +
                            number_text(area, 6) + "; thinnest " +
                            number_text(input.thin_regions.front().minimum, 6) +
                            (specks == 0 ? "" : "; besides, " + set_aside) + ".";
    } else {
      report.verdict = "FAIL";
      report.verdict_text = "thinner than " + threshold + " over area " +
                            number_text(check.thin_area, 6) + ", at least the speck area " +
                            speck_area + ", in " + set_aside + "; thinnest " +
                            number_text(check.specks.front().minimum, 6) + ".";
    }
  }
  return report;
}

}  // namespace bemshape::apps
