// A glTF scene as a coloured surface for the appearance meter
// (metrics/color_distance.h): every TRIANGLES primitive of the default scene in
// world space, with its base colour at any point of any face: the base-colour
// texture (or KHR_materials_pbrSpecularGlossiness' diffuse texture) through its
// TEXCOORD set, sampler and KHR_texture_transform, times the colour factor, times
// COLOR_0 where present. Compressed primitives must have been decoded first.
#pragma once

#include <memory>

#include <tiny_gltf.h>

#include "core/status.h"
#include "mesh/mesh.h"
#include "metrics/color_distance.h"

namespace eqmesh::gltf {

struct ColoredScene {
  Mesh mesh;
  SurfaceColor color;  // valid while the ColoredScene lives
  // True when some face's colour varies over the surface (a texture or COLOR_0);
  // a scene of constant material colours has nothing for the meter to compare.
  bool varies = false;
  std::shared_ptr<const void> data;  // what `color` reads
};

StatusOr<ColoredScene> FlattenWithColor(const tinygltf::Model& model);

}  // namespace eqmesh::gltf
