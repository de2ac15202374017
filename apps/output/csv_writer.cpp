#include "apps/output/csv_writer.hpp"

#include "apps/output/atomic_file.hpp"
#include "apps/output/number_text.hpp"
#include "core/errors.hpp"

namespace bemshape::output {

std::string format_csv(const std::vector<std::string>& header,
                       const Eigen::Ref<const Eigen::MatrixXd>& rows) {
  if (static_cast<Eigen::Index>(header.size()) != rows.cols())
    throw InternalError("format_csv: " + std::to_string(header.size()) + " column names for " +
                        std::to_string(rows.cols()) + " columns");
  std::string text;
  // About 12 characters per value; one allocation for typical tables.
  text.reserve(static_cast<std::size_t>(rows.size()) * 12 + 64);
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (c > 0)
      text += ',';
    text += header[c];
  }
  text += '\n';
  for (Eigen::Index r = 0; r < rows.rows(); ++r) {
    for (Eigen::Index c = 0; c < rows.cols(); ++c) {
      if (c > 0)
        text += ',';
      append_number(text, rows(r, c));
    }
    text += '\n';
  }
  return text;
}

void write_csv(const std::filesystem::path& path, const std::vector<std::string>& header,
               const Eigen::Ref<const Eigen::MatrixXd>& rows) {
  write_file_atomically(path, format_csv(header, rows));
}

}  // namespace bemshape::output
