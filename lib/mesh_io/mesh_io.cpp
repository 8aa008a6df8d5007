// Format selection for ReadMesh / ReadMeshFromBytes: the extension proposes, the
// content's magic disposes. Files are often misnamed (a PLY saved as .obj, a .gltf
// that is really GLB), and a wrong parser gives confusing errors, so content that
// unambiguously identifies a format wins and the switch is noted in the report.
#include <algorithm>
#include <cctype>
#include <cstring>

#include "mesh_io/file_bytes.h"
#include "mesh_io/mesh_io.h"
#include "mesh_io/mesh_reader_support.h"

namespace eqmesh {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "obj" for "a/b/Mesh.OBJ.gz"; empty when the name has no known extension.
std::string FormatFromPath(const std::string& path) {
  std::string lower = Lower(path);
  if (EndsWith(lower, ".gz")) lower.resize(lower.size() - 3);
  for (const char* ext : {"obj", "ply", "off", "gltf", "glb"}) {
    if (EndsWith(lower, std::string(".") + ext)) return ext;
  }
  return "";
}

std::string DirectoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

bool StartsWith(const std::vector<uint8_t>& bytes, const char* magic) {
  const size_t n = std::strlen(magic);
  return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
}

// The first word of the first line that is neither blank nor a '#' comment.
std::string FirstWord(const std::vector<uint8_t>& bytes) {
  size_t i = 0;
  const size_t n = std::min<size_t>(bytes.size(), 4096);
  while (i < n) {
    while (i < n && std::isspace(bytes[i])) ++i;
    if (i < n && bytes[i] == '#') {
      while (i < n && bytes[i] != '\n') ++i;
      continue;
    }
    break;
  }
  size_t j = i;
  while (j < n && !std::isspace(bytes[j])) ++j;
  return std::string(bytes.begin() + static_cast<ptrdiff_t>(i), bytes.begin() + static_cast<ptrdiff_t>(j));
}

// The format the content proves, or empty when it proves none (OBJ has no magic).
std::string SniffFormat(const std::vector<uint8_t>& bytes) {
  if (StartsWith(bytes, "ply\n") || StartsWith(bytes, "ply\r\n")) return "ply";
  if (StartsWith(bytes, "glTF")) return "glb";
  const std::string word = FirstWord(bytes);
  if (word == "OFF" || word == "COFF" || word == "NOFF" || word == "CNOFF" || word == "STOFF") return "off";
  if (!word.empty() && word[0] == '{') return "gltf";
  if (word == "v" || word == "o" || word == "g" || word == "mtllib" || word == "vn" || word == "vt") return "obj";
  return "";
}

std::string NormalizeFormat(const std::string& format) {
  std::string f = Lower(format);
  if (!f.empty() && f[0] == '.') f.erase(0, 1);
  return f;
}

StatusOr<Mesh> Dispatch(const std::vector<uint8_t>& bytes, const std::string& format, const std::string& name,
                        const std::string& base_dir, ReadReport* report) {
  const uint8_t* d = bytes.data();
  const size_t n = bytes.size();
  if (format == "obj") return io_internal::ReadObj(d, n, name, report);
  if (format == "ply") return io_internal::ReadPly(d, n, name, report);
  if (format == "off") return io_internal::ReadOff(d, n, name, report);
  if (format == "gltf") return io_internal::ReadGltf(d, n, false, name, base_dir, report);
  if (format == "glb") return io_internal::ReadGltf(d, n, true, name, base_dir, report);
  return UnsupportedFeature(name + ": unknown mesh format '" + format + "' (expected obj, ply, off, gltf or glb)");
}

StatusOr<Mesh> ReadBytesAs(const std::vector<uint8_t>& bytes, const std::string& declared, const std::string& name,
                           ReadReport* report) {
  if (bytes.empty()) return ParseError(name + ": empty file");
  const std::string sniffed = SniffFormat(bytes);
  std::string format = declared;
  if (format.empty()) {
    if (sniffed.empty()) return UnsupportedFeature(name + ": cannot tell the mesh format from the name or the content");
    format = sniffed;
  } else if (!sniffed.empty() && sniffed != format && sniffed != "obj") {
    report->notes.push_back("content is " + sniffed + " although named as " + format);
    format = sniffed;
  }
  return Dispatch(bytes, format, name, DirectoryOf(name), report);
}

}  // namespace

StatusOr<Mesh> ReadMeshFromBytes(const std::vector<uint8_t>& bytes, const std::string& format,
                                 const std::string& name_for_errors, ReadReport* report) {
  ReadReport local;
  ReadReport* r = report ? report : &local;
  *r = ReadReport();
  if (IsGzip(bytes.data(), bytes.size())) {
    EQMESH_ASSIGN_OR_RETURN(const std::vector<uint8_t> inflated,
                            InflateGzip(bytes.data(), bytes.size(), kDefaultMaxFileBytes, name_for_errors));
    r->notes.push_back("gzip: " + std::to_string(bytes.size()) + " -> " + std::to_string(inflated.size()) + " bytes");
    return ReadBytesAs(inflated, NormalizeFormat(format), name_for_errors, r);
  }
  return ReadBytesAs(bytes, NormalizeFormat(format), name_for_errors, r);
}

StatusOr<Mesh> ReadMesh(const std::string& path, ReadReport* report) {
  ReadReport local;
  ReadReport* r = report ? report : &local;
  *r = ReadReport();
  bool was_gzip = false;
  EQMESH_ASSIGN_OR_RETURN(const std::vector<uint8_t> bytes, ReadFileBytes(path, kDefaultMaxFileBytes, &was_gzip));
  if (was_gzip) r->notes.push_back("gzip: inflated to " + std::to_string(bytes.size()) + " bytes");
  return ReadBytesAs(bytes, FormatFromPath(path), path, r);
}

}  // namespace eqmesh
