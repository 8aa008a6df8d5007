// See huge_pages.h.
#include "tools/huge_pages.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <unistd.h>
#define EQMESH_CAN_REEXEC 1
#endif

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define EQMESH_SANITIZED_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define EQMESH_SANITIZED_ALLOCATOR 1
#endif
#endif

#if defined(EQMESH_CAN_REEXEC) && !defined(EQMESH_SANITIZED_ALLOCATOR)
#define EQMESH_REEXEC_FOR_HUGE_PAGES 1
#endif

namespace eqmesh::cli {
#ifdef EQMESH_REEXEC_FOR_HUGE_PAGES
namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

bool KernelThpIsMadviseOnly() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(in, line) && line.find("[madvise]") != std::string::npos;
}

// valgrind preloads its own allocator, and an exec would leave its tool behind.
bool UnderValgrind() {
  const char* preload = std::getenv("LD_PRELOAD");
  return preload != nullptr && std::strstr(preload, "valgrind") != nullptr;
}

}  // namespace
#endif

void ReexecWithHugePagesIfUseful(char** argv) {
#ifdef EQMESH_REEXEC_FOR_HUGE_PAGES
  const char* opt = std::getenv("EQMESH_HUGE_PAGES");
  if (opt != nullptr && std::strcmp(opt, "0") == 0) return;
  if (std::getenv("GLIBC_TUNABLES") != nullptr) return;
  if (UnderValgrind() || !KernelThpIsMadviseOnly()) return;
  if (setenv("GLIBC_TUNABLES", kTunable, 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");  // exec failed: run as we are
#else
  (void)argv;
#endif
}

}  // namespace eqmesh::cli
