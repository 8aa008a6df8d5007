// Internal to the PLY reader: the header model and its parser (Turk's PLY format:
// "ply", "format <kind> 1.0", comment/obj_info lines, "element <name> <count>",
// "property <type> <name>", "property list <count type> <item type> <name>",
// "end_header").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace eqmesh::io_internal {

enum class PlyType : uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };
enum class PlyFormat : uint8_t { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // the item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::kUInt8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;  // first byte after the end_header line
};

size_t PlyTypeSize(PlyType type);
bool PlyTypeIsInteger(PlyType type);
const char* PlyFormatName(PlyFormat format);

// Parses the header; `name` prefixes errors.
StatusOr<PlyHeader> ParsePlyHeader(const uint8_t* data, size_t size, const std::string& name);

// Fails when the declared element counts need more bytes than the body has, so that
// no count is trusted for an allocation before it is known to be possible.
Status CheckPlyCountsFitBody(const PlyHeader& header, size_t body_bytes, const std::string& name);

}  // namespace eqmesh::io_internal
