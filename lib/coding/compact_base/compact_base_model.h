// Compact base-mesh chunk (stream version 1.2, header flag kCompactBase): the base
// connectivity and the level-0 scaling values of a semi-regular stream in one
// range-coded chunk, shared by the encoder and the decoder (ext_spec Appendix A.6).
//
// Follows the seed paper's plan for the base (Lavu, Choi, Baraniuk, SGP 2003, Sec. 4:
// connectivity by a Touma-Gotsman-style traversal coder, scaling values uniformly
// quantized and entropy coded) with a face-growing traversal close to Rossignac's
// Edgebreaker (IEEE TVCG 1999) and Gumhold-Strasser's cut-border machine (SIGGRAPH
// 1998): faces are grown across the gates (edges with one coded face) of a FIFO;
// each gate says whether a face lies across it and, if so, whether its third corner
// is a new vertex (predicted by the parallelogram rule of Touma-Gotsman and coded
// as an integer residual) or one already coded (an index into the short list of
// vertices joined to the gate by an open edge, else a global index).
// Departures: no CLERS grammar or valence list (a base has ~100-5,000 vertices, so
// a few adaptive binary events per face cost little, and a traversal this plain is
// easy to check on hostile input); manifold, consistently oriented bases only (the
// encoder falls back to the Draco chunk for anything else).
//
// Why not Draco for the base: at 0.25 bits per input vertex a Draco chunk of the
// bunny's 104-vertex base is 43 % of the stream, ~140 B of it Draco's own headers,
// probability tables and connectivity for a mesh this small.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <unordered_map>
#include <vector>

#include "coding/entropy/range_coder.h"
#include "mesh/mesh.h"

namespace eqmesh {

// Order of a compact chunk's symbols. kInterleaved (streams 1.2-1.5): each new
// vertex's residuals follow the gate event that discovers it, predicted by that
// gate's parallelogram. kPositionsAfter (1.6, header flag kCompactPositionsAfter):
// every connectivity event first, then the positions in vertex order, predicted
// from every complete parallelogram around the vertex (compact_positions.h).
enum class CompactLayout { kInterleaved, kPositionsAfter };

// Largest quantization depth of a compact chunk (bits per coordinate).
inline constexpr int kCompactMaxBits = 24;
// A compact chunk may not claim more faces than this many per vertex (plus a
// constant): manifold bases have about two; it bounds the decoder's work.
inline constexpr uint64_t kCompactMaxFacesPerVertex = 8;
inline constexpr uint64_t kCompactFaceSlack = 64;
// Each vertex costs at least four adaptive binary events (is_new, three zero
// flags), over 0.011 bit each at the models' strongest probability (31/4096), so a
// real chunk holds fewer than 180 vertices per payload byte: the decoder refuses
// counts beyond kCompactMaxVerticesPerByte per byte before allocating for them.
inline constexpr uint64_t kCompactMaxVerticesPerByte = 256;
// Longest Exp-Golomb prefix of a position residual (|r| < 2^(kCompactMaxBits + 1)).
inline constexpr int kCompactMaxPrefix = 30;

// The uniform grid positions are quantized to: p = origin + q * step, q in
// [0, 2^bits - 1] per axis, all arithmetic in double from the float32 fields.
struct CompactGrid {
  int bits = 0;
  std::array<float, 3> origin{};
  float step = 1.0f;

  int32_t MaxIndex() const { return static_cast<int32_t>((int64_t{1} << bits) - 1); }
  Vec3 Position(const std::array<int32_t, 3>& q) const;
};

// The nearest grid index of p on each axis, clamped to the grid (encoder side).
std::array<int32_t, 3> QuantizeToGrid(const CompactGrid& grid, const Vec3& p);

// Key of the undirected edge {u, v} in both sides' edge maps.
inline uint64_t CompactEdgeKey(uint32_t u, uint32_t v) {
  return (uint64_t{u > v ? u : v} << 32) | (u > v ? v : u);
}

// A directed edge a->b of a coded face whose third corner is c.
struct CompactGate {
  uint32_t a = 0, b = 0, c = 0;
};

// The traversal state both sides build identically from the faces coded so far.
class CompactBaseState {
 public:
  explicit CompactBaseState(uint32_t num_vertices) : neighbours_(num_vertices), faces_around_(num_vertices, 0) {}

  // Adds face (a, b, c) and queues its gates (a->b, b->c, c->a). False when a corner
  // repeats or an edge would get a third face.
  bool AddFace(uint32_t a, uint32_t b, uint32_t c);
  // Pops gates until one whose edge still has a single face; false when none is left.
  bool NextGate(CompactGate* gate);
  // Vertices joined to a, then to b, by an edge with a single face (in the order the
  // edges appeared), without a, b or repeats.
  void Candidates(uint32_t a, uint32_t b, std::vector<uint32_t>* out) const;
  const std::vector<Face>& faces() const { return faces_; }
  uint32_t FacesAround(uint32_t v) const { return faces_around_[v]; }

 private:
  uint32_t EdgeFaces(uint32_t u, uint32_t v) const;
  void AddToList(uint32_t from, uint32_t skip_a, uint32_t skip_b, std::vector<uint32_t>* out) const;

  std::unordered_map<uint64_t, uint8_t> edge_faces_;  // looked up only, never iterated
  std::vector<std::vector<uint32_t>> neighbours_;     // in the order edges appeared
  std::vector<uint32_t> faces_around_;                // faces added at each vertex so far
  std::deque<CompactGate> gates_;
  std::vector<Face> faces_;
};

// Adaptive models of the chunk (reset at its start).
struct CompactResidualModels {
  AdaptiveBit zero;
  std::array<AdaptiveBit, kCompactMaxPrefix + 1> prefix;
};
// Contexts of a gate's events in the positions-after layout: the faces already
// around each of its two corners (0..6+ each). A corner whose fan is nearly full is
// likely to be closed by this face, which then reuses a vertex instead of adding one.
inline constexpr int kGateFanCap = 6;
inline constexpr size_t kGateContexts = (kGateFanCap + 1) * (kGateFanCap + 1);
// Candidate positions after the first with a unary model each; later ones are bypass.
inline constexpr uint32_t kUnaryCandidates = 4;

struct CompactModels {
  AdaptiveBit more_components, has_face, is_new, in_candidates;
  CompactResidualModels predicted, seed;  // parallelogram residuals, seed-face residuals
  // Positions-after layout only: is_new and "the first candidate" per gate context,
  // and the unary steps of later candidate positions.
  std::array<AdaptiveBit, kGateContexts> gate_is_new, gate_first_candidate;
  std::array<AdaptiveBit, kUnaryCandidates - 1> later_candidate;
};

size_t GateContext(const CompactBaseState& state, const CompactGate& gate);
// The model of a gate's is_new event in `layout`.
AdaptiveBit* GateIsNewModel(CompactModels* models, CompactLayout layout, const CompactBaseState& state,
                            const CompactGate& gate);
// Position k of the third corner among `count` candidates: bypass bits in the
// interleaved layout; in the positions-after layout "first?" by gate context, then
// unary steps up to kUnaryCandidates, then bypass bits of the rest.
void EncodeCandidateIndex(RangeEncoder* enc, CompactModels* models, CompactLayout layout, size_t context,
                          uint64_t k, uint64_t count);
// False when the index read is not below count.
bool DecodeCandidateIndex(RangeDecoder* dec, CompactModels* models, CompactLayout layout, size_t context,
                          uint64_t count, uint64_t* k);

// Prediction of a new vertex across gate (a, b, c): q_a + q_b - q_c, clamped to the grid.
std::array<int32_t, 3> ParallelogramPrediction(const CompactGrid& grid, const std::array<int32_t, 3>& a,
                                               const std::array<int32_t, 3>& b,
                                               const std::array<int32_t, 3>& c);
// Prediction of a new seed-face corner: the last vertex coded, or the grid centre.
std::array<int32_t, 3> SeedPrediction(const CompactGrid& grid, const std::vector<std::array<int32_t, 3>>& coded);

// Bits of a bypass-coded index below `count` (0 for count <= 1).
int IndexBits(uint64_t count);

void EncodeResidual(RangeEncoder* enc, CompactResidualModels* models, int64_t r);
int64_t DecodeResidual(RangeDecoder* dec, CompactResidualModels* models);

}  // namespace eqmesh
