#include "coding/base_mesh_encoder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <set>
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

namespace eqmesh {
namespace {

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

// Decoded vertex -> input vertex by nearest position: each decoded vertex lies
// within Draco's quantization step of its input vertex. Candidates come from a
// window on x (inputs sorted by x), so this is O(n log n + n w).
StatusOr<std::vector<uint32_t>> MatchByPosition(const Mesh& input, const Mesh& decoded,
                                                double tolerance) {
  const uint32_t n = static_cast<uint32_t>(input.positions.size());
  if (decoded.positions.size() != n || decoded.faces.size() != input.faces.size()) {
    return InternalError("Draco changed the base vertex or face count");
  }
  std::vector<uint32_t> by_x(n);
  for (uint32_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](uint32_t a, uint32_t b) {
    return input.positions[a].x() < input.positions[b].x();
  });
  std::vector<uint32_t> map(n);
  std::vector<bool> used(n, false);
  for (uint32_t i = 0; i < n; ++i) {
    const Vec3& p = decoded.positions[i];
    auto it = std::lower_bound(by_x.begin(), by_x.end(), p.x() - tolerance, [&](uint32_t v, double x) {
      return input.positions[v].x() < x;
    });
    double best = tolerance * tolerance;
    uint32_t best_v = n;
    for (; it != by_x.end() && input.positions[*it].x() <= p.x() + tolerance; ++it) {
      const double d = (input.positions[*it] - p).squaredNorm();
      if (d <= best) {
        best = d;
        best_v = *it;
      }
    }
    if (best_v == n || used[best_v]) return InternalError("Draco base vertices are not matchable");
    used[best_v] = true;
    map[i] = best_v;
  }
  return map;
}

// The map must carry every decoded face onto an input face (as vertex sets).
bool FacesCorrespond(const Mesh& input, const Mesh& decoded, const std::vector<uint32_t>& map) {
  auto key = [](uint32_t a, uint32_t b, uint32_t c) {
    std::array<uint32_t, 3> k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
  };
  std::set<std::array<uint32_t, 3>> faces;
  for (const Face& f : input.faces) faces.insert(key(f[0], f[1], f[2]));
  for (const Face& f : decoded.faces) {
    if (faces.erase(key(map[f[0]], map[f[1]], map[f[2]])) != 1) return false;
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

StatusOr<DracoMeshEncoding> EncodeWithMethod(const Mesh& mesh, int bits, int method,
                                             bool need_map) {
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  const DracoMeshLimits limits{n, mesh.faces.size()};
  DracoMeshEncoding out;
  out.bits = bits;
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

double WeightedError(const Mesh& input, const DracoMeshEncoding& enc,
                     const std::vector<double>& weights) {
  double d = 0.0;
  for (size_t i = 0; i < enc.decoded_to_input.size(); ++i) {
    const uint32_t v = enc.decoded_to_input[i];
    d += weights[v] * (enc.decoded.positions[i] - input.positions[v]).squaredNorm();
  }
  return d;
}

}  // namespace

StatusOr<DracoMeshEncoding> EncodeMeshWithDraco(const Mesh& mesh, int bits, bool need_map) {
  if (mesh.positions.empty() || mesh.faces.empty()) {
    return InvalidArgument("Draco mesh chunk needs at least one face");
  }
  try {
    Status last = InternalError("no Draco method tried");
    std::optional<DracoMeshEncoding> best;
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

StatusOr<std::vector<DracoMeshEncoding>> EncodeBaseCandidates(const Mesh& base) {
  std::vector<DracoMeshEncoding> candidates;
  for (int bits = bitstream::kBaseMinBits; bits <= bitstream::kBaseMaxBits; ++bits) {
    EQMESH_ASSIGN_OR_RETURN(DracoMeshEncoding enc, EncodeMeshWithDraco(base, bits));
    candidates.push_back(std::move(enc));
  }
  return candidates;
}

size_t ChooseBaseCandidate(const std::vector<DracoMeshEncoding>& candidates, const Mesh& base,
                           const std::vector<double>& weights, double lambda_world,
                           BaseRdReport* report) {
  size_t best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < candidates.size(); ++i) {
    const double rate = 8.0 * static_cast<double>(candidates[i].bytes.size());
    const double distortion = WeightedError(base, candidates[i], weights);
    const double cost = rate + lambda_world * distortion;
    if (cost < best_cost) {
      best_cost = cost;
      best = i;
      if (report) *report = {candidates[i].bits, rate, distortion};
    }
  }
  return best;
}

StatusOr<DracoMeshEncoding> EncodeBaseMesh(const Mesh& base, const std::vector<double>& weights,
                                           double lambda_world, BaseRdReport* report) {
  if (weights.size() != base.positions.size()) {
    return InternalError("base influence weights do not match the base vertex count");
  }
  EQMESH_ASSIGN_OR_RETURN(std::vector<DracoMeshEncoding> candidates, EncodeBaseCandidates(base));
  const size_t best = ChooseBaseCandidate(candidates, base, weights, lambda_world, report);
  return std::move(candidates[best]);
}

}  // namespace eqmesh
