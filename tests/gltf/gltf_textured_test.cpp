// Textured primitives end to end: the Duck (../shared/meshes/textured/duck.glb,
// baseColor and KHR_materials_pbrSpecularGlossiness' diffuse sampling one JPEG)
// compressed with an atlas and decoded back to a plain textured glTF.
#include <gtest/gtest.h>

#include <algorithm>

#include "gltf/accessor_io.h"
#include "gltf/gltf_converter.h"
#include "gltf/gltf_io.h"
#include "gltf/gltf_loader.h"
#include "gltf/material_textures.h"
#include "gltf/textured_compression.h"
#include "gltf_test_support.h"
#include "mesh/file_bytes.h"
#include "test_support.h"

namespace eqmesh {
namespace {

struct Converted {
  std::string path;
  gltf::ConvertReport report;
};

gltf::ConvertOptions DuckOptions() {
  gltf::ConvertOptions options;
  options.remesh.levels = 3;
  options.codec.lambda = 1.0;
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

}  // namespace
}  // namespace eqmesh
