// Crease probe (developer tool): how much of a remesh's wavelet detail sits at
// the input's sharp edges. Per refinement j -> j+1, an odd vertex counts as
// "at a crease" when it lies within one mean level-j edge length of an input
// edge whose two faces turn by more than ANGLE degrees; the tool prints the
// share of such vertices, of the detail energy (unlifted butterfly details,
// squared length) and of the details longer than the RMS distance of 70 dB
// (diagonal * 10^-3.5: the ones a 70 dB stream must code). It measures what a
// crease-aware predictor (crease rules in the butterfly stencil) could save.
//   crease_probe INPUT REMESH.srm [ANGLE=30]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mesh/mesh_topology.h"
#include "mesh/semi_regular.h"
#include "mesh_io/mesh_io.h"
#include "mesh_io/semi_regular_io.h"
#include "wavelet/transform.h"

using namespace eqmesh;

namespace {

using Segment = std::pair<Vec3, Vec3>;

std::vector<Segment> SharpEdges(const Mesh& mesh, double angle_degrees) {
  const double cos_limit = std::cos(angle_degrees * M_PI / 180.0);
  const std::vector<Vec3> normals = FaceCrossProducts(mesh);
  const MeshTopology topology(mesh);
  std::vector<Segment> sharp;
  for (uint32_t e = 0; e < topology.num_edges(); ++e) {
    if (topology.EdgeFaceCount(e) != 2) continue;
    const IndexRange h = topology.EdgeHalfedges(e);
    const Vec3& a = normals[MeshTopology::HalfedgeFace(h[0])];
    const Vec3& b = normals[MeshTopology::HalfedgeFace(h[1])];
    if (a.dot(b) < cos_limit * a.norm() * b.norm()) {
      const Edge& v = topology.EdgeVertices(e);
      sharp.emplace_back(mesh.positions[v[0]], mesh.positions[v[1]]);
    }
  }
  return sharp;
}

// Points along the sharp edges, at a quarter of `reach` apart, hashed by cells
// of size `reach`: a point is within `reach` of a crease when a sample of the
// 27 cells around it is (up to the sample spacing).
class CreaseGrid {
 public:
  CreaseGrid(const std::vector<Segment>& sharp, double reach) : reach_(reach) {
    for (const auto& [a, b] : sharp) {
      const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / (reach / 4.0))));
      for (int i = 0; i <= n; ++i) {
        const Vec3 p = a + (b - a) * (static_cast<double>(i) / n);
        cells_[Key(p)].push_back(p);
      }
    }
  }

  bool Near(const Vec3& p) const {
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(Key(p + Vec3(dx, dy, dz) * reach_));
          if (it == cells_.end()) continue;
          for (const Vec3& q : it->second) {
            if ((q - p).norm() <= reach_) return true;
          }
        }
      }
    }
    return false;
  }

 private:
  long long Key(const Vec3& p) const {
    const auto cell = [this](double x) { return static_cast<long long>(std::floor(x / reach_)); };
    return cell(p.x()) * 73856093LL ^ cell(p.y()) * 19349663LL ^ cell(p.z()) * 83492791LL;
  }

  double reach_;
  std::unordered_map<long long, std::vector<Vec3>> cells_;
};

double MeanEdgeLength(const Mesh& level) {
  double sum = 0.0;
  for (const Face& f : level.faces) sum += (level.positions[f[0]] - level.positions[f[1]]).norm();
  return level.faces.empty() ? 0.0 : sum / static_cast<double>(level.faces.size());
}

struct Tally {
  size_t details = 0, at_crease = 0, significant = 0, significant_at_crease = 0;
  double energy = 0.0, energy_at_crease = 0.0;

  void Add(const Tally& o) {
    details += o.details;
    at_crease += o.at_crease;
    significant += o.significant;
    significant_at_crease += o.significant_at_crease;
    energy += o.energy;
    energy_at_crease += o.energy_at_crease;
  }
  void Print(const char* label) const {
    const auto share = [](size_t part, size_t whole) {
      return 100.0 * static_cast<double>(part) / static_cast<double>(std::max<size_t>(whole, 1));
    };
    std::printf("%s: %zu details, %.1f %% at a crease, holding %.1f %% of the energy and %zu of %zu (%.1f %%) "
                "details above the 70 dB RMS\n",
                label, details, share(at_crease, details), 100.0 * energy_at_crease / std::max(energy, 1e-300),
                significant_at_crease, significant, share(significant_at_crease, significant));
  }
};

Tally TallyLevel(const SemiRegularMesh& srm, const std::vector<Vec3>& details, int j,
                 const std::vector<Segment>& sharp, double threshold) {
  const CreaseGrid grid(sharp, MeanEdgeLength(ExtractLevel(srm, j)));
  const uint32_t first_odd = srm.hierarchy.NumVertices(j);
  Tally t;
  for (size_t k = 0; k < details.size(); ++k) {
    const bool at_crease = grid.Near(srm.positions[first_odd + k]);
    const double e = details[k].squaredNorm();
    const bool significant = std::sqrt(e) > threshold;
    ++t.details;
    t.energy += e;
    t.significant += significant;
    if (!at_crease) continue;
    ++t.at_crease;
    t.energy_at_crease += e;
    t.significant_at_crease += significant;
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: crease_probe INPUT REMESH.srm [ANGLE=30]\n");
    return 2;
  }
  const StatusOr<Mesh> input = ReadMesh(argv[1], nullptr);
  const StatusOr<SemiRegularMesh> srm = ReadSemiRegular(argv[2]);
  if (!input.ok() || !srm.ok()) {
    std::fprintf(stderr, "crease_probe: %s\n", (input.ok() ? srm.status() : input.status()).message().c_str());
    return 1;
  }
  const double angle = argc > 3 ? std::atof(argv[3]) : 30.0;
  const std::vector<Segment> sharp = SharpEdges(*input, angle);
  std::printf("%zu input edges turn by more than %.0f degrees\n", sharp.size(), angle);
  const double threshold = BoundingBoxDiagonal(*input) * std::pow(10.0, -70.0 / 20.0);
  const WaveletCoefficients c = ForwardTransform(srm->hierarchy, srm->positions, WaveletKind::kUnlifted);
  Tally all;
  for (int j = 0; j < srm->hierarchy.levels(); ++j) {
    const Tally t = TallyLevel(*srm, c.details[j], j, sharp, threshold);
    const std::string label = "level " + std::to_string(j) + "->" + std::to_string(j + 1);
    t.Print(label.c_str());
    all.Add(t);
  }
  all.Print("all levels");
  if (srm->hierarchy.HasCreases()) {
    SemiRegularMesh plain = *srm;
    (void)plain.hierarchy.SetBaseCreases({});
    const WaveletCoefficients p = ForwardTransform(plain.hierarchy, plain.positions, WaveletKind::kUnlifted);
    Tally without;
    for (int j = 0; j < srm->hierarchy.levels(); ++j) without.Add(TallyLevel(plain, p.details[j], j, sharp, threshold));
    std::printf("%zu tagged base edges; without the crease rules: ", srm->hierarchy.BaseCreases().size());
    without.Print("all levels");
  }
  return 0;
}
