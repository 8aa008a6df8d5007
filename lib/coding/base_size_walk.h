// The remeshed representation at other base sizes, for an encode with a target.
//
// The remesher sizes its base by an error bound, holds it to a quality floor and
// tightens it where the finest level folds (remesh.h): a base that carries the
// shape. Coding at a target wants another trade: each base vertex costs 20-30
// bits in the compact chunk, while the levels' details shrink as the base
// follows thin parts more closely; and a base simplified to a vertex count
// (MAPS' own stopping rule) codes better than one whose bound was tightened
// locally. Measured at 70 dB (`encode --psnr 70`): man, 7,667 B from the
// remesher's 380-vertex base, 5,769 B from 380 counted, 5,137 B from 760;
// stanford-bunny 4,519 B from its 121, 3,866 B from 236; horse 2,811 B from
// its 145, no better at 72, 145 or 290 counted.
//
// So the encoder tries remeshes at base sizes counted from the remesher's:
// doubling while each try beats the last, and halving where the first doubling
// does not, each try searched for the target like the first (Guskov et al.
// leave the base size to the user; here the coded stream's size at the target
// chooses it, try by try, as the as-is walk chooses its vertex count).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "coding/encoder.h"
#include "coding/level_count_search.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "remesh/remesh.h"

namespace eqmesh {

// Each try has this factor more (or fewer) base vertices than the last; at most
// kMaxBaseSteps tries each way.
inline constexpr double kBaseStepFactor = 2.0;
inline constexpr int kMaxBaseSteps = 3;
// A try's base keeps at least this many vertices, and at most the input's
// vertices over kMinInputPerBaseVertex (past that the base is the input
// itself, which the as-is representation codes better).
inline constexpr size_t kMinWalkBaseVertices = 8;
inline constexpr size_t kMinInputPerBaseVertex = 4;
// The walk runs on inputs up to this many vertices, where a remesh counted to a
// base size costs seconds and a try a level search: scans up to 50k vertices
// gained (stanford-bunny 11 %, armadillo_50k 18 %; horse nothing, its encode
// 12 -> 45 s). Past it a try costs more than a scan's whole encode did (igea's
// remesh alone takes 9 s, dragon_vrip's 155 s).
inline constexpr size_t kBaseWalkMaxInputVertices = 60'000;

// The options for a try that competes with the best stream so far (`best`,
// encoded as `best_report` says), for the same target: a PSNR target's search
// starts at the best's lambda (near its answer; where quality is monotone in
// lambda the answer does not depend on the start) and gives up once it shows it
// cannot come in under the best (EncodeOptions::outbid_bytes). A rate target's
// search, which takes the first stream within tolerance, starts as asked, as
// does any try while no stream is best. Used by this walk and by the simplified
// as-is walk (representation_choice.h).
EncodeOptions ToBeat(const EncodeOptions& options, const StatusOr<std::vector<uint8_t>>& best,
                     const EncodeReport& best_report);

struct BaseSizeTry {
  size_t base_vertices = 0;
  RemeshReport remesh;  // of a try's remesh (not filled for the first)
  StatusOr<std::vector<uint8_t>> stream = std::vector<uint8_t>();
  EncodeReport report;
  LevelCountReport levels;
};

// Whether `a` replaces `b` for the options' target: with a PSNR target the
// smaller stream (both meet it), with a bpv target the higher PSNR; a failed
// try replaces nothing, and any stream replaces a failed one.
bool BeatsAtTarget(const EncodeOptions& options, const BaseSizeTry& a, const BaseSizeTry& b);

// Whether the walk runs for `options`: a target, and an original of at most
// kBaseWalkMaxInputVertices vertices (the mesh remeshed).
bool BaseWalkApplies(const EncodeOptions& options);

// `first` is the stream of the remesher's own base; tries remeshes of `input`
// (with `remesh`'s options, the base counted) as described above and returns
// the best, `first` where none beats it. `tried` (optional) gets every base size
// tried, in order.
BaseSizeTry WalkBaseSizes(const Mesh& input, const RemeshOptions& remesh, const EncodeOptions& options,
                          BaseSizeTry first, std::vector<size_t>* tried = nullptr);

}  // namespace eqmesh
