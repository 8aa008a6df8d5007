#include "coding/decoder.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "coding/atlas/atlas_layout.h"
#include "coding/base_mesh_decoder.h"
#include "coding/compact_base/compact_base_decoder.h"
#include "coding/crease_chunk.h"
#include "coding/level_decoder.h"
#include "coding/level_synthesis.h"
#include "coding/stream_header.h"
#include "coding/zerotree_decoder.h"
#include "mesh/adaptive_level.h"

namespace eqmesh {
namespace {

StreamInfo MakeStreamInfo(const StreamHeader& h, size_t header_size) {
  StreamInfo s;
  s.version_major = h.version_major;
  s.version_minor = h.version_minor;
  s.transform = h.transform;
  s.coder = h.coder;
  s.levels = h.levels;
  s.lambda = h.lambda();
  s.tangential_factor = h.tangential_factor();
  s.quantum = h.quantum;
  s.has_kept_exactly = h.has_kept();
  s.has_compact_base = h.has_compact_base();
  s.has_compact_kept = h.has_compact_kept();
  s.has_positions_after = h.has_positions_after();
  s.has_tangential_context = h.has_tangential_context();
  s.header_size = header_size;
  s.base_offset = header_size;
  s.base_size = h.base_size;
  s.kept_offset = s.base_offset + s.base_size;
  s.kept_size = h.kept_size;
  s.has_atlas = h.has_atlas();
  s.atlas_offset = s.kept_offset + s.kept_size;
  s.atlas_size = h.atlas_size;
  s.has_creases = h.has_creases();
  s.crease_offset = s.atlas_offset + s.atlas_size;
  s.crease_size = h.crease_size;
  uint64_t offset = s.crease_offset + s.crease_size;
  s.prefix_size.push_back(offset);
  for (const uint64_t size : h.level_sizes) {
    s.level_offsets.push_back(offset);
    s.level_sizes.push_back(size);
    offset += size;  // each <= 2^32, at most kMaxLevels + 2 of them: no overflow
    s.prefix_size.push_back(offset);
  }
  s.total_size = offset;
  return s;
}

int LevelsToDecode(const StreamInfo& s, const uint8_t* data, size_t size, const DecodeOptions& options) {
  int levels = s.levels;
  if (options.max_level >= 0) levels = std::min(levels, options.max_level);
  if (s.coder == bitstream::CoderId::kZerotree) return ZerotreeLevelsAvailable(s, data, size, levels);
  while (levels > 0 && s.prefix_size[levels] > size) --levels;
  return levels;
}

Status CheckLength(const StreamInfo& s, size_t size, const DecodeOptions& options) {
  if (size > s.total_size) {
    return CorruptStream("eqm stream: " + std::to_string(size - s.total_size) +
                         " trailing bytes after the last chunk");
  }
  if (size < s.prefix_size[0]) {
    return CorruptStream("eqm stream truncated before the base mesh ends (" + std::to_string(size) +
                         " of " + std::to_string(s.total_size) + " bytes)");
  }
  if (size < s.total_size && !options.allow_truncated) {
    return CorruptStream("eqm stream truncated (" + std::to_string(size) + " of " +
                         std::to_string(s.total_size) + " bytes)");
  }
  return Status::Ok();
}

CompactLayout CompactLayoutOf(const StreamInfo& s) {
  return s.has_positions_after ? CompactLayout::kPositionsAfter : CompactLayout::kInterleaved;
}

StatusOr<Mesh> DecodeBase(const uint8_t* data, const StreamInfo& s) {
  if (s.has_compact_base) {
    return DecodeCompactBase(data + s.base_offset, static_cast<size_t>(s.base_size), bitstream::kMaxBaseVertices,
                             "eqm base mesh chunk", CompactLayoutOf(s));
  }
  const DracoMeshLimits limits{bitstream::kMaxBaseVertices, bitstream::kMaxFinestFaces};
  return DecodeDracoMesh(data + s.base_offset, static_cast<size_t>(s.base_size), limits, "eqm base mesh chunk");
}

StatusOr<Mesh> DecodeKept(const uint8_t* data, const StreamInfo& s) {
  if (!s.has_kept_exactly) return Mesh();
  if (s.has_compact_kept) {
    return DecodeCompactBase(data + s.kept_offset, static_cast<size_t>(s.kept_size),
                             static_cast<uint32_t>(bitstream::kMaxFinestFaces), "eqm kept-exactly chunk",
                             CompactLayoutOf(s));
  }
  const DracoMeshLimits limits{static_cast<uint32_t>(bitstream::kMaxFinestFaces),
                               bitstream::kMaxFinestFaces};
  return DecodeDracoMesh(data + s.kept_offset, static_cast<size_t>(s.kept_size), limits, "eqm kept-exactly chunk");
}

// Runs the refinements 0 .. levels-1 on top of the decoded base. Level j+1's
// connectivity is built only once level j has decoded, and its coefficients only
// once chunk j has passed DecodeLevelCoefficients' size checks.
Status DecodeLevels(const uint8_t* data, const StreamInfo& s, const StreamHeader& h, int levels,
                    SemiRegularMesh* mesh) {
  const LevelCodingParams params{h.coder,  h.lambda_code, h.lambda(), h.tangential_factor(),
                                 h.quantum, h.has_tangential_context()};
  for (int j = 0; j < levels; ++j) {
    const Status refined = mesh->hierarchy.Refine(bitstream::kMaxFinestFaces);
    if (!refined.ok()) return refined.WithContext("eqm base mesh chunk");
    EQMESH_ASSIGN_OR_RETURN(std::vector<Vec3> local,
                            DecodeLevelCoefficients(params, mesh->hierarchy, j,
                                                    data + s.level_offsets[j], static_cast<size_t>(s.level_sizes[j])));
    const LevelSynthesis step(mesh->hierarchy, j, h.transform);
    std::vector<Vec3> fine;
    EQMESH_RETURN_IF_ERROR(step.Synthesize(mesh->positions, local, &fine));
    EQMESH_RETURN_IF_ERROR(CheckFiniteLevel(fine, j + 1));
    mesh->positions = std::move(fine);
  }
  return Status::Ok();
}

// The crease chunk's tags on the base (a stream whose base is decoded has it:
// it comes before the level chunks).
Status DecodeCreases(const uint8_t* data, const StreamInfo& s, SemiRegularHierarchy* hierarchy) {
  if (!s.has_creases) return Status::Ok();
  EQMESH_ASSIGN_OR_RETURN(std::vector<Edge> tags,
                          ReadCreaseChunk(data + s.crease_offset, static_cast<size_t>(s.crease_size), *hierarchy));
  const Status set = hierarchy->SetBaseCreases(std::move(tags));
  if (!set.ok()) return CorruptStream("eqm crease chunk: " + set.message());
  return Status::Ok();
}

}  // namespace

StatusOr<StreamInfo> ReadStreamInfo(const uint8_t* data, size_t size) {
  size_t header_size = 0;
  EQMESH_ASSIGN_OR_RETURN(StreamHeader h, ReadStreamHeader(data, size, &header_size));
  return MakeStreamInfo(h, header_size);
}

StatusOr<SemiRegularMesh> DecodeSemiRegular(const uint8_t* data, size_t size,
                                            const DecodeOptions& options, DecodeInfo* info) {
  size_t header_size = 0;
  EQMESH_ASSIGN_OR_RETURN(StreamHeader h, ReadStreamHeader(data, size, &header_size));
  const StreamInfo s = MakeStreamInfo(h, header_size);
  EQMESH_RETURN_IF_ERROR(CheckLength(s, size, options));
  const int levels = LevelsToDecode(s, data, size, options);

  EQMESH_ASSIGN_OR_RETURN(Mesh base, DecodeBase(data, s));
  SemiRegularMesh mesh;
  EQMESH_ASSIGN_OR_RETURN(mesh.kept_exactly, DecodeKept(data, s));
  // Refused whole rather than after decoding the levels that fit.
  if (SemiRegularHierarchy::FinestFaceCount(base.faces.size(), levels) > bitstream::kMaxFinestFaces) {
    return ResourceLimit("eqm base mesh chunk: " + std::to_string(base.faces.size()) + " base faces refined " +
                         std::to_string(levels) + " times exceed the limit of " +
                         std::to_string(bitstream::kMaxFinestFaces) + " faces");
  }
  // Level 0 only: each refinement is built when its level is decoded (bounded
  // allocation, decoder.h).
  auto hierarchy = SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()),
                                               std::move(base.faces), 0, bitstream::kMaxFinestFaces);
  if (!hierarchy.ok()) return hierarchy.status().WithContext("eqm base mesh chunk");
  mesh.hierarchy = std::move(hierarchy).value();
  EQMESH_RETURN_IF_ERROR(DecodeCreases(data, s, &mesh.hierarchy));
  mesh.positions = std::move(base.positions);
  if (h.coder == bitstream::CoderId::kZerotree) {
    EQMESH_RETURN_IF_ERROR(DecodeZerotreeLevels(data, size, s, h, levels, &mesh));
  } else {
    EQMESH_RETURN_IF_ERROR(DecodeLevels(data, s, h, levels, &mesh));
  }
  if (info) {
    info->stream = s;
    info->levels_in_stream = s.levels;
    info->levels_decoded = levels;
    info->truncated = size < s.total_size;
  }
  return mesh;
}

StatusOr<std::optional<AtlasLayout>> DecodeAtlas(const uint8_t* data, size_t size, const SemiRegularMesh& mesh) {
  EQMESH_ASSIGN_OR_RETURN(const StreamInfo s, ReadStreamInfo(data, size));
  if (!s.has_atlas) return std::optional<AtlasLayout>();
  if (size < s.atlas_offset + s.atlas_size) return CorruptStream("eqm stream truncated before the atlas chunk ends");
  EQMESH_ASSIGN_OR_RETURN(AtlasLayout atlas, ReadAtlasChunk(data + s.atlas_offset, static_cast<size_t>(s.atlas_size),
                                                            AtlasFaces(mesh)));
  return std::optional<AtlasLayout>(std::move(atlas));
}

std::vector<Face> AtlasFaces(const SemiRegularMesh& mesh) {
  std::vector<Face> faces = mesh.hierarchy.BaseFaces();
  const uint32_t offset = mesh.hierarchy.NumVertices(0);
  for (const Face& f : mesh.kept_exactly.faces) faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  return faces;
}

StatusOr<Mesh> Decode(const uint8_t* data, size_t size, const DecodeOptions& options,
                      DecodeInfo* info) {
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh mesh, DecodeSemiRegular(data, size, options, info));
  if (options.max_triangles > 0) return ExtractAdaptiveLevel(mesh, options.max_triangles);
  const int level = mesh.hierarchy.levels();
  return ExtractLevel(std::move(mesh), level);
}

}  // namespace eqmesh
