// Container logic of EXT_normal_mesh_compression with a stand-in stream
// (fake_stream.h): everything the converter and loader do that does not depend on
// the codec's output. The codec round trip is in gltf_codec_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fake_stream.h"
#include "gltf/accessor_io.h"
#include "gltf/compress_primitives.h"
#include "gltf/extension.h"
#include "gltf/gltf_io.h"
#include "gltf/gltf_loader.h"
#include "gltf_test_support.h"
#include "mesh/semi_regular.h"
#include "test_support.h"

namespace eqmesh {
namespace {

using gltf::kExtensionName;

constexpr int kLevels = 3;

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first ```json block of ext_spec/README.md: the spec's example.
nlohmann::json SpecExample() {
  const std::string text = ReadText(std::string(EQMESH_SOURCE_DIR) + "/ext_spec/README.md");
  const std::smatch m = [&] {
    std::smatch match;
    std::regex_search(text, match, std::regex("```json\\n([\\s\\S]*?)```"));
    return match;
  }();
  return nlohmann::json::parse(m.size() > 1 ? m[1].str() : std::string("null"), nullptr, false);
}

tinygltf::Value ToValue(const nlohmann::json& j) {
  if (j.is_object()) {
    tinygltf::Value::Object o;
    for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = ToValue(it.value());
    return tinygltf::Value(std::move(o));
  }
  if (j.is_array()) {
    tinygltf::Value::Array a;
    for (const auto& e : j) a.push_back(ToValue(e));
    return tinygltf::Value(std::move(a));
  }
  if (j.is_number_integer()) return tinygltf::Value(j.get<int>());
  if (j.is_number()) return tinygltf::Value(j.get<double>());
  if (j.is_string()) return tinygltf::Value(j.get<std::string>());
  if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
  return tinygltf::Value();
}

nlohmann::json SpecExtensionObject() {
  return SpecExample()["meshes"][0]["primitives"][0]["extensions"][kExtensionName];
}

gltf::LoadOptions FakeLoad(int max_level = -1) {
  gltf::LoadOptions options;
  options.max_level = max_level;
  options.decoder = [](const uint8_t* data, size_t size, int level, uint64_t budget) {
    return testing::DecodeFakeStream(data, size, level, budget);
  };
  return options;
}

// Rich scene -> compressed GLB bytes.
std::vector<uint8_t> CompressedRichScene(bool fallback, gltf::ConvertReport* report = nullptr) {
  tinygltf::Model model = testing::MakeRichScene();
  gltf::ConvertReport local;
  const Status s = gltf::CompressPrimitives(&model, testing::FakeCompressor(kLevels), {fallback, false},
                                            report ? report : &local);
  EXPECT_TRUE(s.ok()) << s.ToString();
  auto bytes = gltf::WriteGlbToBytes(model);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  return bytes.ok() ? *bytes : std::vector<uint8_t>{};
}

// The fake stream dressed as an embedded (coder 1) stream: its level chunks are
// announced as one range 1 and empty ranges 2..J, and the decoder reports `coder`.
gltf::DecodedStream AsEmbedded(gltf::DecodedStream d, int coder) {
  uint64_t levels_bytes = 0;
  for (size_t j = 1; j < d.chunk_lengths.size(); ++j) levels_bytes += d.chunk_lengths[j];
  for (size_t j = 1; j < d.chunk_lengths.size(); ++j) d.chunk_lengths[j] = j == 1 ? levels_bytes : 0;
  d.coder = coder;
  return d;
}

gltf::GeometryCompressor EmbeddedFakeCompressor(int levels) {
  return [levels](const gltf::PrimitiveGeometry& primitive, const std::string& label) -> StatusOr<gltf::CompressedGeometry> {
    EQMESH_ASSIGN_OR_RETURN(gltf::CompressedGeometry out, testing::FakeCompressor(levels)(primitive, label));
    gltf::DecodedStream lengths;
    lengths.chunk_lengths = out.chunk_lengths;
    out.chunk_lengths = AsEmbedded(std::move(lengths), gltf::kEmbeddedCoderId).chunk_lengths;
    return out;
  };
}

gltf::LoadOptions EmbeddedFakeLoad(int coder, int max_level = -1) {
  gltf::LoadOptions options;
  options.max_level = max_level;
  options.decoder = [coder](const uint8_t* data, size_t size, int level, uint64_t) -> StatusOr<gltf::DecodedStream> {
    EQMESH_ASSIGN_OR_RETURN(gltf::DecodedStream d, testing::DecodeFakeStream(data, size, level));
    return AsEmbedded(std::move(d), coder);
  };
  return options;
}

size_t ExpectedVertices(const Mesh& base, int level) {
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()), base.faces, level);
  return h.ok() ? h->NumVertices(level) : 0;
}

void WriteFile(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

TEST(GltfExtension, SpecExampleMatchesExampleFileAndParses) {
  const nlohmann::json example = SpecExample();
  ASSERT_FALSE(example.is_discarded()) << "ext_spec/README.md has no parsable ```json example";
  const nlohmann::json file =
      nlohmann::json::parse(ReadText(std::string(EQMESH_SOURCE_DIR) + "/ext_spec/examples/example.gltf"));
  EXPECT_EQ(example, file) << "ext_spec/examples/example.gltf differs from the README's example";
  auto ext = gltf::ParseExtension(ToValue(SpecExtensionObject()));
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  EXPECT_EQ(ext->levels, 3);
  EXPECT_EQ(ext->level_ranges.size(), 4u);
  // Rule 10 against the example's own bufferView.
  EXPECT_EQ(ext->level_ranges.back().end(), example["bufferViews"][0]["byteLength"].get<uint64_t>());
  // Rule 11's vertex / index relation for a closed genus-0 semi-regular mesh: V = F/2 + 2.
  const uint64_t vertices = example["accessors"][0]["count"].get<uint64_t>();
  const uint64_t indices = example["accessors"][2]["count"].get<uint64_t>();
  EXPECT_EQ(vertices, indices / 3 / 2 + 2);
}

TEST(GltfExtension, RejectsObjectsBreakingTheRules) {
  const nlohmann::json good = SpecExtensionObject();
  std::vector<std::pair<std::string, nlohmann::json>> cases;
  auto with = [&](const std::string& name, auto edit) {
    nlohmann::json j = good;
    edit(j);
    cases.emplace_back(name, j);
  };
  with("missing bufferView", [](nlohmann::json& j) { j.erase("bufferView"); });
  with("levels too large", [](nlohmann::json& j) { j["levels"] = 13; });
  with("wrong range count", [](nlohmann::json& j) { j["levels"] = 2; });
  with("gap between ranges", [](nlohmann::json& j) { j["levelByteRanges"][1][0] = 2141; });
  with("range not a pair", [](nlohmann::json& j) { j["levelByteRanges"][0] = {0}; });
  with("empty range", [](nlohmann::json& j) { j["levelByteRanges"][3][1] = 0; });
  with("empty range 1", [](nlohmann::json& j) {
    j["levelByteRanges"][1][1] = 0;
    j["levelByteRanges"][2][0] = 2140;
  });
  with("empty range 0", [](nlohmann::json& j) {
    j["levelByteRanges"][0][1] = 0;
    j["levelByteRanges"][1][0] = 0;
  });
  with("negative offset", [](nlohmann::json& j) { j["levelByteRanges"][0][0] = -1; });
  with("fractional length", [](nlohmann::json& j) { j["levelByteRanges"][0][1] = 2140.5; });
  with("no POSITION", [](nlohmann::json& j) { j["attributes"].erase("POSITION"); });
  with("extra attribute", [](nlohmann::json& j) { j["attributes"]["COLOR_0"] = 3; });
  with("zero triangle budget", [](nlohmann::json& j) { j["triangleBudget"] = 0; });
  with("negative triangle budget", [](nlohmann::json& j) { j["triangleBudget"] = -5; });
  with("fractional triangle budget", [](nlohmann::json& j) { j["triangleBudget"] = 100.5; });
  with("string triangle budget", [](nlohmann::json& j) { j["triangleBudget"] = "100"; });
  for (const auto& [name, j] : cases) {
    EXPECT_FALSE(gltf::ParseExtension(ToValue(j)).ok()) << name;
  }
  nlohmann::json budgeted = good;
  budgeted["triangleBudget"] = 12000;
  auto ext = gltf::ParseExtension(ToValue(budgeted));
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  EXPECT_EQ(ext->triangle_budget, 12000u);
  auto again = gltf::ParseExtension(gltf::ExtensionToValue(*ext));
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->triangle_budget, 12000u);
}

TEST(GltfExtension, AcceptsTheCoder1ShapeOfEmptyRanges) {
  // Ranges 2..J all empty: the shape of a zerotree stream (rule 10), still
  // rejected for other coders once the stream header is read (see below).
  nlohmann::json j = SpecExtensionObject();
  j["levelByteRanges"] = {{0, 2140}, {2140, 4982}, {7122, 0}, {7122, 0}};
  auto ext = gltf::ParseExtension(ToValue(j));
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  EXPECT_TRUE(gltf::CheckRangesForCoder(*ext, gltf::kEmbeddedCoderId).ok());
  for (int coder : {0, 2}) {
    const Status s = gltf::CheckRangesForCoder(*ext, coder);
    EXPECT_FALSE(s.ok()) << coder;
    EXPECT_NE(s.message().find("rule 10"), std::string::npos) << s.message();
  }
}

TEST(GltfExtension, SpecExampleValidatesAgainstSchema) {
  const std::string schema =
      std::string(EQMESH_SOURCE_DIR) + "/ext_spec/schema/mesh.primitive.EXT_normal_mesh_compression.schema.json";
  const std::string good = testing::TempPath("schema_good.json");
  const std::string bad = testing::TempPath("schema_bad.json");
  std::ofstream(good) << SpecExtensionObject().dump();
  nlohmann::json broken = SpecExtensionObject();
  broken.erase("levels");
  broken["attributes"]["COLOR_0"] = 1;
  std::ofstream(bad) << broken.dump();
  std::string why, output;
  const auto valid = testing::RunSchemaValidator(schema, good, &why, &output);
  if (!valid) GTEST_SKIP() << why;
  EXPECT_TRUE(*valid) << output;
  const auto invalid = testing::RunSchemaValidator(schema, bad, &why, &output);
  ASSERT_TRUE(invalid.has_value()) << why;
  EXPECT_FALSE(*invalid) << output;
}

TEST(GltfContainer, CompressedFileKeepsTheSceneAndDropsOldGeometry) {
  gltf::ConvertReport report;
  const std::vector<uint8_t> glb = CompressedRichScene(false, &report);
  EXPECT_EQ(report.compressed, 2u);
  EXPECT_EQ(report.unchanged, 1u);
  EXPECT_NE(report.primitives[2].reason.find("no texture atlas"), std::string::npos) << report.primitives[2].reason;
  auto model = gltf::ReadGltfModelFromBytes(glb, "compressed.glb");
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  const tinygltf::Model original = testing::MakeRichScene();
  EXPECT_EQ(model->extensionsUsed, std::vector<std::string>{kExtensionName});
  EXPECT_EQ(model->extensionsRequired, std::vector<std::string>{kExtensionName});
  ASSERT_EQ(model->nodes.size(), 4u);
  EXPECT_EQ(model->nodes[0].children, std::vector<int>{1});
  EXPECT_EQ(model->nodes[0].translation, original.nodes[0].translation);
  EXPECT_EQ(model->nodes[1].scale, original.nodes[1].scale);
  EXPECT_EQ(model->nodes[0].extras.Get("note").Get<std::string>(), "keep me");
  EXPECT_EQ(model->nodes[2].camera, 0);
  ASSERT_EQ(model->cameras.size(), 1u);
  EXPECT_EQ(model->asset.extras.Get("origin").Get<std::string>(), "gltf_container_test");
  EXPECT_EQ(model->meshes[1].extras.Get("kind").Get<std::string>(), "ring");
  ASSERT_EQ(model->materials.size(), 2u);
  EXPECT_EQ(model->materials[1].extras.Get("finish").Get<std::string>(), "matte");
  EXPECT_EQ(model->materials[0].pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_EQ(model->meshes[0].primitives[0].material, 1);
  EXPECT_EQ(model->meshes[2].primitives[0].material, 0);
  EXPECT_EQ(model->meshes[2].primitives[0].attributes.count("TEXCOORD_0"), 1u);
  ASSERT_EQ(model->animations.size(), 1u);
  EXPECT_EQ(model->animations[0].channels[0].target_node, 1);
  // Buffer views left: 2 streams, the image, the animation's input and output, the
  // quad's three.
  EXPECT_EQ(model->bufferViews.size(), 8u);
  auto quad = gltf::ReadTrianglePrimitive(*model, model->meshes[2].primitives[0]);
  ASSERT_TRUE(quad.ok()) << quad.status().ToString();
  EXPECT_EQ(quad->faces.size(), 2u);
  for (size_t m = 0; m < 2; ++m) {
    const tinygltf::Primitive& p = model->meshes[m].primitives[0];
    ASSERT_EQ(p.extensions.count(kExtensionName), 1u);
    for (const auto& [semantic, accessor] : p.attributes) {
      EXPECT_EQ(model->accessors[static_cast<size_t>(accessor)].bufferView, -1) << semantic << " is a placeholder";
    }
  }
}

TEST(GltfContainer, LoaderRestoresPlainGeometryAndKeepsTheRest) {
  const std::vector<uint8_t> glb = CompressedRichScene(false);
  gltf::LoadReport report;
  auto model = gltf::LoadGltfFromBytes(glb, "compressed.glb", FakeLoad(), &report);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  ASSERT_EQ(report.decoded.size(), 2u);
  EXPECT_TRUE(model->extensionsUsed.empty());
  EXPECT_TRUE(model->extensionsRequired.empty());
  const Mesh bases[2] = {testing::MakeIcosphere(1), testing::MakeTorus(8, 6)};
  for (size_t m = 0; m < 2; ++m) {
    const tinygltf::Primitive& p = model->meshes[m].primitives[0];
    EXPECT_TRUE(p.extensions.empty());
    auto mesh = gltf::ReadTrianglePrimitive(*model, p);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(mesh->positions.size(), ExpectedVertices(bases[m], kLevels));
    EXPECT_EQ(mesh->faces.size(), bases[m].faces.size() << (2 * kLevels));
    auto normals = gltf::ReadVec3Accessor(*model, p.attributes.at("NORMAL"), "NORMAL");
    ASSERT_TRUE(normals.ok());
    for (const Vec3& n : *normals) EXPECT_NEAR(n.norm(), 1.0, 1e-6);
  }
  // The image bytes travel unchanged.
  const tinygltf::Image& image = model->images[0];
  ASSERT_GE(image.bufferView, 0);
  const tinygltf::BufferView& view = model->bufferViews[static_cast<size_t>(image.bufferView)];
  const auto& data = model->buffers[static_cast<size_t>(view.buffer)].data;
  const std::vector<unsigned char> bytes(data.begin() + static_cast<std::ptrdiff_t>(view.byteOffset),
                                         data.begin() + static_cast<std::ptrdiff_t>(view.byteOffset + view.byteLength));
  EXPECT_EQ(bytes, testing::TinyPng());
  // Streams are gone: image, animation x2, quad x3, and 3 geometry views per primitive.
  EXPECT_EQ(model->bufferViews.size(), 6u + 6u);
}

TEST(GltfContainer, MaxLevelGivesEachLevelsVertexCountAndReadsOnlyItsBytes) {
  const std::vector<uint8_t> glb = CompressedRichScene(false);
  const Mesh sphere = testing::MakeIcosphere(1);
  auto compressed = gltf::ReadGltfModelFromBytes(glb, "compressed.glb");
  ASSERT_TRUE(compressed.ok());
  auto ext = gltf::ParseExtension(compressed->meshes[0].primitives[0].extensions.at(kExtensionName));
  ASSERT_TRUE(ext.ok());
  for (int k = 0; k <= kLevels + 1; ++k) {
    gltf::LoadReport report;
    auto model = gltf::LoadGltfFromBytes(glb, "compressed.glb", FakeLoad(k), &report);
    ASSERT_TRUE(model.ok()) << "K=" << k << ": " << model.status().ToString();
    const int level = std::min(k, kLevels);
    const tinygltf::Primitive& p = model->meshes[0].primitives[0];
    const tinygltf::Accessor& pos = model->accessors[static_cast<size_t>(p.attributes.at("POSITION"))];
    EXPECT_EQ(pos.count, ExpectedVertices(sphere, level)) << "K=" << k;
    EXPECT_EQ(report.decoded[0].level_decoded, level);
    EXPECT_EQ(report.decoded[0].stream_bytes_read, ext->level_ranges[static_cast<size_t>(level)].end());
  }
}

TEST(GltfContainer, EmptyLevelRangesLoadForCoder1Only) {
  tinygltf::Model model = testing::MakeRichScene();
  gltf::ConvertReport report;
  ASSERT_TRUE(gltf::CompressPrimitives(&model, EmbeddedFakeCompressor(kLevels), {}, &report).ok());
  ASSERT_EQ(report.compressed, 2u);
  auto ext = gltf::ParseExtension(model.meshes[0].primitives[0].extensions.at(kExtensionName));
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  for (int j = 2; j <= kLevels; ++j) EXPECT_EQ(ext->level_ranges[static_cast<size_t>(j)].length, 0u);
  auto glb = gltf::WriteGlbToBytes(model);
  ASSERT_TRUE(glb.ok());
  const Mesh sphere = testing::MakeIcosphere(1);
  for (int k = 0; k <= kLevels; ++k) {
    gltf::LoadReport load;
    auto loaded = gltf::LoadGltfFromBytes(*glb, "embedded.glb", EmbeddedFakeLoad(gltf::kEmbeddedCoderId, k), &load);
    ASSERT_TRUE(loaded.ok()) << "K=" << k << ": " << loaded.status().ToString();
    const tinygltf::Primitive& p = loaded->meshes[0].primitives[0];
    EXPECT_EQ(loaded->accessors[static_cast<size_t>(p.attributes.at("POSITION"))].count,
              ExpectedVertices(sphere, k));
    // Level 0 needs range 0; every finer level needs range 1, the whole payload.
    EXPECT_EQ(load.decoded[0].stream_bytes_read, ext->level_ranges[k == 0 ? 0 : 1].end());
  }
  // The same JSON over a stream whose header names coder 0 breaks rule 10.
  auto refused = gltf::LoadGltfFromBytes(*glb, "not_embedded.glb", EmbeddedFakeLoad(0));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("not_embedded.glb: mesh 0 primitive 0: "), std::string::npos)
      << refused.status().message();
  EXPECT_NE(refused.status().message().find("rule 10"), std::string::npos) << refused.status().message();
  // The validator sees a valid asset (it does not know the extension's rules).
  const std::string path = testing::TempPath("container_embedded.glb");
  WriteFile(path, *glb);
  std::string why;
  const auto v = testing::RunKhronosValidator(path, &why);
  if (!v) GTEST_SKIP() << why;
  EXPECT_EQ(v->errors, 0) << v->messages;
}

TEST(GltfContainer, FallbackFileOpensInALoaderWithoutTheExtension) {
  const std::vector<uint8_t> glb = CompressedRichScene(true);
  // A plain tinygltf load: no decoding at all.
  auto plain = gltf::ReadGltfModelFromBytes(glb, "fallback.glb");
  ASSERT_TRUE(plain.ok()) << plain.status().ToString();
  EXPECT_EQ(plain->extensionsUsed, std::vector<std::string>{kExtensionName});
  EXPECT_TRUE(plain->extensionsRequired.empty());
  auto plain_mesh = gltf::ReadTrianglePrimitive(*plain, plain->meshes[0].primitives[0]);
  ASSERT_TRUE(plain_mesh.ok()) << plain_mesh.status().ToString();
  const std::vector<uint8_t> stream = testing::MakeFakeStream(testing::MakeIcosphere(1), kLevels);
  auto decoded = testing::DecodeFakeStream(stream.data(), stream.size(), -1);
  ASSERT_TRUE(decoded.ok());
  ASSERT_EQ(plain_mesh->positions.size(), decoded->mesh.positions.size());
  EXPECT_EQ(plain_mesh->faces, decoded->mesh.faces);
  for (size_t i = 0; i < decoded->mesh.positions.size(); ++i) {
    EXPECT_LT((plain_mesh->positions[i] - decoded->mesh.positions[i]).norm(), 1e-6);
  }
  // Our loader decodes the stream instead and drops the fallback copy.
  auto loaded = gltf::LoadGltfFromBytes(glb, "fallback.glb", FakeLoad());
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  EXPECT_TRUE(loaded->extensionsUsed.empty());
  EXPECT_EQ(loaded->bufferViews.size(), 6u + 6u);
}

TEST(GltfContainer, CorruptStreamErrorNamesThePrimitive) {
  gltf::ConvertReport report;
  std::vector<uint8_t> glb = CompressedRichScene(false, &report);
  auto model = gltf::ReadGltfModelFromBytes(glb, "x.glb");
  ASSERT_TRUE(model.ok());
  // Damage the last byte of mesh 1's stream (its last level chunk).
  auto ext = gltf::ParseExtension(model->meshes[1].primitives[0].extensions.at(kExtensionName));
  ASSERT_TRUE(ext.ok());
  tinygltf::BufferView& view = model->bufferViews[static_cast<size_t>(ext->buffer_view)];
  model->buffers[0].data[view.byteOffset + view.byteLength - 1] ^= 0xFF;
  auto damaged = gltf::WriteGlbToBytes(*model);
  ASSERT_TRUE(damaged.ok());
  auto loaded = gltf::LoadGltfFromBytes(*damaged, "damaged.glb", FakeLoad());
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.status().code(), StatusCode::kCorruptStream);
  EXPECT_NE(loaded.status().message().find("damaged.glb: mesh 1 primitive 0: "), std::string::npos)
      << loaded.status().message();
  // Level 2 does not need the damaged chunk.
  EXPECT_TRUE(gltf::LoadGltfFromBytes(*damaged, "damaged.glb", FakeLoad(2)).ok());
}

TEST(GltfContainer, JsonThatContradictsTheStreamIsAnErrorOfThatPrimitive) {
  std::vector<uint8_t> glb = CompressedRichScene(false);
  auto model = gltf::ReadGltfModelFromBytes(glb, "x.glb");
  ASSERT_TRUE(model.ok());
  tinygltf::Primitive& p = model->meshes[0].primitives[0];
  // Declare one vertex too many on the placeholder (rule 11).
  model->accessors[static_cast<size_t>(p.attributes.at("POSITION"))].count += 1;
  auto bytes = gltf::WriteGlbToBytes(*model);
  ASSERT_TRUE(bytes.ok());
  auto loaded = gltf::LoadGltfFromBytes(*bytes, "lying.glb", FakeLoad());
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.status().message().find("mesh 0 primitive 0"), std::string::npos) << loaded.status().message();
  // A primitive attribute the spec forbids (rule 3).
  auto model2 = gltf::ReadGltfModelFromBytes(glb, "x.glb");
  ASSERT_TRUE(model2.ok());
  model2->meshes[1].primitives[0].attributes["COLOR_0"] = 0;
  const Status s = gltf::DecodeCompressedPrimitives(&*model2, FakeLoad());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("mesh 1 primitive 0: attribute COLOR_0"), std::string::npos) << s.message();
  // TEXCOORD_0 the extension does not declare (rule 5).
  auto model3 = gltf::ReadGltfModelFromBytes(glb, "x.glb");
  ASSERT_TRUE(model3.ok());
  model3->meshes[1].primitives[0].attributes["TEXCOORD_0"] = 0;
  const Status s3 = gltf::DecodeCompressedPrimitives(&*model3, FakeLoad());
  ASSERT_FALSE(s3.ok());
  EXPECT_NE(s3.message().find("TEXCOORD_0 differs"), std::string::npos) << s3.message();
}

TEST(GltfContainer, PrimitivesThatCannotBeRemeshedAreLeftAndReported) {
  tinygltf::Model model = testing::MakeRichScene();
  tinygltf::Primitive lines = model.meshes[0].primitives[0];
  lines.mode = TINYGLTF_MODE_LINE;
  lines.material = -1;
  model.meshes[0].primitives.push_back(lines);
  model.meshes[1].primitives[0].attributes["TEXCOORD_0"] = model.meshes[1].primitives[0].attributes["NORMAL"];
  gltf::ConvertReport report;
  ASSERT_TRUE(gltf::CompressPrimitives(&model, testing::FakeCompressor(1), {}, &report).ok());
  ASSERT_EQ(report.primitives.size(), 4u);
  EXPECT_TRUE(report.primitives[0].compressed);
  EXPECT_FALSE(report.primitives[1].compressed);
  EXPECT_NE(report.primitives[1].reason.find("not TRIANGLES"), std::string::npos);
  EXPECT_FALSE(report.primitives[2].compressed);
  EXPECT_NE(report.primitives[2].reason.find("TEXCOORD_0"), std::string::npos);
  EXPECT_FALSE(report.primitives[3].compressed);
  // The line primitive still has its data; the torus is untouched.
  EXPECT_GE(model.accessors[static_cast<size_t>(model.meshes[0].primitives[1].attributes.at("POSITION"))].bufferView, 0);
  EXPECT_TRUE(model.meshes[1].primitives[0].extensions.empty());
  // With drop_other_attributes the torus is compressed too.
  tinygltf::Model again = testing::MakeRichScene();
  again.meshes[1].primitives[0].attributes["TEXCOORD_0"] = again.meshes[1].primitives[0].attributes["NORMAL"];
  gltf::ConvertReport report2;
  ASSERT_TRUE(gltf::CompressPrimitives(&again, testing::FakeCompressor(1), {false, true}, &report2).ok());
  EXPECT_EQ(report2.compressed, 2u);
  // The textured quad stays: the stand-in compressor paints no atlas for its textures.
  EXPECT_NE(report2.primitives[2].reason.find("no texture atlas for material 0"), std::string::npos)
      << report2.primitives[2].reason;
}

TEST(GltfContainer, FlattenAppliesNodeTransforms) {
  const std::vector<uint8_t> glb = CompressedRichScene(false);
  auto model = gltf::LoadGltfFromBytes(glb, "x.glb", FakeLoad(0));
  ASSERT_TRUE(model.ok());
  auto mesh = gltf::FlattenToMesh(*model);
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  const Mesh sphere = testing::MakeIcosphere(1), torus = testing::MakeTorus(8, 6);
  ASSERT_EQ(mesh->positions.size(), sphere.positions.size() + torus.positions.size() + 4);
  // Sphere under parent (translate 1,2,3); torus under child (scale 2) under parent.
  EXPECT_LT((mesh->positions[0] - (sphere.positions[0] + Vec3(1, 2, 3))).norm(), 1e-6);
  const Vec3 t = 2.0 * torus.positions[0] + Vec3(1, 2, 3);
  EXPECT_LT((mesh->positions[sphere.positions.size()] - t).norm(), 1e-5);
}

TEST(GltfContainer, KhronosValidatorAcceptsCompressedAndDecodedFiles) {
  const std::string compressed = testing::TempPath("container_compressed.glb");
  const std::string fallback = testing::TempPath("container_fallback.glb");
  const std::string decoded = testing::TempPath("container_decoded.glb");
  WriteFile(compressed, CompressedRichScene(false));
  WriteFile(fallback, CompressedRichScene(true));
  auto model = gltf::LoadGltf(compressed, FakeLoad());
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  ASSERT_TRUE(gltf::WriteDecodedGlb(*model, decoded).ok());
  std::string why;
  const auto c = testing::RunKhronosValidator(compressed, &why);
  if (!c) GTEST_SKIP() << why;
  EXPECT_EQ(c->errors, 0) << c->messages;
  const auto f = testing::RunKhronosValidator(fallback, &why);
  ASSERT_TRUE(f) << why;
  EXPECT_EQ(f->errors, 0) << f->messages;
  const auto d = testing::RunKhronosValidator(decoded, &why);
  ASSERT_TRUE(d) << why;
  EXPECT_EQ(d->errors, 0) << d->messages;
  EXPECT_EQ(d->warnings, 0) << d->messages;
}

}  // namespace
}  // namespace eqmesh
