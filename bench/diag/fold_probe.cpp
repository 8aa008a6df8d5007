// Fold probe (developer tool): for every folded finest face of a remesh, what
// single-vertex moves of its corners would do (kernel centre of the fan, on and
// off the input; neighbour centroid), to see why the untangler left it.
//   fold_probe INPUT REMESH.srm [LEVEL]   (default: the finest)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "fold_probe_input.h"
#include "mesh/semi_regular.h"
#include "remesh/fan_kernel.h"
#include "remesh/quality_checks.h"

using namespace eqmesh;

int main(int argc, char** argv) {
  if (argc < 3) return 2;
  std::optional<FoldProbeInput> probe = LoadFoldProbeInput(argv[1], argv[2]);
  if (!probe) return 1;
  if (!probe->UseLevel(argc > 3 ? std::atoi(argv[3]) : probe->srm.hierarchy.levels())) return 2;
  const Mesh* input = &probe->input;
  const SemiRegularMesh* srm = &probe->srm;
  const TriangleBvh* bvh = &probe->bvh;
  const auto& faces = probe->faces();
  std::vector<Vec3>& pos = probe->pos;
  const std::vector<std::vector<uint32_t>>& inc = probe->inc;
  auto folded = [&](uint32_t f) { return probe->Folded(f); };
  auto fan_folds = [&](uint32_t v) {
    int n = 0;
    for (uint32_t f : inc[v]) n += folded(f);
    return n;
  };
  auto input_normal = [&](const Vec3& p) { return probe->InputNormalAt(p); };
  std::vector<std::vector<uint32_t>> input_inc(input->positions.size());
  for (uint32_t g = 0; g < input->faces.size(); ++g)
    for (uint32_t v : input->faces[g]) input_inc[v].push_back(g);
  auto face_normal = [&](uint32_t g) { return probe->InputFaceNormal(g); };
  // Whether the input face under a folded face's centroid is itself part of a
  // pleat of the input (a vertex-neighbour facing more than 90 degrees away),
  // and how the folded face sits against the input's area-weighted normal
  // around it: a fold over a pleat faces away from one sheet of it only.
  auto describe_input_under = [&](uint32_t f) {
    const Face& t = faces[f];
    const Vec3 n = (pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]).normalized();
    const ClosestPointResult cp = bvh->ClosestPoint((pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3.0);
    const Vec3 m = face_normal(cp.face).normalized();
    double worst = 1.0;
    Vec3 around = Vec3::Zero();
    for (uint32_t v : input->faces[cp.face]) {
      for (uint32_t g : input_inc[v]) {
        worst = std::min(worst, m.dot(face_normal(g).normalized()));
        around += face_normal(g);
      }
    }
    std::printf("  input face %u under it: face cos %.3f, its least neighbour cos %.3f (%s), 1-ring normal cos %.3f, dist %.2g\n",
                cp.face, n.dot(m), worst, worst < 0.0 ? "pleat" : "no pleat", n.dot(around.normalized()),
                std::sqrt(cp.squared_distance));
  };
  const char* kinds = "BNnb";
  {
    std::vector<int> valence(srm->hierarchy.NumVertices(0), 0);
    for (const Face& f : srm->hierarchy.Faces(0))
      for (uint32_t v : f) ++valence[v];
    std::vector<int> histogram(16, 0);
    for (int d : valence) ++histogram[std::min(d, 15)];
    std::printf("base valences (faces per vertex):");
    for (int d = 0; d < 16; ++d)
      if (histogram[d]) std::printf(" %d:%d", d, histogram[d]);
    std::printf("\n");
    const Mesh base = ExtractLevel(*srm, 0);
    for (uint32_t v = 0; v < valence.size(); ++v) {
      if (valence[v] != 3) continue;
      const double angles = AngleSumAt(base, v);
      std::printf("  valence-3 base vertex %u: angles sum to %.0f deg\n", v, angles * 180.0 / M_PI);
    }
  }
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (!folded(f)) continue;
    std::printf("face %u\n", f);
    describe_input_under(f);
    for (uint32_t v : faces[f]) {
      const Vec3 start = pos[v];
      const Vec3 facing = input_normal(start);
      std::vector<std::pair<Vec3, Vec3>> opposite;
      Vec3 centroid = Vec3::Zero();
      int cn = 0;
      for (uint32_t g : inc[v]) {
        const Face& t = faces[g];
        const int c = t[0] == v ? 0 : t[1] == v ? 1 : 2;
        opposite.emplace_back(pos[t[(c + 1) % 3]], pos[t[(c + 2) % 3]]);
        for (uint32_t w : t) if (w != v) { centroid += pos[w]; ++cn; }
      }
      centroid /= cn;
      std::printf("  v %u kind %c valence %zu folds %d", v, kinds[static_cast<int>(srm->kinds[v])], inc[v].size(), fan_folds(v));
      auto try_at = [&](const char* name, const Vec3& p) {
        pos[v] = p;
        const int n = fan_folds(v);
        pos[v] = start;
        const ClosestPointResult cp = bvh->ClosestPoint(p);
        std::printf(" | %s: folds %d dist %.2g", name, n, std::sqrt(cp.squared_distance));
      };
      const auto kernel = FanKernelCenter(start, facing, opposite);
      if (kernel) {
        try_at("kernel", *kernel);
        try_at("kernel-proj", bvh->ClosestPoint(*kernel).point);
      } else {
        std::printf(" | no kernel");
      }
      try_at("centroid", centroid);
      try_at("centroid-proj", bvh->ClosestPoint(centroid).point);
      std::printf("\n");
    }
  }
  return 0;
}
