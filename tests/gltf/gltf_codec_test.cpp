// EXT_normal_mesh_compression with the real codec: glb -> compressed glb -> loaded
// model, at the promised quality, per level, and through the Khronos validator.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "coding/decoder.h"
#include "gltf/accessor_io.h"
#include "gltf/extension.h"
#include "gltf/gltf_converter.h"
#include "gltf/gltf_io.h"
#include "gltf/gltf_loader.h"
#include "gltf_test_support.h"
#include "mesh_io/mesh_io.h"
#include "mesh/semi_regular.h"
#include "mesh/triangle_bvh.h"
#include "test_support.h"

namespace eqmesh {
namespace {

constexpr double kTargetPsnr = 60.0;
constexpr double kVertexMeterTolerance = 5.0;

// A smooth, not-quite-symmetric closed surface (an ellipsoid with a bump).
Mesh Pebble() {
  Mesh mesh = testing::MakeIcosphere(3);
  for (Vec3& p : mesh.positions) {
    p = Vec3(1.3 * p.x(), 0.9 * p.y(), 0.7 * p.z()) * (1.0 + 0.1 * std::sin(3.0 * p.x()));
  }
  return mesh;
}

// RMS distance of a's vertices to surface b.
double VertexRms(const Mesh& a, const TriangleBvh& b) {
  double sum = 0;
  for (const Vec3& p : a.positions) sum += b.ClosestPoint(p).squared_distance;
  return std::sqrt(sum / static_cast<double>(a.positions.size()));
}

// Symmetric vertex-to-surface PSNR: an independent, cruder meter than the codec's
// Metro sampling (vertices instead of area samples; measured 3.3 dB below it on the
// pebble), hence kVertexMeterTolerance. The promise itself is checked on the
// codec's own Metro figure, and the loaded geometry is checked to be exactly what
// the codec decodes.
double VertexPsnr(const Mesh& original, const Mesh& decoded) {
  auto to_original = TriangleBvh::Build(original);
  auto to_decoded = TriangleBvh::Build(decoded);
  if (!to_original.ok() || !to_decoded.ok()) return 0;
  const double rms = std::max(VertexRms(decoded, *to_original), VertexRms(original, *to_decoded));
  return 20.0 * std::log10(BoundingBoxDiagonal(original) / rms);
}

gltf::ConvertOptions Options(bool fallback = false) {
  gltf::ConvertOptions options;
  // Three levels are enough for the container; the automatic count refines a
  // 642-vertex pebble to ~80k vertices (remesh.cpp), all of it only time here.
  options.remesh.levels = 3;
  options.codec.target_psnr = kTargetPsnr;
  options.codec.measure_psnr = true;
  // The container's promise is under test, not the meter's precision; the
  // loaded mesh is also measured by an independent meter (VertexPsnr).
  options.codec.psnr_samples = 50'000;
  options.fallback = fallback;
  // The pebble's 1,280 triangles cannot carry 60 dB: no budget, so the search runs once
  // (LoadersDecodeWithinTheSourcesTriangleCountByDefault tests the budget).
  options.max_triangles = 0;
  return options;
}

// Pebble as a GLB, converted once for all tests (remeshing is the slow part).
struct Converted {
  std::string input, compressed;
  gltf::ConvertReport report;
  Status status;
};

const Converted& PebbleConverted() {
  static const Converted converted = [] {
    Converted c;
    c.input = testing::TempPath("pebble.glb");
    c.compressed = testing::TempPath("pebble_compressed.glb");
    c.status = gltf::WriteGlb(testing::MakeSingleMeshModel(Pebble()), c.input);
    if (!c.status.ok()) return c;
    auto report = gltf::ConvertToCompressedGltf(c.input, c.compressed, Options());
    c.status = report.status();
    if (report.ok()) c.report = *report;
    return c;
  }();
  return converted;
}

TEST(GltfCodec, LoadedModelMeetsThePromisedPsnr) {
  const Converted& c = PebbleConverted();
  ASSERT_TRUE(c.status.ok()) << c.status.ToString();
  ASSERT_EQ(c.report.compressed, 1u) << c.report.primitives[0].reason;
  EXPECT_GT(c.report.input_bytes, c.report.output_bytes);
  EXPECT_GE(c.report.primitives[0].psnr_db, kTargetPsnr - 0.5);
  auto model = gltf::LoadGltf(c.compressed);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  auto decoded = gltf::ReadTrianglePrimitive(*model, model->meshes[0].primitives[0]);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  // The loader hands out exactly the codec's decoded mesh (to float32).
  auto compressed = gltf::ReadGltfModel(c.compressed);
  ASSERT_TRUE(compressed.ok());
  auto ext = gltf::ParseExtension(compressed->meshes[0].primitives[0].extensions.at(gltf::kExtensionName));
  ASSERT_TRUE(ext.ok());
  const tinygltf::BufferView& view = compressed->bufferViews[static_cast<size_t>(ext->buffer_view)];
  auto reference = Decode(compressed->buffers[0].data.data() + view.byteOffset, view.byteLength);
  ASSERT_TRUE(reference.ok()) << reference.status().ToString();
  ASSERT_EQ(reference->positions.size(), decoded->positions.size());
  EXPECT_EQ(reference->faces, decoded->faces);
  for (size_t i = 0; i < decoded->positions.size(); ++i) {
    EXPECT_LT((reference->positions[i] - decoded->positions[i]).norm(), 1e-6 * BoundingBoxDiagonal(Pebble()));
  }
  const double psnr = VertexPsnr(Pebble(), *decoded);
  std::cout << "[ measured ] pebble " << Pebble().positions.size() << " vertices -> " << c.report.output_bytes
            << " B GLB (" << c.report.primitives[0].stream_bytes << " B stream), codec PSNR "
            << c.report.primitives[0].psnr_db << " dB, vertex PSNR of the loaded mesh " << psnr << " dB\n";
  EXPECT_GE(psnr, kTargetPsnr - kVertexMeterTolerance);
}

// A compressed primitive records its source's triangle count and loaders decode
// within it by default (issue: decoded assets no heavier than their source); 0
// asks for every triangle. Where the budget cannot carry the floor, the primitive
// is decoded whole and the report says why.
TEST(GltfCodec, LoadersDecodeWithinTheSourcesTriangleCountByDefault) {
  const std::string input = testing::TempPath("pebble_budget.glb");
  const std::string compressed = testing::TempPath("pebble_budget_compressed.glb");
  ASSERT_TRUE(gltf::WriteGlb(testing::MakeSingleMeshModel(Pebble()), input).ok());
  gltf::ConvertOptions options = Options();
  options.max_triangles = -1;      // the default: each primitive's own count
  options.codec.target_psnr = 0;   // one fixed-lambda encode; its 3 levels carry 5,120 triangles
  options.codec.lambda = 1.0;
  options.min_psnr = 45.0;
  auto report = gltf::ConvertToCompressedGltf(input, compressed, options);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  ASSERT_EQ(report->compressed, 1u);
  EXPECT_TRUE(report->primitives[0].note.empty()) << report->primitives[0].note;
  const size_t source = Pebble().faces.size();
  EXPECT_LE(report->primitives[0].output_triangles, source);
  auto model = gltf::ReadGltfModel(compressed);
  ASSERT_TRUE(model.ok());
  auto ext = gltf::ParseExtension(model->meshes[0].primitives[0].extensions.at(gltf::kExtensionName));
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  EXPECT_EQ(ext->triangle_budget, source);
  auto loaded = gltf::LoadGltf(compressed);
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  auto mesh = gltf::ReadTrianglePrimitive(*loaded, loaded->meshes[0].primitives[0]);
  ASSERT_TRUE(mesh.ok());
  EXPECT_LE(mesh->faces.size(), source);
  EXPECT_EQ(mesh->faces.size(), report->primitives[0].output_triangles);
  gltf::LoadOptions every;
  every.max_triangles = 0;
  auto full = gltf::LoadGltf(compressed, every);
  ASSERT_TRUE(full.ok()) << full.status().ToString();
  auto full_mesh = gltf::ReadTrianglePrimitive(*full, full->meshes[0].primitives[0]);
  ASSERT_TRUE(full_mesh.ok());
  EXPECT_GT(full_mesh->faces.size(), source);

  // A floor just above what the budget gives: decoded whole, no triangleBudget, a note.
  options.min_psnr = report->primitives[0].psnr_db + 0.01;
  const std::string whole_path = testing::TempPath("pebble_whole_compressed.glb");
  auto whole = gltf::ConvertToCompressedGltf(input, whole_path, options);
  ASSERT_TRUE(whole.ok()) << whole.status().ToString();
  ASSERT_EQ(whole->compressed, 1u) << whole->primitives[0].reason;
  EXPECT_NE(whole->primitives[0].note.find("decoded whole"), std::string::npos) << whole->primitives[0].note;
  EXPECT_GT(whole->primitives[0].output_triangles, source);
  auto whole_model = gltf::ReadGltfModel(whole_path);
  ASSERT_TRUE(whole_model.ok());
  auto whole_ext = gltf::ParseExtension(whole_model->meshes[0].primitives[0].extensions.at(gltf::kExtensionName));
  ASSERT_TRUE(whole_ext.ok());
  EXPECT_EQ(whole_ext->triangle_budget, 0u);
}

TEST(GltfCodec, EachMaxLevelGivesThatLevelsVertexCount) {
  const Converted& c = PebbleConverted();
  ASSERT_TRUE(c.status.ok()) << c.status.ToString();
  gltf::LoadOptions coarse;
  coarse.max_level = 0;
  auto base = gltf::LoadGltf(c.compressed, coarse);
  ASSERT_TRUE(base.ok()) << base.status().ToString();
  auto base_mesh = gltf::ReadTrianglePrimitive(*base, base->meshes[0].primitives[0]);
  ASSERT_TRUE(base_mesh.ok());
  const int levels = c.report.primitives[0].levels;
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(base_mesh->positions.size()), base_mesh->faces, levels);
  ASSERT_TRUE(h.ok()) << h.status().ToString();
  for (int k = 0; k <= levels; ++k) {
    gltf::LoadOptions options;
    options.max_level = k;
    gltf::LoadReport report;
    auto model = gltf::LoadGltf(c.compressed, options, &report);
    ASSERT_TRUE(model.ok()) << "K=" << k << ": " << model.status().ToString();
    const tinygltf::Primitive& p = model->meshes[0].primitives[0];
    EXPECT_EQ(model->accessors[static_cast<size_t>(p.attributes.at("POSITION"))].count, h->NumVertices(k)) << k;
    EXPECT_EQ(model->accessors[static_cast<size_t>(p.indices)].count, 3 * h->Faces(k).size()) << k;
    EXPECT_EQ(report.decoded[0].level_decoded, k);
  }
}

TEST(GltfCodec, CorruptStreamErrorNamesThePrimitive) {
  const Converted& c = PebbleConverted();
  ASSERT_TRUE(c.status.ok()) << c.status.ToString();
  auto model = gltf::ReadGltfModel(c.compressed);
  ASSERT_TRUE(model.ok());
  auto ext = gltf::ParseExtension(model->meshes[0].primitives[0].extensions.at(gltf::kExtensionName));
  ASSERT_TRUE(ext.ok());
  const tinygltf::BufferView& view = model->bufferViews[static_cast<size_t>(ext->buffer_view)];
  model->buffers[0].data[view.byteOffset] ^= 0xFF;  // the magic
  auto bytes = gltf::WriteGlbToBytes(*model);
  ASSERT_TRUE(bytes.ok());
  auto loaded = gltf::LoadGltfFromBytes(*bytes, "bad.glb");
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.status().code(), StatusCode::kCorruptStream);
  EXPECT_NE(loaded.status().message().find("bad.glb: mesh 0 primitive 0: "), std::string::npos)
      << loaded.status().message();
}

TEST(GltfCodec, MeshFileInputBecomesAOneMeshScene) {
  const std::string obj = testing::TempPath("pebble.obj");
  const std::string out = testing::TempPath("pebble_from_obj.glb");
  ASSERT_TRUE(WriteMesh(Pebble(), obj).ok());
  // The container is the subject here, not rate control: one encode at the
  // default lambda instead of a PSNR search (a quarter of this suite's time).
  gltf::ConvertOptions options = Options(true);
  options.codec.target_psnr = 0;
  options.codec.measure_psnr = false;
  auto report = gltf::ConvertToCompressedGltf(obj, out, options);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  EXPECT_EQ(report->compressed, 1u);
  auto plain = gltf::ReadGltfModel(out);  // fallback: no decoder needed
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->meshes.size(), 1u);
  EXPECT_EQ(plain->nodes.size(), 1u);
  EXPECT_TRUE(plain->extensionsRequired.empty());
  auto mesh = gltf::FlattenToMesh(*plain);
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  const double psnr = VertexPsnr(Pebble(), *mesh);
  std::cout << "[ measured ] OBJ input at the default lambda: vertex PSNR " << psnr << " dB\n";
  EXPECT_GE(psnr, kTargetPsnr - kVertexMeterTolerance);
}

// Coder 1 (zerotree) streams carry all levels in one embedded payload: range 1
// holds it, ranges 2..J are empty (rule 10), and every level K >= 1 reads both.
TEST(GltfCodec, ZerotreePrimitiveRoundTripsWithEmptyLevelRanges) {
  const std::string input = testing::TempPath("pebble_zt_in.glb");
  const std::string compressed = testing::TempPath("pebble_zerotree.glb");
  ASSERT_TRUE(gltf::WriteGlb(testing::MakeSingleMeshModel(Pebble()), input).ok());
  // Empty ranges are the subject: one encode at the default lambda, measured,
  // instead of a PSNR search.
  gltf::ConvertOptions options = Options();
  options.codec.target_psnr = 0;
  options.codec.coder = bitstream::CoderId::kZerotree;
  auto report = gltf::ConvertToCompressedGltf(input, compressed, options);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  ASSERT_EQ(report->compressed, 1u) << report->primitives[0].reason;
  const int levels = report->primitives[0].levels;
  ASSERT_GE(levels, 2) << "needs empty ranges to be a test of rule 10";
  std::cout << "[ measured ] zerotree primitive at the default lambda: " << report->primitives[0].psnr_db << " dB\n";
  EXPECT_GE(report->primitives[0].psnr_db, kTargetPsnr - 0.5);

  auto raw = gltf::ReadGltfModel(compressed);
  ASSERT_TRUE(raw.ok()) << raw.status().ToString();
  auto ext = gltf::ParseExtension(raw->meshes[0].primitives[0].extensions.at(gltf::kExtensionName));
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  EXPECT_GT(ext->level_ranges[1].length, 0u);
  for (int j = 2; j <= levels; ++j) EXPECT_EQ(ext->level_ranges[static_cast<size_t>(j)].length, 0u) << j;
  const tinygltf::BufferView& view = raw->bufferViews[static_cast<size_t>(ext->buffer_view)];
  auto info = ReadStreamInfo(raw->buffers[0].data.data() + view.byteOffset, view.byteLength);
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->coder, bitstream::CoderId::kZerotree);

  // Full load: exactly what the codec decodes.
  auto reference = Decode(raw->buffers[0].data.data() + view.byteOffset, view.byteLength);
  ASSERT_TRUE(reference.ok()) << reference.status().ToString();
  auto model = gltf::LoadGltf(compressed);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  auto decoded = gltf::ReadTrianglePrimitive(*model, model->meshes[0].primitives[0]);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  ASSERT_EQ(reference->positions.size(), decoded->positions.size());
  EXPECT_EQ(reference->faces, decoded->faces);
  for (size_t i = 0; i < decoded->positions.size(); ++i) {
    EXPECT_LT((reference->positions[i] - decoded->positions[i]).norm(), 1e-6 * BoundingBoxDiagonal(Pebble()));
  }
  EXPECT_GE(VertexPsnr(Pebble(), *decoded), kTargetPsnr - kVertexMeterTolerance);

  // Every level: its own counts; level 0 reads range 0 only, the others ranges 0 and 1.
  for (int k = 0; k <= levels; ++k) {
    gltf::LoadOptions coarse;
    coarse.max_level = k;
    gltf::LoadReport load;
    auto level = gltf::LoadGltf(compressed, coarse, &load);
    ASSERT_TRUE(level.ok()) << "K=" << k << ": " << level.status().ToString();
    EXPECT_EQ(load.decoded[0].level_decoded, k);
    EXPECT_EQ(load.decoded[0].stream_bytes_read, ext->level_ranges[k == 0 ? 0 : 1].end()) << k;
    auto mesh = gltf::ReadTrianglePrimitive(*level, level->meshes[0].primitives[0]);
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(mesh->faces.size(), reference->faces.size() >> (2 * (levels - k))) << k;
  }

  std::string why;
  const auto validated = testing::RunKhronosValidator(compressed, &why);
  if (!validated) GTEST_SKIP() << why;
  EXPECT_EQ(validated->errors, 0) << validated->messages;
}

TEST(GltfCodec, KhronosValidatorAcceptsCompressedAndDecodedFiles) {
  const Converted& c = PebbleConverted();
  ASSERT_TRUE(c.status.ok()) << c.status.ToString();
  const std::string decoded = testing::TempPath("pebble_decoded.glb");
  auto model = gltf::LoadGltf(c.compressed);
  ASSERT_TRUE(model.ok());
  ASSERT_TRUE(gltf::WriteDecodedGlb(*model, decoded).ok());
  std::string why;
  const auto compressed = testing::RunKhronosValidator(c.compressed, &why);
  if (!compressed) GTEST_SKIP() << why;
  EXPECT_EQ(compressed->errors, 0) << compressed->messages;
  const auto plain = testing::RunKhronosValidator(decoded, &why);
  ASSERT_TRUE(plain) << why;
  EXPECT_EQ(plain->errors, 0) << plain->messages;
  EXPECT_EQ(plain->warnings, 0) << plain->messages;
}

}  // namespace
}  // namespace eqmesh
