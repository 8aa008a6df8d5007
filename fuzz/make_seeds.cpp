// Seed corpora for the fuzz targets (scripts/fuzz.sh corpus): small valid inputs
// for every entry point, written to OUT_DIR/<target>/. Streams come from the real
// encoder (each coder and transform, with and without kept-exactly components),
// GLBs from the real container code, mesh files from the writers plus hand-written
// variants the writers never produce (ascii and big-endian PLY, tristrips, quads,
// comments). Extra .eqm files given on the command line (the golden streams) are
// added to the stream corpus.
//
//   eqmesh_fuzz_seeds OUT_DIR [STREAM.eqm ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "coding/encoder.h"
#include "fuzz/fuzz_checks.h"
#include "gltf/compress_primitives.h"
#include "gltf/gltf_io.h"
#include "gltf/stream_decoder.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh::fuzz {
namespace {

namespace fs = std::filesystem;
using bitstream::CoderId;
using bitstream::TransformId;

Mesh Icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : m.positions) p.normalize();
  return m;
}

// Icosahedron refined `levels` times onto the bumpy sphere r = 1 + 0.1 sin(3x) cos(2y).
SemiRegularMesh BumpySphere(int levels, bool with_kept) {
  const Mesh ico = Icosahedron();
  SemiRegularMesh mesh;
  mesh.hierarchy =
      SemiRegularHierarchy::Build(static_cast<uint32_t>(ico.positions.size()), ico.faces, levels).value();
  std::vector<Vec3> p = ico.positions;
  for (int j = 0; j < levels; ++j) {
    for (uint32_t k = 0; k < mesh.hierarchy.NumOddVertices(j); ++k) {
      const Edge& e = mesh.hierarchy.OddEdge(j, k);
      p.push_back((0.5 * (p[e[0]] + p[e[1]])).normalized());
    }
  }
  for (Vec3& v : p) {
    const Vec3 u = v.normalized();
    v = u * (1.0 + 0.1 * std::sin(3.0 * u.x()) * std::cos(2.0 * u.y()));
  }
  mesh.positions = std::move(p);
  if (with_kept) {
    mesh.kept_exactly.positions = {Vec3(2, 0, 0), Vec3(2.1, 0, 0), Vec3(2, 0.1, 0), Vec3(2, 0, 0.1)};
    mesh.kept_exactly.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  }
  return mesh;
}

void Write(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
}

void Write(const fs::path& path, const std::string& text) { Write(path, std::vector<uint8_t>(text.begin(), text.end())); }

std::vector<uint8_t> WithControl(uint8_t control, const std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> out(bytes.size() + 1);
  out[0] = control;
  std::copy(bytes.begin(), bytes.end(), out.begin() + 1);
  return out;
}

template <typename T>
T OrDie(StatusOr<T> value, const char* what) {
  if (!value.ok()) {
    std::fprintf(stderr, "%s: %s\n", what, value.status().ToString().c_str());
    std::exit(1);
  }
  return std::move(value).value();
}

struct Variant {
  const char* name;
  CoderId coder;
  TransformId transform;
  bool kept;
  int levels;
};

constexpr Variant kVariants[] = {
    {"eq_unlifted_kept", CoderId::kEq, TransformId::kUnlifted, true, 2},
    {"eq_lifted", CoderId::kEq, TransformId::kLifted, false, 3},
    {"zt_unlifted", CoderId::kZerotree, TransformId::kUnlifted, false, 2},
    {"zt_lifted_kept", CoderId::kZerotree, TransformId::kLifted, true, 3},
    {"uniform_unlifted", CoderId::kUniform, TransformId::kUnlifted, true, 2},
};

std::vector<uint8_t> EncodeVariant(const Variant& v, SemiRegularMesh* mesh) {
  *mesh = BumpySphere(v.levels, v.kept);
  EncodeOptions options;
  options.coder = v.coder;
  options.transform = v.transform;
  options.lambda = 0.05;
  return OrDie(Encode(*mesh, options), v.name);
}

void WriteStreamSeeds(const fs::path& dir, const std::vector<std::string>& extra) {
  fs::create_directories(dir);
  for (const Variant& v : kVariants) {
    SemiRegularMesh mesh;
    const std::vector<uint8_t> stream = EncodeVariant(v, &mesh);
    const std::string base = (dir / v.name).string();
    Write(base + ".all", WithControl(kControlAllLevels, stream));
    Write(base + ".semi", WithControl(kControlAllLevels | kControlSemiRegular, stream));
    Write(base + ".level1", WithControl(1, stream));
    // A prefix ending inside the last level chunk, decoded with allow_truncated.
    const std::vector<uint8_t> prefix(stream.begin(), stream.end() - static_cast<std::ptrdiff_t>(stream.size() / 8));
    Write(base + ".prefix", WithControl(kControlAllLevels | kControlAllowTruncated, prefix));
  }
  for (const std::string& path : extra) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> stream((std::istreambuf_iterator<char>(in)), {});
    Write(dir / (fs::path(path).stem().string() + ".all"), WithControl(kControlAllLevels, stream));
  }
}

// One compressed primitive per variant, as the converter writes it (with and
// without the fallback geometry).
void WriteGltfSeeds(const fs::path& dir) {
  fs::create_directories(dir);
  const gltf::StreamDecoderFn decode = gltf::EqmeshStreamDecoder();
  for (const Variant& v : kVariants) {
    SemiRegularMesh mesh;
    const std::vector<uint8_t> stream = EncodeVariant(v, &mesh);
    const gltf::DecodedStream decoded = OrDie(decode(stream.data(), stream.size(), -1, 0), v.name);
    const Mesh plain = ExtractLevel(mesh, mesh.hierarchy.levels());
    for (const bool fallback : {false, true}) {
      tinygltf::Model model =
          OrDie(gltf::ReadGltfModelFromBytes(OrDie(WriteMeshToBytes(plain, "glb"), "glb"), "seed.glb"), "model");
      gltf::GeometryCompressor compressor = [&](const gltf::PrimitiveGeometry&, const std::string&) -> StatusOr<gltf::CompressedGeometry> {
        gltf::CompressedGeometry g;
        g.stream = stream;
        g.chunk_lengths = decoded.chunk_lengths;
        g.decoded = decoded.mesh;
        return g;
      };
      gltf::ContainerOptions options;
      options.fallback = fallback;
      gltf::ConvertReport report;
      const Status status = gltf::CompressPrimitives(&model, compressor, options, &report);
      if (!status.ok() || report.compressed != 1) {
        std::fprintf(stderr, "%s: compressing the seed GLB failed: %s\n", v.name, status.ToString().c_str());
        std::exit(1);
      }
      const std::vector<uint8_t> glb = OrDie(gltf::WriteGlbToBytes(model), "glb bytes");
      const std::string name = std::string(v.name) + (fallback ? "_fallback" : "");
      Write(dir / (name + ".glb"), WithControl(kControlAllLevels, glb));
      Write(dir / (name + ".level1.glb"), WithControl(1, glb));
    }
  }
}

Mesh SmallMesh() {
  const SemiRegularMesh sphere = BumpySphere(1, false);
  return ExtractLevel(sphere, 1);
}

void WriteMeshSeeds(const fs::path& root) {
  const Mesh mesh = SmallMesh();
  for (const char* format : {"obj", "ply", "off"}) {
    fs::create_directories(root / (std::string("read_") + format));
    Write(root / (std::string("read_") + format) / (std::string("sphere.") + format),
          OrDie(WriteMeshToBytes(mesh, format), format));
  }
  WriteOptions doubles;
  doubles.ply_double_positions = true;
  Write(root / "read_ply" / "sphere_double.ply", OrDie(WriteMeshToBytes(mesh, "ply", doubles), "ply"));

  const fs::path obj = root / "read_obj";
  Write(obj / "quad.obj",
        "# comment\nmtllib a.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
        "usemtl m\ns off\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -4//1 -2//1 -1//1\n");
  Write(obj / "crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n");

  const fs::path ply = root / "read_ply";
  const std::string header =
      "ply\nformat ascii 1.0\ncomment made by eqmesh_fuzz_seeds\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\n";
  Write(ply / "ascii_face.ply", header +
                                    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                    "0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n3 0 1 2\n4 0 1 2 3\n");
  Write(ply / "ascii_tristrips.ply", header +
                                         "element tristrips 1\nproperty list int int vertex_indices\n"
                                         "end_header\n0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n6 0 1 2 3 -1 0\n");
  // Big-endian binary: float x y z, then a uchar/uint face list.
  std::string be =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  const float coords[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (const float c : coords) {
    uint32_t bits = 0;
    std::memcpy(&bits, &c, 4);
    for (int s = 24; s >= 0; s -= 8) be.push_back(static_cast<char>(bits >> s));
  }
  be.push_back(3);
  for (uint32_t i = 0; i < 3; ++i) {
    for (int s = 24; s >= 0; s -= 8) be.push_back(static_cast<char>(i >> s));
  }
  Write(ply / "binary_be.ply", be);

  const fs::path off = root / "read_off";
  Write(off / "quad.off", "OFF\n# comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n");
  Write(off / "coff.off", "COFF 3 1 3\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n");
}

}  // namespace
}  // namespace eqmesh::fuzz

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR [STREAM.eqm ...]\n", argv[0]);
    return 2;
  }
  namespace fs = std::filesystem;
  const fs::path root(argv[1]);
  const std::vector<std::string> extra(argv + 2, argv + argc);
  eqmesh::fuzz::WriteStreamSeeds(root / "eqm_decode", extra);
  eqmesh::fuzz::WriteGltfSeeds(root / "gltf_load");
  eqmesh::fuzz::WriteMeshSeeds(root);
  return 0;
}
