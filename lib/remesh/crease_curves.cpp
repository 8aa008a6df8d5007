// Crease chains of the input and the crease point of a remesh edge along one;
// see crease_curves.h for the papers and the departures.
#include "remesh/crease_curves.h"

#include <algorithm>
#include <cmath>

#include "mesh/mesh_topology.h"

namespace eqmesh {
namespace {

// No sharp edge left to walk.
constexpr uint32_t kNoEdge = std::numeric_limits<uint32_t>::max();

struct SharpEdge {
  uint32_t a, b, face;
};

// Manifold edges (two consistently used faces) whose face normals turn by more
// than the bound; degenerate faces (no normal) make no crease.
std::vector<SharpEdge> SharpEdges(const Mesh& mesh, double min_turn_degrees) {
  const MeshTopology topology(mesh);
  const std::vector<Vec3> normals = FaceCrossProducts(mesh);
  const double max_cos = std::cos(min_turn_degrees * 3.14159265358979323846 / 180.0);
  std::vector<SharpEdge> sharp;
  for (uint32_t e = 0; e < topology.num_edges(); ++e) {
    if (topology.EdgeFaceCount(e) != 2 || topology.IsInconsistentEdge(e)) continue;
    const IndexRange h = topology.EdgeHalfedges(e);
    const uint32_t f0 = MeshTopology::HalfedgeFace(h[0]), f1 = MeshTopology::HalfedgeFace(h[1]);
    const double n0 = normals[f0].norm(), n1 = normals[f1].norm();
    if (!(n0 > 0.0) || !(n1 > 0.0)) continue;
    if (normals[f0].dot(normals[f1]) / (n0 * n1) < max_cos) {
      sharp.push_back({topology.EdgeVertices(e)[0], topology.EdgeVertices(e)[1], f0});
    }
  }
  return sharp;
}

}  // namespace

CreaseCurves::CreaseCurves(const Mesh& mesh, double min_turn_degrees) {
  const std::vector<SharpEdge> sharp = SharpEdges(mesh, min_turn_degrees);
  const size_t nv = mesh.positions.size();
  // Sharp edges around each vertex (CSR), and which of them are walked.
  std::vector<uint32_t> offsets(nv + 1, 0), items(2 * sharp.size());
  for (const SharpEdge& s : sharp) {
    ++offsets[s.a + 1];
    ++offsets[s.b + 1];
  }
  for (size_t v = 0; v < nv; ++v) offsets[v + 1] += offsets[v];
  std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (uint32_t i = 0; i < sharp.size(); ++i) {
    items[fill[sharp[i].a]++] = i;
    items[fill[sharp[i].b]++] = i;
  }
  const auto degree = [&](uint32_t v) { return offsets[v + 1] - offsets[v]; };
  std::vector<uint8_t> walked(sharp.size(), 0);
  // Walks from v along sharp edge `first` until a vertex of degree other than
  // two (or v again, for a loop).
  const auto walk = [&](uint32_t v, uint32_t first) {
    CreaseChain chain;
    chain.vertices.push_back(v);
    chain.arc.push_back(0.0);
    uint32_t at = v, edge = first;
    while (edge != kNoEdge && !walked[edge]) {
      walked[edge] = 1;
      const uint32_t next = sharp[edge].a == at ? sharp[edge].b : sharp[edge].a;
      chain.arc.push_back(chain.arc.back() + (mesh.positions[next] - mesh.positions[at]).norm());
      chain.vertices.push_back(next);
      chain.faces.push_back(sharp[edge].face);
      at = next;
      edge = kNoEdge;
      if (degree(at) != 2 || at == v) break;
      for (uint32_t n = offsets[at]; n < offsets[at + 1]; ++n) {
        if (!walked[items[n]]) edge = items[n];
      }
    }
    chain.closed = chain.vertices.back() == v && chain.vertices.size() > 2;
    if (chain.Length() > 0.0) chains_.push_back(std::move(chain));
  };
  for (uint32_t v = 0; v < nv; ++v) {
    if (degree(v) == 2) continue;
    for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) {
      if (!walked[items[n]]) walk(v, items[n]);
    }
  }
  for (uint32_t i = 0; i < sharp.size(); ++i) {
    if (!walked[i]) walk(sharp[i].a, i);
  }
  site_offsets_.assign(nv + 1, 0);
  for (const CreaseChain& c : chains_) {
    for (size_t i = 0; i + (c.closed ? 1 : 0) < c.vertices.size(); ++i) ++site_offsets_[c.vertices[i] + 1];
  }
  for (size_t v = 0; v < nv; ++v) site_offsets_[v + 1] += site_offsets_[v];
  sites_.resize(site_offsets_.back());
  std::vector<uint32_t> at(site_offsets_.begin(), site_offsets_.end() - 1);
  for (uint32_t c = 0; c < chains_.size(); ++c) {
    const CreaseChain& chain = chains_[c];
    for (size_t i = 0; i + (chain.closed ? 1 : 0) < chain.vertices.size(); ++i) {
      sites_[at[chain.vertices[i]]++] = {c, chain.arc[i]};
    }
  }
}

std::vector<CreaseSite> CreaseCurves::SitesOf(uint32_t v) const {
  if (v + 1 >= site_offsets_.size()) return {};
  return std::vector<CreaseSite>(sites_.begin() + site_offsets_[v], sites_.begin() + site_offsets_[v + 1]);
}

std::vector<CreaseSite> CreaseCurves::SitesOfPlace(const CreasePlace& p) const {
  if (p.input_vertex != kNoInputVertex) return SitesOf(p.input_vertex);
  if (p.site.chain != kNoCreaseChain) return {p.site};
  return {};
}

std::optional<CreaseSite> CreaseCurves::SplitSite(const CreasePlace& a, const Vec3& pa, const CreasePlace& b,
                                                  const Vec3& pb) const {
  if (chains_.empty()) return std::nullopt;
  const std::vector<CreaseSite> sa = SitesOfPlace(a);
  if (sa.empty()) return std::nullopt;
  const std::vector<CreaseSite> sb = SitesOfPlace(b);
  const double chord = (pa - pb).norm();
  std::optional<CreaseSite> best;
  double best_gap = kMaxArcToChord * chord;
  for (const CreaseSite& x : sa) {
    for (const CreaseSite& y : sb) {
      if (x.chain != y.chain) continue;
      const CreaseChain& c = chains_[x.chain];
      double from = x.arc, gap = y.arc - x.arc;
      if (c.closed) {
        // The shorter way round a loop.
        const double length = c.Length();
        if (gap > 0.5 * length) gap -= length;
        if (gap < -0.5 * length) gap += length;
      }
      if (!(std::abs(gap) > 0.0) || std::abs(gap) > best_gap) continue;
      best_gap = std::abs(gap);
      double mid = from + 0.5 * gap;
      if (c.closed && mid < 0.0) mid += c.Length();
      if (c.closed && mid >= c.Length()) mid -= c.Length();
      best = CreaseSite{x.chain, mid};
    }
  }
  return best;
}

Vec3 CreaseCurves::PositionAt(const CreaseSite& site, const Mesh& mesh, uint32_t* on_face) const {
  const CreaseChain& c = chains_[site.chain];
  const size_t i = std::min<size_t>(
      std::upper_bound(c.arc.begin(), c.arc.end(), site.arc) - c.arc.begin(), c.arc.size() - 1);
  const size_t s = i == 0 ? 0 : i - 1;  // segment (s, s+1) holds the site
  const double span = c.arc[s + 1] - c.arc[s];
  const double w = span > 0.0 ? std::clamp((site.arc - c.arc[s]) / span, 0.0, 1.0) : 0.0;
  *on_face = c.faces[s];
  return (1.0 - w) * mesh.positions[c.vertices[s]] + w * mesh.positions[c.vertices[s + 1]];
}

}  // namespace eqmesh
