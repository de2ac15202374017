#pragma once
// Comma-separated tables: one header line of column names, then one line per row, numbers in
// their shortest round-trip decimal form (number_text.hpp), '\n' line ends, no quoting (column
// names are plain identifiers). Written atomically (atomic_file.hpp).
//
//   header: #C column names
//   rows:   #R×#C values

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::output {

/// The table as text. Throws InternalError if the column counts differ.
std::string format_csv(const std::vector<std::string>& header,
                       const Eigen::Ref<const Eigen::MatrixXd>& rows);

/// Writes format_csv(header, rows) to `path` atomically; throws InputError on an I/O error.
void write_csv(const std::filesystem::path& path, const std::vector<std::string>& header,
               const Eigen::Ref<const Eigen::MatrixXd>& rows);

}  // namespace bemshape::output
