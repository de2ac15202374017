// `bemshape check-all` end to end (apps/check_all_command.hpp): the set's exit code, an
// unreadable part among good ones, the summary against the reports, the parts a folder and a
// list name, --resume after a SIGINT mid-set, and --timeout per part. The parts are plates
// of known wall (2 × 2 × t) at a coarse mesh, a fraction of a second each.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <set>
#include <thread>

#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"
#include "tests/support/time_bound.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

/// The options every run below gives its parts: h0 near the plates' walls and a coarse mesh
/// (about 500 solver faces per plate); walls thinner than 0.25 fail.
const std::string kPartOptions = " --min-thickness 0.25 --h0 0.3 --max-edge 0.3 --quiet";

/// A plate 2 × 2 × `wall` as binary STL at `path`.
void write_plate(const fs::path& path, double wall) {
  fs::create_directories(path.parent_path());
  const geometry::SurfaceMesh plate =
      geometry::make_box(Eigen::Vector3d(-1, -1, -wall / 2), Eigen::Vector3d(1, 1, wall / 2), 0.3);
  output::write_binary_stl(path.string(), plate.vertices(), plate.faces());
}

/// A file named like a mesh that no reader accepts.
void write_unreadable(const fs::path& path) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "this is not a mesh\n";
}

/// The summary's records, one per line.
std::vector<nlohmann::json> read_summary(const fs::path& path) {
  std::vector<nlohmann::json> records;
  std::istringstream lines(slurp(path));
  std::string line;
  while (std::getline(lines, line))
    records.push_back(nlohmann::json::parse(line));
  return records;
}

/// Files under `folder` whose name marks an AtomicFileWriter temporary (".<name>.tmp-").
int temporaries_under(const fs::path& folder) {
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos)
      ++count;
  return count;
}

std::string quoted(const fs::path& path) {
  return std::string(1, '\'').append(path.string()).append(1, '\'');
}

/// parts/p<i>.stl and its report's name (built by append: GCC 12 warns, wrongly, of
/// overlapping copies in "p" + std::to_string(i) + ".stl" with -Wrestrict).
std::string numbered(const char* prefix, int i, const char* suffix) {
  return std::string(prefix).append(std::to_string(i)).append(suffix);
}

}  // namespace

TEST_CASE(
    "check-all: exit 2 with an unreadable part among good ones, whose reports and "
    "summary agree; 1 and 0 when only thin and passing parts remain") {
  const fs::path parts = scratch_folder() / "exit_codes";
  write_plate(parts / "a_thick.stl", 0.4);
  write_plate(parts / "b_thin.stl", 0.15);
  write_unreadable(parts / "c_bad.stl");
  const fs::path reports = scratch_folder() / "exit_codes_reports";
  const Run all = run_bemshape("check-all " + quoted(parts) + " --reports " + quoted(reports) +
                               " --jobs 2" + kPartOptions);
  CAPTURE(all.out, all.err);
  REQUIRE(all.exit_code == 2);
  const std::vector<nlohmann::json> records = read_summary(reports / "summary.jsonl");
  REQUIRE(records.size() == 3);
  // In the parts' order (a folder's files in path order), whatever order they finished in.
  CHECK(records[0]["part"] == (parts / "a_thick.stl").string());
  CHECK(records[1]["part"] == (parts / "b_thin.stl").string());
  CHECK(records[2]["part"] == (parts / "c_bad.stl").string());
  CHECK(records[0]["verdict"] == "pass");
  CHECK(records[1]["verdict"] == "thin");
  CHECK(records[2]["verdict"] == "error");
  CHECK(records[2]["exit_code"] == 2);
  CHECK(records[2]["error"].get<std::string>().find("c_bad.stl") != std::string::npos);
  CHECK(records[2]["report"].is_null());
  CHECK(!fs::exists(reports / "c_bad.stl.json"));
  // The checked parts' records are their reports' figures; the plates read their walls.
  for (int i : {0, 1}) {
    const nlohmann::json& r = records[std::size_t(i)];
    CAPTURE(r.dump());
    const nlohmann::json report = read_json(r["report"].get<std::string>());
    CHECK(report["input"] == r["part"]);
    CHECK(r["min_thickness"] == report["thickness"]["min"]);
    CHECK(r["min_location"] == report["thickness"]["min_location"]);
    CHECK(r["regions"] == report["check"]["regions"].size());
    CHECK(r["threshold"] == 0.25);
    CHECK(r["h0"] == 0.3);
    CHECK(r["error"].is_null());
    CHECK(r["resumed"] == false);
    CHECK(r["peak_mb"].get<double>() > 0.0);
  }
  CHECK(records[0]["min_thickness"].get<double>() == Approx(0.4).epsilon(0.05));
  CHECK(records[0]["regions"] == 0);
  CHECK(records[1]["min_thickness"].get<double>() == Approx(0.15).epsilon(0.1));
  CHECK(records[1]["regions"].get<int>() >= 1);
  CHECK(records[1]["thin_area"].get<double>() > 4.0);  // most of both faces of the plate
  // One line per part on stdout, counted, and the totals.
  CHECK(all.out.find("[1/3]") != std::string::npos);
  CHECK(all.out.find("[3/3]") != std::string::npos);
  CHECK(all.out.find("1 pass, 1 thin, 1 without verdict") != std::string::npos);

  // Without the unreadable part the set fails on the thin one (exit 1), and with the
  // passing part alone it passes (exit 0); --resume takes both from their reports.
  fs::remove(parts / "c_bad.stl");
  const Run thin = run_bemshape("check-all " + quoted(parts) + " --reports " + quoted(reports) +
                                " --resume" + kPartOptions);
  CAPTURE(thin.out, thin.err);
  CHECK(thin.exit_code == 1);
  for (const nlohmann::json& r : read_summary(reports / "summary.jsonl"))
    CHECK(r["resumed"] == true);
  const Run pass = run_bemshape("check-all " + quoted(parts / "a_thick.stl") + " --reports " +
                                quoted(reports) + " --resume" + kPartOptions);
  CAPTURE(pass.out, pass.err);
  CHECK(pass.exit_code == 0);
}

TEST_CASE(
    "check-all: parts from folders (recursively, hidden ones skipped) and a list file, "
    "each once, with reports named after their path") {
  const fs::path root = scratch_folder() / "listing";
  write_plate(root / "x" / "part.stl", 0.4);
  write_plate(root / "y" / "part.STL", 0.4);  // the same name in another folder
  write_plate(root / "y" / ".hidden" / "skip.stl", 0.4);
  std::ofstream(root / "y" / "notes.txt") << "not a part\n";
  write_plate(root / "listed" / "z.stl", 0.4);
  const fs::path list = root / "parts.txt";
  std::ofstream(list) << "# parts of the order\n\n"
                      << (root / "listed" / "z.stl").string() << "\n"
                      << (root / "x" / "part.stl").string() << "\n";  // named twice
  const fs::path reports = scratch_folder() / "listing_reports";
  const Run r =
      run_bemshape("check-all " + quoted(root / "x") + " " + quoted(root / "y") + " --list " +
                   quoted(list) + " --reports " + quoted(reports) + " --jobs 2" + kPartOptions);
  CAPTURE(r.out, r.err);
  REQUIRE(r.exit_code == 0);
  const std::vector<nlohmann::json> records = read_summary(reports / "summary.jsonl");
  REQUIRE(records.size() == 3);
  CHECK(records[0]["part"] == (root / "x" / "part.stl").string());
  CHECK(records[1]["part"] == (root / "y" / "part.STL").string());
  CHECK(records[2]["part"] == (root / "listed" / "z.stl").string());
  CHECK(records[0]["report"] == (reports / "x" / "part.stl.json").string());
  CHECK(records[1]["report"] == (reports / "y" / "part.STL.json").string());
  CHECK(records[2]["report"] == (reports / "listed" / "z.stl.json").string());
  // --resume with other options refuses instead of mixing verdicts of two thresholds.
  const Run other =
      run_bemshape("check-all " + quoted(root / "x") + " --reports " + quoted(reports) +
                   " --resume --min-thickness 0.3 --h0 0.3 "
                   "--max-edge 0.3 --quiet");
  CHECK(other.exit_code == 2);
  CHECK(other.first_error_line().find("other options") != std::string::npos);
}

TEST_CASE(
    "check-all: SIGINT mid-set stops cleanly (exit 130, no half-written report), and "
    "--resume checks only the parts left") {
  const fs::path parts = scratch_folder() / "interrupt";
  constexpr int kParts = 6;
  for (int i = 0; i < kParts; ++i)
    write_plate(parts / numbered("p", i, ".stl"), 0.3 + 0.02 * i);
  const fs::path reports = scratch_folder() / "interrupt_reports";
  const std::string out_file = scratch("interrupt.stdout"), err_file = scratch("interrupt.stderr");
  std::vector<std::string> args = {BEMSHAPE_EXECUTABLE,
                                   "check-all",
                                   parts.string(),
                                   "--reports",
                                   reports.string(),
                                   "--jobs",
                                   "1",
                                   "--min-thickness",
                                   "0.25",
                                   "--h0",
                                   "0.3",
                                   "--max-edge",
                                   "0.3",
                                   "--quiet"};
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (!std::freopen(out_file.c_str(), "w", stdout) ||
        !std::freopen(err_file.c_str(), "w", stderr))
      ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  // Once the first part's report is there (parts start largest file first), the second part
  // is running: interrupt the set.
  auto first_report = [&] {
    for (int i = 0; i < kParts; ++i)
      if (fs::exists(reports / numbered("p", i, ".stl.json")))
        return true;
    return false;
  };
  const auto started = std::chrono::steady_clock::now();
  while (!first_report() && std::chrono::steady_clock::now() - started < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(first_report());
  ::kill(pid, SIGINT);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  CAPTURE(slurp(out_file), slurp(err_file));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(slurp(err_file).find("--resume") != std::string::npos);
  // Nothing half-written: every report there is complete, no temporary is left.
  CHECK(temporaries_under(reports) == 0);
  std::set<std::string> reported;
  for (int i = 0; i < kParts; ++i) {
    const fs::path report = reports / numbered("p", i, ".stl.json");
    if (!fs::exists(report))
      continue;
    CHECK(read_json(report.string())["check"]["pass"] == true);
    reported.insert((parts / numbered("p", i, ".stl")).string());
  }
  CHECK(!reported.empty());
  REQUIRE(reported.size() < std::size_t(kParts));
  // One job: the first part checked is a largest file.
  std::uintmax_t largest = 0;
  for (int i = 0; i < kParts; ++i)
    largest = std::max(largest, fs::file_size(parts / numbered("p", i, ".stl")));
  const std::string out = slurp(out_file);
  const std::size_t line_end = out.find('\n');
  REQUIRE(line_end != std::string::npos);
  const std::size_t path_start = out.rfind(' ', line_end) + 1;
  CHECK(fs::file_size(out.substr(path_start, line_end - path_start)) == largest);
  // The summary of the stopped set lists every part: checked, or interrupted.
  for (const nlohmann::json& r : read_summary(reports / "summary.jsonl"))
    CHECK(r["verdict"] == (reported.count(r["part"]) ? "pass" : "interrupted"));

  const Run resumed = run_bemshape("check-all " + quoted(parts) + " --reports " + quoted(reports) +
                                   " --resume --jobs 2" + kPartOptions);
  CAPTURE(resumed.out, resumed.err);
  CHECK(resumed.exit_code == 0);
  const std::vector<nlohmann::json> records = read_summary(reports / "summary.jsonl");
  REQUIRE(records.size() == std::size_t(kParts));
  for (const nlohmann::json& r : records) {
    CAPTURE(r.dump());
    CHECK(r["verdict"] == "pass");
    CHECK(r["resumed"] == (reported.count(r["part"]) == 1));
  }
}

TEST_CASE("check-all: --timeout stops a slow part (verdict timeout) and not the others") {
  const fs::path parts = scratch_folder() / "timeout";
  fs::create_directories(parts);
  // About 36,000 faces at --max-edge 0.016: minutes of solving, far beyond the 8 s limit on
  // any machine; the cube, about 700 solver faces, takes half a second. The sanitizer build
  // runs both 5-15 times slower and its limit is 20 times longer (support/time_bound.hpp).
  const double timeout = bemshape::test::time_bound(8.0);
  const geometry::SurfaceMesh ball =
      geometry::make_geodesic_sphere(0.5, geometry::geodesic_frequency_for_edge(0.5, 0.016));
  output::write_binary_stl((parts / "a_slow_ball.stl").string(), ball.vertices(), ball.faces());
  const geometry::SurfaceMesh cube =
      geometry::make_box(Eigen::Vector3d::Constant(-0.05), Eigen::Vector3d::Constant(0.05), 0.016);
  output::write_binary_stl((parts / "b_small_cube.stl").string(), cube.vertices(), cube.faces());
  const fs::path reports = scratch_folder() / "timeout_reports";
  const Run r = run_bemshape("check-all " + quoted(parts) + " --reports " + quoted(reports) +
                             " --jobs 2 --timeout " + std::to_string(long(timeout)) +
                             " --min-thickness 0.05 --h0 0.3 --max-edge 0.016 --quiet");
  CAPTURE(r.out, r.err);
  CHECK(r.exit_code == 2);
  const std::vector<nlohmann::json> records = read_summary(reports / "summary.jsonl");
  REQUIRE(records.size() == 2);
  CHECK(records[0]["verdict"] == "timeout");
  CHECK(records[0]["exit_code"] == 3);
  CHECK(records[0]["error"].get<std::string>().find("--timeout") != std::string::npos);
  CHECK(records[0]["seconds"].get<double>() >= timeout);
  CHECK(records[1]["verdict"] == "pass");
  CHECK(temporaries_under(reports) == 0);
}
