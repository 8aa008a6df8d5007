#include "mesh/mesh.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace eqmesh {

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
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3& a = mesh.positions[f[0]];
    const Vec3& b = mesh.positions[f[1]];
    const Vec3& c = mesh.positions[f[2]];
    const Vec3 n = (b - a).cross(c - a);  // length = 2 * area: area weighting
    for (uint32_t v : f) normals[v] += n;
  }
  for (Vec3& n : normals) {
    const double len = n.norm();
    n = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
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
