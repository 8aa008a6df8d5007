// Running the `eqmesh` command from tests, and the scratch files around it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace eqmesh::testing {

struct ToolRun {
  int exit_code = -1;  // -1: did not exit normally (a crash is a failure too)
  std::string output;  // stdout and stderr together
};

// Runs `eqmesh <args>` through the shell (args are pasted as they are);
// `prefix` goes before the command (e.g. "env NAME=VALUE ").
ToolRun RunTool(const std::string& args, const std::string& prefix = "");

// A fresh, empty directory for one test (removed by the destructor).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string Path(const std::string& file) const { return dir_ + "/" + file; }
  // Names of the files in the directory, sorted.
  std::vector<std::string> Files() const;

 private:
  std::string dir_;
};

bool FileExists(const std::string& path);
std::string ReadText(const std::string& path);
void WriteText(const std::string& path, const std::string& text);
std::vector<uint8_t> ReadFileOrEmpty(const std::string& path);
// 64-bit FNV-1a: a stable fingerprint for pinning bytes in tests.
uint64_t Fnv1a64(const uint8_t* data, size_t size);
uint64_t Fnv1a64(const std::vector<uint8_t>& bytes);
// samples/meshes/blob.obj, the bundled 10k-vertex sample.
std::string BlobPath();

}  // namespace eqmesh::testing
