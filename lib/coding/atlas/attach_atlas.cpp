#include "coding/atlas/attach_atlas.h"

#include <algorithm>

#include "coding/stream_header.h"

namespace eqmesh {

StatusOr<std::vector<uint8_t>> AttachAtlas(const std::vector<uint8_t>& stream, const AtlasLayout& atlas) {
  size_t header_size = 0;
  EQMESH_ASSIGN_OR_RETURN(StreamHeader header, ReadStreamHeader(stream.data(), stream.size(), &header_size));
  if (header.has_atlas()) return InvalidArgument("the stream already has an atlas");
  const uint64_t front = header.base_size + header.kept_size;
  if (stream.size() < header_size + front) return InvalidArgument("the stream is shorter than its header says");
  const std::vector<uint8_t> chunk = WriteAtlasChunk(atlas);
  header.flags = static_cast<uint8_t>(header.flags | bitstream::kHasAtlas);
  header.atlas_size = chunk.size();
  header.version_minor = std::max(header.version_minor, bitstream::kVersionMinorAtlas);
  std::vector<uint8_t> out = WriteStreamHeader(header);
  const auto body = stream.begin() + static_cast<std::ptrdiff_t>(header_size);
  out.insert(out.end(), body, body + static_cast<std::ptrdiff_t>(front));
  out.insert(out.end(), chunk.begin(), chunk.end());
  out.insert(out.end(), body + static_cast<std::ptrdiff_t>(front), stream.end());
  return out;
}

}  // namespace eqmesh
