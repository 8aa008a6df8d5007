#include "gltf_test_support.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "gltf/accessor_io.h"
#include "gltf/buffer_layout.h"
#include "test_support.h"

namespace eqmesh::testing {
namespace {

const std::string kToolDir = std::string(EQMESH_SOURCE_DIR) + "/tests/gltf/validator";

bool ToolsAvailable(const std::string& package, std::string* why) {
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    *why = "node is not installed";
    return false;
  }
  if (!std::filesystem::exists(kToolDir + "/node_modules/" + package)) {
    *why = package + " is not installed: run `npm ci` in tests/gltf/validator";
    return false;
  }
  return true;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int AddAccessorWithData(tinygltf::Model* model, const std::vector<float>& values, int type, int target) {
  const int view = gltf::AppendBufferView(model, reinterpret_cast<const uint8_t*>(values.data()),
                                          values.size() * sizeof(float), target);
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = type;
  const size_t width = type == TINYGLTF_TYPE_SCALAR ? 1 : 3;
  a.count = values.size() / width;
  a.minValues.assign(width, 1e30);
  a.maxValues.assign(width, -1e30);
  for (size_t i = 0; i < values.size(); ++i) {
    a.minValues[i % width] = std::min(a.minValues[i % width], static_cast<double>(values[i]));
    a.maxValues[i % width] = std::max(a.maxValues[i % width], static_cast<double>(values[i]));
  }
  model->accessors.push_back(a);
  return static_cast<int>(model->accessors.size()) - 1;
}

// Appends `mesh` as a new glTF mesh with one primitive; returns the mesh index.
int AddMesh(tinygltf::Model* model, const Mesh& mesh, const std::string& name) {
  const int first = static_cast<int>(model->accessors.size());
  model->accessors.resize(model->accessors.size() + 3);
  const auto views = gltf::WriteGeometry(model, mesh, {first, first + 1, first + 2}, true);
  (void)views;
  tinygltf::Primitive p;
  p.attributes = {{"POSITION", first}, {"NORMAL", first + 1}};
  p.indices = first + 2;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh m;
  m.name = name;
  m.primitives.push_back(p);
  model->meshes.push_back(m);
  return static_cast<int>(model->meshes.size()) - 1;
}

tinygltf::Value Extra(const std::string& key, const std::string& value) {
  return tinygltf::Value(tinygltf::Value::Object{{key, tinygltf::Value(value)}});
}

void AddTexturedMaterial(tinygltf::Model* model) {
  tinygltf::Image image;
  image.name = "checker";
  image.mimeType = "image/png";
  image.bufferView = gltf::AppendBufferView(model, TinyPng().data(), TinyPng().size(), 0);
  model->images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  model->samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  model->textures.push_back(texture);
  tinygltf::Material material;
  material.name = "painted";
  material.pbrMetallicRoughness.baseColorTexture.index = 0;
  material.pbrMetallicRoughness.baseColorFactor = {0.5, 0.6, 0.7, 1.0};
  model->materials.push_back(material);
  tinygltf::Material plain;
  plain.name = "plain";
  plain.pbrMetallicRoughness.baseColorFactor = {0.8, 0.3, 0.2, 1.0};
  plain.extras = Extra("finish", "matte");
  model->materials.push_back(plain);
}

// A textured quad (POSITION, TEXCOORD_0, u16 indices): a primitive the converter
// must leave as it is.
int AddTexturedQuad(tinygltf::Model* model) {
  tinygltf::Primitive p;
  p.attributes["POSITION"] = AddAccessorWithData(model, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3,
                                                 TINYGLTF_TARGET_ARRAY_BUFFER);
  const std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 1};
  const int uv_view = gltf::AppendBufferView(model, reinterpret_cast<const uint8_t*>(uv.data()),
                                             uv.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  tinygltf::Accessor uv_accessor;
  uv_accessor.bufferView = uv_view;
  uv_accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  uv_accessor.type = TINYGLTF_TYPE_VEC2;
  uv_accessor.count = 4;
  model->accessors.push_back(uv_accessor);
  p.attributes["TEXCOORD_0"] = static_cast<int>(model->accessors.size()) - 1;
  const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
  tinygltf::Accessor index_accessor;
  index_accessor.bufferView = gltf::AppendBufferView(model, reinterpret_cast<const uint8_t*>(indices.data()),
                                                     indices.size() * 2, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  index_accessor.type = TINYGLTF_TYPE_SCALAR;
  index_accessor.count = 6;
  model->accessors.push_back(index_accessor);
  p.indices = static_cast<int>(model->accessors.size()) - 1;
  p.material = 0;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.name = "label";
  mesh.primitives.push_back(p);
  model->meshes.push_back(mesh);
  return static_cast<int>(model->meshes.size()) - 1;
}

void AddAnimation(tinygltf::Model* model, int node) {
  tinygltf::AnimationSampler sampler;
  sampler.input = AddAccessorWithData(model, {0.0f, 1.0f}, TINYGLTF_TYPE_SCALAR, 0);
  sampler.output = AddAccessorWithData(model, {0, 0, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3, 0);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = node;
  channel.target_path = "translation";
  tinygltf::Animation animation;
  animation.name = "bob";
  animation.samplers.push_back(sampler);
  animation.channels.push_back(channel);
  model->animations.push_back(animation);
}

}  // namespace

const std::vector<unsigned char>& TinyPng() {
  static const std::vector<unsigned char> png = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
      0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xdf, 0xe0, 0xf0, 0x1f, 0x00, 0x07, 0x00, 0x02, 0xbf,
      0x2b, 0xd7, 0xc7, 0xe2, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  return png;
}

tinygltf::Model MakeRichScene() {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "eqmesh tests";
  model.asset.extras = Extra("origin", "gltf_container_test");
  AddTexturedMaterial(&model);
  const int sphere = AddMesh(&model, MakeIcosphere(1), "sphere");
  const int torus = AddMesh(&model, MakeTorus(8, 6), "torus");
  const int quad = AddTexturedQuad(&model);
  model.meshes[static_cast<size_t>(sphere)].primitives[0].material = 1;
  model.meshes[static_cast<size_t>(torus)].extras = Extra("kind", "ring");
  tinygltf::Camera camera;
  camera.type = "perspective";
  camera.perspective.yfov = 0.8;
  camera.perspective.znear = 0.1;
  camera.perspective.zfar = 100.0;
  model.cameras.push_back(camera);
  tinygltf::Node parent, child, eye;
  parent.name = "parent";
  parent.mesh = sphere;
  parent.translation = {1.0, 2.0, 3.0};
  parent.children = {1};
  parent.extras = Extra("note", "keep me");
  child.name = "child";
  child.mesh = torus;
  child.scale = {2.0, 2.0, 2.0};
  eye.name = "eye";
  eye.camera = 0;
  tinygltf::Node sign;
  sign.name = "sign";
  sign.mesh = quad;
  sign.translation = {0.0, -3.0, 0.0};
  model.nodes = {parent, child, eye, sign};
  tinygltf::Scene scene;
  scene.nodes = {0, 2, 3};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  AddAnimation(&model, 1);
  return model;
}

tinygltf::Model MakeSingleMeshModel(const Mesh& mesh) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  AddMesh(&model, mesh, "only");
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  model.scenes.emplace_back();
  model.scenes[0].nodes = {0};
  model.defaultScene = 0;
  return model;
}

std::string TempPath(const std::string& name) {
  const std::string dir = std::string(EQMESH_BINARY_DIR) + "/tests/gltf/tmp";
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

std::optional<ValidatorCounts> RunKhronosValidator(const std::string& path, std::string* why) {
  if (!ToolsAvailable("gltf-validator", why)) return std::nullopt;
  const std::string out = path + ".validator.json";
  const std::string command = "node '" + kToolDir + "/validate_gltf.js' '" + path + "' > '" + out + "'";
  if (std::system(command.c_str()) != 0) {
    *why = "validator run failed: " + command;
    return std::nullopt;
  }
  const nlohmann::json report = nlohmann::json::parse(ReadText(out), nullptr, false);
  if (report.is_discarded()) {
    *why = "validator printed no JSON";
    return std::nullopt;
  }
  ValidatorCounts counts;
  counts.errors = report.value("errors", -1);
  counts.warnings = report.value("warnings", -1);
  counts.infos = report.value("infos", -1);
  counts.messages = report["messages"].dump();
  return counts;
}

std::optional<bool> RunSchemaValidator(const std::string& schema_path, const std::string& instance_path,
                                       std::string* why, std::string* output) {
  if (!ToolsAvailable("ajv", why)) return std::nullopt;
  const std::string out = instance_path + ".ajv.json";
  const std::string command = "node '" + kToolDir + "/validate_schema.js' '" + schema_path + "' '" +
                              instance_path + "' > '" + out + "'";
  const int rc = std::system(command.c_str());
  *output = ReadText(out);
  if (rc == -1 || !WIFEXITED(rc) || WEXITSTATUS(rc) > 1) {
    *why = "schema validator failed to run: " + *output;
    return std::nullopt;
  }
  return WEXITSTATUS(rc) == 0;
}

}  // namespace eqmesh::testing
