// Multi-parallelogram position pass of a compact chunk: see compact_positions.h.
#include "coding/compact_base/compact_positions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <unordered_map>

namespace eqmesh {
namespace {

using Quanta = std::vector<std::array<int32_t, 3>>;
using V3 = std::array<double, 3>;

// How a vertex was predicted: by two or more parallelograms, by one, by the mean of
// its decoded neighbours, or (first vertex of a component) by the previous vertex.
enum PredictionKind : int { kMulti = 0, kSingle = 1, kNeighbours = 2, kSeed = 3, kKinds = 4 };
// Activity buckets: bit length of the neighbours' mean L1 residual, capped.
constexpr int kActivityBuckets = 8;
// Residual classes: an axis of the grid (or of an axis frame), a frame's normal, a
// frame's tangent.
enum ResidualClass : int { kAxis = 0, kNormal = 1, kTangent = 2, kClasses = 3 };
// Largest |residual| either side writes (EncodeResidual's range).
constexpr int64_t kMaxResidual = (int64_t{1} << kCompactMaxPrefix) - 1;

struct PositionModels {
  // One set per (class, kind, neighbours' activity), shared by the components of a
  // class: conditioning the second and third on the first measured no better.
  std::array<CompactResidualModels, kClasses * kKinds * kActivityBuckets> sets;

  CompactResidualModels* Of(int residual_class, int kind, uint64_t activity) {
    int bucket = 0;
    while (activity != 0 && bucket < kActivityBuckets - 1) {
      ++bucket;
      activity >>= 1;
    }
    return &sets[static_cast<size_t>((residual_class * kKinds + kind) * kActivityBuckets + bucket)];
  }
};

// The faces around each vertex and, per directed edge, the corner opposite it; both
// sides build it from the decoded connectivity.
class Neighbourhood {
 public:
  Neighbourhood(uint32_t n, const std::vector<Face>& faces) : faces_(faces), first_(n + 1, 0), l1_(n, 0) {
    for (const Face& f : faces) {
      for (int k = 0; k < 3; ++k) {
        ++first_[f[k] + 1];
        opposite_[Key(f[k], f[(k + 1) % 3])] = f[(k + 2) % 3];
      }
    }
    for (uint32_t v = 0; v < n; ++v) first_[v + 1] += first_[v];
    incident_.resize(first_[n]);
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (uint32_t i = 0; i < faces.size(); ++i) {
      for (int k = 0; k < 3; ++k) incident_[fill[faces[i][k]]++] = i;
    }
  }

  // For each face (v, x, y) around v: neighbour(x) when x < v, and parallelogram(x,
  // y, z) when x, y and the corner z across x->y all precede v.
  template <class Neighbour, class Parallelogram>
  void Visit(uint32_t v, Neighbour&& neighbour, Parallelogram&& parallelogram) const {
    VisitCoded(v, [v](uint32_t x) { return x < v; }, neighbour, parallelogram);
  }

  // The same with `coded(x)` for "x precedes v" (the greedy order below).
  template <class Coded, class Neighbour, class Parallelogram>
  void VisitCoded(uint32_t v, Coded&& coded, Neighbour&& neighbour, Parallelogram&& parallelogram) const {
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
      const Face& f = faces_[incident_[i]];
      const int k = f[0] == v ? 0 : f[1] == v ? 1 : 2;
      const uint32_t x = f[(k + 1) % 3], y = f[(k + 2) % 3];
      if (coded(x)) neighbour(x);
      if (!coded(x) || !coded(y)) continue;
      const auto it = opposite_.find(Key(y, x));
      if (it != opposite_.end() && coded(it->second)) parallelogram(x, y, it->second);
    }
  }

  // Every vertex whose prediction coding v can change: v's neighbours and the
  // corners across the edges of v's faces.
  template <class Touch>
  void ForEachAffected(uint32_t v, Touch&& touch) const {
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
      const Face& f = faces_[incident_[i]];
      for (int k = 0; k < 3; ++k) {
        touch(f[k]);
        const auto it = opposite_.find(Key(f[(k + 1) % 3], f[k]));
        if (it != opposite_.end()) touch(it->second);
      }
    }
  }

  // Kind and activity context of v (call after Visit's counts).
  static int Kind(int parallelograms, int neighbours) {
    return parallelograms >= 2 ? kMulti : parallelograms == 1 ? kSingle : neighbours > 0 ? kNeighbours : kSeed;
  }
  uint64_t L1(uint32_t x) const { return l1_[x]; }
  void Record(uint32_t v, const std::array<int64_t, 3>& q) {
    uint64_t l1 = 0;
    for (const int64_t r : q) l1 += static_cast<uint64_t>(r < 0 ? -r : r);
    l1_[v] = l1;
  }

 private:
  static uint64_t Key(uint32_t a, uint32_t b) { return (uint64_t{a} << 32) | b; }

  const std::vector<Face>& faces_;
  std::vector<uint32_t> first_;                      // CSR offsets of each vertex's faces
  std::vector<uint32_t> incident_;                   // face ids, grouped by vertex
  std::unordered_map<uint64_t, uint32_t> opposite_;  // directed edge a->b -> third corner; looked up only
  std::vector<uint64_t> l1_;                         // L1 norm of each coded vertex's residual
};

// The order the grid-with-choice mode codes positions in (compact_positions.h): next
// the vertex with the most complete parallelograms (up to kOrderParallelogramCap),
// then the most coded neighbours, then the lowest index; both sides derive it from
// the decoded faces.
constexpr int kOrderParallelogramCap = 3;
constexpr int kOrderNeighbourCap = 63;
constexpr uint32_t kNoVertex = 0xffffffffu;

class GreedyOrder {
 public:
  GreedyOrder(const Neighbourhood& hood, uint32_t n) : hood_(hood), coded_(n, 0), key_(n, 0) {
    for (uint32_t v = 0; v < n; ++v) queue_.insert({0, v});
  }

  bool Coded(uint32_t v) const { return coded_[v] != 0; }
  uint32_t Previous() const { return previous_; }  // kNoVertex before the first
  uint32_t Next() const { return queue_.begin()->second; }

  void MarkCoded(uint32_t v) {
    queue_.erase({-key_[v], v});
    coded_[v] = 1;
    previous_ = v;
    hood_.ForEachAffected(v, [&](uint32_t w) {
      if (!coded_[w]) Update(w);
    });
  }

 private:
  void Update(uint32_t w) {
    int parallelograms = 0, neighbours = 0;
    hood_.VisitCoded(
        w, [&](uint32_t x) { return coded_[x] != 0; }, [&](uint32_t) { ++neighbours; },
        [&](uint32_t, uint32_t, uint32_t) { ++parallelograms; });
    const int64_t key = int64_t{std::min(parallelograms, kOrderParallelogramCap)} * (kOrderNeighbourCap + 1) +
                        std::min(neighbours, kOrderNeighbourCap);
    if (key == key_[w]) return;
    queue_.erase({-key_[w], w});
    key_[w] = key;
    queue_.insert({-key, w});
  }

  const Neighbourhood& hood_;
  std::vector<uint8_t> coded_;
  std::vector<int64_t> key_;
  std::set<std::pair<int64_t, uint32_t>> queue_;  // (-key, vertex): the next one first
  uint32_t previous_ = kNoVertex;
};

// ---- Axis grid: integer indices, exact. ----

// sum / count rounded to nearest (halves up), clamped to the grid.
std::array<int32_t, 3> MeanIndex(const CompactGrid& grid, const std::array<int64_t, 3>& sum, int64_t count) {
  std::array<int32_t, 3> p{};
  for (size_t c = 0; c < 3; ++c) {
    const int64_t num = 2 * sum[c] + count, den = 2 * count;
    const int64_t q = num >= 0 ? num / den : -((-num + den - 1) / den);
    p[c] = static_cast<int32_t>(std::clamp<int64_t>(q, 0, grid.MaxIndex()));
  }
  return p;
}

struct GridPrediction {
  std::array<int32_t, 3> value{};
  CompactResidualModels* models = nullptr;
  std::vector<std::array<int32_t, 3>> singles;  // each parallelogram alone, where there are two or more
};

// Models of the parallelogram choice: "a single one?" by the number of
// parallelograms (2, 3, 4+), then the unary steps of its position.
struct ChoiceModels {
  std::array<AdaptiveBit, 3> single;
  std::array<AdaptiveBit, 8> index;

  AdaptiveBit* Single(size_t count) { return &single[std::min<size_t>(count, 4) - 2]; }
  AdaptiveBit* Step(size_t i) { return &index[std::min<size_t>(i, index.size() - 1)]; }
};

// Estimated bits of a residual triple under an Exp-Golomb-like code: what the
// encoder's choice compares.
double EstimatedResidualBits(const std::array<int64_t, 3>& r) {
  double bits = 0.0;
  for (const int64_t x : r) bits += x == 0 ? 1.0 : 2.0 * std::log2(static_cast<double>(x < 0 ? -x : x) + 1.0) + 2.0;
  return bits;
}

// A single parallelogram replaces the mean only where it saves at least this many
// estimated bits beyond log2(count) for its index.
constexpr double kChoiceMarginBits = 2.0;

// The prediction of v: the mean of its parallelograms (with an order, the greedy one,
// also each one alone), else of its neighbours, else the previous vertex.
GridPrediction PredictIndex(const Neighbourhood& hood, const CompactGrid& grid, uint32_t v, const Quanta& quanta,
                            PositionModels* models, const GreedyOrder* order) {
  std::array<int64_t, 3> parallelograms{}, neighbours{};
  std::vector<std::array<int32_t, 3>> singles;
  const bool with_singles = order != nullptr;
  int num_parallelograms = 0, num_neighbours = 0;
  uint64_t activity = 0;
  hood.VisitCoded(
      v, [&](uint32_t x) { return order ? order->Coded(x) : x < v; },
      [&](uint32_t x) {
        for (size_t c = 0; c < 3; ++c) neighbours[c] += quanta[x][c];
        ++num_neighbours;
        activity += hood.L1(x);
      },
      [&](uint32_t x, uint32_t y, uint32_t z) {
        std::array<int64_t, 3> one{};
        for (size_t c = 0; c < 3; ++c) {
          one[c] = int64_t{quanta[x][c]} + quanta[y][c] - quanta[z][c];
          parallelograms[c] += one[c];
        }
        if (with_singles) singles.push_back(MeanIndex(grid, one, 1));
        ++num_parallelograms;
      });
  const int kind = Neighbourhood::Kind(num_parallelograms, num_neighbours);
  GridPrediction p;
  if (num_parallelograms >= 2) p.singles = std::move(singles);
  p.models = models->Of(kAxis, kind, num_neighbours > 0 ? activity / static_cast<uint64_t>(num_neighbours) : 0);
  const uint32_t previous = order ? order->Previous() : (v > 0 ? v - 1 : kNoVertex);
  p.value = kind == kSeed         ? (previous != kNoVertex ? quanta[previous] : SeedPrediction(grid, {}))
            : kind == kNeighbours ? MeanIndex(grid, neighbours, num_neighbours)
                                  : MeanIndex(grid, parallelograms, num_parallelograms);
  return p;
}

// ---- Surface frames: real positions, scalar double arithmetic on both sides. ----

V3 Sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 Cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double Dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 Scaled(const V3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

struct Frame {
  std::array<V3, 3> axes{};      // unit vectors
  std::array<double, 3> steps{};  // quantization step along each
  std::array<int, 3> classes{};
};

struct FramePrediction {
  V3 value{};
  Frame frame;
  int kind = kSeed;
  uint64_t activity = 0;
};

class FrameCoder {
 public:
  FrameCoder(const CompactPositionCoding& coding, uint32_t n, const std::vector<Face>& faces)
      : grid_(coding.grid), hood_(n, faces), positions_(n, V3{0, 0, 0}),
        tangential_step_(static_cast<double>(coding.grid.step) * coding.tangential_quarters / 4.0) {
    const double step = static_cast<double>(grid_.step);
    for (size_t k = 0; k < 3; ++k) {
      lo_[k] = static_cast<double>(grid_.origin[k]);
      hi_[k] = lo_[k] + static_cast<double>(grid_.MaxIndex()) * step;
    }
  }

  FramePrediction Predict(uint32_t v) const {
    V3 parallelograms{0, 0, 0}, neighbours{0, 0, 0}, normal{0, 0, 0};
    int num_parallelograms = 0, num_neighbours = 0;
    uint64_t activity = 0;
    hood_.Visit(
        v,
        [&](uint32_t x) {
          for (size_t c = 0; c < 3; ++c) neighbours[c] += positions_[x][c];
          ++num_neighbours;
          activity += hood_.L1(x);
        },
        [&](uint32_t x, uint32_t y, uint32_t z) {
          const V3& px = positions_[x];
          const V3& py = positions_[y];
          const V3& pz = positions_[z];
          for (size_t c = 0; c < 3; ++c) parallelograms[c] += px[c] + py[c] - pz[c];
          // Face (v, x, y) with v = x + y - z has normal (z - y) x (z - x).
          const V3 nf = Cross(Sub(pz, py), Sub(pz, px));
          for (size_t c = 0; c < 3; ++c) normal[c] += nf[c];
          ++num_parallelograms;
        });
    FramePrediction p;
    p.kind = Neighbourhood::Kind(num_parallelograms, num_neighbours);
    p.activity = num_neighbours > 0 ? activity / static_cast<uint64_t>(num_neighbours) : 0;
    if (p.kind == kMulti || p.kind == kSingle) {
      p.value = Scaled(parallelograms, 1.0 / num_parallelograms);
    } else if (p.kind == kNeighbours) {
      p.value = Scaled(neighbours, 1.0 / num_neighbours);
    } else if (v > 0) {
      p.value = positions_[v - 1];
    } else {
      for (size_t c = 0; c < 3; ++c) p.value[c] = 0.5 * (lo_[c] + hi_[c]);
    }
    p.frame = MakeFrame(normal, p.kind == kMulti || p.kind == kSingle);
    return p;
  }

  // The position the residual q gives, clamped to the grid's box; recorded for later
  // predictions.
  V3 Reconstruct(uint32_t v, const FramePrediction& p, const std::array<int64_t, 3>& q) {
    V3 x = p.value;
    for (size_t k = 0; k < 3; ++k) {
      const double amount = static_cast<double>(q[k]) * p.frame.steps[k];
      for (size_t c = 0; c < 3; ++c) x[c] += amount * p.frame.axes[k][c];
    }
    for (size_t c = 0; c < 3; ++c) x[c] = std::clamp(x[c], lo_[c], hi_[c]);
    positions_[v] = x;
    hood_.Record(v, q);
    return x;
  }

  const std::vector<V3>& positions() const { return positions_; }

 private:
  // A frame on the parallelograms' normal when there is one, else the grid's axes
  // with the grid step on all three.
  Frame MakeFrame(const V3& normal, bool has_normal) const {
    Frame f;
    const double len2 = Dot(normal, normal);
    if (!has_normal || !(len2 > 0) || !std::isfinite(len2)) {
      for (size_t k = 0; k < 3; ++k) {
        f.axes[k] = V3{0, 0, 0};
        f.axes[k][k] = 1.0;
        f.steps[k] = static_cast<double>(grid_.step);
        f.classes[k] = kAxis;
      }
      return f;
    }
    const V3 n = Scaled(normal, 1.0 / std::sqrt(len2));
    // The first tangent is n crossed with the axis least aligned with n (lowest index
    // on ties), so it is never near zero.
    size_t axis = 0;
    for (size_t k = 1; k < 3; ++k) {
      if (std::fabs(n[k]) < std::fabs(n[axis])) axis = k;
    }
    V3 e{0, 0, 0};
    e[axis] = 1.0;
    const V3 c = Cross(n, e);
    const V3 t1 = Scaled(c, 1.0 / std::sqrt(Dot(c, c)));
    f.axes = {n, t1, Cross(n, t1)};
    f.steps = {static_cast<double>(grid_.step), tangential_step_, tangential_step_};
    f.classes = {kNormal, kTangent, kTangent};
    return f;
  }

  const CompactGrid& grid_;
  Neighbourhood hood_;
  std::vector<V3> positions_;
  const double tangential_step_;
  V3 lo_{}, hi_{};
};

Vec3 ToVec3(const V3& a) { return Vec3(a[0], a[1], a[2]); }

// The encoder's parallelogram choice for v (compact_positions.h): codes it and
// returns the prediction it selects.
std::array<int32_t, 3> ChooseParallelogram(RangeEncoder* enc, ChoiceModels* models, const GridPrediction& p,
                                           const std::array<int32_t, 3>& target) {
  const auto bits_from = [&](const std::array<int32_t, 3>& prediction) {
    std::array<int64_t, 3> r{};
    for (size_t c = 0; c < 3; ++c) r[c] = int64_t{target[c]} - prediction[c];
    return EstimatedResidualBits(r);
  };
  const size_t count = p.singles.size();
  const double index_bits = std::log2(static_cast<double>(count));
  double best = bits_from(p.value) - kChoiceMarginBits;
  size_t pick = count;
  for (size_t i = 0; i < count; ++i) {
    const double bits = bits_from(p.singles[i]) + index_bits;
    if (bits < best) {
      best = bits;
      pick = i;
    }
  }
  enc->EncodeBit(models->Single(count), pick < count);
  if (pick == count) return p.value;
  for (size_t i = 0; i + 1 < count; ++i) {
    enc->EncodeBit(models->Step(i), pick > i);
    if (pick == i) break;
  }
  return p.singles[pick];
}

// The decoder's side of ChooseParallelogram (a failed read shows in dec->ok()).
std::array<int32_t, 3> ReadParallelogramChoice(RangeDecoder* dec, ChoiceModels* models, const GridPrediction& p) {
  const size_t count = p.singles.size();
  if (!dec->DecodeBit(models->Single(count))) return p.value;
  size_t pick = 0;
  while (pick + 1 < count && dec->DecodeBit(models->Step(pick))) ++pick;
  return p.singles[pick];
}

std::vector<Vec3> EncodeOnGrid(RangeEncoder* enc, const CompactPositionCoding& coding, const std::vector<Face>& faces,
                               const std::vector<Vec3>& positions) {
  const CompactGrid& grid = coding.grid;
  const uint32_t n = static_cast<uint32_t>(positions.size());
  Quanta quanta(n);
  for (uint32_t v = 0; v < n; ++v) quanta[v] = QuantizeToGrid(grid, positions[v]);
  Neighbourhood hood(n, faces);
  PositionModels models;
  ChoiceModels choices;
  std::optional<GreedyOrder> order;
  if (coding.parallelogram_choice) order.emplace(hood, n);
  std::vector<Vec3> decoded(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t v = order ? order->Next() : i;
    GridPrediction p = PredictIndex(hood, grid, v, quanta, &models, order ? &*order : nullptr);
    if (!p.singles.empty()) p.value = ChooseParallelogram(enc, &choices, p, quanta[v]);
    std::array<int64_t, 3> r{};
    for (size_t c = 0; c < 3; ++c) {
      r[c] = int64_t{quanta[v][c]} - p.value[c];
      EncodeResidual(enc, p.models, r[c]);
    }
    hood.Record(v, r);
    if (order) order->MarkCoded(v);
    decoded[v] = grid.Position(quanta[v]);
  }
  return decoded;
}

bool DecodeOnGrid(RangeDecoder* dec, const CompactPositionCoding& coding, const std::vector<Face>& faces, uint32_t n,
                  std::vector<Vec3>* positions) {
  const CompactGrid& grid = coding.grid;
  Quanta quanta(n, {0, 0, 0});
  Neighbourhood hood(n, faces);
  PositionModels models;
  ChoiceModels choices;
  std::optional<GreedyOrder> order;
  if (coding.parallelogram_choice) order.emplace(hood, n);
  for (uint32_t i = 0; i < n && dec->ok(); ++i) {
    const uint32_t v = order ? order->Next() : i;
    GridPrediction p = PredictIndex(hood, grid, v, quanta, &models, order ? &*order : nullptr);
    if (!p.singles.empty()) p.value = ReadParallelogramChoice(dec, &choices, p);
    std::array<int64_t, 3> r{};
    for (size_t c = 0; c < 3; ++c) {
      r[c] = DecodeResidual(dec, p.models);
      const int64_t value = int64_t{p.value[c]} + r[c];
      if (value < 0 || value > grid.MaxIndex()) return false;
      quanta[v][c] = static_cast<int32_t>(value);
    }
    hood.Record(v, r);
    if (order) order->MarkCoded(v);
  }
  if (!dec->ok()) return false;
  positions->resize(n);
  for (uint32_t v = 0; v < n; ++v) (*positions)[v] = grid.Position(quanta[v]);
  return true;
}

std::vector<Vec3> EncodeInFrames(RangeEncoder* enc, const CompactPositionCoding& coding,
                                 const std::vector<Face>& faces, const std::vector<Vec3>& positions) {
  const uint32_t n = static_cast<uint32_t>(positions.size());
  FrameCoder coder(coding, n, faces);
  PositionModels models;
  std::vector<Vec3> decoded(n);
  for (uint32_t v = 0; v < n; ++v) {
    const FramePrediction p = coder.Predict(v);
    const V3 d = Sub(V3{positions[v][0], positions[v][1], positions[v][2]}, p.value);
    std::array<int64_t, 3> q{};
    for (size_t k = 0; k < 3; ++k) {
      const double t = std::round(Dot(d, p.frame.axes[k]) / p.frame.steps[k]);
      q[k] = static_cast<int64_t>(std::clamp(t, -static_cast<double>(kMaxResidual), static_cast<double>(kMaxResidual)));
      EncodeResidual(enc, models.Of(p.frame.classes[k], p.kind, p.activity), q[k]);
    }
    decoded[v] = ToVec3(coder.Reconstruct(v, p, q));
  }
  return decoded;
}

bool DecodeInFrames(RangeDecoder* dec, const CompactPositionCoding& coding, const std::vector<Face>& faces,
                    uint32_t n, std::vector<Vec3>* positions) {
  FrameCoder coder(coding, n, faces);
  PositionModels models;
  for (uint32_t v = 0; v < n && dec->ok(); ++v) {
    const FramePrediction p = coder.Predict(v);
    std::array<int64_t, 3> q{};
    for (size_t k = 0; k < 3; ++k) q[k] = DecodeResidual(dec, models.Of(p.frame.classes[k], p.kind, p.activity));
    coder.Reconstruct(v, p, q);
  }
  if (!dec->ok()) return false;
  positions->resize(n);
  for (uint32_t v = 0; v < n; ++v) (*positions)[v] = ToVec3(coder.positions()[v]);
  return true;
}

}  // namespace

std::vector<Vec3> EncodeCompactPositions(RangeEncoder* enc, const CompactPositionCoding& coding,
                                         const std::vector<Face>& faces, const std::vector<Vec3>& positions) {
  if (coding.tangential_quarters == kGridTangentialQuarters) return EncodeOnGrid(enc, coding, faces, positions);
  return EncodeInFrames(enc, coding, faces, positions);
}

bool DecodeCompactPositions(RangeDecoder* dec, const CompactPositionCoding& coding, const std::vector<Face>& faces,
                            uint32_t num_vertices, std::vector<Vec3>* positions) {
  if (coding.tangential_quarters == kGridTangentialQuarters) {
    return DecodeOnGrid(dec, coding, faces, num_vertices, positions);
  }
  return DecodeInFrames(dec, coding, faces, num_vertices, positions);
}

}  // namespace eqmesh
