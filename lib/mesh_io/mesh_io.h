// Reading and writing triangle meshes: OBJ, PLY (ascii and binary), OFF, glTF/GLB,
// each optionally gzip-compressed.
//
// The readers are meant for untrusted files: bad input gives a non-OK Status whose
// one-line message names the file (and the line or record) and the problem. Element
// counts declared in a header are checked against the bytes actually present before
// anything is allocated, so a lying header cannot force a huge allocation, and the
// output of any reader is bounded by a small multiple of the input size (glTF
// instancing included: at most 64 flattened vertices + faces per input byte).
//
// Every reader returns the same normal form, so later stages never see format quirks:
//  * polygons are fan-triangulated (v0, vi, vi+1); faces with fewer than three
//    corners are skipped (counted in a note);
//  * vertices that no face uses are dropped, the others keep their order;
//  * duplicate positions are NOT merged (that is a diagnosis decision, not I/O);
//  * every index is in range and every coordinate is finite, or the read fails;
//  * a mesh without faces is an error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// What a reader did to the file's contents on the way to the normal form.
struct ReadReport {
  std::string format;                        // "obj", "ply", "off", "gltf" or "glb"
  size_t dropped_unreferenced_vertices = 0;  // vertices stored but used by no face
  size_t polygons_triangulated = 0;          // faces with more than 3 corners
  size_t primitives_skipped = 0;             // glTF primitives that are not TRIANGLES
  std::vector<std::string> notes;            // gzip, sniffed format, skipped faces, ...
};

// Reads `path`. The format comes from the extension (.obj .ply .off .gltf .glb, each
// optionally followed by .gz, case-insensitive); content that clearly belongs to
// another format (PLY/GLB magic, an OFF header, JSON) wins over the extension and
// is noted in the report. gzip is detected by its magic bytes, not by the name.
StatusOr<Mesh> ReadMesh(const std::string& path, ReadReport* report = nullptr);

// Same as ReadMesh on bytes already in memory (gzip inflated if present).
// `format` is "obj", "ply", "off", "gltf" or "glb" (a leading dot is accepted);
// empty means "sniff the content". `name_for_errors` prefixes every message; a
// .gltf's external buffers are resolved relative to its directory.
StatusOr<Mesh> ReadMeshFromBytes(const std::vector<uint8_t>& bytes, const std::string& format,
                                 const std::string& name_for_errors,
                                 ReadReport* report = nullptr);

struct WriteOptions {
  // PLY: store positions as double instead of float32 (exact round trip).
  bool ply_double_positions = false;
};

// Writes by extension: .obj (text, shortest round-trip decimal doubles), .ply
// (binary little endian, float32 x y z unless options ask for double, uchar/int
// face lists), .off (text) or .glb (one mesh, one TRIANGLES primitive, float32
// POSITION with exact min/max, uint16 indices when they fit, else uint32; valid
// for the Khronos glTF validator). Refuses meshes with out-of-range indices,
// non-finite coordinates or, for PLY float32 and GLB, coordinates beyond float
// range. GLB also refuses a mesh without faces (glTF forbids empty accessors).
Status WriteMesh(const Mesh& mesh, const std::string& path, const WriteOptions& options = {});

// The bytes WriteMesh would write; `format` is "obj", "ply", "off" or "glb".
StatusOr<std::vector<uint8_t>> WriteMeshToBytes(const Mesh& mesh, const std::string& format,
                                                const WriteOptions& options = {});

}  // namespace eqmesh
