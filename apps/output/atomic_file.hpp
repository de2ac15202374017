#pragma once
// Atomic file output: bytes go to a temporary file in the target's folder, which is flushed,
// fsync'ed and renamed over the target on commit() (the folder is fsync'ed after the rename).
// commit() refuses (CancelledError) once the run was cancelled (core/cancellation.hpp). A run that fails (exception, crash,
// full disk) never leaves a half-written target: the temporary is removed by the destructor
// if commit() was not reached, and rename() within one folder is atomic on POSIX.

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace bemshape::output {

class AtomicFileWriter {
 public:
  /// Creates "<folder>/.<name>.tmp-XXXXXX". Throws InputError if the folder does not exist or
  /// is not writable.
  explicit AtomicFileWriter(std::filesystem::path target);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  /// Appends bytes; throws InputError on a write error (e.g. disk full).
  void write(const void* data, std::size_t bytes);
  void write(std::string_view text) { write(text.data(), text.size()); }
  /// Flushes, fsyncs and renames the temporary file over the target.
  void commit();

  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  bool committed_ = false;
};

/// Writes `bytes` to `path` atomically (a convenience over AtomicFileWriter).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace bemshape::output
