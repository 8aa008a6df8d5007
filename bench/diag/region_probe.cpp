// Region probe (developer tool): for every folded finest face of a remesh, what a
// planar Tutte re-embedding of the rings around it would do: the region's
// movable vertices are placed at the uniform-weight barycentric embedding of
// their projection on the region's mean input plane, then lifted back onto the
// input along that plane's normal.
//   region_probe INPUT REMESH.srm
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/Sparse>

#include "fold_probe_input.h"
#include "mesh/semi_regular.h"
#include "remesh/quality_checks.h"

using namespace eqmesh;

int main(int argc, char** argv) {
  if (argc < 3) return 2;
  std::optional<FoldProbeInput> probe = LoadFoldProbeInput(argv[1], argv[2]);
  if (!probe) return 1;
  const SemiRegularMesh* srm = &probe->srm;
  const TriangleBvh* bvh = &probe->bvh;
  const auto& faces = probe->faces();
  std::vector<Vec3>& pos = probe->pos;
  const std::vector<std::vector<uint32_t>>& inc = probe->inc;
  auto folded = [&](uint32_t f) { return probe->Folded(f); };
  auto input_normal = [&](const Vec3& p) { return probe->InputNormalAt(p); };
  auto input_face_normal = [&](uint32_t g) { return Vec3(probe->InputFaceNormal(g).normalized()); };
  std::vector<uint32_t> folds;
  for (uint32_t f = 0; f < faces.size(); ++f)
    if (folded(f)) folds.push_back(f);
  std::printf("%zu folded faces\n", folds.size());
  for (uint32_t f0 : folds) {
    std::printf("face %u (kinds", f0);
    for (uint32_t v : faces[f0]) std::printf(" %d", static_cast<int>(srm->kinds[v]));
    std::printf(")\n");
    for (int rings = 1; rings <= 6; ++rings) {
      std::set<uint32_t> region(faces[f0].begin(), faces[f0].end());
      for (int r = 0; r < rings; ++r) {
        std::set<uint32_t> next = region;
        for (uint32_t v : region)
          for (uint32_t g : inc[v])
            for (uint32_t w : faces[g]) next.insert(w);
        region = next;
      }
      // Movable: interior to the region, not a base or boundary vertex.
      std::map<uint32_t, int> index;
      std::vector<uint32_t> movable;
      for (uint32_t v : region) {
        const VertexKind k = srm->kinds[v];
        if (k == VertexKind::kBase || k == VertexKind::kBoundary) continue;
        index[v] = static_cast<int>(movable.size());
        movable.push_back(v);
      }
      std::set<uint32_t> touched_faces, all_verts;
      for (uint32_t v : movable)
        for (uint32_t g : inc[v]) {
          touched_faces.insert(g);
          for (uint32_t w : faces[g]) all_verts.insert(w);
        }
      Vec3 n = Vec3::Zero();
      for (uint32_t v : all_verts) n += input_normal(pos[v]);
      n.normalize();
      const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
      int before = 0, against_before = 0;
      for (uint32_t g : touched_faces) {
        before += folded(g);
        const Face& t = faces[g];
        if ((pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]).dot(n) <= 0) ++against_before;
      }
      // Tutte: sum_j (x_i - x_j) = 0 for movable i, neighbours by edges.
      std::vector<std::set<uint32_t>> nb(movable.size());
      for (uint32_t v : movable)
        for (uint32_t g : inc[v])
          for (uint32_t w : faces[g])
            if (w != v) nb[index[v]].insert(w);
      const int m = static_cast<int>(movable.size());
      Eigen::SparseMatrix<double> L(m, m);
      std::vector<Eigen::Triplet<double>> trip;
      Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
      for (int i = 0; i < m; ++i) {
        trip.emplace_back(i, i, static_cast<double>(nb[i].size()));
        for (uint32_t w : nb[i]) {
          auto it = index.find(w);
          if (it != index.end()) {
            trip.emplace_back(i, it->second, -1.0);
          } else {
            rhs(i, 0) += pos[w].dot(e1);
            rhs(i, 1) += pos[w].dot(e2);
          }
        }
      }
      L.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
      const Eigen::MatrixXd q = solver.solve(rhs);
      int flat2d = 0;
      {
        auto at2 = [&](uint32_t v) {
          auto it = index.find(v);
          if (it != index.end()) return Eigen::Vector2d(q(it->second, 0), q(it->second, 1));
          return Eigen::Vector2d(pos[v].dot(e1), pos[v].dot(e2));
        };
        for (uint32_t g : touched_faces) {
          const Face& t = faces[g];
          const Eigen::Vector2d a = at2(t[0]), b = at2(t[1]), c = at2(t[2]);
          if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0) ++flat2d;
        }
      }
      int lifted = 0;
      double max_move = 0.0, radius = 0.0;
      for (uint32_t v : all_verts) radius = std::max(radius, (pos[v] - pos[faces[f0][0]]).norm());
      if (rings == 1 && std::getenv("DUMP")) {
        for (uint32_t v : all_verts) {
          auto it = index.find(v);
          std::printf("    v %u %s 2d (%.4f, %.4f) h %.4f ncos %.3f", v, it != index.end() ? "mov" : "fix", pos[v].dot(e1), pos[v].dot(e2), pos[v].dot(n), input_normal(pos[v]).dot(n));
          if (it != index.end()) std::printf(" -> (%.4f, %.4f)", q(it->second, 0), q(it->second, 1));
          std::printf("\n");
        }
      }
      std::vector<Vec3> newpos(m);
      bool ok = true;
      for (int i = 0; i < m; ++i) {
        const uint32_t v = movable[i];
        const double h = pos[v].dot(n);
        const Vec3 p = q(i, 0) * e1 + q(i, 1) * e2 + h * n;
        std::vector<RayHit> hits;
        bvh->RayAllHits(p - 2 * radius * n, n, 0.0, 4 * radius, &hits);
        double best = 1e300;
        Vec3 best_p;
        for (const RayHit& hit : hits) {
          if (input_face_normal(hit.face).dot(n) <= 0.0) continue;
          const Vec3 x = p - 2 * radius * n + hit.t * n;
          const double dh = std::abs(x.dot(n) - h);
          if (dh < best) {
            best = dh;
            best_p = x;
          }
        }
        if (best == 1e300) {
          ok = false;
          newpos[i] = p;
        } else {
          ++lifted;
          newpos[i] = best_p;
        }
        max_move = std::max(max_move, (newpos[i] - pos[v]).norm());
      }
      std::vector<Vec3> old(m);
      for (int i = 0; i < m; ++i) {
        old[i] = pos[movable[i]];
        pos[movable[i]] = newpos[i];
      }
      int after = 0, flat_inverted = 0;
      for (uint32_t g : touched_faces) {
        after += folded(g);
        const Face& t = faces[g];
        const Vec3 c = (pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]);
        if (c.dot(n) <= 0) ++flat_inverted;
      }
      for (int i = 0; i < m; ++i) pos[movable[i]] = old[i];
      std::printf("  rings %d: movable %d faces %zu folds %d -> %d (lifted %d/%d%s), against n before %d, 2D inverted %d, against n after %d, max move %.2g of radius %.2g\n",
                  rings, m, touched_faces.size(), before, after, lifted, m, ok ? "" : " SOME UNLIFTED", against_before, flat2d, flat_inverted,
                  max_move, radius);
    }
  }
  return 0;
}
