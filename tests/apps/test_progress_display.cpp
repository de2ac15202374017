// apps/progress_display.hpp: one line per finished stage in lines mode, and nothing before
// the silent period has passed (what `check` uses to stay quiet on small files).
#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <sstream>
#include <thread>

#include "apps/progress_display.hpp"

using bemshape::apps::ProgressDisplay;

TEST_CASE("progress display: one line per finished stage, in order") {
  std::ostringstream out;
  {
    ProgressDisplay display(ProgressDisplay::Mode::lines, out);
    display.update("reading", 0.0);
    display.update("welding", 0.5);
    display.update("welding", 1.0);
    display.finish();
  }
  const std::string text = out.str();
  CHECK(text.find("reading") < text.find("welding"));
  CHECK(std::count(text.begin(), text.end(), '\n') == 2);
  CHECK(text.find("stopped") == std::string::npos);
}

TEST_CASE("progress display: stages that end within the silent period print nothing") {
  using namespace std::chrono_literals;
  constexpr double kSilent = 0.2;  // [s]
  std::ostringstream out;
  ProgressDisplay display(ProgressDisplay::Mode::lines, out, kSilent);
  display.update("reading", 0.0);
  display.update("welding", 0.0);  // "reading" ends at once: silent
  CHECK(out.str().empty());
  std::this_thread::sleep_for(250ms);
  display.update("validation", 0.0);  // "welding" ends after the silent period
  display.finish();
  const std::string text = out.str();
  CHECK(text.find("reading") == std::string::npos);
  CHECK(text.find("welding") != std::string::npos);
  CHECK(text.find("validation") != std::string::npos);
}
