// Textured primitives end to end: the Duck (../shared/meshes/textured/duck.glb,
// baseColor and KHR_materials_pbrSpecularGlossiness' diffuse sampling one JPEG)
// compressed with an atlas and decoded back to a plain textured glTF.
#include <gtest/gtest.h>

#include <algorithm>

#include "gltf/accessor_io.h"
#include "gltf/buffer_layout.h"
#include "gltf/gltf_converter.h"
#include "gltf/gltf_io.h"
#include "gltf/gltf_loader.h"
#include "gltf/material_textures.h"
#include "gltf/surface_color.h"
#include "gltf/textured_compression.h"
#include "gltf_test_support.h"
#include "mesh_io/file_bytes.h"
#include "test_support.h"

namespace eqmesh {
namespace {

struct Converted {
  std::string path;
  gltf::ConvertReport report;
};

// Three levels and a 128-texel atlas: the properties checked do not depend on
// size, and the sanitizer build runs this too.
gltf::ConvertOptions DuckOptions() {
  gltf::ConvertOptions options;
  options.remesh.levels = 3;
  options.codec.lambda = 1.0;
  options.texture_size = 128;
  return options;
}

// The Duck converted once (a remesh and an atlas paint: a few seconds).
const Converted& Duck() {
  static const Converted converted = [] {
    Converted c;
    c.path = testing::TempPath("duck_textured.glb");
    auto report = gltf::ConvertToCompressedGltf(testing::SharedPath("meshes/textured/duck.glb"), c.path, DuckOptions());
    EXPECT_TRUE(report.ok()) << report.status().ToString();
    if (report.ok()) c.report = *report;
    return c;
  }();
  return converted;
}

TEST(GltfTextured, TheDuckIsCompressedWithOneAtlasImageForItsTwoSlots) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no ../shared/meshes";
  const Converted& duck = Duck();
  ASSERT_EQ(duck.report.compressed, 1u) << (duck.report.primitives.empty() ? "" : duck.report.primitives[0].reason);
  auto model = gltf::ReadGltfModel(duck.path);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  ASSERT_EQ(model->images.size(), 1u);  // the input's image is gone, the atlas shared
  ASSERT_EQ(model->materials.size(), 1u);
  const std::vector<gltf::TextureSlot> slots = gltf::UsedTextureSlots(model->materials[0]);
  ASSERT_EQ(slots.size(), 2u);
  EXPECT_EQ(slots[0].index, slots[1].index);
  for (const gltf::TextureSlot& s : slots) EXPECT_EQ(s.tex_coord, 0);
  const tinygltf::Primitive& p = model->meshes[0].primitives[0];
  EXPECT_EQ(p.attributes.count("TEXCOORD_0"), 1u);
}

TEST(GltfTextured, DecodedDuckHasTexcoordsInsideTheAtlasAndWatertightPositions) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no ../shared/meshes";
  const Converted& duck = Duck();
  ASSERT_EQ(duck.report.compressed, 1u);
  for (int level : {0, 2, -1}) {
    gltf::LoadOptions load;
    load.max_level = level;
    auto model = gltf::LoadGltf(duck.path, load);
    ASSERT_TRUE(model.ok()) << model.status().ToString();
    const tinygltf::Primitive& p = model->meshes[0].primitives[0];
    ASSERT_EQ(p.attributes.count("TEXCOORD_0"), 1u);
    auto uv = gltf::ReadTexcoordAccessor(*model, p.attributes.at("TEXCOORD_0"), "TEXCOORD_0");
    ASSERT_TRUE(uv.ok()) << uv.status().ToString();
    auto mesh = gltf::ReadTrianglePrimitive(*model, p);
    ASSERT_TRUE(mesh.ok());
    ASSERT_EQ(uv->size(), mesh->positions.size());
    for (const auto& t : *uv) EXPECT_TRUE(t[0] > 0 && t[0] < 1 && t[1] > 0 && t[1] < 1);
    // Split copies repeat positions exactly: welding them closes every seam, so
    // the welded mesh has no more boundary than the input's (the Duck has none).
    const Mesh welded = gltf::WeldedByPosition(*mesh);
    EXPECT_LT(welded.positions.size(), mesh->positions.size());
  }
}

TEST(GltfTextured, ConversionIsDeterministicAndValidatorClean) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no ../shared/meshes";
  const Converted& duck = Duck();
  const std::string again = testing::TempPath("duck_textured_again.glb");
  ASSERT_TRUE(gltf::ConvertToCompressedGltf(testing::SharedPath("meshes/textured/duck.glb"), again, DuckOptions()).ok());
  auto a = ReadFileBytes(duck.path, 1u << 30), b = ReadFileBytes(again, 1u << 30);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(*a == *b);
  const std::string decoded = testing::TempPath("duck_textured_decoded.glb");
  auto model = gltf::LoadGltf(duck.path);
  ASSERT_TRUE(model.ok());
  ASSERT_TRUE(gltf::WriteDecodedGlb(*model, decoded).ok());
  std::string why;
  for (const std::string& path : {duck.path, decoded}) {
    const auto counts = testing::RunKhronosValidator(path, &why);
    if (!counts) GTEST_SKIP() << why;
    EXPECT_EQ(counts->errors, 0) << path;
    EXPECT_EQ(counts->warnings, 0) << path;
  }
}

// A vertex-coloured mesh: COLOR_0 = a smooth RGB ramp over the position, no
// material (glTF's default one).
tinygltf::Model VertexColoured(const Mesh& mesh) {
  auto model = gltf::ModelFromMesh(mesh);
  EXPECT_TRUE(model.ok());
  std::vector<float> colors;
  for (const Vec3& p : mesh.positions) {
    for (double c : {0.5 + 0.4 * p.x(), 0.5 + 0.4 * p.y(), 0.5 + 0.4 * p.z()}) colors.push_back(static_cast<float>(c));
  }
  tinygltf::Accessor accessor;
  accessor.bufferView = gltf::AppendBufferView(&*model, reinterpret_cast<const uint8_t*>(colors.data()),
                                               colors.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = TINYGLTF_TYPE_VEC3;
  accessor.count = mesh.positions.size();
  model->accessors.push_back(accessor);
  model->meshes[0].primitives[0].attributes["COLOR_0"] = static_cast<int>(model->accessors.size()) - 1;
  return *model;
}

tinygltf::Model VertexColouredSphere() { return VertexColoured(testing::MakeIcosphere(4)); }

// A short conversion (two levels, a coarse lambda): the tests are about what the
// primitive becomes, not about its rate.
StatusOr<gltf::ConvertReport> ConvertShort(tinygltf::Model* model) {
  gltf::ConvertOptions options;
  options.remesh.levels = 2;
  options.codec.lambda = 1.0;
  return gltf::ConvertModel(model, options);
}

TEST(GltfTextured, VertexColoursAreBakedIntoABaseColourTexture) {
  const tinygltf::Model original = VertexColouredSphere();
  tinygltf::Model model = original;
  auto report = ConvertShort(&model);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  ASSERT_EQ(report->compressed, 1u) << report->primitives[0].reason;
  const tinygltf::Primitive& p = model.meshes[0].primitives[0];
  EXPECT_EQ(p.attributes.count("COLOR_0"), 0u);
  ASSERT_GE(p.material, 0);
  const tinygltf::Material& material = model.materials[static_cast<size_t>(p.material)];
  EXPECT_GE(material.pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_EQ(material.pbrMetallicRoughness.metallicFactor, 1.0);  // glTF's default material otherwise
  ASSERT_TRUE(gltf::DecodeCompressedPrimitives(&model).ok());
  auto a = gltf::FlattenWithColor(original);
  auto b = gltf::FlattenWithColor(model);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(a->varies && b->varies);
  auto d = CompareColors(a->mesh, a->color, b->mesh, b->color, {100000});
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_GT(d->psnr_db, 35.0) << "colour rms " << d->rms;
}

TEST(GltfTextured, TouchingPartsAreWeldedOnlyWhereThatKeepsTheSurfaceManifold) {
  // Two spheres touching at one point through two vertices: a weld of every
  // coincident pair would pinch them there, and the remesher refuses a pinch.
  const Mesh sphere = testing::MakeIcosphere(3);
  const Mesh touching = testing::WithComponent(sphere, sphere, 2.0 * sphere.positions[0]);
  tinygltf::Model model = VertexColoured(touching);
  auto report = ConvertShort(&model);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  EXPECT_EQ(report->compressed, 1u) << report->primitives[0].reason;
}

}  // namespace
}  // namespace eqmesh
