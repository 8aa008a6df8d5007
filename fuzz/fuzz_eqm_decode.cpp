// libFuzzer target. The .eqm stream decoder: Decode / DecodeSemiRegular / ReadStreamInfo (fuzz_checks.h).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_checks.h"
#include "fuzz/fuzz_main.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return eqmesh::fuzz::Report(eqmesh::fuzz::CheckStreamDecoder(data, size));
}
