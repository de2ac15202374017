#pragma once
// The JSON report of a thickness run (`bemshape thickness --report`, the "report" of the
// Python module's thickness()): parameters, the units check's warning, mesh sizes, the
// thickness statistics, the check (its verdict, the thin area, its thin regions and the specks
// set aside, all most severe first), the solver's figures, stage times and memory. Lengths in
// the input's units.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "analysis/measure_thickness.hpp"
#include "analysis/stage_times.hpp"
#include "apps/report/report_json.hpp"
#include "apps/report/units_check.hpp"

namespace bemshape::apps {

/// Where a thickness run's input came from and its outputs went, as the user named them.
struct ThicknessRunNames {
  std::string input;                         ///< file path, or the name of the arrays
  std::string measure;                       ///< the measure as the user chose it ("principal", …)
  std::optional<std::string> output;         ///< -o file, if any
  std::optional<std::string> solver_output;  ///< --solver-output file, if any
};

/// The report of `result`, computed with `options`; `times` holds every stage of the run
/// (the job's and the front end's, e.g. "write"); `units` the front end's units check.
nlohmann::json thickness_report_json(const analysis::ThicknessOptions& options,
                                     const analysis::ThicknessResult& result,
                                     const ThicknessRunNames& names,
                                     const analysis::StageTimes& times, const RunFigures& run,
                                     const UnitsCheck& units = {});

}  // namespace bemshape::apps
