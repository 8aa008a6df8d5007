// Level-count search over truncated streams (see level_count_search.h).
#include "coding/level_count_search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "coding/decoder.h"
#include "coding/stream_psnr.h"

namespace eqmesh {
namespace {

// Samples per direction when ranking level counts: enough to order candidates
// whose PSNR differs by tenths of a dB (the meter's seed spread at 1M samples is
// below 0.01 dB), a quarter of the default's cost. The chosen stream is measured
// again at the default count when the caller asked for --measure.
constexpr uint64_t kRankingSamples = 250'000;

// PSNR of the uncoded mesh truncated to `levels`: no stream of that many levels
// can do better, so a PSNR target above it need not be searched at all.
StatusOr<double> CeilingPsnr(const SemiRegularMesh& mesh, int levels, const Mesh& original,
                             uint64_t samples = kRankingSamples, const PreparedOriginal* prepared = nullptr) {
  return MeasureMeshPsnr(ExtractLevel(mesh, levels), original, samples, prepared);
}

// Coding only adds error to the truncated geometry; this margin covers the
// meter's sampling spread (about 0.01 dB at kRankingSamples).
constexpr double kCeilingMarginDb = 0.05;

// A ceiling only decides whether a level count is searched, so it is first
// read at kGlanceSamples, and again at the ranking count only where that
// reading lies within kGlanceMarginDb of the target: most lie several dB off
// (the coarse counts of every walk try), and a glance costs a fifth. Readings of
// mushroom's truncated remesh over five seeds spread by 0.11 and 0.21 dB at 50k
// samples (67.7 and 78.2 dB), 0.09 and 0.12 dB at 250k.
constexpr uint64_t kGlanceSamples = 50'000;
constexpr double kGlanceMarginDb = 1.0;

// The ceiling of `levels` as far as a PSNR target's scan needs it (see above);
// at the ranking count where `exact` (its reading is reported) or where the
// caller fixed the count (EncodeOptions::psnr_samples).
StatusOr<double> CeilingForTarget(const SemiRegularMesh& mesh, int levels, const EncodeOptions& options,
                                  bool exact) {
  const PreparedOriginal* prepared = options.prepared_original.get();
  if (!exact && options.psnr_samples == 0) {
    EQMESH_ASSIGN_OR_RETURN(const double glance,
                            CeilingPsnr(mesh, levels, *options.original, kGlanceSamples, prepared));
    if (std::abs(glance - options.target_psnr) > kGlanceMarginDb) return glance;
  }
  return CeilingPsnr(mesh, levels, *options.original, MeasureSamples(options, kRankingSamples), prepared);
}

constexpr char kOutOfReach[] = "is out of reach: ";

Status TargetOutOfReach(double target, double best, const std::string& what) {
  char text[160];
  std::snprintf(text, sizeof(text), "PSNR target %.2f dB %s%s measures %.2f dB", target, kOutOfReach,
                what.c_str(), best);
  return Status(StatusCode::kTargetOutOfReach, text);
}

struct Candidate {
  std::vector<uint8_t> bytes;
  EncodeReport report;
  // A rate target's candidate whose PSNR was read at kGlanceSamples: enough to
  // rank it against counts more than kGlanceMarginDb away (most are several dB
  // apart: horse at 4 bpv 51.7 / 60.8 / 70.3 / 79.2 / 84.5 / 85.9 dB for 1-6
  // levels), read again at the ranking count (Settle) where one is nearer and
  // before it is kept.
  bool glanced = false;
};

// `c`'s PSNR at the ranking count, where it was glanced.
Status Settle(Candidate* c, const EncodeOptions& options) {
  if (!c->glanced) return Status::Ok();
  EQMESH_ASSIGN_OR_RETURN(c->report.psnr_db, MeasureEncodedPsnr(c->bytes, options, kRankingSamples));
  c->glanced = false;
  return Status::Ok();
}

// Whether two candidates' readings, glanced or not, can be compared as they are.
bool FarApart(const Candidate& a, const Candidate& b) {
  return std::abs(a.report.psnr_db - b.report.psnr_db) > kGlanceMarginDb;
}

// `start_lambda` > 0 starts a PSNR target's lambda search there.
StatusOr<Candidate> EncodeTruncated(const SemiRegularMesh& mesh, int levels, const EncodeOptions& options,
                                    double start_lambda = 0) {
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh truncated, TruncateLevels(mesh, levels));
  EncodeOptions o = options;
  o.measure_psnr = false;
  if (start_lambda > 0) o.lambda = start_lambda;
  Candidate c;
  EQMESH_ASSIGN_OR_RETURN(c.bytes, Encode(truncated, o, &c.report));
  if (!c.report.psnr_measured) {
    c.glanced = options.psnr_samples == 0;
    EQMESH_ASSIGN_OR_RETURN(c.report.psnr_db,
                            MeasureEncodedPsnr(c.bytes, options, c.glanced ? kGlanceSamples : kRankingSamples));
    c.report.psnr_measured = true;
  }
  return c;
}

// Better for a bpv target: higher PSNR; a stream that also stays smaller wins ties.
bool BetterAtRate(const Candidate& a, const Candidate& b) {
  if (a.report.psnr_db != b.report.psnr_db) return a.report.psnr_db > b.report.psnr_db;
  return a.bytes.size() < b.bytes.size();
}

// Settles `c` and the candidates it is compared with (the previous count's and
// the best so far, either may be null) where glanced readings lie too close to
// decide between them.
Status SettleNear(Candidate* c, Candidate* previous, Candidate* best, const EncodeOptions& options) {
  const bool near_previous = previous != nullptr && !FarApart(*c, *previous);
  const bool near_best = best != nullptr && !FarApart(*c, *best);
  if (!near_previous && !near_best) return Status::Ok();
  EQMESH_RETURN_IF_ERROR(Settle(c, options));
  if (near_previous) EQMESH_RETURN_IF_ERROR(Settle(previous, options));
  if (near_best && previous != nullptr && best->glanced && best->bytes == previous->bytes && !previous->glanced) {
    best->report.psnr_db = previous->report.psnr_db;  // the same candidate, settled above
    best->glanced = false;
  }
  if (near_best) EQMESH_RETURN_IF_ERROR(Settle(best, options));
  return Status::Ok();
}

// Scans K = 1, 2, ... and stops at the first level count that does worse than the
// previous one (`worse(next, previous)`); returns the best of those tried.
template <typename Better, typename Worse>
StatusOr<Candidate> ScanLevels(const SemiRegularMesh& mesh, const EncodeOptions& options, Better better,
                               Worse worse, LevelCountReport* out) {
  const int top = mesh.hierarchy.levels();
  Candidate best, previous;
  bool have_best = false, have_previous = false;
  bool some_ceiling_reaches = false;
  bool outbid = false;
  for (int k = top > 0 ? 1 : 0; k <= top; ++k) {
    ReportProgress(options.progress, "levels " + std::to_string(k) + "/" + std::to_string(top),
                   static_cast<double>(k) / static_cast<double>(top + 1));
    if (options.target_psnr > 0 && (k < top || !some_ceiling_reaches)) {
      // A level count whose uncoded geometry misses the target cannot meet it:
      // one measurement instead of a whole lambda search (such hopeless searches at
      // the coarse counts would take most of a PSNR-target encode's time).
      // When every coarser count missed, the whole remesh is measured too: a
      // target above it fails at once instead of after a futile search.
      EQMESH_ASSIGN_OR_RETURN(const double ceiling, CeilingForTarget(mesh, k, options, k == top));
      if (ceiling + kCeilingMarginDb < options.target_psnr) {
        out->trials.push_back({k, 0.0, ceiling, 0, false, false});
        if (k == top) return TargetOutOfReach(options.target_psnr, ceiling, kUncodedCeiling);
        continue;
      }
      some_ceiling_reaches = true;
    }
    // A PSNR target's lambda at one more level is near the last one's: starting
    // there saves most of the bracketing. (The search's answer does not depend on
    // where it starts where quality is monotone in lambda; a rate target's, which
    // takes the first stream within tolerance, would, so it starts as asked.)
    const double start = options.target_psnr > 0 && have_previous ? previous.report.lambda : 0.0;
    StatusOr<Candidate> coded = EncodeTruncated(mesh, k, options, start);
    if (!coded.ok() && coded.status().code() == StatusCode::kOutbid) {
      // No stream of this count beats the bound (EncodeOptions::outbid_bytes).
      // Past a count that does, this one is the larger and the scan stops, as
      // its rule says; before one, the next count may still beat it.
      out->trials.push_back({k, 0.0, 0.0, 0, false, true});
      outbid = true;
      if (have_best && best.bytes.size() < options.outbid_bytes) break;
      continue;
    }
    EQMESH_ASSIGN_OR_RETURN(Candidate c, std::move(coded));
    EQMESH_RETURN_IF_ERROR(SettleNear(&c, have_previous ? &previous : nullptr, have_best ? &best : nullptr, options));
    const bool feasible = options.target_psnr <= 0 || c.report.psnr_db >= options.target_psnr;
    out->trials.push_back({k, c.report.bpv, c.report.psnr_db, c.bytes.size(), feasible});
    const bool stop = have_previous && worse(c, previous);
    if (feasible && (!have_best || better(c, best))) {
      best = c;
      have_best = true;
      out->chosen_levels = k;
    }
    if (stop && have_best) break;
    previous = std::move(c);
    have_previous = true;
  }
  if (!have_best && outbid) return Status(StatusCode::kOutbid, "no level count beats the stream it competes with");
  if (!have_best) {
    double closest = 0.0;
    for (const LevelCountTrial& t : out->trials) closest = std::max(closest, t.psnr_db);
    return TargetOutOfReach(options.target_psnr, closest, "the best stream");
  }
  if (best.glanced) {
    EQMESH_RETURN_IF_ERROR(Settle(&best, options));
    for (LevelCountTrial& t : out->trials) {
      if (t.levels == out->chosen_levels && t.coded) t.psnr_db = best.report.psnr_db;
    }
  }
  return best;
}

// Smallest stream meeting the PSNR target; a level count that needs more bytes
// than the previous one (both meeting it) ends the scan. The candidates are
// compared as their searches measured them, and only the kept one is measured
// again at the meter's default count (EncodeOptions::verify_target), which
// saves a default-count measurement per level count. Should the kept stream
// miss the target there, the scan is run again verifying every candidate, as
// the search within one level count does, so the answer is the one a fully
// verified scan gives.
StatusOr<Candidate> ScanLevelsForQuality(const SemiRegularMesh& mesh, const EncodeOptions& options,
                                         LevelCountReport* out) {
  auto better = [](const Candidate& a, const Candidate& b) { return a.bytes.size() < b.bytes.size(); };
  auto worse = [&](const Candidate& next, const Candidate& prev) {
    return prev.report.psnr_db >= options.target_psnr && next.bytes.size() > prev.bytes.size();
  };
  EncodeOptions unverified = options;
  unverified.verify_target = false;
  EQMESH_ASSIGN_OR_RETURN(Candidate chosen, ScanLevels(mesh, unverified, better, worse, out));
  EQMESH_ASSIGN_OR_RETURN(const double verified, MeasureEncodedPsnr(chosen.bytes, options, 0));
  if (verified >= options.target_psnr) {
    chosen.report.psnr_db = verified;
    for (LevelCountTrial& t : out->trials) {
      if (t.levels == out->chosen_levels && t.coded) t.psnr_db = verified;
    }
    return chosen;
  }
  *out = LevelCountReport();
  return ScanLevels(mesh, options, better, worse, out);
}

}  // namespace

std::string OutOfReachReached(const Status& status) {
  const std::string& m = status.message();
  const size_t at = status.code() == StatusCode::kTargetOutOfReach ? m.find(kOutOfReach) : std::string::npos;
  return at == std::string::npos ? m : m.substr(at + sizeof(kOutOfReach) - 1);
}

StatusOr<double> RemeshCeilingPsnr(const SemiRegularMesh& mesh, const Mesh& original) {
  return CeilingPsnr(mesh, mesh.hierarchy.levels(), original);
}

StatusOr<SemiRegularMesh> TruncateLevels(const SemiRegularMesh& mesh, int levels) {
  const SemiRegularHierarchy& h = mesh.hierarchy;
  if (levels < 0 || levels > h.levels()) {
    return InvalidArgument("cannot truncate a " + std::to_string(h.levels()) + "-level mesh to " +
                           std::to_string(levels) + " levels");
  }
  SemiRegularMesh out;
  EQMESH_ASSIGN_OR_RETURN(out.hierarchy, SemiRegularHierarchy::Build(h.NumVertices(0), h.BaseFaces(), levels));
  EQMESH_RETURN_IF_ERROR(out.hierarchy.SetBaseCreases(h.BaseCreases()));
  const size_t n = h.NumVertices(levels);
  if (mesh.positions.size() < n) return InvalidArgument("semi-regular mesh has too few positions");
  out.positions.assign(mesh.positions.begin(), mesh.positions.begin() + static_cast<std::ptrdiff_t>(n));
  if (mesh.kinds.size() >= n) {
    out.kinds.assign(mesh.kinds.begin(), mesh.kinds.begin() + static_cast<std::ptrdiff_t>(n));
  }
  out.kept_exactly = mesh.kept_exactly;
  return out;
}

StatusOr<std::vector<uint8_t>> EncodeChoosingLevels(const SemiRegularMesh& mesh, const EncodeOptions& requested,
                                                    EncodeReport* report, LevelCountReport* levels) {
  const EncodeOptions options = WithPreparedOriginal(requested);
  LevelCountReport local;
  LevelCountReport& out = levels ? *levels : local;
  out = LevelCountReport();
  const bool targeted = options.target_bpv > 0 || options.target_psnr > 0;
  if (!targeted || options.original == nullptr) {
    out.chosen_levels = mesh.hierarchy.levels();
    return Encode(mesh, options, report);
  }
  Candidate chosen;
  if (options.target_psnr > 0) {
    EQMESH_ASSIGN_OR_RETURN(chosen, ScanLevelsForQuality(mesh, options, &out));
  } else {
    auto worse = [](const Candidate& next, const Candidate& prev) {
      return next.report.psnr_db < prev.report.psnr_db;
    };
    EQMESH_ASSIGN_OR_RETURN(chosen, ScanLevels(mesh, options, BetterAtRate, worse, &out));
  }
  if (options.measure_psnr && options.target_psnr <= 0) {  // a PSNR target's choice is measured so already
    EQMESH_ASSIGN_OR_RETURN(chosen.report.psnr_db, MeasureEncodedPsnr(chosen.bytes, options, 0));
  }
  if (report) *report = chosen.report;
  return std::move(chosen.bytes);
}

}  // namespace eqmesh
