// encode_and_load MESH COMPRESSED.glb: the C++ side of the installed package. Remeshes
// and encodes MESH with eqmesh::encoder, decodes the stream back, and loads a glTF
// whose primitives are compressed with EXT_normal_mesh_compression through
// eqmesh::loader; prints what each gave. Exit status 0 on success.
#include <cstdio>

#include "coding/decoder.h"
#include "coding/encoder.h"
#include "gltf/gltf_loader.h"
#include "mesh_io/mesh_io.h"
#include "remesh/remesh.h"

namespace {

int Fail(const eqmesh::Status& status) {
  std::fprintf(stderr, "encode_and_load: %s\n", status.ToString().c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: encode_and_load MESH COMPRESSED.glb\n");
    return 2;
  }
  auto input = eqmesh::ReadMesh(argv[1]);
  if (!input.ok()) return Fail(input.status());
  eqmesh::RemeshOptions remesh_options;
  remesh_options.levels = 4;
  eqmesh::RemeshReport remesh_report;
  auto remeshed = eqmesh::Remesh(*input, remesh_options, &remesh_report);
  if (!remeshed.ok()) return Fail(remeshed.status());
  eqmesh::EncodeOptions options;
  options.target_bpv = 2.0;
  options.input_vertices = input->positions.size();
  auto stream = eqmesh::Encode(*remeshed, options);
  if (!stream.ok()) return Fail(stream.status());
  auto decoded = eqmesh::Decode(stream->data(), stream->size());
  if (!decoded.ok()) return Fail(decoded.status());
  std::printf("encoded %zu vertices into %zu bytes; decoded %zu vertices, %zu triangles\n",
              input->positions.size(), stream->size(), decoded->positions.size(), decoded->faces.size());

  auto model = eqmesh::gltf::LoadGltf(argv[2]);
  if (!model.ok()) return Fail(model.status());
  auto flat = eqmesh::gltf::FlattenToMesh(*model);
  if (!flat.ok()) return Fail(flat.status());
  std::printf("loaded %s: %zu vertices, %zu triangles\n", argv[2], flat->positions.size(), flat->faces.size());
  return 0;
}
