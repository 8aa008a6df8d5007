// Encoding of the base mesh (connectivity + level-0 scaling values) and of the
// kept-exactly components: the base in the compact chunk (compact_base/) where it
// is a manifold, consistently oriented mesh, else (and the kept components always)
// with Google Draco (see base_mesh_decoder.h for the departure from the seed
// paper's TG coder).
//
// R-D choice of the scaling-value depth (seed paper sec. 4 quantizes scaling
// coefficients "using variable bit rate" but does not say how; its future work asks
// for the R-D trade-off between scaling and wavelet coefficients). We try every
// position depth b in [kBaseMinBits, kBaseMaxBits] (quarter bits for the compact
// chunk, whose step is free; a whole bit is 6 dB, too coarse a staircase when the
// base is the whole stream) and keep the b minimising
//     J(b) = R(b) + lambda_world * sum_i w_i * |x_i - x^_i(b)|^2
// with R in bits (the whole chunk), x^ the decoded value and w_i the
// influence of base vertex i: the squared-norm energy, at the finest level, of the
// subdivision basis function of vertex i (BaseInfluenceWeights). That is the error
// a base displacement leaves when no finer detail corrects it. The closed loop
// corrects part of it (each level's details are measured against the decoded base),
// so J weighs it by kBaseUncorrectedShare = 1/4 (measured, base_mesh_encoder.cpp).
// lambda_world is the level coder's lambda expressed per squared world unit.
//
// Draco reorders vertices and faces (edgebreaker traversal). The encoder decodes
// its own chunk and matches each decoded vertex to the input vertex within the
// quantization tolerance (a bijection is required), then checks that the decoded
// faces are exactly the input faces under that map; if either fails for a method,
// the next method is tried. (An extra index attribute would give the map directly,
// but Draco then numbers points differently from the real, one-attribute stream.)
// The codec renumbers the semi-regular mesh to the decoded base order
// (semi_regular_reorder.h).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "coding/compact_base/compact_base_model.h"
#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// Compact-chunk depths are tried in steps of 1/kCompactDepthSteps bit.
inline constexpr int kCompactDepthSteps = 4;
// Tangential steps (quarter grid steps) tried for a base that is the whole surface.
inline constexpr int kSurfaceTangentialQuarters[] = {4, 6, 8, 12, 16};

struct MeshChunkEncoding {
  std::vector<uint8_t> bytes;                // the chunk that goes in the stream
  Mesh decoded;                              // exactly what the chunk's decoder returns for it
  std::vector<uint32_t> decoded_to_input;    // decoded vertex i was input vertex [i]
                                             // (empty when no map was asked for)
  double depth = 0;                          // position quantization depth in bits (compact: any
                                             // quarter bit; Draco: whole bits)
  bool compact = false;                      // a compact chunk (stream flag kCompactBase), else Draco
  int tangential_quarters = 4;               // compact: tangential step in quarter grid steps
  bool parallelogram_choice = false;         // compact: grid with the parallelogram choice (stream 1.7)
  CompactLayout layout = CompactLayout::kPositionsAfter;  // compact: its layout (a stream flag)
};

// One Draco encoding at a fixed depth, with the decoded result and (need_map) the
// vertex map. Picks the smallest of edgebreaker / sequential connectivity that
// round-trips.
StatusOr<MeshChunkEncoding> EncodeMeshWithDraco(const Mesh& mesh, int bits, bool need_map = true);

struct BaseRdReport {
  double depth = 0;
  double rate_bits = 0;
  double weighted_distortion = 0;
};

// Every depth of [kBaseMinBits, kBaseMaxBits], in order (independent of lambda, so
// rate control computes them once): the compact chunk (compact_base/), in steps of
// 1/kCompactDepthSteps bit and in both layouts (the interleaved one is smaller on
// bases of about 100 vertices, whose many position contexts of the other one have
// too few samples to learn), where the base is a manifold, consistently oriented
// mesh, else Draco in whole bits.
// surface_frames (a base with no refinement levels, i.e. the decoded surface itself)
// adds the compact chunk's surface-frame codings (kSurfaceTangentialQuarters) at
// every depth.
StatusOr<std::vector<MeshChunkEncoding>> EncodeBaseCandidates(const Mesh& base, bool draco_only = false,
                                                              bool surface_frames = false);

// Index of the candidate minimising J (weights.size() == base.num_vertices()). With
// quadrics (SurfaceErrorQuadrics, one per base vertex) a vertex's error is e^T Q e
// instead of |e|^2.
size_t ChooseBaseCandidate(const std::vector<MeshChunkEncoding>& candidates, const Mesh& base,
                           const std::vector<double>& weights, double lambda_world,
                           BaseRdReport* report, const std::vector<Eigen::Matrix3d>* quadrics = nullptr);

// Both steps at once.
StatusOr<MeshChunkEncoding> EncodeBaseMesh(const Mesh& base, const std::vector<double>& weights,
                                           double lambda_world, BaseRdReport* report = nullptr);

}  // namespace eqmesh
