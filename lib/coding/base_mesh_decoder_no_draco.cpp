// DecodeDracoMesh (base_mesh_decoder.h) for a decoder built without libdraco
// (EQMESH_WITH_DRACO=OFF): streams whose base chunk is compact decode as usual;
// a Draco buffer (a --draco-base stream's base, any stream's kept-exactly chunk)
// is refused with a status that says why.
#include "coding/base_mesh_decoder.h"

namespace eqmesh {

StatusOr<Mesh> DecodeDracoMesh(const uint8_t*, size_t, const DracoMeshLimits&, const std::string& what) {
  return UnsupportedFeature(what + " is a Draco buffer, and this decoder was built without Draco (EQMESH_WITH_DRACO=OFF)");
}

}  // namespace eqmesh
