#include "coding/atlas/atlas_layout.h"

#include <string>

#include "coding/bitstream_shared.h"
#include "coding/entropy/byte_io.h"

namespace eqmesh {
namespace {

constexpr uint8_t kEdgeMask = 0x3;
constexpr uint8_t kPairedBit = 0x4;

uint32_t Corner(const Face& f, int k) { return f[static_cast<size_t>(k % 3)]; }

// Corner of `b` where b's copy of the directed edge (from, to) reversed starts, or -1.
int ReversedEdgeCorner(const Face& b, uint32_t from, uint32_t to) {
  for (int k = 0; k < 3; ++k) {
    if (Corner(b, k) == to && Corner(b, k + 1) == from) return k;
  }
  return -1;
}

Status ReadGrid(ByteReader* r, AtlasLayout* atlas) {
  uint64_t width = 0, height = 0, gutter = 0;
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxAtlasSide, "atlas width", &width));
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxAtlasSide, "atlas height", &height));
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxAtlasGutter, "atlas gutter", &gutter));
  if (width == 0 || height == 0) return r->Corrupt("empty atlas grid");
  atlas->width = static_cast<uint32_t>(width);
  atlas->height = static_cast<uint32_t>(height);
  atlas->gutter = static_cast<uint32_t>(gutter);
  return Status::Ok();
}

Status ReadCell(ByteReader* r, const AtlasLayout& atlas, size_t face_count, AtlasCell* cell) {
  uint64_t a = 0, b = 0, x = 0, y = 0, side = 0;
  uint8_t code = 0;
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(face_count - 1, "atlas face", &a));
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&code));
  if ((code & ~(kEdgeMask | kPairedBit)) != 0 || (code & kEdgeMask) > 2) return r->Corrupt("bad atlas cell code");
  if ((code & kPairedBit) != 0) {
    EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(face_count - 1, "atlas face", &b));
  }
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(atlas.width, "atlas cell x", &x));
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(atlas.height, "atlas cell y", &y));
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxAtlasSide, "atlas cell side", &side));
  if (side <= 2 * uint64_t{atlas.gutter} || x + side > atlas.width || y + side > atlas.height) {
    return r->Corrupt("atlas cell outside the grid or smaller than its gutters");
  }
  *cell = {static_cast<uint32_t>(a), static_cast<uint32_t>(b), static_cast<uint8_t>(code & kEdgeMask),
           (code & kPairedBit) != 0, static_cast<uint32_t>(x), static_cast<uint32_t>(y),
           static_cast<uint32_t>(side)};
  return Status::Ok();
}

// Every face in exactly one cell; a pair shares face a's hypotenuse, reversed.
Status CheckCellFaces(const ByteReader& r, const AtlasCell& cell, const std::vector<Face>& faces,
                      std::vector<bool>* placed) {
  for (uint32_t f : {cell.face_a, cell.face_b}) {
    if (f == cell.face_b && !cell.paired) break;
    if ((*placed)[f]) return r.Corrupt("atlas face " + std::to_string(f) + " placed twice");
    (*placed)[f] = true;
  }
  if (!cell.paired) return Status::Ok();
  const Face& a = faces[cell.face_a];
  if (ReversedEdgeCorner(faces[cell.face_b], Corner(a, cell.edge), Corner(a, cell.edge + 1)) < 0) {
    return r.Corrupt("atlas faces " + std::to_string(cell.face_a) + " and " + std::to_string(cell.face_b) +
                     " paired across an edge they do not share");
  }
  return Status::Ok();
}

}  // namespace

std::vector<uint8_t> WriteAtlasChunk(const AtlasLayout& atlas) {
  ByteWriter w;
  w.PutVarint(atlas.width);
  w.PutVarint(atlas.height);
  w.PutVarint(atlas.gutter);
  w.PutVarint(atlas.cells.size());
  for (const AtlasCell& c : atlas.cells) {
    w.PutVarint(c.face_a);
    w.PutU8(static_cast<uint8_t>(c.edge | (c.paired ? kPairedBit : 0)));
    if (c.paired) w.PutVarint(c.face_b);
    w.PutVarint(c.x);
    w.PutVarint(c.y);
    w.PutVarint(c.side);
  }
  return w.Take();
}

StatusOr<AtlasLayout> ReadAtlasChunk(const uint8_t* data, size_t size, const std::vector<Face>& faces) {
  ByteReader r(data, size, "eqm atlas chunk");
  AtlasLayout atlas;
  EQMESH_RETURN_IF_ERROR(ReadGrid(&r, &atlas));
  if (faces.empty()) return r.Corrupt("atlas for a mesh without faces");
  uint64_t count = 0;
  EQMESH_RETURN_IF_ERROR(r.ReadBoundedVarint(faces.size(), "atlas cell count", &count));
  std::vector<bool> placed(faces.size(), false);
  atlas.cells.resize(static_cast<size_t>(count));
  for (AtlasCell& cell : atlas.cells) {
    EQMESH_RETURN_IF_ERROR(ReadCell(&r, atlas, faces.size(), &cell));
    EQMESH_RETURN_IF_ERROR(CheckCellFaces(r, cell, faces, &placed));
  }
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!placed[f]) return r.Corrupt("atlas face " + std::to_string(f) + " has no cell");
  }
  if (r.remaining() != 0) return r.Corrupt(std::to_string(r.remaining()) + " bytes left over");
  return atlas;
}

std::vector<FaceTexCoords> FaceCornerTexCoords(const AtlasLayout& atlas, const std::vector<Face>& faces) {
  std::vector<FaceTexCoords> out(faces.size());
  const double w = atlas.width, h = atlas.height;
  for (const AtlasCell& c : atlas.cells) {
    const double lo_x = (c.x + atlas.gutter) / w, lo_y = (c.y + atlas.gutter) / h;
    const double hi_x = (c.x + c.side - atlas.gutter) / w, hi_y = (c.y + c.side - atlas.gutter) / h;
    const TexCoord start{hi_x, lo_y}, end{lo_x, hi_y};
    FaceTexCoords& a = out[c.face_a];
    a[c.edge] = start;
    a[(c.edge + 1) % 3] = end;
    a[(c.edge + 2) % 3] = {lo_x, lo_y};
    if (!c.paired) continue;
    const Face& fa = faces[c.face_a];
    const int k = ReversedEdgeCorner(faces[c.face_b], Corner(fa, c.edge), Corner(fa, c.edge + 1));
    FaceTexCoords& b = out[c.face_b];
    b[static_cast<size_t>(k)] = end;
    b[static_cast<size_t>((k + 1) % 3)] = start;
    b[static_cast<size_t>((k + 2) % 3)] = {hi_x, hi_y};
  }
  return out;
}

}  // namespace eqmesh
