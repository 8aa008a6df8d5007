// libFuzzer target. The ply reader (mesh_io.h) on raw file bytes.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_checks.h"
#include "fuzz/fuzz_main.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return eqmesh::fuzz::Report(eqmesh::fuzz::CheckMeshReader("ply", data, size));
}
