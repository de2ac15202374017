#include "apps/report/features_report_json.hpp"

#include <cstddef>

namespace bemshape::apps {
namespace {

/// {"min", "min_location", "max"} of `values` over the inside points; null when none is inside.
nlohmann::json inside_range_json(const Eigen::VectorXd& values, const analysis::FeaturesResult& r) {
  Eigen::Index lowest = -1, highest = -1;
  for (Eigen::Index p = 0; p < values.size(); ++p) {
    if (!r.field.inside[static_cast<std::size_t>(p)])
      continue;
    if (lowest < 0 || values(p) < values(lowest))
      lowest = p;
    if (highest < 0 || values(p) > values(highest))
      highest = p;
  }
  if (lowest < 0)
    return nullptr;
  return {{"min", values(lowest)},
          {"min_location", point_json(r.points.row(lowest).transpose())},
          {"max", values(highest)}};
}

}  // namespace

nlohmann::json features_report_json(const analysis::FeaturesOptions& options,
                                    const analysis::FeaturesResult& result,
                                    const std::string& input,
                                    const std::optional<std::string>& output,
                                    const analysis::StageTimes& times, const RunFigures& run) {
  const analysis::BoundarySolve& solve = result.boundary;
  std::size_t inside = 0;
  for (const char flag : result.field.inside)
    inside += flag ? 1 : 0;
  nlohmann::json grid = nullptr;
  if (result.grid) {
    const analysis::PointGrid& g = *result.grid;
    grid = {{"nodes", {g.cells[0] + 1, g.cells[1] + 1, g.cells[2] + 1}},
            {"origin", {g.origin[0], g.origin[1], g.origin[2]}},
            {"spacing", {g.spacing[0], g.spacing[1], g.spacing[2]}}};
  }
  nlohmann::json report = report_header("features", input);
  report["output"] = output ? nlohmann::json(*output) : nlohmann::json(nullptr);
  report["parameters"] = {{"h0", options.solve.h0},
                          {"a", options.solve.a},
                          {"kappa", solve.solution.parameters.kappa},
                          {"max_edge", solve.max_edge},
                          {"max_edge_rule", solve.max_edge_rule},
                          {"skeleton_width", result.parameters.skeleton_width},
                          {"threads", run.threads},
                          {"march", build_march()}};
  report["mesh"] = mesh_json(result.input.report, solve);
  report["points"] = {{"count", result.points.rows()},
                      {"inside", inside},
                      {"clamped", result.clamped_points},
                      {"grid", grid}};
  report["features"] = {{"h_f", inside_range_json(result.features.h_f, result)},
                        {"h_p", inside_range_json(result.features.h_p, result)}};
  report["solver"] = solver_json(solve);
  report["timing"] = timing_json(times);
  report["memory"] = memory_json(run);
  return report;
}

}  // namespace bemshape::apps
