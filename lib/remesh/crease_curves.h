// The input's crease curves (chains of sharp edges), and the crease point a
// remesh edge along one of them refines to.
//
// MAPS (Lee et al. 1998) keeps tagged feature lines on base edges, so their
// refinement stays on them; Guskov et al.'s normal meshes (2000) pierce every
// new vertex along the normal. Here the creases are found (sharp input edges)
// rather than given, and the base domain is not constrained by them (a crease
// vertex may be collapsed across the crease); a base edge is tagged as a
// crease (mesh/semi_regular.h) where both its ends lie on the same crease
// chain and the chain between them is nearly as short as the edge, and a
// tagged edge is refined onto the chain, at its arc-length midpoint between
// the edge's ends, while they lie on it. Piercing along the butterfly
// normal lands beside the crease (the prediction smooths it) and each level cuts
// the crease again: a box remeshed on its 8 corners measured 79.9 dB at level 7.
// The vertex is then non-normal (it costs three coefficients, not one); crease
// vertices are a small share of a level (they grow as 2^j, the level as 4^j).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh {

inline constexpr uint32_t kNoCreaseChain = std::numeric_limits<uint32_t>::max();
inline constexpr uint32_t kNoInputVertex = std::numeric_limits<uint32_t>::max();

// A point on a crease chain, by arc length from the chain's first vertex.
struct CreaseSite {
  uint32_t chain = kNoCreaseChain;
  double arc = 0.0;
};

// Where a remesh vertex lies on the creases: an input vertex (base vertices;
// its sites are the chains through it, several at a corner) or a single site
// (a vertex placed on a crease), or nowhere.
struct CreasePlace {
  uint32_t input_vertex = kNoInputVertex;
  CreaseSite site;
};

struct CreaseChain {
  std::vector<uint32_t> vertices;  // input vertices; a closed chain repeats its first at the end
  std::vector<double> arc;         // cumulative length at each vertex
  std::vector<uint32_t> faces;     // an input face on each segment (vertices[i], vertices[i+1])
  bool closed = false;
  double Length() const { return arc.back(); }
};

// Input edges whose two faces' normals turn by more than this are sharp. A box
// or a machined part turns by 90 degrees; 60 keeps the facets of low-poly
// organic meshes (rarely above 40 degrees away from their thin parts) out.
inline constexpr double kCreaseTurnDegrees = 60.0;

class CreaseCurves {
 public:
  CreaseCurves() = default;
  // Chains of the sharp manifold edges of `mesh`, split at every vertex where
  // other than two of them meet; loops without such a vertex are closed chains.
  explicit CreaseCurves(const Mesh& mesh, double min_turn_degrees = kCreaseTurnDegrees);

  bool empty() const { return chains_.empty(); }
  const std::vector<CreaseChain>& chains() const { return chains_; }
  // The chains through input vertex v (several at a corner), as sites.
  std::vector<CreaseSite> SitesOf(uint32_t v) const;

  // The crease point for a remesh edge whose ends lie at `a` and `b` (positions
  // pa, pb): the arc-length midpoint of the shortest stretch of one chain
  // joining them, if that stretch is at most kMaxArcToChord times the edge's
  // length.
  std::optional<CreaseSite> SplitSite(const CreasePlace& a, const Vec3& pa, const CreasePlace& b,
                                      const Vec3& pb) const;
  // The point of `mesh` at `site`; writes the input face of its chain segment to
  // *on_face.
  Vec3 PositionAt(const CreaseSite& site, const Mesh& mesh, uint32_t* on_face) const;

 private:
  std::vector<CreaseSite> SitesOfPlace(const CreasePlace& p) const;
  std::vector<CreaseChain> chains_;
  std::vector<uint32_t> site_offsets_;  // per input vertex, CSR into sites_
  std::vector<CreaseSite> sites_;
};

// A crease stretch longer than this times the remesh edge it would refine is
// not followed: the edge cuts across a bend of the crease, or joins its ends
// the long way round.
inline constexpr double kMaxArcToChord = 1.1;

}  // namespace eqmesh
