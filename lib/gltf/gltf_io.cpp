#include "gltf/gltf_io.h"

#include <cstring>
#include <sstream>

#include "gltf/buffer_layout.h"
#include "gltf/placeholder_indices.h"
#include "mesh_io/atomic_file.h"
#include "mesh_io/file_bytes.h"
#include "mesh_io/mesh_reader_support.h"

namespace eqmesh::gltf {
namespace {

// tinygltf's image callback: keep the encoded bytes as they are (`as_is`). Images
// stored in a bufferView stay there, so their bytes are not copied a second time.
bool KeepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  if (image->bufferView < 0 && bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

// Images are written by WriteGlbToBytes itself; tinygltf must not write files.
bool NoImageWrite(const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*,
                  void*) {
  return false;
}

std::string FirstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

std::string DirectoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// Images loaded from a URI (data: or file) move into the BIN chunk so the GLB
// stands alone.
void EmbedLoadedImages(tinygltf::Model* model) {
  for (tinygltf::Image& image : model->images) {
    if (image.bufferView >= 0 || image.image.empty()) continue;
    image.bufferView = AppendBufferView(model, image.image.data(), image.image.size(), 0);
    if (image.mimeType.empty()) image.mimeType = GuessMimeType(image.image);
    image.uri.clear();
    image.image.clear();
  }
}

// File access for bytes with no directory (base_dir empty: "none allowed",
// gltf_io.h). tinygltf's default callbacks would resolve a relative URI against the
// working directory and take an absolute one ("/etc/passwd") as it is.
bool NoFileExists(const std::string&, void*) { return false; }
std::string KeepPath(const std::string& path, void*) { return path; }
bool NoFileRead(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err != nullptr) *err += "external file '" + path + "' not allowed for a file read from memory\n";
  return false;
}
bool NoFileWrite(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

StatusOr<tinygltf::Model> ParseWithTinygltf(const std::vector<uint8_t>& bytes,
                                            const std::string& name_for_errors, const std::string& base_dir) {
  tinygltf::TinyGLTF reader;
  reader.SetImageLoader(KeepEncodedImage, nullptr);
  if (base_dir.empty()) reader.SetFsCallbacks({NoFileExists, KeepPath, NoFileRead, NoFileWrite, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    const bool is_glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    if (is_glb) {
      EQMESH_RETURN_IF_ERROR(io_internal::CheckGlbChunkLengths(bytes.data(), bytes.size(), name_for_errors));
      ok = reader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                       static_cast<unsigned int>(bytes.size()), base_dir);
    } else {
      const std::string text(bytes.begin(), bytes.end());
      ok = reader.LoadASCIIFromString(&model, &err, &warn, text.data(),
                                      static_cast<unsigned int>(text.size()), base_dir);
    }
  } catch (const std::exception& e) {
    return ParseError(name_for_errors + ": " + e.what());
  }
  if (!ok) return ParseError(name_for_errors + ": " + FirstLine(err.empty() ? warn : err));
  return model;
}

}  // namespace

std::string GuessMimeType(const std::vector<unsigned char>& bytes) {
  static const unsigned char kPng[4] = {0x89, 'P', 'N', 'G'};
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), kPng, 4) == 0) return "image/png";
  if (bytes.size() >= 2 && bytes[0] == 0xFF && bytes[1] == 0xD8) return "image/jpeg";
  return "application/octet-stream";
}


StatusOr<tinygltf::Model> ReadGltfModelFromBytes(const std::vector<uint8_t>& bytes,
                                                 const std::string& name_for_errors,
                                                 const std::string& base_dir) {
  if (bytes.empty()) return ParseError(name_for_errors + ": empty file");
  if (bytes.size() > 0x7FFFFFFFu) return ResourceLimit(name_for_errors + ": file larger than 2 GiB");
  // The chunks are checked before the placeholder patch rewrites the JSON, so
  // a byte offset in the message is one of the file (as ReadMesh reports it).
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
    EQMESH_RETURN_IF_ERROR(io_internal::CheckGlbChunkLengths(bytes.data(), bytes.size(), name_for_errors));
  }
  std::vector<DetachedIndices> detached;
  auto patched = DetachPlaceholderIndices(bytes, &detached);
  if (!patched.ok()) return patched.status().WithContext(name_for_errors);
  EQMESH_ASSIGN_OR_RETURN(tinygltf::Model model, ParseWithTinygltf(*patched, name_for_errors, base_dir));
  EQMESH_RETURN_IF_ERROR(ReattachPlaceholderIndices(detached, &model).WithContext(name_for_errors));
  return model;
}

StatusOr<tinygltf::Model> ReadGltfModel(const std::string& path) {
  auto bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.status();
  return ReadGltfModelFromBytes(*bytes, path, DirectoryOf(path));
}

StatusOr<std::vector<uint8_t>> WriteGlbToBytes(const tinygltf::Model& model) {
  tinygltf::Model out = model;
  EQMESH_RETURN_IF_ERROR(MergeBuffers(&out));
  EmbedLoadedImages(&out);
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(NoImageWrite, nullptr);
  std::ostringstream stream;
  try {
    if (!writer.WriteGltfSceneToStream(&out, stream, false, true)) return IoError("GLB serialization failed");
  } catch (const std::exception& e) {
    return InternalError(std::string("GLB serialization failed: ") + e.what());
  }
  const std::string s = stream.str();
  return std::vector<uint8_t>(s.begin(), s.end());
}

Status WriteGlb(const tinygltf::Model& model, const std::string& path) {
  auto bytes = WriteGlbToBytes(model);
  if (!bytes.ok()) return bytes.status().WithContext(path);
  return WriteFileAtomically(path, *bytes);
}

}  // namespace eqmesh::gltf
