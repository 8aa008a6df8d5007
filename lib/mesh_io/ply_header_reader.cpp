#include "mesh_io/ply_header_reader.h"

#include <cstring>
#include <limits>

#include "mesh_io/mesh_reader_support.h"

namespace eqmesh::io_internal {
namespace {

struct TypeName {
  const char* name;
  PlyType type;
};

// Both the original names and the sized aliases written by newer tools.
constexpr TypeName kTypeNames[] = {
    {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUInt8},
    {"uint8", PlyType::kUInt8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
    {"ushort", PlyType::kUInt16},  {"uint16", PlyType::kUInt16},   {"int", PlyType::kInt32},
    {"int32", PlyType::kInt32},    {"uint", PlyType::kUInt32},     {"uint32", PlyType::kUInt32},
    {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
    {"float64", PlyType::kFloat64},
};

bool LookUpType(const std::string& word, PlyType* type) {
  for (const TypeName& t : kTypeNames) {
    if (word == t.name) {
      *type = t.type;
      return true;
    }
  }
  return false;
}

std::vector<std::string> SplitWords(const char* b, const char* e) {
  std::vector<std::string> words;
  while ((b = SkipBlanks(b, e)) < e) {
    const char* w = SkipToken(b, e);
    words.emplace_back(b, w);
    b = w;
  }
  return words;
}

Status ParseFormat(const std::vector<std::string>& w, PlyHeader* header, const std::string& where) {
  if (w.size() < 2) return ParseError(where + "format line without a format");
  if (w[1] == "ascii") header->format = PlyFormat::kAscii;
  else if (w[1] == "binary_little_endian") header->format = PlyFormat::kBinaryLittleEndian;
  else if (w[1] == "binary_big_endian") header->format = PlyFormat::kBinaryBigEndian;
  else return ParseError(where + "unknown PLY format '" + w[1] + "'");
  return Status::Ok();
}

Status ParseElement(const std::vector<std::string>& w, PlyHeader* header, const std::string& where) {
  if (w.size() != 3) return ParseError(where + "element line needs a name and a count");
  int64_t count = -1;
  const char* b = w[2].data();
  const char* e = b + w[2].size();
  if (ParseInt64(b, e, &count) != e || count < 0) return ParseError(where + "bad element count '" + w[2] + "'");
  header->elements.push_back({w[1], static_cast<uint64_t>(count), {}});
  return Status::Ok();
}

Status ParseProperty(const std::vector<std::string>& w, PlyHeader* header, const std::string& where) {
  if (header->elements.empty()) return ParseError(where + "property before any element");
  PlyProperty prop;
  bool known = false;
  if (w.size() == 5 && w[1] == "list") {
    prop.is_list = true;
    known = LookUpType(w[2], &prop.count_type) && LookUpType(w[3], &prop.type);
    if (known && !PlyTypeIsInteger(prop.count_type)) return ParseError(where + "list count type must be an integer type");
  } else if (w.size() == 3) {
    known = LookUpType(w[1], &prop.type);
  } else {
    return ParseError(where + "malformed property line");
  }
  if (!known) return ParseError(where + "unknown property type in '" + w[1] + (prop.is_list ? " " + w[2] + " " + w[3] : "") + "'");
  prop.name = w.back();
  header->elements.back().properties.push_back(std::move(prop));
  return Status::Ok();
}

Status ParseHeaderLine(const std::vector<std::string>& w, PlyHeader* header, bool* saw_format,
                       const std::string& where) {
  const std::string& key = w[0];
  if (key == "comment" || key == "obj_info") return Status::Ok();
  if (key == "format") {
    *saw_format = true;
    return ParseFormat(w, header, where);
  }
  if (key == "element") return ParseElement(w, header, where);
  if (key == "property") return ParseProperty(w, header, where);
  return ParseError(where + "unknown header keyword '" + key + "'");
}

// Smallest number of bytes one element can occupy in the body.
uint64_t MinElementBytes(const PlyElement& element, PlyFormat format) {
  uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    // ascii: a digit and a separator per value; binary: the scalar or the list count.
    bytes += format == PlyFormat::kAscii ? 2 : PlyTypeSize(p.is_list ? p.count_type : p.type);
  }
  return bytes;
}

}  // namespace

size_t PlyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::kInt8: case PlyType::kUInt8: return 1;
    case PlyType::kInt16: case PlyType::kUInt16: return 2;
    case PlyType::kInt32: case PlyType::kUInt32: case PlyType::kFloat32: return 4;
    case PlyType::kFloat64: return 8;
  }
  return 1;
}

bool PlyTypeIsInteger(PlyType type) { return type != PlyType::kFloat32 && type != PlyType::kFloat64; }

const char* PlyFormatName(PlyFormat format) {
  switch (format) {
    case PlyFormat::kAscii: return "ascii";
    case PlyFormat::kBinaryLittleEndian: return "binary_little_endian";
    case PlyFormat::kBinaryBigEndian: return "binary_big_endian";
  }
  return "?";
}

StatusOr<PlyHeader> ParsePlyHeader(const uint8_t* data, size_t size, const std::string& name) {
  const char* p = reinterpret_cast<const char*>(data);
  const char* const end = p + size;
  PlyHeader header;
  bool saw_format = false;
  for (size_t line = 1; p < end; ++line) {
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<size_t>(end - p)));
    if (eol == nullptr) break;
    const std::vector<std::string> w = SplitWords(p, eol);
    p = eol + 1;
    const std::string where = name + ": line " + std::to_string(line) + ": ";
    if (line == 1) {
      if (w.size() != 1 || w[0] != "ply") return ParseError(name + ": not a PLY file (no 'ply' magic line)");
      continue;
    }
    if (w.empty()) continue;
    if (w[0] == "end_header") {
      if (!saw_format) return ParseError(name + ": PLY header without a format line");
      header.body_offset = static_cast<size_t>(p - reinterpret_cast<const char*>(data));
      return header;
    }
    EQMESH_RETURN_IF_ERROR(ParseHeaderLine(w, &header, &saw_format, where));
  }
  return ParseError(name + (size == 0 ? ": empty file" : ": PLY header has no end_header line"));
}

Status CheckPlyCountsFitBody(const PlyHeader& header, size_t body_bytes, const std::string& name) {
  // ascii: the last value may end the file without a separator.
  uint64_t room = body_bytes + (header.format == PlyFormat::kAscii ? 1 : 0);
  for (const PlyElement& e : header.elements) {
    if (e.count == 0) continue;
    const uint64_t min_bytes = MinElementBytes(e, header.format);
    if (min_bytes == 0) return ParseError(name + ": element '" + e.name + "' has no properties");
    if (e.count > room / min_bytes) {
      return ParseError(name + ": header declares " + std::to_string(e.count) + " '" + e.name +
                        "' elements, more than the remaining " + std::to_string(room) + " bytes of the file can hold");
    }
    room -= e.count * min_bytes;
  }
  return Status::Ok();
}

}  // namespace eqmesh::io_internal
