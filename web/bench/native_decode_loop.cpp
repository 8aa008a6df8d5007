// Native counterpart of the browser decode timing (web/bench/run_bench.sh): decodes
// one .eqm stream repeatedly with the C++ decoder and computes the same unit
// normals the wasm module does, so both sides time the same work. Prints one JSON
// line: vertices, triangles, the median and the minimum over the runs.
//   native_decode_loop STREAM.eqm [RUNS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "coding/decoder.h"
#include "mesh/mesh.h"

namespace {

std::vector<uint8_t> ReadFile(const char* path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// One decode plus normals; returns milliseconds, or -1 on a decode error.
double TimeOnce(const std::vector<uint8_t>& bytes, eqmesh::Mesh* mesh) {
  const auto start = std::chrono::steady_clock::now();
  auto decoded = eqmesh::Decode(bytes.data(), bytes.size());
  if (!decoded.ok()) {
    std::fprintf(stderr, "%s\n", decoded.status().ToString().c_str());
    return -1;
  }
  std::vector<eqmesh::Vec3> normals = eqmesh::VertexNormals(*decoded);
  for (eqmesh::Vec3& n : normals) n = n.norm() > 0 ? eqmesh::Vec3(n.normalized()) : eqmesh::Vec3(0, 0, 1);
  const auto end = std::chrono::steady_clock::now();
  *mesh = std::move(*decoded);
  return std::chrono::duration<double, std::milli>(end - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: native_decode_loop STREAM.eqm [RUNS]\n");
    return 2;
  }
  const std::vector<uint8_t> bytes = ReadFile(argv[1]);
  const int runs = argc > 2 ? std::max(1, std::stoi(argv[2])) : 10;
  eqmesh::Mesh mesh;
  if (TimeOnce(bytes, &mesh) < 0) return 1;  // warm-up
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) ms.push_back(TimeOnce(bytes, &mesh));
  std::sort(ms.begin(), ms.end());
  std::printf("{\"vertices\": %zu, \"triangles\": %zu, \"median_ms\": %.3f, \"min_ms\": %.3f}\n",
              mesh.num_vertices(), mesh.num_faces(), ms[ms.size() / 2], ms.front());
  return 0;
}
