// Helpers for the mesh I/O tests: scratch files and byte builders.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh::testing {

// A fresh path in the test temp directory ending in `file_name`.
std::string TempPath(const std::string& file_name);
void WriteFile(const std::string& path, const std::vector<uint8_t>& bytes);
void WriteFile(const std::string& path, const std::string& text);
std::vector<uint8_t> ToBytes(const std::string& s);
// gzip-compresses with zlib (for .gz tests built by the test itself).
std::vector<uint8_t> Gzip(const std::vector<uint8_t>& bytes);

// Appends a scalar in the given byte order.
template <typename T>
void AppendScalar(std::vector<uint8_t>* out, T v, bool big_endian) {
  uint8_t raw[sizeof(T)];
  __builtin_memcpy(raw, &v, sizeof(T));
  if (big_endian) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) {
      const uint8_t t = raw[i];
      raw[i] = raw[sizeof(T) - 1 - i];
      raw[sizeof(T) - 1 - i] = t;
    }
  }
  out->insert(out->end(), raw, raw + sizeof(T));
}

// Two triangles sharing an edge (a unit square in z = 0), handy as a tiny input.
Mesh MakeSquare();

}  // namespace eqmesh::testing
