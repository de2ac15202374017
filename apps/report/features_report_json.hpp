#pragma once
// The JSON report of a features run (`bemshape features --report`, the "report" of the
// Python module's features()): parameters, mesh sizes, the points (count, inside, the grid),
// the range of h_f and h_p over the inside points with the position of their minimum, the
// solver's figures, stage times and memory. Lengths in the input's units.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "analysis/measure_features.hpp"
#include "analysis/stage_times.hpp"
#include "apps/report/report_json.hpp"

namespace bemshape::apps {

/// The report of `result`, computed with `options`; `input` names the mesh, `output` the file
/// the values went to (if any), `times` holds every stage of the run.
nlohmann::json features_report_json(const analysis::FeaturesOptions& options,
                                    const analysis::FeaturesResult& result,
                                    const std::string& input,
                                    const std::optional<std::string>& output,
                                    const analysis::StageTimes& times, const RunFigures& run);

}  // namespace bemshape::apps
