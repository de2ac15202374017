#pragma once
// The JSON report of a mesh's validation and repair (`bemshape check --report`, the Python
// module's check()): format and unit (3MF), sizes as read and as prepared, shells, cavities, volume, area, bounding
// box, every problem with its status, count and first position, every repair, the verdict.

#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/mesh_preparation.hpp"

namespace bemshape::apps {

/// "repaired", "REFUSED", "note" or "DEFECT", as the reports print a problem's status.
const char* problem_status_label(geometry::MeshProblem::Status status);

nlohmann::json mesh_report_json(const geometry::MeshReport& report);

/// The regions where the surface crosses itself and is used as given, largest first:
/// [{"what", "why", "centre", "size", "box": {"min", "max"}, "pairs"}].
nlohmann::json defects_json(const std::vector<geometry::DefectZone>& defects);

}  // namespace bemshape::apps
