// The entry points the fuzz targets drive (fuzz/fuzz_*.cpp) and the checks they
// apply to whatever those entry points return. Shared with the GoogleTest that
// replays the minimized crash inputs (tests/fuzz_regressions/), so a reproducer
// runs exactly the code the fuzzer ran.
//
// Each Check* function feeds `data` to one entry point and returns an empty string
// when the outcome is acceptable (a clean error Status, or a result that satisfies
// the entry point's documented promises: finite coordinates, indices in range,
// output bounded by the input), else a one-line description of what broke. Crashes,
// leaks and sanitizer reports are left to the sanitizers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace eqmesh::fuzz {

// The .eqm stream decoder. data[0] is a control byte, the rest the stream:
//   bits 0-3  max_level (0..12; 13..15 mean -1 = every level)
//   bit 4     DecodeOptions::allow_truncated
//   bit 5     DecodeSemiRegular instead of Decode
// ReadStreamInfo runs on every input too.
std::string CheckStreamDecoder(const uint8_t* data, size_t size);

// gltf::LoadGltfFromBytes (GLB or JSON glTF carrying EXT_normal_mesh_compression),
// then FlattenToMesh on the decoded model. data[0] is a control byte (bits 0-3:
// LoadOptions::max_level as above), the rest the file.
std::string CheckGltfLoader(const uint8_t* data, size_t size);

// The OBJ / PLY / OFF readers on the raw file bytes (no control byte). `format` is
// "obj", "ply" or "off".
std::string CheckMeshReader(const char* format, const uint8_t* data, size_t size);

// The control byte's max_level (shared with the seed generator).
int MaxLevelFromControl(uint8_t control);
constexpr uint8_t kControlAllLevels = 0x0F;
constexpr uint8_t kControlAllowTruncated = 0x10;
constexpr uint8_t kControlSemiRegular = 0x20;

}  // namespace eqmesh::fuzz
