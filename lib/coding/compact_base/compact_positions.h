// Position pass of a compact chunk in the positions-after layout (stream 1.6, header
// flag kCompactPositionsAfter): the connectivity is coded first, so every vertex's
// position is predicted from ALL the faces around it whose other corners are already
// decoded, not only from the gate that discovered it.
//
// Follows Cohen-Or, Cohen and Irony's multi-way prediction and Draco's multi-parallelogram
// position predictor (the average of every complete parallelogram around the vertex,
// Touma-Gotsman's rule applied to each), with residuals coded EQ-style: adaptive
// models chosen by a context the decoder derives from what it has already decoded
// (seed paper, Lavu-Choi-Baraniuk SGP 2003, sec. 3: estimate, then quantize).
// Departures: Draco's "constrained" variant sends a crease flag per vertex; here the
// context (how many parallelograms there are, how large the neighbours' residuals
// were) takes that role at no signalling cost.
//
// Surface frames (tangential step > grid step): the normal-mesh idea (Guskov et al.
// 2000) applied to the vertices themselves. Moving a vertex within its surface moves
// the surface far less than moving it off it, so the residual is expressed in a frame
// whose normal is that of the predicting parallelograms' faces, and its two
// tangential parts are quantized F times coarser than the normal part (F a quarter
// multiple the encoder chooses by measurement). Positions then leave the grid: both
// sides compute them in double precision with the same operations in the same order
// (no fused multiply-add, scalar code) and clamp them to the grid's box.
//
// Parallelogram choice (axis grid only, stream 1.7): where two or more parallelograms
// predict a vertex, one adaptive bit says whether their mean or a single one predicts
// it, and unary bits which one. Draco's constrained multi-parallelogram sends such
// choices too; the mean alone fails at creases, where one parallelogram lies across
// the crease: on an extruded gear every rim vertex averaged an exact prediction from
// its side with a wrong one from its cap (1,474 B against 716-823 B for Draco at 61-74
// dB). The encoder takes a single parallelogram where its residual is estimated to
// cost more than two bits less than the mean's, after the choice's own cost.
// In this mode positions are coded in a greedy order both sides derive from the
// faces (most complete parallelograms first, then most coded neighbours, then the
// lowest index) instead of the traversal's: the traversal reaches a cylinder's rim
// through its cap's fan, whose only parallelogram points at the cap's centre, and
// the greedy order reaches it along the side strip (a two-ring, 194-vertex cylinder
// at 9 bits: 449 -> 217 B; Draco 349 B at that depth).
#pragma once

#include <cstdint>
#include <vector>

#include "coding/compact_base/compact_base_model.h"
#include "coding/entropy/range_coder.h"
#include "mesh/mesh.h"

namespace eqmesh {

// Tangential step of the axis grid (integer indices, no frames), in quarter steps.
inline constexpr int kGridTangentialQuarters = 4;

// The positions-after chunk's mode byte for the axis grid with the parallelogram
// choice (stream 1.7); other values are tangential_quarters (4: the axis grid).
inline constexpr uint8_t kGridChoiceModeByte = 0;

struct CompactPositionCoding {
  CompactGrid grid;
  int tangential_quarters = kGridTangentialQuarters;  // tangential step / grid step, times 4
  bool parallelogram_choice = false;                  // axis grid only
};

// Codes positions[0..n-1] (in decoded vertex order; faces in decoded ids) and
// returns what the decoder will rebuild.
std::vector<Vec3> EncodeCompactPositions(RangeEncoder* enc, const CompactPositionCoding& coding,
                                         const std::vector<Face>& faces, const std::vector<Vec3>& positions);

// Reads num_vertices positions; false when a grid index leaves the grid or the
// decoder fails.
bool DecodeCompactPositions(RangeDecoder* dec, const CompactPositionCoding& coding, const std::vector<Face>& faces,
                            uint32_t num_vertices, std::vector<Vec3>* positions);

}  // namespace eqmesh
