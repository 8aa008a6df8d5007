#include "mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

namespace eqmesh {

Status CheckIndicesAndCoordinates(const Mesh& mesh) {
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t v : mesh.faces[f]) {
      if (v >= mesh.positions.size()) {
        return InvalidMesh("face " + std::to_string(f) + " uses vertex " + std::to_string(v) + " but the mesh has " +
                           std::to_string(mesh.positions.size()) + " vertices");
      }
      if (!mesh.positions[v].allFinite()) {
        return InvalidMesh("vertex " + std::to_string(v) + " has a non-finite coordinate");
      }
    }
  }
  return Status::Ok();
}

size_t DropUnreferencedVertices(Mesh* mesh) {
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> remap(mesh->positions.size(), kUnused);
  for (const Face& f : mesh->faces) {
    for (uint32_t i : f) remap[i] = 0;
  }
  uint32_t next = 0;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == kUnused) continue;
    mesh->positions[next] = mesh->positions[v];
    remap[v] = next++;
  }
  const size_t dropped = mesh->positions.size() - next;
  if (dropped == 0) return 0;
  mesh->positions.resize(next);
  for (Face& f : mesh->faces) {
    for (uint32_t& i : f) i = remap[i];
  }
  return dropped;
}

BoundingBox ComputeBoundingBox(const Mesh& mesh) {
  BoundingBox box;
  bool first = true;
  for (const Face& f : mesh.faces) {
    for (uint32_t v : f) {
      if (v >= mesh.positions.size()) continue;
      const Vec3& p = mesh.positions[v];
      if (first) {
        box.min = box.max = p;
        first = false;
      } else {
        box.min = box.min.cwiseMin(p);
        box.max = box.max.cwiseMax(p);
      }
    }
  }
  return box;
}

double BoundingBoxDiagonal(const Mesh& mesh) { return ComputeBoundingBox(mesh).Diagonal(); }

double PowerOfTwoUnitScale(const Mesh& mesh) {
  const BoundingBox box = ComputeBoundingBox(mesh);
  const double side = (0.5 * box.max - 0.5 * box.min).maxCoeff();  // halves: no overflow
  const double largest = std::max(box.max.cwiseAbs().maxCoeff(), box.min.cwiseAbs().maxCoeff());
  if (!(side > 0.0) || !std::isfinite(side) || !std::isfinite(largest)) return 1.0;
  const int exponent = std::min(-std::ilogb(side), 400 - std::ilogb(largest));
  return std::ldexp(1.0, std::clamp(exponent, -1000, 1000));
}

size_t CountReferencedVertices(const Mesh& mesh) {
  std::vector<uint8_t> used(mesh.positions.size(), 0);
  size_t count = 0;
  for (const Face& f : mesh.faces) {
    for (uint32_t v : f) {
      if (v < used.size() && !used[v]) {
        used[v] = 1;
        ++count;
      }
    }
  }
  return count;
}

std::vector<Vec3> VertexNormals(const Mesh& mesh) {
  return VertexNormals(mesh.faces, mesh.positions.size(), mesh.positions);
}

std::vector<Vec3> VertexNormals(const std::vector<Face>& faces, size_t num_vertices,
                                const std::vector<Vec3>& positions) {
  std::vector<Vec3> normals(num_vertices, Vec3::Zero());
  for (const Face& f : faces) {
    const Vec3& a = positions[f[0]];
    const Vec3& b = positions[f[1]];
    const Vec3& c = positions[f[2]];
    const Vec3 n = (b - a).cross(c - a);  // length = 2 * area: area weighting
    for (uint32_t v : f) normals[v] += n;
  }
  for (Vec3& n : normals) {
    const double len = n.norm();
    n = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
  }
  return normals;
}

std::vector<Vec3> UnitVertexNormals(const Mesh& mesh) {
  std::vector<Vec3> normals = VertexNormals(mesh);
  for (Vec3& n : normals) {
    if (n.squaredNorm() == 0.0) n = Vec3::UnitZ();
  }
  return normals;
}

std::vector<Vec3> FaceCrossProducts(const Mesh& mesh) {
  std::vector<Vec3> out;
  out.reserve(mesh.faces.size());
  const std::vector<Vec3>& x = mesh.positions;
  for (const Face& f : mesh.faces) out.push_back((x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]));
  return out;
}

double CornerAngle(const Vec3& apex, const Vec3& a, const Vec3& b) {
  const double cosine = (a - apex).normalized().dot((b - apex).normalized());
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

double AngleSumAt(const Mesh& mesh, uint32_t v) {
  double sum = 0.0;
  for (const Face& f : mesh.faces) {
    for (size_t c = 0; c < 3; ++c) {
      if (f[c] == v) sum += CornerAngle(mesh.positions[v], mesh.positions[f[(c + 1) % 3]], mesh.positions[f[(c + 2) % 3]]);
    }
  }
  return sum;
}

}  // namespace eqmesh
