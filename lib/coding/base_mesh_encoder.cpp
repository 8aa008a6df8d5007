#include "coding/base_mesh_encoder.h"

#include <cstring>
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

std::unique_ptr<draco::Mesh> ToDracoMesh(const Mesh& mesh, bool with_index_probe) {
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
  if (with_index_probe) {
    draco::GeometryAttribute idx;
    idx.Init(draco::GeometryAttribute::GENERIC, nullptr, 1, draco::DT_INT32, false,
             sizeof(int32_t), 0);
    const int idx_id = dm->AddAttribute(idx, true, n);
    for (uint32_t i = 0; i < n; ++i) {
      const int32_t v = static_cast<int32_t>(i);
      dm->attribute(idx_id)->SetAttributeValue(draco::AttributeValueIndex(i), &v);
    }
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

// Decoded vertex -> input vertex, read from the probe's integer attribute.
StatusOr<std::vector<uint32_t>> ReadProbeMap(const std::vector<uint8_t>& bytes, uint32_t n) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return InternalError("Draco probe decode failed");
  const draco::Mesh& dm = *decoded.value();
  const draco::PointAttribute* idx = dm.GetNamedAttribute(draco::GeometryAttribute::GENERIC);
  if (idx == nullptr || dm.num_points() != n) {
    return InternalError("Draco probe changed the vertex count");
  }
  std::vector<uint32_t> map(n);
  std::vector<bool> seen(n, false);
  for (uint32_t i = 0; i < n; ++i) {
    int32_t v = -1;
    idx->ConvertValue<int32_t>(idx->mapped_index(draco::PointIndex(i)), 1, &v);
    if (v < 0 || static_cast<uint32_t>(v) >= n || seen[v]) {
      return InternalError("Draco probe map is not a permutation");
    }
    seen[v] = true;
    map[i] = static_cast<uint32_t>(v);
  }
  return map;
}

bool SameMesh(const Mesh& a, const Mesh& b) {
  if (a.faces != b.faces || a.positions.size() != b.positions.size()) return false;
  for (size_t i = 0; i < a.positions.size(); ++i) {
    if (a.positions[i] != b.positions[i]) return false;
  }
  return true;
}

StatusOr<DracoMeshEncoding> EncodeWithMethod(const Mesh& mesh, int bits, int method) {
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  const DracoMeshLimits limits{n, mesh.faces.size()};
  DracoMeshEncoding out;
  out.bits = bits;
  EQMESH_ASSIGN_OR_RETURN(out.bytes, RunDraco(*ToDracoMesh(mesh, false), bits, method));
  EQMESH_ASSIGN_OR_RETURN(out.decoded, DecodeDracoMesh(out.bytes.data(), out.bytes.size(), limits,
                                                       "base mesh self-check"));
  EQMESH_ASSIGN_OR_RETURN(std::vector<uint8_t> probe,
                          RunDraco(*ToDracoMesh(mesh, true), bits, method));
  EQMESH_ASSIGN_OR_RETURN(out.decoded_to_input, ReadProbeMap(probe, n));
  EQMESH_ASSIGN_OR_RETURN(Mesh probe_mesh, DecodeDracoMesh(probe.data(), probe.size(), limits,
                                                           "base mesh probe"));
  // The map is only valid if the index attribute did not change Draco's traversal.
  if (!SameMesh(out.decoded, probe_mesh)) {
    return InternalError("Draco probe traversal differs from the real encoding");
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

StatusOr<DracoMeshEncoding> EncodeMeshWithDraco(const Mesh& mesh, int bits) {
  if (mesh.positions.empty() || mesh.faces.empty()) {
    return InvalidArgument("Draco mesh chunk needs at least one face");
  }
  try {
    Status last = InternalError("no Draco method tried");
    std::optional<DracoMeshEncoding> best;
    for (const int method : kDracoMethods) {
      auto enc = EncodeWithMethod(mesh, bits, method);
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

StatusOr<DracoMeshEncoding> EncodeBaseMesh(const Mesh& base, const std::vector<double>& weights,
                                           double lambda_world, BaseRdReport* report) {
  if (weights.size() != base.positions.size()) {
    return InternalError("base influence weights do not match the base vertex count");
  }
  std::optional<DracoMeshEncoding> best;
  double best_cost = std::numeric_limits<double>::infinity();
  BaseRdReport best_report;
  for (int bits = bitstream::kBaseMinBits; bits <= bitstream::kBaseMaxBits; ++bits) {
    EQMESH_ASSIGN_OR_RETURN(DracoMeshEncoding enc, EncodeMeshWithDraco(base, bits));
    const double rate = 8.0 * static_cast<double>(enc.bytes.size());
    const double distortion = WeightedError(base, enc, weights);
    const double cost = rate + lambda_world * distortion;
    if (cost < best_cost) {
      best_cost = cost;
      best_report = {bits, rate, distortion};
      best = std::move(enc);
    }
  }
  if (report) *report = best_report;
  return std::move(*best);
}

}  // namespace eqmesh
