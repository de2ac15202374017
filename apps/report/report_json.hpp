#pragma once
// The blocks every JSON report of a solving job shares (thickness, features): the program's
// header, the mesh sizes, the solver's figures, the stage times and the memory. Lengths are
// in the input's units, times in wall seconds, memory in megabytes (10⁶ bytes).

#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "analysis/boundary_solve.hpp"
#include "analysis/stage_times.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::apps {

/// What a report says about the run besides the job's result: the front end measures these.
struct RunFigures {
  int threads = 0;       ///< OpenMP threads the run used
  double peak_mb = 0.0;  ///< peak resident memory of the process [MB]
};

/// [x, y, z].
nlohmann::json point_json(const Eigen::Vector3d& p);

/// {"bemshape": version, "command": command, "input": input, "units": ...}.
nlohmann::json report_header(const std::string& command, const std::string& input);

/// Input and solver mesh sizes, area, volume and the repairs made to the input.
nlohmann::json mesh_json(const geometry::MeshReport& input, const analysis::BoundarySolve& run);

/// The linear solver's method, size, iterations, residuals, operator memory and stage times.
nlohmann::json solver_json(const analysis::BoundarySolve& run);

/// mesh.memory_fit: null, or what --fit-memory refused and took instead (its faces, the
/// refused estimate and the budget in GB, meshes tried, the edge and faces solved on).
nlohmann::json memory_fit_json(const analysis::BoundarySolve& run);

/// The one stderr line --fit-memory writes when it replaced the mesh; empty if it did not.
std::string memory_fit_note(const analysis::BoundarySolve& run);

/// {stage: seconds, ..., "total": seconds since `times` was constructed}.
nlohmann::json timing_json(const analysis::StageTimes& times);

/// {"peak_mb": ..., "heap_huge_pages": ...}.
nlohmann::json memory_json(const RunFigures& run);

/// The build's instruction set (-march value; empty: the compiler's default).
const char* build_march();

}  // namespace bemshape::apps
