// libFuzzer target. The glTF loader on GLB / glTF bytes with EXT_normal_mesh_compression (fuzz_checks.h).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_checks.h"
#include "fuzz/fuzz_main.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return eqmesh::fuzz::Report(eqmesh::fuzz::CheckGltfLoader(data, size));
}
