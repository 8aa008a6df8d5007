// A decoded semi-regular mesh cut down to a triangle budget: faces are refined
// where the surface departs most from their flat parent, not level by level, and
// the result is closed with red-green transition faces so it stays conforming.
//
// Papers: Guskov, Vidimče, Sweldens, Schröder, "Normal Meshes" (SIGGRAPH 2000),
// Sec. 6 (adaptive normal meshes); Bank, Sherman, Weiser (1983) red-green
// refinement; the restricted (1-balanced) quadtree of the finite-element and
// terrain literature (e.g. Lindstrom et al. 1996 for the priority-driven split).
// Departures: the split priority is a face's largest edge-midpoint deviation in
// its subtree, squared, times its area (a bound on the flat face's contribution to
// the RMS error), computed from the decoded positions alone, so encoder and any
// decoder derive the same mesh; and faces are never merged back (one greedy pass
// per budget, then closure).
#pragma once

#include <cstdint>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct AdaptiveLevelReport {
  uint64_t refined_faces = 0;    // faces split 1-to-4 (by priority and by closure)
  uint64_t green_faces = 0;      // leaves split in two to close a hanging vertex
  int finest_level = 0;          // deepest level a face of the result comes from
  bool within_budget = true;     // false only when the base alone exceeds it
};

// The mesh of at most `max_triangles` triangles (kept components included) that
// refines `mesh` where it matters most; every face lies on the hierarchy's faces
// (levels 0..levels()) or halves one of them. Vertices are those of
// mesh.positions (finest decoded values) that the faces use, in increasing index
// order, then the kept components. Conforming: no vertex lies inside another
// face's edge, so the result is manifold and watertight wherever the uniform
// levels are. Deterministic. When even level 0 exceeds the budget, level 0.
Mesh ExtractAdaptiveLevel(const SemiRegularMesh& mesh, uint64_t max_triangles,
                          AdaptiveLevelReport* report = nullptr);

}  // namespace eqmesh
