#include "apps/output/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "core/cancellation.hpp"
#include "core/errors.hpp"

namespace bemshape::output {
namespace {

std::string error_text(const std::filesystem::path& path, const char* action) {
  return path.string() + ": cannot " + action + " (" + std::strerror(errno) +
         "); check that the folder exists, is writable and the disk is not full";
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::filesystem::path target) : target_(std::move(target)) {
  std::filesystem::path folder = target_.parent_path();
  if (folder.empty())
    folder = ".";
  std::string hidden_name = ".";
  hidden_name += target_.filename().string();
  hidden_name += ".tmp-XXXXXX";
  const std::string pattern = (folder / hidden_name).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0)
    throw InputError(error_text(target_, "create a temporary file next to"));
  temporary_ = name.data();
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0)
    ::close(fd_);
  if (!committed_ && !temporary_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFileWriter::write(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t written = ::write(fd_, p, bytes);
    if (written < 0) {
      if (errno == EINTR)
        continue;
      throw InputError(error_text(target_, "write"));
    }
    p += written;
    bytes -= static_cast<std::size_t>(written);
  }
}

void AtomicFileWriter::commit() {
  // A run stopped by --timeout or a signal publishes nothing: the destructor removes the
  // temporary file and an existing target stays as it was.
  throw_if_cancelled();
  // Readable like an ordinary new file (mkstemp creates it 0600).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(fd_, 0666 & ~mask) != 0)
    throw InputError(error_text(target_, "set permissions of"));
  if (::fsync(fd_) != 0)
    throw InputError(error_text(target_, "flush"));
  if (::close(fd_) != 0) {
    fd_ = -1;
    throw InputError(error_text(target_, "close"));
  }
  fd_ = -1;
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0)
    throw InputError(error_text(target_, "rename the temporary file onto"));
  committed_ = true;
  // The rename itself is durable once the folder is synced; a failure here (some file
  // systems do not allow syncing a folder) leaves a complete file, so it is not an error.
  std::filesystem::path folder = target_.parent_path();
  if (folder.empty())
    folder = ".";
  const int folder_fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (folder_fd >= 0) {
    ::fsync(folder_fd);
    ::close(folder_fd);
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFileWriter writer(path);
  writer.write(bytes);
  writer.commit();
}

}  // namespace bemshape::output
