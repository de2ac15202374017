// analysis/memory_budget.hpp: what a held allocation leaves of --max-memory, and the dense
// system's refusal, whose suggested --max-edge gives a system within the budget.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <string>

#include "analysis/memory_budget.hpp"
#include "bem/solve/dense_transmission_solver.hpp"
#include "core/errors.hpp"

using namespace bemshape;

TEST_CASE("remaining memory limit: the rest of --max-memory, at least a byte, none stays none") {
  CHECK(analysis::remaining_memory_limit(0, 12345) == 0);
  CHECK(analysis::remaining_memory_limit(1000, 300) == 700);
  CHECK(analysis::remaining_memory_limit(1000, 1000) == 1);
  CHECK(analysis::remaining_memory_limit(1000, 5000) == 1);
}

TEST_CASE("dense system refused with a --max-edge whose mesh fits in the budget") {
  const std::uint64_t budget = 20'000'000;  // 20 MB: 559 faces at 64·N² bytes
  analysis::DenseSystemRefusal refusal;
  refusal.source = "part.stl";
  refusal.solver_faces = 5000;
  refusal.max_edge = 0.1;
  refusal.max_edge_rule = "--max-edge";
  refusal.flat_wall_max_edge = 0.25;
  refusal.max_memory_bytes = budget;
  std::string message;
  try {
    analysis::refuse_dense_system(refusal, budget);
  } catch (const ResourceError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.rfind("part.stl: the dense BEM solver needs ", 0) == 0);
  std::smatch edge;
  REQUIRE(std::regex_search(message, edge, std::regex("e\\.g\\. --max-edge ([0-9.e+-]+)")));
  // Faces scale like 1/edge²: the suggested edge's mesh and its dense system.
  const double suggested = std::stod(edge[1].str());
  const auto faces =
      static_cast<Eigen::Index>(std::ceil(5000.0 * std::pow(refusal.max_edge / suggested, 2)));
  CHECK(bem::dense_solver_memory_bytes(faces) <= budget);
  CHECK(bem::dense_solver_memory_bytes(2 * faces) > budget);  // not far below it either
  CHECK(message.find("up to --max-edge 0.25") != std::string::npos);
  // Within the budget nothing is refused (500 faces: 16 MB); a 5000-face system is.
  refusal.solver_faces = 500;
  CHECK_NOTHROW(analysis::require_dense_system_fits(refusal));
  refusal.solver_faces = 5000;
  CHECK_THROWS_AS(analysis::require_dense_system_fits(refusal), ResourceError);
}
