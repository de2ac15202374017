#pragma once
// Reading query points for `bemshape features --points`: a CSV or whitespace-separated text
// file with three coordinates per line [model units]. An optional first line of column names
// is recognised by a non-numeric first field; if it names columns x, y and z those are used,
// otherwise the first three columns. Empty lines and lines starting with '#' are skipped.

#include <filesystem>

#include <Eigen/Core>

namespace bemshape::apps {

/// #P×3 points. Throws InputError naming the file and line of the first unreadable entry.
Eigen::MatrixX3d read_points(const std::filesystem::path& path);

}  // namespace bemshape::apps
