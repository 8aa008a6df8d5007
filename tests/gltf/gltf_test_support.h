// Fixtures for the glTF tests: a scene exercising everything the converter must
// keep, temporary files, and the node-based tools in tests/gltf/validator.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "mesh/mesh.h"

namespace eqmesh::testing {

// 1x1 RGBA PNG (generated for this test; 70 bytes).
const std::vector<unsigned char>& TinyPng();

// Meshes 0 (icosphere) and 1 (torus), compressible, and 2, a textured quad with
// TEXCOORD_0 that must stay as it is; materials 0 (textured: PNG in a bufferView)
// and 1 (plain, on the sphere); nodes parent (sphere, TRS) -> child (torus), eye
// (camera), sign (quad); an animation on the child's translation; extras on the
// asset, a node, a mesh and material 1.
tinygltf::Model MakeRichScene();

// A model holding `mesh` as one TRIANGLES primitive (POSITION, NORMAL, indices).
tinygltf::Model MakeSingleMeshModel(const Mesh& mesh);

// A fresh path under the build tree (removed by nothing: the build dir is scratch).
std::string TempPath(const std::string& name);

struct ValidatorCounts {
  int errors = 0, warnings = 0, infos = 0;
  std::string messages;  // for failure output
};

// Runs the Khronos validator (tests/gltf/validator) on `path`; nullopt with *why set
// when node or the npm packages are missing (the caller skips).
std::optional<ValidatorCounts> RunKhronosValidator(const std::string& path, std::string* why);

// Validates `instance_path` against `schema_path` with ajv (tests/gltf/validator);
// nullopt with *why when unavailable, else whether it is valid (*output: ajv's line).
std::optional<bool> RunSchemaValidator(const std::string& schema_path, const std::string& instance_path,
                                       std::string* why, std::string* output);

}  // namespace eqmesh::testing
