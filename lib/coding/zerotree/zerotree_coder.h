// Zerotree coder of semi-regular mesh wavelet coefficients: the seed paper's
// baseline ("ZT" in Lavu, Choi, Baraniuk 2003, §2.2, Tables 1-2), after
// Khodakovsky, Schröder, Sweldens 2000 (PGC) and Khodakovsky & Guskov 2003, with
// SPIHT set partitioning (Said & Pearlman 1996; Shapiro 1993) on the edge quadtree
// (edge_tree.h) and adaptive binary range coding (spiht_engine.h, bit_io.h).
//
// Coefficients: coeffs[j][k] is the detail of odd vertex k of refinement level j
// in its local frame, (normal, tangent, bitangent), world units.
//
// Integer representation (both sides compute it the same way):
//   scale(c, j) = w_c * 2^(s * (J - 1 - j)) / q0,  w_normal = 1,
//                 w_tangent = w_bitangent = 1 / sqrt(tangential_factor)
//   integer     = round(value * scale)         (encoder; |integer| < 2^41)
//   value       = reconstruction / scale       (decoder)
// so the tangential channels (tangential_factor = 100: amplitude weight 1/10, the
// seed's "tangential lambda x 100") reach each bit plane later, and with s > 0 the
// coarser levels are weighted 2^s per level up (an L2 surface-error order: a
// coarse detail moves ~4x more surface per level; notes §2.3). s is a header
// field. Measured (icosphere base, 5 levels, details ~2^-j, unlifted butterfly
// synthesis, same byte budgets 200..8000 B): finest-level vertex RMS error with
// s = 1 is 25-50 % below s = 0 (plain magnitude) and 5-15 % below s = 2, so s = 1
// is the default. q0 is then the quantum of the finest level; level j is
// quantized 2^(J-1-j) times finer when the stream is complete.
// Reconstruction: a coefficient whose bits are known down to plane p, |integer| in
// [a, a + 2^p - 1], decodes to sign * (a + (2^p - 1) / 2); insignificant ones to 0.
// A complete stream coded down to plane 0 therefore gives back the integers exactly.
//
// Stream layout (all of it is the level payload the container carries):
//   version        u8       kZerotreeVersion (1)
//   levels         u8       J: levels coded (0..hierarchy levels), coeffs.size()
//   level_shift    u8       s, 0..kMaxLevelShift
//   top_plane[3]   u8 each  1 + the top bit plane of the normal, tangent,
//                           bitangent channel (0: channel all zero), <= 41
//   symbols        varint   unsigned LEB128: binary decisions the encoder coded
//   payload        bytes    range coder output (coding/entropy/range_coder.h);
//                           empty when symbols = 0
// The payload is the symbol sequence of spiht_engine.h, each decision coded with
// its adaptive context (significance, set significance, refinement; signs raw).
// Embedded: any prefix of the stream that keeps the header decodes; the decoder
// stops at the last symbol the prefix determines (bit_io.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

constexpr uint8_t kZerotreeVersion = 1;
constexpr int kZerotreeMaxLevelShift = 4;

struct ZerotreeOptions {
  double quantum = 0;               // q0 > 0, world units; the decoder is given the same value
  double tangential_factor = 100;   // > 0; tangential amplitude weight 1/sqrt(factor)
  uint64_t byte_budget = 0;         // total stream bytes (header included); 0 = until min_plane
  int min_plane = 0;                // last bit plane coded, 0..40
  int level_shift = 1;              // s above, 0..kZerotreeMaxLevelShift
};

struct ZerotreeEncodeReport {
  // Bit plane being coded when the stream ended (min_plane when it ran to the
  // end): the finest level's quantizer step is then ~2^last_plane quanta, which is
  // what rate control turns into an R-D slope.
  int last_plane = 0;
};

// Codes coeffs (coeffs.size() <= hierarchy.levels(), coeffs[j].size() ==
// NumOddVertices(j)). The stream never exceeds byte_budget; a budget below the
// smallest stream (ZerotreeMinBytes(), the header) is an error. Deterministic.
StatusOr<std::vector<uint8_t>> EncodeZerotree(const SemiRegularHierarchy& hierarchy,
                                              const std::vector<std::vector<Vec3>>& coeffs,
                                              const ZerotreeOptions& options,
                                              ZerotreeEncodeReport* report = nullptr);

// Bytes of the smallest stream (the header of an empty one).
size_t ZerotreeMinBytes();

// Whether a stream prefix holds the whole header (fixed fields and symbol count),
// valid or not: a shorter prefix of a truncated container decodes no level.
bool ZerotreeHeaderComplete(const uint8_t* data, size_t size);

// The level count J a stream header announces (version checked as DecodeZerotree
// does it), read without a hierarchy: the container compares it with its own header
// before it builds the J-level hierarchy the payload is decoded against.
StatusOr<int> ReadZerotreeHeaderLevels(const uint8_t* data, size_t size);

// Decodes a stream or any prefix of it that holds the header; returns levels()
// of the header entries, coeffs[j] with NumOddVertices(j) entries each.
// Hostile input gives kCorruptStream, never a crash or unbounded allocation (the
// allocation is bounded by the caller's hierarchy).
StatusOr<std::vector<std::vector<Vec3>>> DecodeZerotree(const SemiRegularHierarchy& hierarchy,
                                                        const uint8_t* data, size_t size, double quantum,
                                                        double tangential_factor);

// The integers the encoder codes, mapped back to world units: what a complete
// stream coded down to plane 0 decodes to (tests, rate control).
StatusOr<std::vector<std::vector<Vec3>>> QuantizeZerotree(const std::vector<std::vector<Vec3>>& coeffs,
                                                          const ZerotreeOptions& options);

}  // namespace eqmesh
