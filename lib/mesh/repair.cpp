// Topological repair before remeshing.
//
// Follows the preprocessing of the normal-mesh remesher (Guskov et al. 2000 and
// MAPS, Lee et al. 1998, both assume a manifold, consistently oriented input) as
// summarised in shared/notes/remeshing.md step 1, with the cutting strategy of
// Gueziec, Taubin, Lazarus, Horn, "Cutting and stitching: converting sets of
// polygons to manifold surfaces" (IEEE TVCG 2001): non-manifold edges and
// vertices are removed by cutting (duplicating vertices per fan), never by
// deleting surface. Departures: stitching is limited to welding bitwise-equal
// positions, and non-orientable components are cut along the edges where
// breadth-first orientation propagation conflicts instead of along a minimal cut.
#include "mesh/repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>

#include <Eigen/Geometry>

#include "mesh/mesh_topology.h"

namespace eqmesh {
namespace {

constexpr uint32_t kNone = MeshTopology::kNone;

Status ValidateInput(const Mesh& mesh) {
  const size_t n = mesh.positions.size();
  if (n > kNone) return ResourceLimit("mesh has more vertices than 32-bit indices can address");
  return CheckIndicesAndCoordinates(mesh);
}

bool Contains(const Face& f, uint32_t v) { return f[0] == v || f[1] == v || f[2] == v; }

// ---------------------------------------------------------------- step 1: weld
//
// Welds are decided jointly, not pair by pair: closing a seam needs both ends of
// every seam edge welded before any of its edges is shared. So every group of
// identical positions is welded tentatively, the result is checked, and the
// groups at fault are taken apart again until nothing is at fault.

struct WeldGroups {
  std::vector<uint32_t> rep;         // per vertex: lowest referenced vertex at its position
  std::vector<uint32_t> members;     // per vertex: group size when it is a rep, else 0
  std::vector<uint32_t> fans_apart;  // per rep: fans of all members before welding
  std::vector<uint8_t> face_in_non_orientable;  // per face: its input component is non-orientable
};

WeldGroups FindWeldGroups(const Mesh& mesh) {
  WeldGroups g;
  const size_t n = mesh.positions.size();
  g.rep.resize(n);
  std::iota(g.rep.begin(), g.rep.end(), 0u);
  g.members.assign(n, 0);
  std::vector<uint8_t> referenced(n, 0);
  for (const Face& f : mesh.faces)
    for (uint32_t v : f) referenced[v] = 1;
  const std::vector<uint32_t> first = FirstVertexWithSamePosition(mesh.positions);
  std::vector<uint32_t> lowest_referenced(n, kNone);  // indexed by first[]
  for (uint32_t v = 0; v < n; ++v) {
    if (!referenced[v]) continue;
    uint32_t& r = lowest_referenced[first[v]];
    if (r == kNone) r = v;  // v ascends, so the first seen is the lowest
    g.rep[v] = r;
    ++g.members[r];
  }
  return g;
}

// Group reps (groups of two or more) that are still welded.
bool IsActiveRep(const WeldGroups& g, const std::vector<uint8_t>& reverted, uint32_t v) {
  return g.rep[v] == v && g.members[v] > 1 && !reverted[v];
}

std::vector<Face> WeldedFaces(const Mesh& mesh, const WeldGroups& g, const std::vector<uint8_t>& reverted) {
  std::vector<Face> faces = mesh.faces;
  for (Face& f : faces)
    for (uint32_t& v : f) v = reverted[g.rep[v]] ? v : g.rep[v];
  return faces;
}

// True when the faces on welded edge e came from more than one input edge, i.e.
// the weld (not the input) put them together.
bool WeldJoinedEdge(const MeshTopology& welded, uint32_t e, const Mesh& input) {
  Edge seen{kNone, kNone};
  for (uint32_t h : welded.EdgeHalfedges(e)) {
    const Face& t = input.faces[h / 3];
    Edge original{t[h % 3], t[(h % 3 + 1) % 3]};
    if (original[0] > original[1]) std::swap(original[0], original[1]);
    if (seen[0] != kNone && original != seen) return true;
    seen = original;
  }
  return false;
}

// Welds that close a non-orientable loop (e.g. re-zipping a Mobius strip that
// step 5 cut open) are undone for the whole component, unless the input was
// non-orientable there already.
bool RevertNonOrientableWelds(const MeshTopology& welded, const WeldGroups& g, std::vector<uint8_t>* reverted) {
  const std::vector<uint32_t>& comp = welded.FaceComponents();
  std::vector<uint8_t> guilty(welded.num_components(), 0);
  for (uint32_t e : welded.PlanConsistentOrientation().conflict_edges) guilty[welded.EdgeComponent(e)] = 1;
  for (uint32_t f = 0; f < welded.num_faces(); ++f)
    if (welded.FaceUsable(f) && g.face_in_non_orientable[f]) guilty[comp[f]] = 0;
  bool found = false;
  for (uint32_t v = 0; v < welded.num_vertices(); ++v) {
    if (!IsActiveRep(g, *reverted, v) || welded.VertexFaces(v).empty()) continue;
    if (guilty[comp[welded.VertexFaces(v)[0]]]) {
      (*reverted)[v] = 1;
      found = true;
    }
  }
  return found;
}

// What a weld may leave behind. Before the rest of the repair, pinches and
// inconsistent edges are left to steps 4 and 5; a weld that is all there is
// (WeldSeams) must leave neither where the input had none.
enum class WeldMode { kBeforeRepair, kAlone };

// Marks the groups at fault in `welded`; returns whether any was found. At
// fault: a weld that closes a non-orientable loop, joins no fans (it only
// pinches sheets together at a point) or joins an edge into more than two
// faces; alone (WeldSeams), also one that leaves a pinch (fans joined, but not
// into one) or joins an edge whose two faces run it the same way.
bool RevertFaultyWelds(const Mesh& input, const MeshTopology& welded, const WeldGroups& g, WeldMode mode,
                       std::vector<uint8_t>* reverted) {
  const bool alone = mode == WeldMode::kAlone;
  bool found = RevertNonOrientableWelds(welded, g, reverted);
  std::vector<uint32_t> labels;
  for (uint32_t v = 0; v < welded.num_vertices(); ++v) {
    if (!IsActiveRep(g, *reverted, v)) continue;
    const uint32_t fans = welded.VertexFans(v, &labels);
    if (fans >= g.fans_apart[v] || (alone && fans > 1)) {
      (*reverted)[v] = 1;
      found = true;
    }
  }
  for (uint32_t e = 0; e < welded.num_edges(); ++e) {
    const bool faulty = welded.IsNonManifoldEdge(e) || (alone && welded.IsInconsistentEdge(e));
    if (!faulty || !WeldJoinedEdge(welded, e, input)) continue;
    for (uint32_t v : welded.EdgeVertices(e)) {
      if (IsActiveRep(g, *reverted, v)) {
        (*reverted)[v] = 1;
        found = true;
      }
    }
  }
  return found;
}

void WeldDuplicatePositions(Mesh* mesh, WeldMode mode, RepairReport* report) {
  WeldGroups g = FindWeldGroups(*mesh);
  const size_t n = mesh->positions.size();
  std::vector<uint8_t> reverted(n, 0);
  bool any_group = false;
  for (uint32_t v = 0; v < n; ++v) any_group = any_group || IsActiveRep(g, reverted, v);
  if (!any_group) return;
  {
    const MeshTopology apart(*mesh);
    g.fans_apart.assign(n, 0);
    std::vector<uint32_t> labels;
    for (uint32_t v = 0; v < n; ++v)
      if (g.members[g.rep[v]] > 1) g.fans_apart[g.rep[v]] += apart.VertexFans(v, &labels);
    std::vector<uint8_t> non_orientable(apart.num_components(), 0);
    for (uint32_t e : apart.PlanConsistentOrientation().conflict_edges) non_orientable[apart.EdgeComponent(e)] = 1;
    g.face_in_non_orientable.assign(mesh->faces.size(), 0);
    for (uint32_t f = 0; f < mesh->faces.size(); ++f)
      if (apart.FaceUsable(f)) g.face_in_non_orientable[f] = non_orientable[apart.FaceComponents()[f]];
  }
  // Each round reverts at least one group, so this ends; the cap only bounds
  // time on pathological inputs, which then get no welding at all.
  constexpr int kMaxRounds = 32;
  Mesh welded;
  welded.positions = mesh->positions;
  bool settled = false;
  for (int round = 0; round < kMaxRounds && !settled; ++round) {
    welded.faces = WeldedFaces(*mesh, g, reverted);
    settled = !RevertFaultyWelds(*mesh, MeshTopology(welded), g, mode, &reverted);
  }
  if (!settled) std::fill(reverted.begin(), reverted.end(), uint8_t{1});
  for (uint32_t v = 0; v < n; ++v) {
    if (g.members[v] <= 1 || g.rep[v] != v) continue;
    (reverted[v] ? report->welds_refused : report->vertices_welded) += g.members[v] - 1;
  }
  mesh->faces = WeldedFaces(*mesh, g, reverted);
}

// ---------------------------------------------------------------- step 2: drop

void DropDegenerateAndDuplicateFaces(Mesh* mesh, double tolerance, RepairReport* report) {
  std::vector<uint8_t> keep(mesh->faces.size(), 1);
  std::vector<std::pair<Face, uint32_t>> sorted;
  for (uint32_t f = 0; f < mesh->faces.size(); ++f) {
    if (IsDegenerateFace(*mesh, mesh->faces[f], tolerance)) {
      keep[f] = 0;
      ++report->degenerate_faces_removed;
      continue;
    }
    Face key = mesh->faces[f];
    std::sort(key.begin(), key.end());
    sorted.emplace_back(key, f);
  }
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i].first != sorted[i - 1].first) continue;
    keep[sorted[i].second] = 0;  // a later copy of the same triangle
    ++report->duplicate_faces_removed;
  }
  size_t out = 0;
  for (size_t f = 0; f < mesh->faces.size(); ++f)
    if (keep[f]) mesh->faces[out++] = mesh->faces[f];
  mesh->faces.resize(out);
}

// ------------------------------------------------------ vertex splitting (3-5)

// Gives each fan of v after the first its own copy of v. Fans are taken from
// `topo` (built on the current faces) with `cut_mask`; returns copies made.
size_t SplitVertexFans(const MeshTopology& topo, uint32_t v, const std::vector<uint8_t>* cut_mask,
                       Mesh* mesh) {
  std::vector<uint32_t> labels;
  const uint32_t fans = topo.VertexFans(v, &labels, cut_mask);
  if (fans <= 1) return 0;
  const uint32_t base = static_cast<uint32_t>(mesh->positions.size());
  for (uint32_t k = 1; k < fans; ++k) mesh->positions.push_back(mesh->positions[v]);
  const IndexRange star = topo.VertexFaces(v);
  for (size_t i = 0; i < star.size(); ++i) {
    if (labels[i] == 0) continue;
    for (uint32_t& w : mesh->faces[star[i]]) w = w == v ? base + labels[i] - 1 : w;
  }
  return fans - 1;
}

// Moves corner `v` of face f to a fresh vertex only f uses.
void GivePrivateCopy(uint32_t f, uint32_t v, Mesh* mesh) {
  const uint32_t copy = static_cast<uint32_t>(mesh->positions.size());
  mesh->positions.push_back(mesh->positions[v]);
  for (uint32_t& w : mesh->faces[f]) w = w == v ? copy : w;
}

// Bit of face-corner edge (a, b) in a cut mask, whichever way the face runs it.
uint8_t EdgeBit(const Face& t, uint32_t a, uint32_t b) {
  for (int i = 0; i < 3; ++i) {
    const uint32_t p = t[i], q = t[(i + 1) % 3];
    if ((p == a && q == b) || (p == b && q == a)) return static_cast<uint8_t>(1u << i);
  }
  return 0;
}

// Faces of a non-manifold edge that do not stay on it: all but the first face
// and the first face running the edge the other way (else the second face).
std::vector<uint32_t> ExtraFaces(const MeshTopology& topo, uint32_t e) {
  const IndexRange hs = topo.EdgeHalfedges(e);
  size_t partner = 1;
  for (size_t k = 1; k < hs.size(); ++k) {
    if (topo.HalfedgeFrom(hs[k]) != topo.HalfedgeFrom(hs[0])) {
      partner = k;
      break;
    }
  }
  std::vector<uint32_t> extra;
  for (size_t k = 1; k < hs.size(); ++k)
    if (k != partner) extra.push_back(hs[k] / 3);
  return extra;
}

// ---------------------------------------------------- step 3: non-manifold edges

void SplitNonManifoldEdges(Mesh* mesh, RepairReport* report) {
  std::vector<uint32_t> endpoints;
  {
    const MeshTopology topo(*mesh);
    std::vector<uint8_t> cut(mesh->faces.size(), 0);
    for (uint32_t e = 0; e < topo.num_edges(); ++e) {
      if (!topo.IsNonManifoldEdge(e)) continue;
      ++report->non_manifold_edges_split;
      const Edge& ab = topo.EdgeVertices(e);
      for (uint32_t f : ExtraFaces(topo, e)) {
        cut[f] |= EdgeBit(mesh->faces[f], ab[0], ab[1]);
        ++report->faces_detached;
      }
      endpoints.push_back(ab[0]);
      endpoints.push_back(ab[1]);
    }
    if (endpoints.empty()) return;
    std::sort(endpoints.begin(), endpoints.end());
    endpoints.erase(std::unique(endpoints.begin(), endpoints.end()), endpoints.end());
    for (uint32_t v : endpoints) report->vertices_split += SplitVertexFans(topo, v, &cut, mesh);
  }
  // Where both endpoints reconnect around the edge the cut did not separate the
  // faces; detach the leftovers outright.
  const MeshTopology topo(*mesh);
  for (uint32_t e = 0; e < topo.num_edges(); ++e) {
    if (!topo.IsNonManifoldEdge(e)) continue;
    const Edge ab = topo.EdgeVertices(e);
    for (uint32_t f : ExtraFaces(topo, e)) {
      GivePrivateCopy(f, ab[0], mesh);
      GivePrivateCopy(f, ab[1], mesh);
      report->vertices_split += 2;
    }
  }
}

// ---------------------------------------------------- step 4: non-manifold vertices

void SplitNonManifoldVertices(Mesh* mesh, RepairReport* report) {
  const MeshTopology topo(*mesh);
  std::vector<uint32_t> labels;
  for (uint32_t v = 0; v < topo.num_vertices(); ++v) {
    if (topo.VertexFans(v, &labels) <= 1) continue;
    ++report->non_manifold_vertices_split;
    report->vertices_split += SplitVertexFans(topo, v, nullptr, mesh);
  }
}

// ---------------------------------------------------------- step 5: orientation

// Cuts a non-orientable surface open along its conflict edges; on the first
// round by splitting fans at the edge's endpoints, later by detaching a face.
void CutConflicts(const MeshTopology& topo, const std::vector<uint32_t>& conflicts, int round, Mesh* mesh,
                  RepairReport* report) {
  report->orientation_cuts += conflicts.size();
  if (round == 0) {
    std::vector<uint8_t> cut(mesh->faces.size(), 0);
    std::vector<uint32_t> endpoints;
    for (uint32_t e : conflicts) {
      const Edge& ab = topo.EdgeVertices(e);
      for (uint32_t h : topo.EdgeHalfedges(e)) cut[h / 3] |= EdgeBit(mesh->faces[h / 3], ab[0], ab[1]);
      endpoints.push_back(ab[0]);
      endpoints.push_back(ab[1]);
    }
    std::sort(endpoints.begin(), endpoints.end());
    endpoints.erase(std::unique(endpoints.begin(), endpoints.end()), endpoints.end());
    for (uint32_t v : endpoints) report->vertices_split += SplitVertexFans(topo, v, &cut, mesh);
    return;
  }
  for (uint32_t e : conflicts) {
    const uint32_t f = topo.EdgeHalfedges(e)[1] / 3;
    const Edge& ab = topo.EdgeVertices(e);
    if (!Contains(mesh->faces[f], ab[0]) || !Contains(mesh->faces[f], ab[1])) continue;  // done already
    GivePrivateCopy(f, ab[0], mesh);
    GivePrivateCopy(f, ab[1], mesh);
    report->vertices_split += 2;
  }
}

double SignedVolumeTimesSix(const Mesh& mesh, const Face& f) {
  return mesh.positions[f[0]].dot(mesh.positions[f[1]].cross(mesh.positions[f[2]]));
}

// Applies `plan`, then per component picks the global orientation: outward for
// closed components, fewest flipped faces for the others.
void ApplyOrientation(const MeshTopology& topo, const OrientationPlan& plan, Mesh* mesh,
                      RepairReport* report) {
  const size_t nc = topo.num_components();
  std::vector<double> volume(nc, 0.0);
  std::vector<size_t> faces(nc, 0), flipped(nc, 0), boundary(nc, 0);
  for (uint32_t e = 0; e < topo.num_edges(); ++e)
    if (topo.IsBoundaryEdge(e)) ++boundary[topo.EdgeComponent(e)];
  for (uint32_t f = 0; f < mesh->faces.size(); ++f) {
    Face& t = mesh->faces[f];
    if (plan.flip[f]) std::swap(t[1], t[2]);
    const uint32_t c = topo.FaceComponents()[f];
    ++faces[c];
    flipped[c] += plan.flip[f];
    volume[c] += SignedVolumeTimesSix(*mesh, t);
  }
  std::vector<uint8_t> reverse(nc, 0);
  for (size_t c = 0; c < nc; ++c) {
    if (boundary[c] == 0) {
      reverse[c] = volume[c] < 0.0 ? 1 : 0;
      report->components_turned_outward += reverse[c];
    } else {
      reverse[c] = 2 * flipped[c] > faces[c] ? 1 : 0;
    }
    report->faces_flipped += reverse[c] ? faces[c] - flipped[c] : flipped[c];
  }
  for (uint32_t f = 0; f < mesh->faces.size(); ++f)
    if (reverse[topo.FaceComponents()[f]]) std::swap(mesh->faces[f][1], mesh->faces[f][2]);
}

Status OrientConsistently(Mesh* mesh, RepairReport* report) {
  constexpr int kMaxRounds = 8;
  for (int round = 0; round < kMaxRounds; ++round) {
    const MeshTopology topo(*mesh);
    const OrientationPlan plan = topo.PlanConsistentOrientation();
    if (plan.conflict_edges.empty()) {
      ApplyOrientation(topo, plan, mesh, report);
      return Status::Ok();
    }
    CutConflicts(topo, plan.conflict_edges, round, mesh, report);
    // Cutting can leave pinched vertices behind; they are split as in step 4.
    SplitNonManifoldVertices(mesh, report);
  }
  return InternalError("repair could not orient the mesh consistently after " + std::to_string(kMaxRounds) +
                       " rounds of cutting");
}

// ---------------------------------------------------------------- step 6: compact (mesh.h)

Status CheckRepaired(const Mesh& mesh, double tolerance) {
  DiagnoseOptions options;
  options.degenerate_area_tolerance = tolerance;
  const MeshDiagnosis d = Diagnose(mesh, options);
  if (d.non_manifold_edges || d.non_manifold_vertices || d.inconsistent_edges || d.degenerate_faces)
    return InternalError("repair left " + std::to_string(d.non_manifold_edges) + " non-manifold edges, " +
                         std::to_string(d.non_manifold_vertices) + " non-manifold vertices, " +
                         std::to_string(d.inconsistent_edges) + " inconsistent edges, " +
                         std::to_string(d.degenerate_faces) + " degenerate faces");
  return Status::Ok();
}

}  // namespace

bool RepairReport::Unchanged() const {
  return vertices_welded == 0 && degenerate_faces_removed == 0 && duplicate_faces_removed == 0 &&
         non_manifold_edges_split == 0 && vertices_split == 0 && orientation_cuts == 0 &&
         faces_flipped == 0 && unreferenced_vertices_removed == 0;
}

std::string RepairReport::Summary() const {
  std::ostringstream s;
  s << "welded " << vertices_welded << " vertices (" << welds_refused << " refused), removed "
    << degenerate_faces_removed << " degenerate + " << duplicate_faces_removed << " duplicate faces, split "
    << non_manifold_edges_split << " non-manifold edges (" << faces_detached << " faces detached) and "
    << non_manifold_vertices_split << " non-manifold vertices (" << vertices_split << " vertex copies), "
    << orientation_cuts << " orientation cuts, flipped " << faces_flipped << " faces ("
    << components_turned_outward << " closed components turned outward), dropped "
    << unreferenced_vertices_removed << " unreferenced vertices";
  return s.str();
}

StatusOr<Mesh> RepairForRemeshing(const Mesh& input, RepairReport* report, const RepairOptions& options) {
  RepairReport local;
  RepairReport* r = report ? report : &local;
  *r = RepairReport{};
  EQMESH_RETURN_IF_ERROR(ValidateInput(input));
  Mesh mesh = input;
  WeldDuplicatePositions(&mesh, WeldMode::kBeforeRepair, r);
  DropDegenerateAndDuplicateFaces(&mesh, options.degenerate_area_tolerance, r);
  if (mesh.faces.empty()) return InvalidMesh("no non-degenerate faces left to repair");
  SplitNonManifoldEdges(&mesh, r);
  SplitNonManifoldVertices(&mesh, r);
  EQMESH_RETURN_IF_ERROR(OrientConsistently(&mesh, r));
  r->unreferenced_vertices_removed += DropUnreferencedVertices(&mesh);
  EQMESH_RETURN_IF_ERROR(CheckRepaired(mesh, options.degenerate_area_tolerance));
  return mesh;
}

Mesh WeldSeams(const Mesh& mesh, size_t* vertices_welded) {
  RepairReport report;
  Mesh out = mesh;
  // Invalid input is left to the caller's own checks, which name the fault.
  if (ValidateInput(mesh).ok()) WeldDuplicatePositions(&out, WeldMode::kAlone, &report);
  if (vertices_welded) *vertices_welded = report.vertices_welded;
  return out;
}

}  // namespace eqmesh
