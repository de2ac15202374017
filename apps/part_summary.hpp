#pragma once
// One line of `bemshape check-all`'s JSON-lines summary: what a release gate needs of one
// part, taken from its thickness report (apps/report/thickness_report_json.hpp) or, for a
// part without a report, from how its process ended. docs/usage.md, "bemshape check-all",
// lists the fields; the Python module's bemshape.dask (python/bemshape/dask.py) writes the
// same records, and python/tests/test_dask.py compares the two.
//
//   part          the part's path, as given
//   verdict       "pass" | "thin" (a wall thinner than threshold) | "error" (no verdict:
//                 unreadable or invalid file, memory refused, numerical failure, crash) |
//                 "timeout" (--timeout reached) | "interrupted" (the set was stopped first)
//   exit_code     what `bemshape thickness` exits with for the part (0, 1, 2, 3, 128 + signal)
//   threshold     --min-thickness
//   min_thickness, min_location   the thinnest wall and where (null without a verdict)
//   regions       the number of thin regions listed (specks set aside: not counted)
//   thin_area     the area of every face thinner than threshold, specks included
//   h0            the characteristic length used
//   units_warning the part's units warning (apps/report/units_check.hpp), or null
//   seconds       the part's wall time [s];  peak_mb  its peak resident memory [MB]
//   error         the part's error message, null with a verdict
//   report        the part's JSON report, null without one;  resumed  true if --resume
//                 took the part from an existing report

#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace bemshape::apps {

/// The verdicts of a part, as the summary spells them.
inline constexpr const char* kVerdictPass = "pass";
inline constexpr const char* kVerdictThin = "thin";
inline constexpr const char* kVerdictError = "error";
inline constexpr const char* kVerdictTimeout = "timeout";
inline constexpr const char* kVerdictInterrupted = "interrupted";

/// The record of a part whose thickness report `report` (as `thickness --report` writes it,
/// with a check) is at `report_path`. Throws InputError if the report lacks a field the
/// record needs (e.g. no check: it was made without --min-thickness).
nlohmann::ordered_json part_summary_from_report(const std::string& part,
                                                const nlohmann::json& report,
                                                const std::string& report_path, bool resumed);

/// The record of a part that has no report: its `verdict` (error, timeout, interrupted),
/// `error` message and `exit_code`, with what was measured of its run.
nlohmann::ordered_json part_summary_without_report(const std::string& part, const char* verdict,
                                                   const std::string& error, int exit_code,
                                                   double threshold, double seconds,
                                                   std::optional<double> peak_mb);

}  // namespace bemshape::apps
