#include "apps/part_summary.hpp"

#include "apps/exit_codes.hpp"
#include "core/errors.hpp"

namespace bemshape::apps {
namespace {

/// report[a][b], or InputError naming the report and the field.
const nlohmann::json& field(const nlohmann::json& report, const std::string& report_path,
                            const char* a, const char* b) {
  const auto outer = report.find(a);
  if (outer == report.end() || !outer->is_object() || !outer->contains(b))
    throw InputError(report_path + ": not a complete thickness report with a check (no " +
                     std::string(a) + "." + b + "); run the part again without --resume");
  return (*outer)[b];
}

}  // namespace

nlohmann::ordered_json part_summary_from_report(const std::string& part,
                                                const nlohmann::json& report,
                                                const std::string& report_path, bool resumed) {
  const bool pass = field(report, report_path, "check", "pass").get<bool>();
  const nlohmann::json& regions = field(report, report_path, "check", "regions");
  return {{"part", part},
          {"verdict", pass ? kVerdictPass : kVerdictThin},
          {"exit_code", pass ? kExitSuccess : kExitCheckFailed},
          {"threshold", field(report, report_path, "check", "threshold")},
          {"min_thickness", field(report, report_path, "thickness", "min")},
          {"min_location", field(report, report_path, "thickness", "min_location")},
          {"regions", regions.size()},
          {"thin_area", field(report, report_path, "check", "thin_area")},
          {"h0", field(report, report_path, "parameters", "h0")},
          {"units_warning", report.value("units_warning", nlohmann::json(nullptr))},
          {"seconds", field(report, report_path, "timing", "total")},
          {"peak_mb", field(report, report_path, "memory", "peak_mb")},
          {"error", nullptr},
          {"report", report_path},
          {"resumed", resumed}};
}

nlohmann::ordered_json part_summary_without_report(const std::string& part, const char* verdict,
                                                   const std::string& error, int exit_code,
                                                   double threshold, double seconds,
                                                   std::optional<double> peak_mb) {
  return {{"part", part},
          {"verdict", verdict},
          {"exit_code", exit_code},
          {"threshold", threshold},
          {"min_thickness", nullptr},
          {"min_location", nullptr},
          {"regions", nullptr},
          {"thin_area", nullptr},
          {"h0", nullptr},
          {"units_warning", nullptr},
          {"seconds", seconds},
          {"peak_mb", peak_mb ? nlohmann::ordered_json(*peak_mb) : nlohmann::ordered_json(nullptr)},
          {"error", error},
          {"report", nullptr},
          {"resumed", false}};
}

}  // namespace bemshape::apps
