#include "coding/stream_header.h"

#include <cmath>
#include <cstring>

#include "coding/entropy/byte_io.h"

namespace eqmesh {

using bitstream::kLogCodeScale;

int64_t LogCode(double value) {
  return static_cast<int64_t>(std::llround(std::log2(value) * kLogCodeScale));
}

double FromLogCode(int64_t code) {
  return std::exp2(static_cast<double>(code) / kLogCodeScale);
}

double StreamHeader::lambda() const { return FromLogCode(lambda_code); }
double StreamHeader::tangential_factor() const { return FromLogCode(tangential_code); }

std::vector<uint8_t> WriteStreamHeader(const StreamHeader& h) {
  ByteWriter w;
  w.PutBytes(bitstream::kMagic, sizeof bitstream::kMagic);
  w.PutU8(h.version_major);
  w.PutU8(h.version_minor);
  w.PutU8(static_cast<uint8_t>(h.transform));
  w.PutU8(static_cast<uint8_t>(h.coder));
  w.PutU8(static_cast<uint8_t>(h.levels));
  w.PutU8(h.flags);
  w.PutSignedVarint(h.lambda_code);
  w.PutSignedVarint(h.tangential_code);
  w.PutF32(h.quantum);
  w.PutVarint(h.base_size);
  if (h.has_kept()) w.PutVarint(h.kept_size);
  if (h.has_atlas()) w.PutVarint(h.atlas_size);
  if (h.has_creases()) w.PutVarint(h.crease_size);
  for (const uint64_t s : h.level_sizes) w.PutVarint(s);
  return w.Take();
}

namespace {

Status ReadIdentification(ByteReader* r, StreamHeader* h) {
  const uint8_t* magic = nullptr;
  if (r->remaining() < sizeof bitstream::kMagic) {
    return CorruptStream("eqm header: stream shorter than its magic");
  }
  EQMESH_RETURN_IF_ERROR(r->ReadSpan(sizeof bitstream::kMagic, &magic));
  if (std::memcmp(magic, bitstream::kMagic, sizeof bitstream::kMagic) != 0) {
    return CorruptStream("eqm header: not an eqmesh stream (bad magic)");
  }
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&h->version_major));
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&h->version_minor));
  // Minor versions only add optional features that set flags; a newer minor with
  // no unknown flag is readable, so only the major version gates decoding.
  if (h->version_major != bitstream::kVersionMajor) {
    return UnsupportedVersion("eqm stream version " + std::to_string(h->version_major) + "." +
                              std::to_string(h->version_minor) + ", this build reads " +
                              std::to_string(bitstream::kVersionMajor) + ".x");
  }
  return Status::Ok();
}

Status ReadCodingSetup(ByteReader* r, StreamHeader* h) {
  uint8_t transform = 0, coder = 0, levels = 0;
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&transform));
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&coder));
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&levels));
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&h->flags));
  // Ids a later minor version may add: unsupported here, not corrupt (ext_spec A.5).
  if (transform > static_cast<uint8_t>(bitstream::TransformId::kLifted)) {
    return UnsupportedFeature("eqm header: unknown transform id " + std::to_string(transform) +
                              " (stream version " + std::to_string(h->version_major) + "." +
                              std::to_string(h->version_minor) + ")");
  }
  if (coder > bitstream::kMaxCoderId) {
    return UnsupportedFeature("eqm header: unknown coder id " + std::to_string(coder) + " (stream version " +
                              std::to_string(h->version_major) + "." + std::to_string(h->version_minor) + ")");
  }
  if (levels > bitstream::kMaxLevels) {
    return r->Corrupt("level count " + std::to_string(levels) + " exceeds " +
                      std::to_string(bitstream::kMaxLevels));
  }
  if ((h->flags & ~bitstream::kKnownFlags) != 0) return r->Corrupt("unknown header flags");
  if (h->has_compact_kept() && !h->has_kept()) return r->Corrupt("compact-kept flag on a stream without a kept chunk");
  if (h->has_positions_after() && !h->has_compact_base() && !h->has_compact_kept()) {
    return r->Corrupt("positions-after flag on a stream without a compact chunk");
  }
  if ((h->flags & bitstream::kParallelogramChoice) != 0 && !(h->has_compact_base() && h->has_positions_after())) {
    return r->Corrupt("parallelogram-choice flag on a stream without a positions-after compact base");
  }
  if (h->has_creases() && levels == 0) return r->Corrupt("crease flag on a stream without levels");
  if (h->has_tangential_context() && coder != static_cast<uint8_t>(bitstream::CoderId::kEq)) {
    return r->Corrupt("tangential-context flag on a stream whose coder is not EQ");
  }
  h->transform = static_cast<bitstream::TransformId>(transform);
  h->coder = static_cast<bitstream::CoderId>(coder);
  h->levels = levels;
  EQMESH_RETURN_IF_ERROR(r->ReadSignedVarint(&h->lambda_code));
  EQMESH_RETURN_IF_ERROR(r->ReadSignedVarint(&h->tangential_code));
  if (std::llabs(h->lambda_code) > bitstream::kMaxLogCode ||
      std::llabs(h->tangential_code) > bitstream::kMaxLogCode) {
    return r->Corrupt("lambda or tangential code out of range");
  }
  EQMESH_RETURN_IF_ERROR(r->ReadFiniteF32(&h->quantum));
  if (!(h->quantum > 0.0f)) return r->Corrupt("quantum must be positive");
  return Status::Ok();
}

// Coder 1 carries one embedded payload for all levels as chunk 0 (ext_spec A.4).
Status CheckZerotreeChunks(const ByteReader& r, const StreamHeader& h) {
  if (h.coder != bitstream::CoderId::kZerotree || h.levels == 0) return Status::Ok();
  if (h.level_sizes[0] == 0) return r.Corrupt("zerotree stream with an empty level payload");
  for (size_t j = 1; j < h.level_sizes.size(); ++j) {
    if (h.level_sizes[j] != 0) return r.Corrupt("zerotree stream with a non-empty level chunk " + std::to_string(j));
  }
  return Status::Ok();
}

Status ReadChunkTable(ByteReader* r, StreamHeader* h) {
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxChunkBytes, "base chunk size",
                                              &h->base_size));
  if (h->base_size == 0) return r->Corrupt("empty base chunk");
  if (h->has_kept()) {
    EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxChunkBytes, "kept chunk size",
                                                &h->kept_size));
    if (h->kept_size == 0) return r->Corrupt("empty kept-exactly chunk");
  }
  if (h->has_atlas()) {
    EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxChunkBytes, "atlas chunk size", &h->atlas_size));
    if (h->atlas_size == 0) return r->Corrupt("empty atlas chunk");
  }
  if (h->has_creases()) {
    EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxChunkBytes, "crease chunk size", &h->crease_size));
    if (h->crease_size == 0) return r->Corrupt("empty crease chunk");
  }
  h->level_sizes.resize(static_cast<size_t>(h->levels));
  for (uint64_t& s : h->level_sizes) {
    EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(bitstream::kMaxChunkBytes, "level chunk size", &s));
  }
  return CheckZerotreeChunks(*r, *h);
}

}  // namespace

StatusOr<StreamHeader> ReadStreamHeader(const uint8_t* data, size_t size, size_t* header_size) {
  ByteReader r(data, size, "eqm header");
  StreamHeader h;
  EQMESH_RETURN_IF_ERROR(ReadIdentification(&r, &h));
  EQMESH_RETURN_IF_ERROR(ReadCodingSetup(&r, &h));
  EQMESH_RETURN_IF_ERROR(ReadChunkTable(&r, &h));
  *header_size = r.offset();
  return h;
}

}  // namespace eqmesh
