// The refinement of one level j -> j+1 (piercing.h), shared by piercing.cpp
// (hits, midpoints, parameter update) and placement_repair.cpp (fold and
// lopsidedness repair). Internal to lib/remesh.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mesh/semi_regular.h"
#include "mesh/triangle_bvh.h"
#include "remesh/crease_curves.h"
#include "remesh/level_domain.h"
#include "remesh/param_point.h"
#include "remesh/piercing.h"
#include "wavelet/butterfly.h"

namespace eqmesh::remesh_internal {

using Vec3d = Eigen::Vector3d;

struct EdgeChoice {
  Vec3 position = Vec3::Zero();
  Vec3d u = Vec3d::Zero();  // parameter in the left face's chart
  VertexKind kind = VertexKind::kNonNormal;
  bool needs_forward = false;
  uint32_t on_face = kNoFace;  // input triangle the position lies on, where known
  CreaseSite crease;           // where the position lies on a crease chain, if it does
};

class LevelRefiner {
 public:
  LevelRefiner(const SemiRegularHierarchy& h, int j, const InputSurface& s, const RemeshParts& parts,
               std::vector<Vec3>* positions, const std::vector<uint32_t>& on_faces, std::vector<ParamPoint>* params,
               const std::vector<CreasePlace>* creases)
      : h_(h), j_(j), s_(s), parts_(parts), dom_(h, j), pos_(*positions), on_face_(on_faces), params_(*params),
        creases_(creases) {
    fine_ = RefinedIn3d(dom_.faces().size(), s.mesh->faces.size());
  }

  void Run(const StencilTable& stencils, std::vector<Vec3>* positions, std::vector<uint32_t>* on_faces,
           std::vector<VertexKind>* kinds, LevelStats* stats);
  // The crease places of the odd vertices Run placed, in their order.
  void AppendCreasePlaces(std::vector<CreasePlace>* places) const;
  std::vector<ParamPoint> TakeParams() { return std::move(params_out_); }

 private:
  void BuildBuckets();
  EdgeChoice PierceEdge(uint32_t k, Chart* chart) const;
  std::vector<EdgeChoice> NormalCandidates(uint32_t k, Chart* chart, size_t limit) const;
  EdgeChoice MidpointChoice(uint32_t k) const;
  bool SurfaceParam(uint32_t k, const Vec3& x, uint32_t face, const std::array<double, 3>& bary, Chart* chart,
                    Vec3d* u) const;
  bool RelaxedChoice(uint32_t k, double blend, Chart* chart, EdgeChoice* out) const;
  EdgeChoice BoundaryPoint(uint32_t k) const;
  std::optional<EdgeChoice> CreasePoint(uint32_t k) const;
  bool InKite(const Vec3d& u, int slot) const;
  bool InDiamond(const Vec3d& u, int slot) const;
  Vec3 MidpointPosition(uint32_t k, const Vec3d& u, Chart* chart, uint32_t* on_face) const;
  Vec3d DiamondParam(uint32_t k, const Vec3& x) const;
  Vec3 FineMidpoint(uint32_t k, uint32_t* on_face) const;
  std::optional<RayHit> NearestHit(const Vec3& p, const Vec3& n, double reach, uint32_t part) const;
  bool FacesAlong(uint32_t input_face, const Vec3& n) const;
  bool OnEdgeSheet(uint32_t k, uint32_t input_face) const;
  uint32_t EdgePart(uint32_t k) const;
  bool OnPart(uint32_t input_face, uint32_t part) const;
  std::optional<Vec3> ForwardMap(uint32_t root, const Vec3d& u, const Vec3& near, double reach, Chart* chart,
                                 uint32_t* on_face) const;
  Vec3d EdgePointIn(uint32_t f, int i) const;
  bool ChildrenValid(uint32_t f) const;
  void DemoteInvalidFaces();
  struct PlacementScore {
    size_t folds = 0;
    bool lopsided = false;
    double shape = 0.0;  // ShapeAround: larger is better
    double error = 0.0;
    bool operator<(const PlacementScore& o) const {
      if (folds != o.folds) return folds < o.folds;
      if (lopsided != o.lopsided) return !lopsided;
      if (shape != o.shape) return shape > o.shape;
      return error < o.error;
    }
  };
  // Returns the level-(j+1) faces still folded.
  std::vector<uint32_t> RepairPlacements();
  bool TryAlternatives(uint32_t k, const PlacementScore& before, Chart* chart);
  double Lopsidedness(uint32_t k) const;
  PlacementScore ScorePlacement(uint32_t k) const;
  const Vec3& FinePosition(uint32_t v) const;
  uint32_t FineFace(uint32_t v) const;
  bool SurelyUnfolded(const Face& t, const Vec3& normal) const;
  bool Folded(uint32_t child, double* error = nullptr) const;
  std::array<uint32_t, 6> FacesAround(uint32_t k) const;
  size_t FoldsAround(uint32_t k, double* error = nullptr) const;
  double ChildQuality(uint32_t child) const;
  double ShapeAround(uint32_t k) const;
  double SliverBound(const std::vector<uint8_t>& slivers_in) const;
  void ForwardMapDemoted();
  std::array<std::array<Vec3d, 3>, 4> Children(uint32_t f) const;
  ParamPoint Relocate(uint32_t f, uint32_t x) const;
  bool RelocateBoundary(uint32_t f, uint32_t x, ParamPoint* out) const;
  void UpdateParams(std::vector<ParamPoint>* next) const;
  double RmsError(const std::vector<Vec3>& fine_pos, const std::vector<ParamPoint>& next) const;

  const SemiRegularHierarchy& h_;
  const int j_;
  const InputSurface& s_;
  const RemeshParts& parts_;
  const LevelDomain dom_;
  const std::vector<Vec3>& pos_;
  const std::vector<uint32_t>& on_face_;  // of pos_
  const std::vector<ParamPoint>& params_;
  const std::vector<CreasePlace>* creases_;  // of pos_; null: no crease is followed
  std::vector<uint32_t> bucket_offsets_, bucket_items_;
  std::vector<Vec3> predicted_;
  std::vector<LocalFrame> frames_;
  std::vector<EdgeChoice> choice_;
  std::vector<ParamPoint> params_out_;
  // A level with at least kFineLevelFaceRatio faces per input face: hits are validated and
  // demoted midpoints placed in 3D (DiamondParam, FineMidpoint) instead of
  // through charts.
  bool fine_ = false;
  // RepairPlacements' SliverBound for this level.
  double sliver_quality_ = 0.0;
};

}  // namespace eqmesh::remesh_internal
