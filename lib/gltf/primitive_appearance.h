// Container side of a primitive's appearance when it is remeshed: which of its
// material's textures and its COLOR_0 can follow it into a new texture atlas, what
// the compressor is handed to paint them (compress_primitives.h TextureJob), and
// the material the compressed primitive then samples. COLOR_0 does not survive as
// a vertex attribute (the remesh has other vertices): it is baked into the base
// colour, multiplied into the base colour texture or as a new one. A normal map is
// re-expressed in the decoded surface's tangent frames (TANGENT then goes: engines
// derive the frames, as for any primitive without it).
#pragma once

#include <string>

#include <tiny_gltf.h>

#include "core/status.h"
#include "gltf/compress_primitives.h"

namespace eqmesh::gltf {

struct AppearancePlan {
  int tex_coord = -1;          // the TEXCOORD set the material samples; -1: none
  bool vertex_colors = false;  // COLOR_0 is baked into the base colour
  bool NeedsAtlas() const { return tex_coord >= 0 || vertex_colors; }
};

// Empty when the primitive's appearance can follow it into an atlas, else why not
// (a normal map inside a material extension, two TEXCOORD sets, an image that is
// not PNG or JPEG, COLOR_0 alpha under blending); `plan` says what the atlas must
// carry.
std::string AppearanceDisqualification(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                       AppearancePlan* plan);

// The attributes the plan carries into the atlas (which the primitive may lose).
bool CarriedByAtlas(const AppearancePlan& plan, const std::string& semantic);

// Fills out->texcoords, out->colors, out->textures (one job per distinct texture
// the material samples, plus one for COLOR_0 when no base colour texture exists)
// and, for a normal map, out->normals and out->tangents as given.
Status ReadAppearance(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const AppearancePlan& plan,
                      PrimitiveGeometry* out);

// Points the primitive at a copy of its material (a default one if it had none)
// whose slots sample the painted atlas images through TEXCOORD_0.
void ReplaceAppearance(const AppearancePlan& plan, const CompressedGeometry& geometry, tinygltf::Model* model,
                       tinygltf::Primitive* primitive);

}  // namespace eqmesh::gltf
