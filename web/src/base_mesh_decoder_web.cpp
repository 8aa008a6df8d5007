// WebAssembly stand-in for lib/coding/base_mesh_decoder.cpp: the base and kept
// chunks are Draco mesh buffers, and Debian ships Draco only as a native library,
// so the browser build hands those bytes to a Draco decoder module on the JS side
// (three.js ships one: examples/jsm/libs/draco/) instead of linking libdraco.
//
// Same contract as the native file (coding/base_mesh_decoder.h): the JS side is
// untrusted code on untrusted bytes, so its counts are checked against the limits
// before anything is allocated here, and its output is checked (indices in range,
// no repeated corner, finite coordinates) before eqmesh uses it.
#include <emscripten.h>

#include <cmath>
#include <string>
#include <vector>

#include "coding/base_mesh_decoder.h"

// The JS side keeps the decoded mesh between the calls so that the C++ side can
// check the counts before it allocates room for the data.
EM_JS(int, eqmesh_js_draco_decode, (const uint8_t* data, uint32_t size, uint32_t* counts), {
  var hook = Module["eqmeshDracoDecode"];
  var result;
  try {
    result = hook ? hook(HEAPU8.slice(data, data + size))
                  : {error: "no Draco decoder module was given to the eqmesh decoder"};
  } catch (e) {
    result = {error: "Draco threw: " + e};
  }
  Module["eqmeshDracoPending"] = result;
  if (result.error) return 1;
  HEAPU32[counts >> 2] = result.positions.length / 3;
  HEAPU32[(counts >> 2) + 1] = result.indices.length / 3;
  return 0;
});

EM_JS(void, eqmesh_js_draco_take, (float* positions, uint32_t* faces), {
  var result = Module["eqmeshDracoPending"];
  Module["eqmeshDracoPending"] = null;
  if (positions) HEAPF32.set(result.positions, positions >> 2);
  if (faces) HEAPU32.set(result.indices, faces >> 2);
});

// ASCII only, so no UTF-8 helper from the runtime is needed.
EM_JS(void, eqmesh_js_draco_error, (char* out, int capacity), {
  var result = Module["eqmeshDracoPending"];
  Module["eqmeshDracoPending"] = null;
  var text = String(result && result.error ? result.error : "unknown error");
  var n = Math.min(text.length, capacity - 1);
  for (var i = 0; i < n; ++i) {
    var c = text.charCodeAt(i);
    HEAPU8[out + i] = c < 128 ? c : 63;
  }
  HEAPU8[out + n] = 0;
});

namespace eqmesh {
namespace {

Status CheckFaces(const Mesh& mesh, const std::string& what) {
  const size_t n = mesh.positions.size();
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const Face& f = mesh.faces[i];
    if (f[0] >= n || f[1] >= n || f[2] >= n) {
      return CorruptStream(what + ": face " + std::to_string(i) + " references a missing vertex");
    }
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      return CorruptStream(what + ": face " + std::to_string(i) + " repeats a vertex");
    }
  }
  return Status::Ok();
}

Status DracoError(const std::string& what) {
  char text[256];
  eqmesh_js_draco_error(text, sizeof(text));
  return CorruptStream(what + ": Draco: " + text);
}

StatusOr<Mesh> TakeDecodedMesh(uint32_t points, uint32_t faces, const std::string& what) {
  std::vector<float> xyz(size_t{points} * 3);
  std::vector<uint32_t> corners(size_t{faces} * 3);
  eqmesh_js_draco_take(xyz.data(), corners.data());
  Mesh mesh;
  mesh.positions.resize(points);
  for (size_t i = 0; i < points; ++i) {
    const float* p = &xyz[3 * i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return CorruptStream(what + ": non-finite position");
    }
    mesh.positions[i] = Vec3(p[0], p[1], p[2]);
  }
  mesh.faces.resize(faces);
  for (size_t i = 0; i < faces; ++i) {
    mesh.faces[i] = {corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]};
  }
  EQMESH_RETURN_IF_ERROR(CheckFaces(mesh, what));
  return mesh;
}

}  // namespace

StatusOr<Mesh> DecodeDracoMesh(const uint8_t* data, size_t size, const DracoMeshLimits& limits,
                               const std::string& what) {
  uint32_t counts[2] = {0, 0};
  if (eqmesh_js_draco_decode(data, static_cast<uint32_t>(size), counts) != 0) return DracoError(what);
  if (counts[0] > limits.max_vertices || counts[1] > limits.max_faces) {
    eqmesh_js_draco_take(nullptr, nullptr);
    return ResourceLimit(what + ": " + std::to_string(counts[0]) + " vertices / " +
                         std::to_string(counts[1]) + " faces exceed the stream limits");
  }
  return TakeDecodedMesh(counts[0], counts[1], what);
}

}  // namespace eqmesh
