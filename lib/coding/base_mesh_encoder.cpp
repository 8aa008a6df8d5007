#include "coding/base_mesh_encoder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <set>
#include <string>
#include <exception>
#include <limits>
#include <memory>
#include <optional>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "coding/base_mesh_decoder.h"
#include "coding/bitstream_shared.h"
#include "coding/compact_base/compact_base_encoder.h"

namespace eqmesh {
namespace {

// Share of a base vertex's uncorrected influence (BaseInfluenceWeights) that the
// closed loop leaves: the finer details are coded against the decoded base and
// absorb the rest. 1/4 gains up to 0.5 dB at 0.25 bpv over share 1 and 1/16 no more
// (measured: bench/log/2026-12-05-codec-notebook.md, "Base chunk").
constexpr double kBaseUncorrectedShare = 0.25;

// Draco connectivity methods we try, smallest output wins.
constexpr int kDracoMethods[] = {draco::MESH_EDGEBREAKER_ENCODING, draco::MESH_SEQUENTIAL_ENCODING};

std::unique_ptr<draco::Mesh> ToDracoMesh(const Mesh& mesh) {
  auto dm = std::make_unique<draco::Mesh>();
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  dm->set_num_points(n);
  draco::GeometryAttribute pos;
  pos.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false,
           sizeof(float) * 3, 0);
  const int pos_id = dm->AddAttribute(pos, true, n);
  for (uint32_t i = 0; i < n; ++i) {
    const float xyz[3] = {static_cast<float>(mesh.positions[i].x()),
                          static_cast<float>(mesh.positions[i].y()),
                          static_cast<float>(mesh.positions[i].z())};
    dm->attribute(pos_id)->SetAttributeValue(draco::AttributeValueIndex(i), xyz);
  }
  for (const Face& f : mesh.faces) {
    dm->AddFace({draco::PointIndex(f[0]), draco::PointIndex(f[1]), draco::PointIndex(f[2])});
  }
  return dm;
}

StatusOr<std::vector<uint8_t>> RunDraco(const draco::Mesh& dm, int bits, int method) {
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  encoder.SetSpeedOptions(0, 0);  // densest: the base is tiny, speed is irrelevant
  encoder.SetEncodingMethod(method);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(dm, &buffer);
  if (!status.ok()) return InternalError("Draco encode failed: " + status.error_msg_string());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

using FaceKey = std::array<uint32_t, 3>;

FaceKey SortedFace(uint32_t a, uint32_t b, uint32_t c) {
  FaceKey k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

// Input vertices within tolerance of decoded position p, nearest first. Several
// when input vertices (nearly) share a position, as in scans with duplicated
// points or meshes whose non-manifold vertices were split: quantization then
// maps them to one decoded position.
std::vector<uint32_t> NearbyCandidates(const Mesh& input, const std::vector<uint32_t>& by_x, const Vec3& p,
                                       double tolerance) {
  auto it = std::lower_bound(by_x.begin(), by_x.end(), p.x() - tolerance, [&](uint32_t v, double x) {
    return input.positions[v].x() < x;
  });
  std::vector<std::pair<double, uint32_t>> found;
  for (; it != by_x.end() && input.positions[*it].x() <= p.x() + tolerance; ++it) {
    const double d = (input.positions[*it] - p).squaredNorm();
    if (d <= tolerance * tolerance) found.push_back({d, *it});
  }
  std::sort(found.begin(), found.end());
  std::vector<uint32_t> out;
  for (const auto& [d, v] : found) out.push_back(v);
  return out;
}

constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();

// The matching under construction: decoded vertex -> input vertex (kUnset while
// open), which inputs are taken, and the candidates of the vertices that have
// more than one.
struct Matching {
  std::vector<uint32_t> map;
  std::vector<bool> used;
  std::vector<std::vector<uint32_t>> ambiguous;
};

// Every decoded vertex's input candidates within `tolerance` (a window on x over
// the inputs sorted by x: O(n log n + n w)); a single candidate is taken at once.
Status MatchUniquePositions(const Mesh& input, const Mesh& decoded, double tolerance, Matching* m) {
  const uint32_t n = static_cast<uint32_t>(input.positions.size());
  std::vector<uint32_t> by_x(n);
  for (uint32_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](uint32_t a, uint32_t b) {
    return input.positions[a].x() < input.positions[b].x();
  });
  m->map.assign(n, kUnset);
  m->used.assign(n, false);
  m->ambiguous.assign(n, {});
  for (uint32_t i = 0; i < n; ++i) {
    std::vector<uint32_t> c = NearbyCandidates(input, by_x, decoded.positions[i], tolerance);
    if (c.empty()) {
      return InternalError("Draco base vertex " + std::to_string(i) + " has no input vertex within " +
                           std::to_string(tolerance));
    }
    if (c.size() > 1) {
      m->ambiguous[i] = std::move(c);
      continue;
    }
    if (m->used[c[0]]) {
      return InternalError("Draco base vertices are not matchable (two take input " + std::to_string(c[0]) + ")");
    }
    m->used[c[0]] = true;
    m->map[i] = c[0];
  }
  return Status::Ok();
}

// How many input faces decoded vertex i would complete, were it `candidate`, with
// the neighbours matched so far.
class FaceCompletion {
 public:
  FaceCompletion(const Mesh& input, const Mesh& decoded) : decoded_(decoded), faces_of_(decoded.positions.size()) {
    for (const Face& f : input.faces) input_faces_.insert(SortedFace(f[0], f[1], f[2]));
    for (uint32_t f = 0; f < decoded.faces.size(); ++f) {
      for (uint32_t v : decoded.faces[f]) faces_of_[v].push_back(f);
    }
  }

  int Score(uint32_t i, uint32_t candidate, const std::vector<uint32_t>& map) const {
    int s = 0;
    for (uint32_t f : faces_of_[i]) {
      const Face& t = decoded_.faces[f];
      FaceKey k;
      bool known = true;
      for (int c = 0; c < 3 && known; ++c) {
        k[c] = t[c] == i ? candidate : map[t[c]];
        known = k[c] != kUnset;
      }
      if (known && input_faces_.count(SortedFace(k[0], k[1], k[2]))) ++s;
    }
    return s;
  }

 private:
  const Mesh& decoded_;
  std::set<FaceKey> input_faces_;
  std::vector<std::vector<uint32_t>> faces_of_;
};

// One pass over the open vertices in vertex order: each takes its free candidate
// completing the most input faces, except that one completing none waits while
// the pass has assigned nothing yet (its neighbours may settle it). Returns
// whether anything was assigned.
StatusOr<bool> AssignBestScoring(const FaceCompletion& completion, Matching* m) {
  bool progress = false;
  for (uint32_t i = 0; i < m->map.size(); ++i) {
    if (m->map[i] != kUnset || m->ambiguous[i].empty()) continue;
    int best_score = -1;
    uint32_t best_v = kUnset;
    for (uint32_t c : m->ambiguous[i]) {
      if (m->used[c]) continue;
      const int sc = completion.Score(i, c, m->map);
      if (sc > best_score) {
        best_score = sc;
        best_v = c;
      }
    }
    if (best_v == kUnset) return InternalError("Draco base vertices are not matchable (candidates used up)");
    if (best_score == 0 && !progress) continue;
    m->used[best_v] = true;
    m->map[i] = best_v;
    progress = true;
  }
  return progress;
}

// When a pass assigns nothing: the first open vertex takes its first free candidate.
bool AssignFirstFree(Matching* m) {
  for (uint32_t i = 0; i < m->map.size(); ++i) {
    if (m->map[i] != kUnset) continue;
    for (uint32_t c : m->ambiguous[i]) {
      if (m->used[c]) continue;
      m->used[c] = true;
      m->map[i] = c;
      return true;
    }
  }
  return false;
}

// Decoded vertex -> input vertex by nearest position: each decoded vertex lies
// within Draco's quantization step of its input vertex. Vertices that share a
// position are told apart by connectivity (FaceCompletion), pass after pass.
StatusOr<std::vector<uint32_t>> MatchByPosition(const Mesh& input, const Mesh& decoded, double tolerance) {
  if (decoded.positions.size() != input.positions.size() || decoded.faces.size() != input.faces.size()) {
    return InternalError("Draco changed the base vertex or face count");
  }
  Matching m;
  EQMESH_RETURN_IF_ERROR(MatchUniquePositions(input, decoded, tolerance, &m));
  const FaceCompletion completion(input, decoded);
  for (bool progress = true; progress;) {
    EQMESH_ASSIGN_OR_RETURN(progress, AssignBestScoring(completion, &m));
    if (!progress) progress = AssignFirstFree(&m);
  }
  for (uint32_t v : m.map) {
    if (v == kUnset) return InternalError("Draco base vertices are not matchable");
  }
  return m.map;
}

// The map must carry every decoded face onto an input face (as vertex sets).
bool FacesCorrespond(const Mesh& input, const Mesh& decoded, const std::vector<uint32_t>& map) {
  std::set<FaceKey> faces;
  for (const Face& f : input.faces) faces.insert(SortedFace(f[0], f[1], f[2]));
  for (const Face& f : decoded.faces) {
    if (faces.erase(SortedFace(map[f[0]], map[f[1]], map[f[2]])) != 1) return false;
  }
  return faces.empty();
}

double QuantizationTolerance(const Mesh& mesh, int bits) {
  Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Vec3& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Draco's step is max extent / (2^bits - 1); a vertex moves <= sqrt(3)/2 steps.
  // Twice the step plus float32 slack leaves room without admitting neighbours
  // (the bijection and face checks catch the rest).
  const double extent = (hi - lo).maxCoeff();
  return 2.0 * extent / (std::ldexp(1.0, bits) - 1.0) + 1e-6 * (extent + 1.0);
}

StatusOr<MeshChunkEncoding> EncodeWithMethod(const Mesh& mesh, int bits, int method,
                                             bool need_map) {
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  const DracoMeshLimits limits{n, mesh.faces.size()};
  MeshChunkEncoding out;
  out.depth = bits;
  EQMESH_ASSIGN_OR_RETURN(out.bytes, RunDraco(*ToDracoMesh(mesh), bits, method));
  EQMESH_ASSIGN_OR_RETURN(out.decoded, DecodeDracoMesh(out.bytes.data(), out.bytes.size(), limits,
                                                       "base mesh self-check"));
  if (!need_map) return out;
  EQMESH_ASSIGN_OR_RETURN(out.decoded_to_input,
                          MatchByPosition(mesh, out.decoded, QuantizationTolerance(mesh, bits)));
  if (!FacesCorrespond(mesh, out.decoded, out.decoded_to_input)) {
    return InternalError("Draco base faces do not match the input faces");
  }
  return out;
}

double WeightedError(const Mesh& input, const MeshChunkEncoding& enc, const std::vector<double>& weights,
                     const std::vector<Eigen::Matrix3d>* quadrics) {
  double d = 0.0;
  for (size_t i = 0; i < enc.decoded_to_input.size(); ++i) {
    const uint32_t v = enc.decoded_to_input[i];
    const Vec3 e = enc.decoded.positions[i] - input.positions[v];
    d += weights[v] * (quadrics ? e.dot((*quadrics)[v] * e) : e.squaredNorm());
  }
  return d;
}

MeshChunkEncoding FromCompact(CompactBaseEncoding c, const CompactVariant& v) {
  MeshChunkEncoding out;
  out.bytes = std::move(c.bytes);
  out.decoded = std::move(c.decoded);
  out.decoded_to_input = std::move(c.decoded_to_input);
  out.depth = v.depth;
  out.compact = true;
  out.tangential_quarters = v.tangential_quarters;
  out.parallelogram_choice = v.parallelogram_choice;
  return out;
}

// Every compact depth (and, for a surface, tangential step) in one traversal.
StatusOr<std::vector<MeshChunkEncoding>> EncodeCompactCandidates(const Mesh& base, bool surface_frames) {
  std::vector<CompactVariant> variants;
  for (int bits = bitstream::kBaseMinBits; bits <= bitstream::kBaseMaxBits; ++bits) {
    for (int step = 0; step < kCompactDepthSteps; ++step) {
      if (bits == bitstream::kBaseMaxBits && step > 0) break;
      const double depth = bits + static_cast<double>(step) / kCompactDepthSteps;
      for (const int quarters : kSurfaceTangentialQuarters) {
        if (quarters == kGridTangentialQuarters || surface_frames) variants.push_back({depth, quarters});
      }
      // A surface (the as-is representation) may hold creases, where the mean of
      // the parallelograms fails (compact_positions.h); a remeshed base is smooth.
      if (surface_frames) variants.push_back({depth, kGridTangentialQuarters, true});
    }
  }
  EQMESH_ASSIGN_OR_RETURN(std::vector<CompactBaseEncoding> chunks, EncodeCompactBaseVariants(base, variants));
  std::vector<MeshChunkEncoding> out;
  for (size_t i = 0; i < chunks.size(); ++i) out.push_back(FromCompact(std::move(chunks[i]), variants[i]));
  if (surface_frames) return out;  // a whole surface: thousands of vertices, frames only in this layout
  for (const CompactVariant& v : variants) {
    EQMESH_ASSIGN_OR_RETURN(CompactBaseEncoding c, EncodeCompactBase(base, v.depth, CompactLayout::kInterleaved));
    out.push_back(FromCompact(std::move(c), v));
    out.back().layout = CompactLayout::kInterleaved;
  }
  return out;
}

}  // namespace

StatusOr<MeshChunkEncoding> EncodeMeshWithDraco(const Mesh& mesh, int bits, bool need_map) {
  if (mesh.positions.empty() || mesh.faces.empty()) {
    return InvalidArgument("Draco mesh chunk needs at least one face");
  }
  try {
    Status last = InternalError("no Draco method tried");
    std::optional<MeshChunkEncoding> best;
    for (const int method : kDracoMethods) {
      auto enc = EncodeWithMethod(mesh, bits, method, need_map);
      if (!enc.ok()) {
        last = enc.status();
        continue;
      }
      if (!best || enc->bytes.size() < best->bytes.size()) best = std::move(enc).value();
    }
    if (!best) return last;
    return std::move(*best);
  } catch (const std::exception& e) {
    return InternalError(std::string("Draco threw: ") + e.what());
  }
}

StatusOr<std::vector<MeshChunkEncoding>> EncodeBaseCandidates(const Mesh& base, bool draco_only,
                                                              bool surface_frames) {
  // The compact chunk wherever the base is a manifold, consistently oriented mesh;
  // else Draco at every whole depth. A coarse Draco depth can merge base vertices
  // that lie closer than its step (scans with near-duplicate points): such a depth
  // cannot be matched back to the input and is skipped; the finer ones always can.
  if (!draco_only) {
    auto compact = EncodeCompactCandidates(base, surface_frames);
    if (compact.ok()) return compact;
  }
  std::vector<MeshChunkEncoding> candidates;
  Status last = Status::Ok();
  for (int bits = bitstream::kBaseMinBits; bits <= bitstream::kBaseMaxBits; ++bits) {
    StatusOr<MeshChunkEncoding> enc = EncodeMeshWithDraco(base, bits);
    if (enc.ok()) {
      candidates.push_back(std::move(*enc));
    } else {
      last = enc.status();
    }
  }
  if (candidates.empty()) return last;
  return candidates;
}

size_t ChooseBaseCandidate(const std::vector<MeshChunkEncoding>& candidates, const Mesh& base,
                           const std::vector<double>& weights, double lambda_world,
                           BaseRdReport* report, const std::vector<Eigen::Matrix3d>* quadrics) {
  size_t best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < candidates.size(); ++i) {
    const double rate = 8.0 * static_cast<double>(candidates[i].bytes.size());
    const double distortion = WeightedError(base, candidates[i], weights, quadrics);
    const double cost = rate + lambda_world * kBaseUncorrectedShare * distortion;
    if (cost < best_cost) {
      best_cost = cost;
      best = i;
      if (report) *report = {candidates[i].depth, rate, distortion};
    }
  }
  return best;
}

StatusOr<MeshChunkEncoding> EncodeBaseMesh(const Mesh& base, const std::vector<double>& weights,
                                           double lambda_world, BaseRdReport* report) {
  if (weights.size() != base.positions.size()) {
    return InternalError("base influence weights do not match the base vertex count");
  }
  EQMESH_ASSIGN_OR_RETURN(std::vector<MeshChunkEncoding> candidates, EncodeBaseCandidates(base));
  const size_t best = ChooseBaseCandidate(candidates, base, weights, lambda_world, report);
  return std::move(candidates[best]);
}

}  // namespace eqmesh
