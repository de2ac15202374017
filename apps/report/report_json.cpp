#include "apps/report/report_json.hpp"

#include "core/huge_pages.hpp"
#include "core/number_text.hpp"

namespace bemshape::apps {

nlohmann::json point_json(const Eigen::Vector3d& p) {
  return nlohmann::json::array({p.x(), p.y(), p.z()});
}

nlohmann::json report_header(const std::string& command, const std::string& input) {
  return {{"bemshape", BEMSHAPE_VERSION},
          {"command", command},
          {"input", input},
          {"units", "lengths in the input file's units"}};
}

nlohmann::json mesh_json(const geometry::MeshReport& input, const analysis::BoundarySolve& run) {
  // The graded solver mesh's sizes and why (analysis::SolverMeshRule::wall_reading).
  nlohmann::json graded = nullptr;
  if (run.graded) {
    const geometry::GradedMeshReport& g = *run.graded;
    nlohmann::json area = nlohmann::json::object();
    for (int r = 0; r < geometry::kSizeReasons; ++r)
      if (g.area_by_reason[std::size_t(r)] > 0.0)
        area[geometry::to_string(static_cast<geometry::SizeReason>(r))] =
            g.area_by_reason[std::size_t(r)];
    graded = {{"min_edge", g.min_edge},
              {"mean_edge", g.mean_edge},
              {"max_edge", g.max_edge},
              {"min_angle_degrees", g.min_angle_degrees},
              {"creases", g.creases},
              {"smoothed_edges", g.smoothed_edges},
              {"kept_input", g.kept_input},
              {"area_by_size_reason", area}};
  }
  return {{"input_faces", input.faces},
          {"input_vertices", input.vertices},
          {"solver_faces", run.solver_mesh.num_faces()},
          {"solver_vertices", run.solver_mesh.num_vertices()},
          {"solver_max_edge", run.solver_mesh.max_edge_length()},
          {"area", input.area},
          {"volume", input.volume},
          {"repairs", input.repairs},
          {"graded", graded},
          {"memory_fit", memory_fit_json(run)}};
}

nlohmann::json memory_fit_json(const analysis::BoundarySolve& run) {
  if (!run.memory_fit)
    return nullptr;
  const analysis::MemoryFit& f = *run.memory_fit;
  return {{"fitted", true},
          {"refused_faces", f.refused_faces},
          {"refused_gb", f.refused_bytes / 1e9},
          {"budget_gb", f.budget_bytes / 1e9},
          {"attempts", f.attempts},
          {"max_edge", run.max_edge},
          {"solver_faces", run.solver_mesh.num_faces()}};
}

std::string memory_fit_note(const analysis::BoundarySolve& run) {
  if (!run.memory_fit)
    return {};
  const analysis::MemoryFit& f = *run.memory_fit;
  return "--fit-memory: the solver mesh of " + std::to_string(f.refused_faces) + " faces needed " +
         number_text(f.refused_bytes / 1e9, 3) + " GB of the " +
         number_text(f.budget_bytes / 1e9, 3) + " GB budget; solved instead on a uniform mesh of "
         "--max-edge " + number_text(run.max_edge, 3) + " (" +
         std::to_string(run.solver_mesh.num_faces()) + " faces)";
}

nlohmann::json solver_json(const analysis::BoundarySolve& run) {
  const auto& report = run.solution.report;
  // Wall seconds of the assembly's and the solve's stages, megabytes of the operators' parts
  // (the H-matrix path; empty for the dense path).
  nlohmann::json assembly_stages = nlohmann::json::object();
  for (const auto& [stage, seconds] : report.assembly_stages)
    assembly_stages[stage] = seconds;
  nlohmann::json solve_stages = nlohmann::json::object();
  for (const auto& [stage, seconds] : report.solve_stages)
    solve_stages[stage] = seconds;
  nlohmann::json operator_parts = nlohmann::json::object();
  for (const auto& [part, bytes] : report.operator_parts)
    operator_parts[part] = double(bytes) / 1e6;
  return {{"method", report.method},
          {"unknowns", report.unknowns},
          {"iterations", report.iterations},
          {"gmres_restart", report.restart},
          {"residual", report.residual},
          {"preconditioned_residual", report.preconditioned_residual},
          {"operator_mb", double(report.operator_bytes) / 1e6},
          {"compression", report.compression},
          {"assembly_stages", assembly_stages},
          {"solve_stages", solve_stages},
          {"operator_parts_mb", operator_parts}};
}

nlohmann::json timing_json(const analysis::StageTimes& times) {
  nlohmann::json timing = nlohmann::json::object();
  for (const auto& [stage, seconds] : times.stages())
    timing[stage] = seconds;
  timing["total"] = times.elapsed();
  return timing;
}

nlohmann::json memory_json(const RunFigures& run) {
  return {{"peak_mb", run.peak_mb}, {"heap_huge_pages", heap_uses_huge_pages()}};
}

const char* build_march() {
  return BEMSHAPE_ARCH_NAME;
}

}  // namespace bemshape::apps
