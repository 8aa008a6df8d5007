// The EXT_normal_mesh_compression object of a mesh.primitive (ext_spec/README.md,
// "glTF Schema Updates"): parsing with the spec's validity rules, and writing.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"

namespace eqmesh::gltf {

inline constexpr char kExtensionName[] = "EXT_normal_mesh_compression";
// Stream levels the spec allows (validity rule 9; bitstream kMaxLevels).
inline constexpr int kMaxExtensionLevels = 12;
// Stream coder id whose level data is one embedded payload (ext_spec A.4, coder 1):
// levelByteRanges[1] holds it and ranges 2..J are empty (rule 10).
inline constexpr int kEmbeddedCoderId = 1;

struct ByteRange {
  uint64_t offset = 0;
  uint64_t length = 0;
  uint64_t end() const { return offset + length; }
  bool operator==(const ByteRange& o) const { return offset == o.offset && length == o.length; }
};

struct NormalMeshExtension {
  int buffer_view = -1;
  int levels = 0;                        // J
  std::vector<ByteRange> level_ranges;   // J + 1 entries, inside the buffer view
  int position_accessor = -1;
  int normal_accessor = -1;              // -1 when the primitive has no NORMAL
  int texcoord_accessor = -1;            // TEXCOORD_0 from the stream's atlas; -1 without
  // The source primitive's triangle count: loaders decode at most this many
  // triangles unless asked otherwise (0: absent, no default budget).
  uint64_t triangle_budget = 0;
};

// Reads the extension object. Checks the JSON shape and the rules that need nothing
// but the object itself (9, and 10 except the end-of-buffer-view check and the
// coder: ranges 0 and 1 must be non-empty, ranges 2..J either all non-empty or all
// empty, the latter only valid for coder 1; see CheckRangesForCoder).
StatusOr<NormalMeshExtension> ParseExtension(const tinygltf::Value& value);

// The extension object as tinygltf stores it.
tinygltf::Value ExtensionToValue(const NormalMeshExtension& ext);

// Rules 2-8 and the buffer-view half of 10 against the model holding `primitive`.
// `fallback` says whether placeholder accessors may have data (rule 12).
Status CheckExtensionAgainstModel(const NormalMeshExtension& ext, const tinygltf::Primitive& primitive,
                                  const tinygltf::Model& model, bool fallback);

// The coder half of rule 10, once the stream header is known: empty ranges (2..J,
// all of them) only for kEmbeddedCoderId, none for every other coder.
Status CheckRangesForCoder(const NormalMeshExtension& ext, int coder);

// Contiguous ranges starting at 0 from chunk lengths (level 0 first): rule 10's form.
std::vector<ByteRange> RangesFromLengths(const std::vector<uint64_t>& lengths);

// True when the model lists the extension in extensionsRequired.
bool IsExtensionRequired(const tinygltf::Model& model);

// Adds / removes `name` from a list of extension names, keeping the order of the rest.
void AddExtensionName(std::vector<std::string>* names, const std::string& name);
void RemoveExtensionName(std::vector<std::string>* names, const std::string& name);

}  // namespace eqmesh::gltf
