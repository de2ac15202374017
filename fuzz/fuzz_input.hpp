#pragma once
// Shared by the fuzz harnesses (fuzz/*.cpp): the readers take paths, so each input is
// written to a file first; and the one rule every harness checks: a reader or the mesh
// pipeline may refuse an input only with InputError or ResourceError (a one-line message
// and exit code 2 in the executable). Any other exception — InternalError, an exception
// from a third-party library, std::bad_alloc — escapes the harness and is a finding, as are
// crashes, sanitizer reports, hangs and out-of-memory.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "core/errors.hpp"

namespace bemshape::fuzz {

/// The folder "<temp>/bemshape_fuzz_<pid>" of one process's input files, created on first
/// use and removed with its files when the process exits normally (the regression replay in
/// the test suite runs every harness, and would otherwise leave one folder per run).
class InputFolder {
 public:
  InputFolder()
      : path_(std::filesystem::temp_directory_path() /
              ("bemshape_fuzz_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  InputFolder(const InputFolder&) = delete;
  InputFolder& operator=(const InputFolder&) = delete;
  ~InputFolder() {
    std::error_code ignored;  // a folder that cannot be removed is left, not an error
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Writes `size` bytes to "<temp>/bemshape_fuzz_<pid>/input<extension>" (one file per
/// process and extension, overwritten by each input) and returns its path.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size,
                                        const std::string& extension) {
  static const InputFolder folder;
  const auto path = folder.path() / ("input" + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// Runs `f`, accepting the documented refusals (InputError, ResourceError).
template <class F>
void refusal_allowed(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const ResourceError&) {
  }
}

}  // namespace bemshape::fuzz
