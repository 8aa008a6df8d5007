// The body every libFuzzer target shares: run one check, abort on a finding so
// libFuzzer records the input as a crash.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace eqmesh::fuzz {

inline int Report(const std::string& problem) {
  if (problem.empty()) return 0;
  std::fprintf(stderr, "eqmesh fuzz check failed: %s\n", problem.c_str());
  std::abort();
}

}  // namespace eqmesh::fuzz
