#include "mesh_io/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace eqmesh {
namespace {

std::string ErrnoText() { return std::strerror(errno); }

// The temporary name keeps the target's directory (rename cannot cross file
// systems) and is unique per call (mkstemp), so two runs writing the same
// output never share a temporary.
std::string TemporaryTemplate(const std::string& path) { return path + ".eqmesh-tmp-XXXXXX"; }

Status WriteAll(int fd, const uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return IoError("write failed (" + ErrnoText() + ")");
    data += n;
    size -= static_cast<size_t>(n);
  }
  return Status::Ok();
}

// mkstemp creates 0600; an output file should look like any other new file.
void GiveUsualPermissions(int fd) {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  (void)::fchmod(fd, 0666 & ~mask);
}

Status FillTemporary(int fd, const uint8_t* data, size_t size) {
  GiveUsualPermissions(fd);
  const Status written = WriteAll(fd, data, size);
  const int closed = ::close(fd);
  if (!written.ok()) return written;
  if (closed != 0) return IoError("write failed (" + ErrnoText() + ")");
  return Status::Ok();
}

}  // namespace

Status WriteFileAtomically(const std::string& path, const uint8_t* data, size_t size) {
  std::string temporary = TemporaryTemplate(path);
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) return IoError(path + ": cannot open for writing (" + ErrnoText() + ")");
  Status status = FillTemporary(fd, data, size);
  if (status.ok() && ::rename(temporary.c_str(), path.c_str()) != 0) {
    status = IoError("cannot replace the file (" + ErrnoText() + ")");
  }
  if (!status.ok()) {
    ::unlink(temporary.c_str());
    return status.WithContext(path);
  }
  return Status::Ok();
}

Status WriteFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes) {
  return WriteFileAtomically(path, bytes.data(), bytes.size());
}

bool IsSameFile(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace eqmesh
