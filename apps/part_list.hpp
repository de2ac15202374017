#pragma once
// The parts of a `bemshape check-all` run and where each one's report goes.
//
//   INPUT    a mesh file (any name: a file that cannot be read is a part with an error), or
//            a folder: its mesh files (.stl, .obj, .off, .ply, .3mf, any case), searched
//            recursively, hidden files and folders skipped, in path order;
//   --list   a text file naming one INPUT per line (blank lines and lines starting with #
//            skipped; relative paths relative to the current folder, as `find` prints them).
//
// A part named twice is checked once. Its report is REPORTS/<its path relative to the folder
// all parts share>.json (parts/a/x.stl → REPORTS/a/x.stl.json when every part is under
// parts/), so parts of the same name in different folders keep reports of their own.

#include <filesystem>
#include <string>
#include <vector>

namespace bemshape::apps {

struct Part {
  std::string path;              ///< as given (or as found under a given folder)
  std::filesystem::path report;  ///< REPORTS/<relative path>.json
};

/// The parts named by `inputs` and the list files `lists`, in that order, with their reports
/// in `reports`. Throws InputError for a list file that cannot be read, a folder without
/// mesh files, or no parts at all.
std::vector<Part> list_parts(const std::vector<std::string>& inputs,
                             const std::vector<std::string>& lists,
                             const std::filesystem::path& reports);

}  // namespace bemshape::apps
