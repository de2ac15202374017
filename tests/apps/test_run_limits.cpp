// apps/run_limits.hpp end to end: --timeout and SIGINT stop a long solve cleanly (exit code,
// one-line message, no output file, an existing output untouched, no temporary file left),
// and --max-memory accepts units and refuses what does not fit (meshes, voxel grids, images,
// and both halves of compare).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <regex>
#include <thread>

#include "tests/support/labelled_parts.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"
#include "tests/support/resident_bound.hpp"
#include "tests/support/time_bound.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

/// A ball (R = 0.5) whose solve at --max-edge 0.055 takes far longer than the limits below:
/// about 2400 solver faces; dense: a 4800² system (0.37 GB), a minute of assembly on two
/// cores; H-matrix (the default above 2000 faces): about 45 s.
const char* kSlowOptions = " --h0 0.3 --max-edge 0.055";

/// The memory watch's limit in the running-account test [bytes]: above what the process
/// holds when the watch starts, below the H-matrix assembly's peak on the slow ball (4280
/// solver faces; its estimated peak is 0.16 GB).
constexpr unsigned long long kAccountLimit = bemshape::test::resident_bound_mb(100) * 1'000'000;

std::string slow_ball() {
  static const std::string path = write_mesh(geometry::make_geodesic_sphere(0.5, 8), "slow_ball.stl");
  return path;
}

/// Files in the scratch folder whose name starts with ".<name>.tmp-" (AtomicFileWriter's
/// temporaries).
int temporaries_of(const std::string& name) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(scratch_folder()))
    if (entry.path().filename().string().rfind("." + name + ".tmp-", 0) == 0) ++count;
  return count;
}

struct Child {
  pid_t pid = -1;
  std::string err_file;
};

/// Starts `bemshape <arguments...>` with stdout and stderr in files; does not wait.
Child start_bemshape(const std::vector<std::string>& arguments, const std::string& tag) {
  Child child;
  child.err_file = scratch(tag + ".stderr");
  const std::string out_file = scratch(tag + ".stdout");
  std::vector<std::string> argv_strings{BEMSHAPE_EXECUTABLE};
  argv_strings.insert(argv_strings.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  child.pid = ::fork();
  REQUIRE(child.pid >= 0);
  if (child.pid == 0) {
    if (!std::freopen(out_file.c_str(), "w", stdout) ||
        !std::freopen(child.err_file.c_str(), "w", stderr))
      ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return child;
}

/// Waits for `child`; returns its exit code (-signal if a signal ended it).
int wait_for(const Child& child) {
  int status = 0;
  REQUIRE(::waitpid(child.pid, &status, 0) == child.pid);
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return WEXITSTATUS(status);
}

}  // namespace

TEST_CASE("thickness --timeout 1 on a minute-long solve: exit 3 within seconds, one line, no output") {
  // Both solvers: the dense path polls every assembly row and LU panel, the H-matrix path
  // every assembled block, near-field row and GMRES iteration.
  for (const std::string solver : {"dense", "hmatrix"}) {
    const std::string out = scratch("timeout_" + solver + ".csv");
    const Run r = run_bemshape("thickness '" + slow_ball() + "'" + kSlowOptions + " --solver " +
                               solver + " --timeout 1 --quiet -o '" + out + "'");
    CAPTURE(solver, r.out, r.err, r.seconds);
    CHECK(r.exit_code == 3);
    CHECK(r.err ==
          "bemshape: error: time limit of 1 s (--timeout) reached; stopped cleanly, no "
          "output file was written or changed; raise --timeout or use a coarser mesh\n");
    // Reading and remeshing take a fraction of a second; the rest is one unit of work.
    CHECK(r.seconds < bemshape::test::time_bound(10.0));
    CHECK_FALSE(fs::exists(out));
    CHECK(temporaries_of("timeout_" + solver + ".csv") == 0);
  }
}

TEST_CASE("thickness --timeout leaves an existing output file byte for byte as it was") {
  const std::string out = scratch("kept.csv");
  const std::string before = "x,y,z\n1,2,3\n";
  std::ofstream(out, std::ios::binary) << before;
  const Run r = run_bemshape("thickness '" + slow_ball() + "'" + kSlowOptions +
                             " --timeout 0.5 --quiet -o '" + out + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 3);
  CHECK(slurp(out) == before);
  CHECK(temporaries_of("kept.csv") == 0);
}

TEST_CASE("features and fem --timeout: exit 3 as well") {
  const Run features = run_bemshape("features '" + slow_ball() + "'" + kSlowOptions +
                                    " --grid 0.1 --timeout 1 --quiet -o '" +
                                    scratch("features_timeout.vti") + "'");
  CAPTURE(features.err);
  CHECK(features.exit_code == 3);
  CHECK_THAT(features.err, Catch::Contains("--timeout"));
  CHECK_FALSE(fs::exists(scratch("features_timeout.vti")));
  // Cells of 0.012 on a ball of diameter 1: about 128³ cells, voxelisation and CG take
  // well over a second.
  const Run fem = run_bemshape("fem '" + slow_ball() + "' --cell 0.012 --timeout 1 -o '" +
                               scratch("fem_timeout.vti") + "'");
  CAPTURE(fem.err);
  CHECK(fem.exit_code == 3);
  CHECK_THAT(fem.err, Catch::Contains("--timeout"));
  CHECK_FALSE(fs::exists(scratch("fem_timeout.vti")));
}

TEST_CASE("timeout must be a positive number of seconds") {
  for (const char* value : {"0", "-3", "abc"}) {
    const Run r = run_bemshape("thickness '" + slow_ball() + "' --h0 0.3 --timeout " + value);
    CAPTURE(value, r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--timeout"));
  }
}

TEST_CASE("SIGINT during the solve: exit 130, one line, no output, existing output untouched") {
  const std::string out = scratch("interrupted.csv");
  const std::string before = "previous result\n";
  std::ofstream(out, std::ios::binary) << before;
  const Child child = start_bemshape(
      {"thickness", slow_ball(), "--h0", "0.3", "--max-edge", "0.055", "-o", out}, "sigint");
  // The progress display (stderr is not a terminal: one line per finished stage) reports
  // "remeshing done" when the assembly starts.
  const auto start = std::chrono::steady_clock::now();
  while (slurp(child.err_file).find("remeshing") == std::string::npos &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto sent = std::chrono::steady_clock::now();
  REQUIRE(::kill(child.pid, SIGINT) == 0);
  const int code = wait_for(child);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string err = slurp(child.err_file);
  CAPTURE(err, seconds);
  CHECK(code == 130);
  CHECK_THAT(err, Catch::EndsWith("bemshape: error: interrupted by signal 2; stopped cleanly, "
                                  "no output file was written or changed\n"));
  CHECK_THAT(err, Catch::Contains("assemble") && Catch::Contains("stopped"));  // not "done"
  CHECK(seconds < bemshape::test::time_bound(10.0));
  CHECK(slurp(out) == before);
  CHECK(temporaries_of("interrupted.csv") == 0);
}

TEST_CASE("SIGTERM stops the run the same way, exit 143") {
  const Child child = start_bemshape(
      {"thickness", slow_ball(), "--h0", "0.3", "--max-edge", "0.055", "--quiet"}, "sigterm");
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  REQUIRE(::kill(child.pid, SIGTERM) == 0);
  CHECK(wait_for(child) == 143);
  CHECK_THAT(slurp(child.err_file), Catch::Contains("interrupted by signal 15"));
}

TEST_CASE("max-memory with units: too small is refused naming the option, bad units too") {
  const std::string mesh = write_mesh(geometry::make_geodesic_sphere(0.5, 3), "small_ball.stl");
  // About 80 solver faces at --max-edge 0.3: a 160² system, 0.4 MB with its copy.
  Run r =
      run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.3 --max-memory 100KB --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("(--max-memory)") && Catch::Contains("--max-edge"));
  r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.3 --max-memory 0.5KiB --quiet");
  CHECK(r.exit_code == 2);
  for (const char* bad : {"12XB", "0", "-5", "G"}) {
    r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-memory " + bad);
    CAPTURE(bad, r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--max-memory '") && Catch::Contains("expected a positive size"));
  }
  r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.3 --max-memory 0.5GiB --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 0);
  r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.3 --max-memory 500 --quiet");
  CHECK(r.exit_code == 0);  // plain number: MB
}

TEST_CASE("hmatrix --max-memory: the exterior matrix's size follows the element size in kappa") {
  // h0 = 3 on a ball of radius 0.5: κ = 2/(a·h0) = 3.3 and the exterior cutoff 18.4/κ = 5.5 is
  // wider than the ball, so every pair of the N ≈ 10⁴ solver faces at --max-edge 0.03 is
  // kept: 2N entries per exterior row, 12·2N² bytes, several GB. An estimate at the default
  // element size's ~1300 entries per row would put the whole solver below 1 GB and let it
  // start.
  const std::string mesh = write_mesh(geometry::make_geodesic_sphere(0.5, 8), "wide_cutoff_ball.stl");
  const Run r = run_bemshape("thickness '" + mesh +
                             "' --h0 3 --max-edge 0.03 --solver hmatrix --max-memory 1G --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("the hierarchical-matrix BEM system of") &&
                        Catch::Contains("(--max-memory)") && Catch::Contains("--max-edge"));
}

TEST_CASE("hmatrix --max-memory: a part whose estimate exceeds it is refused in seconds") {
  // The tube (labelled part, 3 mm wall) at --max-edge 1: 72328 solver faces (the facet
  // creases of its 128-sided cylinders), whose estimated peak is 2.28 GB; refused after
  // remeshing, before any assembly. The process then holds about 0.15 GB, and up to 0.5 GB in
  // the sanitizer build (whose allocator keeps freed memory for a while): 1 GB lets the
  // remeshing finish in both.
  const std::string mesh = write_mesh(testing::make_labelled_part("tube").mesh, "tube.stl");
  const std::string out = scratch("tube_refused.csv");
  const Run r = run_bemshape("thickness '" + mesh +
                             "' --h0 3 --max-edge 1 --max-memory 1G --quiet -o '" + out + "'");
  CAPTURE(r.err, r.seconds);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::StartsWith("bemshape: error: " + mesh +
                               ": the hierarchical-matrix BEM system of ") &&
                 Catch::Contains(" GB (estimated peak of the process) but only 1 GB may be "
                                 "used (--max-memory); use a coarser mesh (larger --max-edge)") &&
                 Catch::Contains("or a larger --max-memory; a mesh that fits: --max-edge ") &&
                 Catch::EndsWith("or --fit-memory to take it"));
  // Remeshing, counting, and remeshing and counting again at the edge named (about 45 s alone
  // on the 2-core machine, up to 110 s beside another test); nothing assembled, which at
  // 72328 faces would take many minutes.
  CHECK(r.seconds < bemshape::test::time_bound(150.0));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE(
    "thickness --max-memory below the default mesh's need: the refusal names a --max-edge that "
    "fits, and --fit-memory takes a mesh that fits itself, saying so") {
  // The L-bracket (labelled part, 32 segments) at its default graded mesh: about 4400 solver
  // faces, an H-matrix estimate of 0.13 GB. 50 MB (plus the sanitizers' overhead) is above
  // what the process holds (about 22 MB) and far below that estimate: the fitting mesh has a
  // few hundred faces, solved densely in seconds.
  const std::string mesh =
      write_mesh(testing::make_labelled_part("l-bracket", 32).mesh, "fit_bracket.stl");
  const double budget_mb = double(bemshape::test::resident_bound_mb(50));
  const std::string budget = " --max-memory " + std::to_string(long(budget_mb)) + "MB";
  const Run refused = run_bemshape("thickness '" + mesh + "' --min-thickness 2" + budget + " --quiet");
  CAPTURE(refused.err);
  REQUIRE(refused.exit_code == 2);  // refused, not ended by a signal
  std::smatch named_mesh;
  const std::string line = refused.first_error_line();
  REQUIRE(std::regex_search(
      line, named_mesh,
      std::regex("; a mesh that fits: --max-edge ([0-9.e+-]+) \\(([0-9]+) solver faces, "
                 "estimated peak ([0-9.e+-]+) GB; ([^)]*)\\), or --fit-memory to take it$")));
  const std::string edge = named_mesh[1].str();
  const long named_faces = std::stol(named_mesh[2].str());
  CHECK(std::stod(named_mesh[3].str()) * 1e3 < budget_mb);  // the solver's estimate fits
  CHECK(!named_mesh[4].str().empty());                       // the accuracy to expect there

  // The named setting runs within the same budget, on the mesh the refusal counted.
  const std::string named_report = scratch("fit_named.json");
  const Run named = run_bemshape("thickness '" + mesh + "' --min-thickness 2 --max-edge " + edge +
                                 budget + " --quiet --report '" + named_report + "'");
  CAPTURE(named.err);
  REQUIRE((named.exit_code == 0 || named.exit_code == 1));
  const nlohmann::json named_json = read_json(named_report);
  CHECK(named_json["mesh"]["memory_fit"].is_null());
  CHECK(named_json["mesh"]["solver_faces"].get<long>() == named_faces);
  CHECK(named_json["memory"]["peak_mb"].get<double>() < budget_mb);

  // --fit-memory takes such a mesh itself, says so on stderr and in the report.
  const std::string fitted_report = scratch("fit_memory.json");
  const std::string fitted_map = scratch("fit_memory.csv");
  const Run fitted = run_bemshape("thickness '" + mesh + "' --min-thickness 2 --fit-memory" +
                                  budget + " --quiet --report '" + fitted_report + "' -o '" +
                                  fitted_map + "'");
  CAPTURE(fitted.err);
  REQUIRE((fitted.exit_code == 0 || fitted.exit_code == 1));
  CHECK_THAT(fitted.err, Catch::Contains("bemshape: --fit-memory: the solver mesh of "));
  const nlohmann::json report = read_json(fitted_report);
  const nlohmann::json& fit = report["mesh"]["memory_fit"];
  CAPTURE(fit.dump());
  REQUIRE(fit.is_object());
  CHECK(fit["fitted"] == true);
  CHECK(fit["max_edge"].get<double>() > 0.0);  // the edge taken (as the refusal named, up to
                                                // what the process held when it predicted)
  CHECK(fit["refused_faces"].get<long>() > fit["solver_faces"].get<long>());
  CHECK(fit["refused_gb"].get<double>() > fit["budget_gb"].get<double>());
  CHECK(report["mesh"]["solver_faces"] == fit["solver_faces"]);
  CHECK(report["mesh"]["graded"].is_null());
  CHECK(fs::file_size(fitted_map) > 0);  // the thickness map
  // It finished inside the budget: the process's measured peak below what --max-memory allows.
  CHECK(report["memory"]["peak_mb"].get<double>() < budget_mb);
}

TEST_CASE("the running account stops an assembly whose estimate fitted, exit 2, no output") {
  // The estimate is checked against the machine's memory and fits; the memory watch's own
  // limit is set below what the assembly reaches (BEMSHAPE_TEST_RESIDENT_LIMIT, the watch's
  // test hook), as if the estimate had been low: the run stops during the assembly with
  // the watch's message, and the existing output stays as it was.
  const std::string out = scratch("account.csv");
  const std::string before = "previous result\n";
  std::ofstream(out, std::ios::binary) << before;
  // --tolerance 1e-6: the compression of the surface values' default, whose assembly
  // reaches above kAccountLimit (the wall reading's 1e-5 stays below it on this ball).
  const Run r = run_bemshape("thickness '" + slow_ball() + "'" + kSlowOptions +
                             " --solver hmatrix --tolerance 1e-6 --quiet -o '" + out + "'",
                             "BEMSHAPE_TEST_RESIDENT_LIMIT=" + std::to_string(kAccountLimit));
  CAPTURE(r.err, r.seconds);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::StartsWith("bemshape: error: " + slow_ball() +
                               ": the hierarchical-matrix BEM system of ") &&
                 Catch::Contains(" GB it may use (BEMSHAPE_TEST_RESIDENT_LIMIT); stopped cleanly, "
                                 "no output file was written or changed; use a coarser mesh"));
  CHECK(r.seconds < bemshape::test::time_bound(60.0));
  CHECK(slurp(out) == before);
  CHECK(temporaries_of("account.csv") == 0);
}

namespace {

/// The options a refusal message suggests: what follows "e.g. " up to ", or" or the end of
/// the line ("" if there is none).
std::string suggested_options(const std::string& message) {
  const std::string key = "e.g. ";
  const std::size_t at = message.find(key);
  if (at == std::string::npos)
    return "";
  const std::size_t begin = at + key.size();
  const std::size_t end = std::min(message.find(", or", begin), message.find('\n', begin));
  return message.substr(begin, end - begin);
}

}  // namespace

TEST_CASE("fem --max-memory: a grid that does not fit is refused, naming a --cell that fits") {
  const std::string mesh = write_mesh(geometry::make_geodesic_sphere(0.5, 3), "fem_ball.stl");
  const std::string out = scratch("fem_memory.vti");
  const std::string prefix = "bemshape: error: " + mesh + ": the voxel FEM on ";
  // Cells of 0.02 on a ball of diameter 1 (h0 = 20 cells, margin 24 cells): 112³ cells,
  // 0.45 GB by the estimate of 16 MB + 310 bytes per cell.
  Run r = run_bemshape("fem '" + mesh + "' --cell 0.02 --max-memory 100MB -o '" + out + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::StartsWith(prefix) && Catch::Contains(" of size 0.02, --cell) needs 0.") &&
                 Catch::Contains(" GB but only 0.1 GB may be used (--max-memory); use a larger "
                                 "cell size, e.g. --cell "));
  CHECK_THAT(r.err, !Catch::Contains("multigrid"));  // refused before the solver started
  CHECK_FALSE(fs::exists(out));
  // The suggestion fits the same budget.
  std::string suggestion = suggested_options(r.first_error_line());
  REQUIRE(suggestion.rfind("--cell ", 0) == 0);
  r = run_bemshape("fem '" + mesh + "' " + suggestion + " --max-memory 100MB -o '" + out + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(out));

  // 20 MB: with h0 following the cell (20 cells) the margin alone needs more cells than
  // that, so the suggestion keeps this run's h0 (0.4), which fits.
  fs::remove(out);
  r = run_bemshape("fem '" + mesh + "' --cell 0.02 --max-memory 20MB -o '" + out + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::StartsWith(prefix) &&
                 Catch::Contains("no cell size fits with the default h0 of 20 cells") &&
                 Catch::Contains(" --h0 0.4, or raise --max-memory"));
  suggestion = suggested_options(r.first_error_line());
  r = run_bemshape("fem '" + mesh + "' " + suggestion + " --max-memory 20MB -o '" + out + "'");
  CAPTURE(suggestion, r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(out));

  // 2-D: the L-shaped image at cells of 0.1 pixel is 464² cells (68 MB).
  const std::string png = write_l_shape_png("fem_memory_l.png");
  const std::string out_2d = scratch("fem_memory_l.vti");
  r = run_bemshape("fem '" + png + "' --cell 0.1 --max-memory 30MB -o '" + out_2d + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::Contains("(464 x 464 of size 0.1, --cell) needs 0.0677 GB but only 0.03 GB "
                             "may be used (--max-memory); use a larger cell size, e.g. --cell "));
  CHECK_FALSE(fs::exists(out_2d));
  r = run_bemshape("fem '" + png + "' " + suggested_options(r.first_error_line()) +
                   " --max-memory 30MB -o '" + out_2d + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 0);
  r = run_bemshape("fem '" + png + "' --cell 0.1 --max-memory 12XB -o '" + out_2d + "'");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--max-memory '12XB': expected a positive size"));
}

TEST_CASE("fem --max-memory: an image is refused from its header before its pixels are read") {
  // A 5000² PNG (all void, a few kB on disk) claims 25 million pixels: 2 bytes each while
  // it is decoded, 0.05 GB.
  fem::BinaryImage<2> blank;
  blank.size = {5000, 5000};
  blank.solid.assign(25'000'000, 0);
  const std::string png = scratch("fem_memory_blank.png");
  fem::write_binary_png(png, blank);
  const std::string out = scratch("fem_memory_blank.vti");
  Run r = run_bemshape("fem '" + png + "' --cell 1 --max-memory 40MB -o '" + out + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.first_error_line() ==
        "bemshape: error: " + png +
            ": reading its 25000000 pixels needs 0.05 GB but only 0.04 GB may be used "
            "(--max-memory); downsample the image or raise --max-memory");
  CHECK_FALSE(fs::exists(out));

  // A folder of two such slices: each fits on its own (1 byte per voxel in a volume), the
  // volume of 50 million voxels does not.
  const fs::path slices = scratch("fem_memory_slices");
  fs::create_directories(slices);
  fs::copy_file(png, slices / "0.png", fs::copy_options::overwrite_existing);
  fs::copy_file(png, slices / "1.png", fs::copy_options::overwrite_existing);
  r = run_bemshape("fem '" + slices.string() + "' --cell 1 --max-memory 40MB -o '" + out + "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::EndsWith(": reading its 50000000 voxels needs 0.05 GB but only 0.04 GB may "
                             "be used (--max-memory); downsample the image or raise --max-memory"));

  // A raw volume: its size is checked against --dims first, then the budget. The file is
  // sparse, so it takes no disk space.
  const std::string raw = scratch("fem_memory_volume.raw");
  { std::ofstream create(raw, std::ios::binary); }
  fs::resize_file(raw, 400ULL * 400 * 400);
  r = run_bemshape("fem '" + raw + "' --dims 400,400,400 --cell 1 --max-memory 50MB -o '" + out +
                   "'");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.first_error_line() ==
        "bemshape: error: " + raw +
            ": reading its 64000000 voxels needs 0.064 GB but only 0.05 GB may be used "
            "(--max-memory); downsample the image or raise --max-memory");
  CHECK_FALSE(fs::exists(out));
  fs::remove(raw);
  fs::remove_all(slices);
}

TEST_CASE("compare --max-memory: the voxel grid and the BEM are both held to it") {
  const std::string mesh = write_mesh(geometry::make_geodesic_sphere(0.5, 8), "compare_memory.stl");
  // The voxel grid first: cells of 0.02 around the ball with h0 = 0.3 are 0.2 GB or more.
  Run r = run_bemshape("compare '" + mesh +
                       "' --h0 0.3 --cell 0.02 --max-probes 100 --max-memory 100MB --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::StartsWith("bemshape: error: " + mesh + ": the voxel FEM on ") &&
                 Catch::Contains("of size 0.02, --cell) needs ") &&
                 Catch::Contains("(--max-memory); use a larger cell size, e.g. --cell "));
  const std::string suggestion = suggested_options(r.first_error_line());
  REQUIRE(suggestion.rfind("--cell ", 0) == 0);
  // The suggested cell fits; the BEM on edges of 0.02 (about 2·10⁴ faces) does not.
  r = run_bemshape("compare '" + mesh + "' --h0 0.3 " + suggestion +
                   " --max-edge 0.02 --max-probes 100 --max-memory 100MB --quiet");
  CAPTURE(suggestion, r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(),
             Catch::Contains("(--max-memory)") && Catch::Contains("--max-edge"));
  CHECK_THAT(r.err, !Catch::Contains("voxel FEM"));
}
