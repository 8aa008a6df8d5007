// eqmesh encoder: semi-regular (normal) mesh -> scale-wise progressive .eqm stream.
//
// Papers: Lavu, Choi, Baraniuk, SGP 2003 (EQ coding of normal-mesh wavelet
// coefficients, lambda-driven R-D quantization, tangential lambda x100 -- our defaults
// are x4 lifted and x2 unlifted, measured, see tangential_factor);
// Khodakovsky, Schröder, Sweldens 2000 (PGC: butterfly wavelets in local frames).
// Departures: the encoder is closed-loop (details are computed against the
// geometry the decoder reconstructs, level by level, so quantization error does
// not accumulate); the base scaling values' quantization depth is chosen by the
// same J = R + lambda D (base_mesh_encoder.h); the EQ chunks' lambda doubles per
// level towards the base (level_encoder.cpp: a coarse error spreads over a larger
// area); see encoder.cpp for the exact loop.
// Coder kZerotree (PGC baseline) is open loop instead, one embedded payload for all
// levels (zerotree_encoder.h): a bpv target cuts it to the byte budget exactly (no
// lambda search), lambda picks its last bit plane, a PSNR target searches the budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "coding/bitstream_shared.h"
#include "core/progress.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct PreparedOriginal;

// How near a --bpv target the encoder must land (relative); the CLI warns beyond it.
constexpr double kBpvTolerance = 0.03;

struct EncodeOptions {
  // Lifted by default: it measures better than the unlifted transform at every rate
  // (0.25-4 bpv) on all five bench meshes, bunny +0.8 to +1.1 dB (measured:
  // bench/log/2026-12-05-codec-notebook.md).
  bitstream::TransformId transform = bitstream::TransformId::kLifted;
  bitstream::CoderId coder = bitstream::CoderId::kEq;
  // R-D slope, dimensionless: every part of the stream minimises
  // R[bits] + lambda * D / q0^2 with q0 = bbox diagonal * 2^-16 and D the squared
  // error in world units. Used as is when no target is set; otherwise the start of
  // the search. Range (0, 2^200).
  double lambda = 1.0 / 64.0;
  // Targets (at most one may be > 0): bits per input vertex (hit within +-3 % by a
  // search on lambda, then on the tangential factor where the size jumps between
  // adjacent lambda codes; the nearest stream when neither reaches it; needs
  // input_vertices), or PSNR in dB of the decoded
  // full-resolution mesh against *original (smallest stream that meets it).
  double target_bpv = 0;
  double target_psnr = 0;
  // Tangential components use lambda / tangential_factor; 0 = the default for the
  // transform, DefaultTangentialFactor below. The seed paper uses 100; on our normal
  // meshes the non-normal (parametric-midpoint) vertices carry large tangential
  // details that 100 zeroes (bunny at 1 bpv: 61.5 dB against 67.4 with 1; measured:
  // bench/log/2026-12-05-codec-notebook.md). Zerotree: tangential amplitude weight
  // 1/sqrt(factor).
  double tangential_factor = 0;
  // Vertices of the original irregular mesh (the bpv denominator).
  size_t input_vertices = 0;
  // The original irregular mesh, for target_psnr and measure_psnr.
  const Mesh* original = nullptr;
  // *original prepared for the meter (stream_psnr.h), shared by every
  // measurement of one encode. The encoder's entry points prepare it
  // (WithPreparedOriginal) where it is missing or was prepared from another mesh.
  std::shared_ptr<const PreparedOriginal> prepared_original;
  // Decode the final stream and measure its PSNR against *original.
  bool measure_psnr = false;
  // Triangle budget the stream is meant to be decoded within (0: none): PSNR
  // targets and measurements are then of that decode (DecodeOptions::max_triangles),
  // so the rate-distortion choices are made for what a loader shows.
  uint64_t max_triangles = 0;
  // Metro samples per direction for every PSNR the encoder measures (0: its
  // defaults, 200k while searching lambda, 250k ranking level counts, the meter's own
  // for the reported PSNR). Fewer samples measure faster and coarser: for tests.
  uint64_t psnr_samples = 0;
  // A PSNR-target search measures the stream it chose once more, at the meter's
  // default sample count, before returning it (a search measures 200k samples).
  // False returns the search's choice as measured: for a caller that compares
  // several such streams and verifies only the one it keeps (the level search).
  bool verify_target = true;
  // PSNR target, for a candidate that only matters if it is smaller than a
  // stream of this many bytes (0: none): a searched pass that misses the target
  // in at least as many bytes ends the encode with kOutbid, since where quality
  // and size grow together with lambda no stream meeting the target is smaller.
  // (The walks over base sizes and simplified as-is meshes: most tries lose.)
  size_t outbid_bytes = 0;
  // Code the base with Draco (streams version 1.1 decoders read) instead of the
  // compact base chunk (format 1.2, compact_base/): it costs the bunny 0.5 dB at 0.25 bpv.
  bool draco_base = false;
  // EQ: context-model the tangential components (format 1.3, eq_model.h); false
  // writes the seed's iid tangential classes (1.2 chunks).
  bool eq_tangential_context = true;
  ProgressFn progress;
};

// 4 for the lifted transform, 2 for the unlifted one. With the per-level lambda of the
// EQ chunks (level_encoder.cpp) 4 gains 0.4-1.2 dB over 1 (zerotree too), but unlifted it
// leaves outliers on the decoded surface (igea at 4 bpv: -6.5 dB); 2 gains up to 1.1 dB
// over 1 there without them. Measured: bench/log/2026-12-05-codec-notebook.md.
double DefaultTangentialFactor(bitstream::TransformId transform);

// The samples a measurement takes: options.psnr_samples, else `fallback`.
inline uint64_t MeasureSamples(const EncodeOptions& options, uint64_t fallback) {
  return options.psnr_samples > 0 ? options.psnr_samples : fallback;
}

// `options` with prepared_original made for *options.original, where a target or
// a measurement will measure against it and it is missing or was prepared from
// another mesh; otherwise `options` as they are. Where the meter cannot prepare
// the original, each measurement tries on its own and reports why.
EncodeOptions WithPreparedOriginal(const EncodeOptions& options);

// The decoded `stream`'s PSNR against *options.original, as every measurement of
// the encoder takes it: decoded within options.max_triangles, with
// MeasureSamples(options, fallback) samples (0: the meter's default).
StatusOr<double> MeasureEncodedPsnr(const std::vector<uint8_t>& stream, const EncodeOptions& options,
                                    uint64_t fallback);

struct EncodeReport {
  double lambda = 0;          // as coded (after the log2 code)
  int lambda_code = 0;
  double tangential_factor = 1;  // as coded; --bpv may have moved it (EncodeOptions)
  double base_bits = 0;       // depth chosen for the base scaling values (quarter bits)
  bool base_compact = false;  // compact base chunk (else Draco)
  double base_tangential_step = 1;  // compact chunk: tangential / normal step (> 1: surface frames)
  size_t header_bytes = 0;
  size_t base_bytes = 0;
  size_t kept_bytes = 0;
  std::vector<size_t> level_bytes;
  size_t total_bytes = 0;
  double bpv = 0;             // 8 * total_bytes / input_vertices (0 if unknown)
  double psnr_db = 0;         // when measured (target_psnr or measure_psnr)
  bool psnr_measured = false;
  int rate_evaluations = 0;   // encodes the lambda search ran
};

// Encodes `mesh` (positions at every level; kinds may be empty). Deterministic:
// the same input and options give the same bytes.
StatusOr<std::vector<uint8_t>> Encode(const SemiRegularMesh& mesh, const EncodeOptions& options,
                                      EncodeReport* report = nullptr);

}  // namespace eqmesh
