#include "apps/report/thickness_report_json.hpp"

#include "apps/report/mesh_report_json.hpp"

namespace bemshape::apps {
namespace {

nlohmann::json optional_text(const std::optional<std::string>& text) {
  return text ? nlohmann::json(*text) : nlohmann::json(nullptr);
}

nlohmann::json box_json(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  return {{"min", point_json(min)}, {"max", point_json(max)}};
}

nlohmann::json region_json(const analysis::ThinRegion& r) {
  return {{"area", r.area},
          {"min", r.minimum},
          {"min_location", point_json(r.min_location)},
          {"centroid", point_json(r.centroid)},
          {"box", box_json(r.box_min, r.box_max)},
          {"faces", r.faces},
          {"solver_faces", r.face_indices}};
}

nlohmann::json region_json(const analysis::ThickRegion& r) {
  return {{"area", r.area},
          {"max", r.maximum},
          {"max_location", point_json(r.max_location)},
          {"skeleton_point", r.skeleton_point.allFinite() ? point_json(r.skeleton_point)
                                                          : nlohmann::json(nullptr)},
          {"centroid", point_json(r.centroid)},
          {"box", box_json(r.box_min, r.box_max)},
          {"faces", r.faces},
          {"solver_faces", r.face_indices}};
}

const char* edges_name(analysis::EdgeMode edges) {
  return edges == analysis::EdgeMode::exact ? "exact" : "wall";
}

}  // namespace

nlohmann::json thickness_report_json(const analysis::ThicknessOptions& options,
                                     const analysis::ThicknessResult& result,
                                     const ThicknessRunNames& names,
                                     const analysis::StageTimes& times, const RunFigures& run,
                                     const UnitsCheck& units) {
  const analysis::BoundarySolve& solve = result.boundary;
  const analysis::ThicknessStatistics& s = result.statistics;
  nlohmann::json parameters = {{"h0", result.h0},
                               {"h0_rule", result.h0_rule},
                               {"a", options.solve.a},
                               {"kappa", solve.solution.parameters.kappa},
                               {"measure", names.measure},
                               {"edges", edges_name(options.edges)},
                               {"max_thickness", nullptr},
                               {"min_region_area", result.min_region_area},
                               {"max_edge", solve.max_edge},
                               {"max_edge_rule", solve.max_edge_rule},
                               {"min_thickness", nullptr},
                               {"units_check", units.enabled},
                               {"threads", run.threads},
                               {"march", build_march()}};
  nlohmann::json check = nullptr;
  if (options.min_thickness) {
    parameters["min_thickness"] = *options.min_thickness;
    nlohmann::json regions = nlohmann::json::array();
    for (const analysis::ThinRegion& r : result.regions)
      regions.push_back(region_json(r));
    nlohmann::json specks = nlohmann::json::array();
    for (const analysis::ThinRegion& r : result.check.specks)
      specks.push_back(region_json(r));
    check = {{"threshold", *options.min_thickness},
             {"pass", result.check.pass},
             {"unmeasurable", result.check.unmeasurable},
             {"regions", regions},
             {"thin_area", result.check.thin_area},
             {"speck_area", result.check.speck_area},
             {"set_aside_area", result.check.speck_total},
             {"specks", specks}};
  }
  nlohmann::json thick = nullptr;
  if (options.max_thickness) {
    parameters["max_thickness"] = *options.max_thickness;
    nlohmann::json regions = nlohmann::json::array();
    for (const analysis::ThickRegion& r : result.thick_regions)
      regions.push_back(region_json(r));
    thick = {{"threshold", *options.max_thickness}, {"regions", regions}};
  }
  nlohmann::json wall_search = nullptr;
  if (result.column == analysis::kColumnWall) {
    nlohmann::json fallback = nlohmann::json::object();
    for (int k = 0; k < analysis::kFallbackKinds; ++k) {
      const analysis::FallbackFaces& b = result.wall.fallback[static_cast<std::size_t>(k)];
      fallback[analysis::to_string(static_cast<analysis::Fallback>(k))] = {
          {"faces", b.faces},
          {"area", b.area},
          {"box", {{"min", point_json(b.box.min)}, {"max", point_json(b.box.max)}}}};
    }
    wall_search = {{"evaluations", result.wall.evaluations},
                   {"faces_without_mid_surface", result.wall.filled_faces},
                   {"faces_paired_across_the_wall", result.wall.paired_faces},
                   {"fallback", fallback}};
  }
  nlohmann::json report = report_header("thickness", names.input);
  report["output"] = optional_text(names.output);
  report["solver_output"] = optional_text(names.solver_output);
  report["parameters"] = parameters;
  report["units_warning"] = units.warning ? nlohmann::json(*units.warning) : nullptr;
  report["mesh"] = mesh_json(result.input.report, solve);
  report["thickness"] = {{"measure", result.measure_column},
                         {"min", s.minimum},
                         {"max", s.maximum},
                         {"mean", s.mean},
                         {"median", s.median},
                         {"p05", s.p05},
                         {"p95", s.p95},
                         {"min_location", point_json(s.min_location)},
                         {"measured_area", s.measured_area},
                         {"unmeasurable_area", s.unmeasurable_area},
                         {"clamped_faces", result.clamped_faces},
                         {"mid_surface_search", wall_search},
                         {"histogram",
                          {{"edges", result.histogram.edges},
                           {"area", result.histogram.area},
                           {"unmeasurable_area", result.histogram.other_area}}}};
  // Where the surface crosses itself and was measured as given, with the solver faces within
  // h0 of each region (the faces the outputs mark 'defect').
  nlohmann::json defects = defects_json(result.input.report.defects);
  for (std::size_t i = 0; i < result.input.report.defects.size(); ++i) {
    const std::vector<char> near = geometry::faces_near_defects(
        solve.solver_mesh, {result.input.report.defects[i]}, result.h0);
    std::size_t faces = 0;
    double area = 0.0;
    for (std::size_t f = 0; f < near.size(); ++f)
      if (near[f] != 0) {
        ++faces;
        area += solve.solver_mesh.face_areas()(static_cast<Eigen::Index>(f));
      }
    defects[i]["solver_faces_marked"] = faces;
    defects[i]["area_marked"] = area;
  }
  report["defects"] = defects;
  report["check"] = check;
  report["thick_regions"] = thick;
  report["solver"] = solver_json(solve);
  report["timing"] = timing_json(times);
  report["memory"] = memory_json(run);
  // The memory guard's bound on the peak, checked before the solve (docs/reliability.md).
  report["memory"]["estimate_mb"] = double(solve.solution.report.memory_estimate_bytes) / 1e6;
  return report;
}

}  // namespace bemshape::apps
