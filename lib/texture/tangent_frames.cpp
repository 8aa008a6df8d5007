#include "texture/tangent_frames.h"

#include <cmath>

namespace eqmesh::texture {
std::vector<Vec4> VertexTangents(const Mesh& mesh, const std::vector<std::array<double, 2>>& texcoords,
                                 const std::vector<Vec3>& normals) {
  std::vector<Vec3> tan(mesh.positions.size(), Vec3::Zero()), bit(mesh.positions.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3 e1 = mesh.positions[f[1]] - mesh.positions[f[0]], e2 = mesh.positions[f[2]] - mesh.positions[f[0]];
    const double du1 = texcoords[f[1]][0] - texcoords[f[0]][0], dv1 = texcoords[f[1]][1] - texcoords[f[0]][1];
    const double du2 = texcoords[f[2]][0] - texcoords[f[0]][0], dv2 = texcoords[f[2]][1] - texcoords[f[0]][1];
    const double det = du1 * dv2 - du2 * dv1;
    if (det == 0.0) continue;
    // dP/du and dP/dv, weighted by the face's area (|e1 x e2| / |det| per unit of
    // texture area, times the texture area |det| / 2).
    const double area = 0.5 * e1.cross(e2).norm();
    const Vec3 t = (e1 * dv2 - e2 * dv1) / det, b = (e2 * du1 - e1 * du2) / det;
    const double wt = area / std::max(t.norm(), 1e-300), wb = area / std::max(b.norm(), 1e-300);
    for (uint32_t v : f) {
      tan[v] += wt * t;
      bit[v] += wb * b;
    }
  }
  std::vector<Vec4> out(mesh.positions.size());
  for (size_t v = 0; v < out.size(); ++v) {
    const Vec3& n = normals[v];
    Vec3 t = tan[v] - n * n.dot(tan[v]);
    t = t.squaredNorm() > 0 ? t.normalized() : n.unitOrthogonal();
    const double w = n.cross(t).dot(bit[v]) < 0.0 ? -1.0 : 1.0;
    out[v] = Vec4(t.x(), t.y(), t.z(), w);
  }
  return out;
}

Frame FrameAt(const Mesh& mesh, const std::vector<Vec4>& tangents, const std::vector<Vec3>& normals, uint32_t face,
              const std::array<float, 3>& barycentric) {
  Vec3 n = Vec3::Zero(), t = Vec3::Zero();
  double w = 0.0;
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t v = mesh.faces[face][k];
    n += barycentric[k] * normals[v];
    t += barycentric[k] * tangents[v].head<3>();
    w += barycentric[k] * tangents[v].w();
  }
  n = n.squaredNorm() > 0 ? n.normalized() : Vec3::UnitZ();
  t -= n * n.dot(t);
  t = t.squaredNorm() > 0 ? t.normalized() : n.unitOrthogonal();
  return {t, (w < 0 ? -1.0 : 1.0) * n.cross(t), n};
}

}  // namespace eqmesh::texture
