#include "apps/report/mesh_report_json.hpp"

#include "apps/report/report_json.hpp"

namespace bemshape::apps {

const char* problem_status_label(geometry::MeshProblem::Status status) {
  using Status = geometry::MeshProblem::Status;
  switch (status) {
    case Status::repaired:
      return "repaired";
    case Status::refused:
      return "REFUSED";
    case Status::note:
      return "note";
    case Status::defect:
      return "DEFECT";
  }
  return "";
}

nlohmann::json defects_json(const std::vector<geometry::DefectZone>& defects) {
  nlohmann::json list = nlohmann::json::array();
  for (const geometry::DefectZone& d : defects)
    list.push_back({{"what", d.what},
                    {"why", d.why},
                    {"centre", point_json(d.centre())},
                    {"size", d.size()},
                    {"box", {{"min", point_json(d.box.min)}, {"max", point_json(d.box.max)}}},
                    {"pairs", d.pairs}});
  return list;
}

nlohmann::json mesh_report_json(const geometry::MeshReport& r) {
  nlohmann::json problems = nlohmann::json::array();
  for (const geometry::MeshProblem& p : r.problems)
    problems.push_back({{"status", problem_status_label(p.status)},
                        {"what", p.what},
                        {"count", p.count},
                        {"first_at", point_json(p.first)},
                        {"consequence", p.consequence}});
  return {{"source", r.source},
          {"format", r.format},
          {"unit", r.unit},
          {"converted_from", r.converted_from},
          {"triangles_read", r.triangles_read},
          {"vertices_read", r.vertices_read},
          {"faces", r.faces},
          {"vertices", r.vertices},
          {"shells", r.shells},
          {"cavities", r.cavities},
          {"volume", r.volume},
          {"area", r.area},
          {"bounding_box",
           {{"min", point_json(r.bounding_box.min)}, {"max", point_json(r.bounding_box.max)}}},
          {"weld_tolerance", r.weld_tolerance},
          {"problems", problems},
          {"repairs", r.repairs},
          {"defects", defects_json(r.defects)},
          {"usable", r.usable()}};
}

}  // namespace bemshape::apps
