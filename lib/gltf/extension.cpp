#include "gltf/extension.h"

#include <algorithm>
#include <cmath>

namespace eqmesh::gltf {
namespace {

// JSON numbers reach us as int or double (tinygltf keeps large integers as double);
// both are accepted when they hold an exact non-negative integer below 2^53.
bool ReadCount(const tinygltf::Value& v, uint64_t* out) {
  if (!v.IsNumber()) return false;
  const double d = v.GetNumberAsDouble();
  if (!(d >= 0.0) || d > 9007199254740992.0 || std::floor(d) != d) return false;
  *out = static_cast<uint64_t>(d);
  return true;
}

bool ReadIndex(const tinygltf::Value& v, int* out) {
  uint64_t n = 0;
  if (!ReadCount(v, &n) || n > 0x7FFFFFFFu) return false;
  *out = static_cast<int>(n);
  return true;
}

Status ReadRanges(const tinygltf::Value& array, std::vector<ByteRange>* ranges) {
  if (!array.IsArray()) return ParseError("levelByteRanges is not an array");
  for (size_t i = 0; i < array.ArrayLen(); ++i) {
    const tinygltf::Value& pair = array.Get(static_cast<int>(i));
    ByteRange r;
    if (!pair.IsArray() || pair.ArrayLen() != 2 || !ReadCount(pair.Get(0), &r.offset) ||
        !ReadCount(pair.Get(1), &r.length)) {
      return ParseError("levelByteRanges[" + std::to_string(i) +
                        "] is not a pair of non-negative integers");
    }
    ranges->push_back(r);
  }
  return Status::Ok();
}

// Rule 10 without the buffer view and the coder: contiguous from 0; ranges 0 and 1
// non-empty; ranges 2..J all non-empty or (coder 1, checked later) all empty.
Status CheckRangesTile(const std::vector<ByteRange>& ranges) {
  uint64_t expected = 0;
  for (size_t i = 0; i < ranges.size(); ++i) {
    if (ranges[i].offset != expected) {
      return ParseError("levelByteRanges[" + std::to_string(i) + "] starts at " +
                        std::to_string(ranges[i].offset) + ", expected " + std::to_string(expected));
    }
    if (ranges[i].length == 0 && i < 2) {
      return ParseError("levelByteRanges[" + std::to_string(i) + "] is empty (rule 10)");
    }
    if (i > 2 && (ranges[i].length == 0) != (ranges[2].length == 0)) {
      return ParseError("levelByteRanges[2.." + std::to_string(ranges.size() - 1) +
                        "] mix empty and non-empty ranges (rule 10)");
    }
    expected = ranges[i].end();
  }
  return Status::Ok();
}

Status ReadAttributes(const tinygltf::Value& object, NormalMeshExtension* ext) {
  if (!object.IsObject()) return ParseError("attributes is not an object");
  for (const std::string& key : object.Keys()) {
    int* slot = key == "POSITION"     ? &ext->position_accessor
                : key == "NORMAL"     ? &ext->normal_accessor
                : key == "TEXCOORD_0" ? &ext->texcoord_accessor
                                      : nullptr;
    if (slot == nullptr) {
      return ParseError("attributes." + key + " is not allowed (POSITION, NORMAL, TEXCOORD_0 only)");
    }
    if (!ReadIndex(object.Get(key), slot)) return ParseError("attributes." + key + " is not an accessor index");
  }
  if (ext->position_accessor < 0) return ParseError("attributes.POSITION is missing");
  return Status::Ok();
}

}  // namespace

StatusOr<NormalMeshExtension> ParseExtension(const tinygltf::Value& value) {
  if (!value.IsObject()) return ParseError(std::string(kExtensionName) + " is not an object");
  for (const char* key : {"bufferView", "levels", "levelByteRanges", "attributes"}) {
    if (!value.Has(key)) return ParseError(std::string("required property ") + key + " is missing");
  }
  NormalMeshExtension ext;
  if (!ReadIndex(value.Get("bufferView"), &ext.buffer_view)) return ParseError("bufferView is not an index");
  if (!ReadIndex(value.Get("levels"), &ext.levels) || ext.levels > kMaxExtensionLevels) {
    return ParseError("levels is not an integer in [0, " + std::to_string(kMaxExtensionLevels) + "]");
  }
  EQMESH_RETURN_IF_ERROR(ReadRanges(value.Get("levelByteRanges"), &ext.level_ranges));
  if (ext.level_ranges.size() != static_cast<size_t>(ext.levels) + 1) {
    return ParseError("levelByteRanges has " + std::to_string(ext.level_ranges.size()) +
                      " entries, levels + 1 = " + std::to_string(ext.levels + 1) + " expected");
  }
  EQMESH_RETURN_IF_ERROR(CheckRangesTile(ext.level_ranges));
  EQMESH_RETURN_IF_ERROR(ReadAttributes(value.Get("attributes"), &ext));
  if (value.Has("triangleBudget") &&
      (!ReadCount(value.Get("triangleBudget"), &ext.triangle_budget) || ext.triangle_budget == 0)) {
    return ParseError("triangleBudget is not a positive integer");
  }
  return ext;
}

namespace {

// Ints print as JSON integers; beyond 2 GiB only a double holds the value (exactly,
// up to 2^53), which tinygltf prints as a number with a zero fraction.
tinygltf::Value CountValue(uint64_t n) {
  if (n <= 0x7FFFFFFFu) return tinygltf::Value(static_cast<int>(n));
  return tinygltf::Value(static_cast<double>(n));
}

}  // namespace

tinygltf::Value ExtensionToValue(const NormalMeshExtension& ext) {
  tinygltf::Value::Array ranges;
  for (const ByteRange& r : ext.level_ranges) {
    ranges.emplace_back(tinygltf::Value::Array{CountValue(r.offset), CountValue(r.length)});
  }
  tinygltf::Value::Object attributes;
  attributes["POSITION"] = tinygltf::Value(ext.position_accessor);
  if (ext.normal_accessor >= 0) attributes["NORMAL"] = tinygltf::Value(ext.normal_accessor);
  if (ext.texcoord_accessor >= 0) attributes["TEXCOORD_0"] = tinygltf::Value(ext.texcoord_accessor);
  tinygltf::Value::Object object;
  object["bufferView"] = tinygltf::Value(ext.buffer_view);
  object["levels"] = tinygltf::Value(ext.levels);
  object["levelByteRanges"] = tinygltf::Value(std::move(ranges));
  object["attributes"] = tinygltf::Value(std::move(attributes));
  if (ext.triangle_budget > 0) object["triangleBudget"] = CountValue(ext.triangle_budget);
  return tinygltf::Value(std::move(object));
}

namespace {

Status CheckAccessorShape(const tinygltf::Model& model, int index, const char* what, int type,
                          bool fallback) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
    return ParseError(std::string(what) + " accessor " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
  if (a.type != type) return ParseError(std::string(what) + " accessor has the wrong type");
  if (!fallback && (a.bufferView >= 0 || a.sparse.isSparse)) {
    return ParseError(std::string(what) +
                      " placeholder accessor has data although the extension is required (rule 7)");
  }
  return Status::Ok();
}

Status CheckPrimitiveShape(const NormalMeshExtension& ext, const tinygltf::Primitive& p) {
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES) return ParseError("mode is not TRIANGLES (rule 2)");
  for (const auto& [semantic, accessor] : p.attributes) {
    if (semantic != "POSITION" && semantic != "NORMAL" && semantic != "TEXCOORD_0") {
      return ParseError("attribute " + semantic + " is not allowed on a compressed primitive (rule 3)");
    }
  }
  if (!p.targets.empty()) return ParseError("morph targets are not allowed (rule 3)");
  if (p.indices < 0) return ParseError("indices are missing (rule 4)");
  const auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end() || pos->second != ext.position_accessor) {
    return ParseError("attributes.POSITION differs from the primitive's POSITION (rule 5)");
  }
  const auto nor = p.attributes.find("NORMAL");
  const int primitive_normal = nor == p.attributes.end() ? -1 : nor->second;
  if (primitive_normal != ext.normal_accessor) {
    return ParseError("attributes.NORMAL differs from the primitive's NORMAL (rule 5)");
  }
  const auto uv = p.attributes.find("TEXCOORD_0");
  if ((uv == p.attributes.end() ? -1 : uv->second) != ext.texcoord_accessor) {
    return ParseError("attributes.TEXCOORD_0 differs from the primitive's TEXCOORD_0 (rule 5)");
  }
  return Status::Ok();
}

}  // namespace

Status CheckExtensionAgainstModel(const NormalMeshExtension& ext, const tinygltf::Primitive& primitive,
                                  const tinygltf::Model& model, bool fallback) {
  EQMESH_RETURN_IF_ERROR(CheckPrimitiveShape(ext, primitive));
  EQMESH_RETURN_IF_ERROR(CheckAccessorShape(model, ext.position_accessor, "POSITION", TINYGLTF_TYPE_VEC3, fallback));
  if (ext.normal_accessor >= 0) {
    EQMESH_RETURN_IF_ERROR(CheckAccessorShape(model, ext.normal_accessor, "NORMAL", TINYGLTF_TYPE_VEC3, fallback));
  }
  if (ext.texcoord_accessor >= 0) {
    EQMESH_RETURN_IF_ERROR(
        CheckAccessorShape(model, ext.texcoord_accessor, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, fallback));
  }
  EQMESH_RETURN_IF_ERROR(CheckAccessorShape(model, primitive.indices, "indices", TINYGLTF_TYPE_SCALAR, fallback));
  if (ext.buffer_view < 0 || static_cast<size_t>(ext.buffer_view) >= model.bufferViews.size()) {
    return ParseError("bufferView " + std::to_string(ext.buffer_view) + " does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(ext.buffer_view)];
  if (view.byteStride != 0 || view.target != 0) {
    return ParseError("the stream's bufferView has a byteStride or target (rule 8)");
  }
  if (ext.level_ranges.back().end() != view.byteLength) {
    return ParseError("levelByteRanges end at " + std::to_string(ext.level_ranges.back().end()) +
                      " but the bufferView holds " + std::to_string(view.byteLength) + " bytes (rule 10)");
  }
  return Status::Ok();
}

Status CheckRangesForCoder(const NormalMeshExtension& ext, int coder) {
  if (coder == kEmbeddedCoderId) return Status::Ok();  // the stream header pins its sizes (rule 11)
  for (size_t i = 0; i < ext.level_ranges.size(); ++i) {
    if (ext.level_ranges[i].length == 0) {
      return ParseError("levelByteRanges[" + std::to_string(i) + "] is empty, which only coder " +
                        std::to_string(kEmbeddedCoderId) + " streams allow; this stream uses coder " +
                        std::to_string(coder) + " (rule 10)");
    }
  }
  return Status::Ok();
}

std::vector<ByteRange> RangesFromLengths(const std::vector<uint64_t>& lengths) {
  std::vector<ByteRange> ranges;
  uint64_t offset = 0;
  for (uint64_t length : lengths) {
    ranges.push_back({offset, length});
    offset += length;
  }
  return ranges;
}

bool IsExtensionRequired(const tinygltf::Model& model) {
  const auto& r = model.extensionsRequired;
  return std::find(r.begin(), r.end(), kExtensionName) != r.end();
}

void AddExtensionName(std::vector<std::string>* names, const std::string& name) {
  if (std::find(names->begin(), names->end(), name) == names->end()) names->push_back(name);
}

void RemoveExtensionName(std::vector<std::string>* names, const std::string& name) {
  names->erase(std::remove(names->begin(), names->end(), name), names->end());
}

}  // namespace eqmesh::gltf
