// Which representation a mesh travels in: the remeshed normal mesh, or the input
// itself coded as is (a stream with no refinement levels whose base is the input,
// in the compact chunk's surface frames, compact_positions.h), or the input
// simplified (kSimplifyShare) and coded as is.
//
// The normal-mesh codec wins where the input is dense next to its shape (scans,
// sculpts: a few bits per input vertex reach 70 dB, the seed paper's regime). On a
// low-poly asset (a few thousand vertices, creases, thin parts) the semi-regular
// form needs more vertices than the artist's mesh to reach the same error, and no
// coder of its coefficients can then beat a good coder of the input itself. The
// encoder measures both where the second can win and keeps the better: for a PSNR
// target the smaller stream that meets it, for a rate target the higher PSNR,
// without a target the smaller at the remeshed stream's quality.
// Departure from the seed: the seed codes every input as a normal mesh.
// Departure from Garland & Heckbert's use of their simplification (a target
// vertex count or error): here the vertex count is chosen by the coded stream's
// own size at the target, measured try by try.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "coding/encoder.h"
#include "coding/level_count_search.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"
#include "remesh/remesh.h"

namespace eqmesh {

// An as-is stream costs its connectivity (2-3 bits per vertex, measured exactly by
// a traversal) plus its positions, which need this many bits per vertex for any
// useful quality (2 per coordinate, about 50 dB on a low-poly asset): a remeshed
// stream that leaves less than that beside the connectivity is not compared.
inline constexpr double kAsIsMinPositionBits = 6.0;

// The input as a semi-regular mesh with no levels (base = input).
StatusOr<SemiRegularMesh> AsIsMesh(const Mesh& input, bool repair);

// The as-is representation is also tried at fewer vertices, at the quality the
// choice asks of it (a PSNR target, the remeshed stream's PSNR, or the as-is
// stream's own at the caller's lambda; for a bpv target at the same rate)
// (remesh/quadric_simplification.h): each try keeps this share of the last
// one's vertices, while each beats the last (at most kMaxSimplifySteps times);
// where the first does not, the share's square root is tried instead. A
// low-poly asset at 70 dB often has more vertices than its error needs (femur,
// 3,897 vertices: 6,635 B as is, 4,336 B at 55 % of them).
inline constexpr double kSimplifyShare = 0.8;
inline constexpr int kMaxSimplifySteps = 6;

// Whether `bytes` leave room for an as-is stream of `as_is` (AsIsMesh): its
// connectivity, measured by a traversal (about 3 bits per vertex where the compact
// chunk cannot hold it), plus kAsIsMinPositionBits per vertex.
bool AsIsFitsIn(const SemiRegularMesh& as_is, size_t bytes);

struct RepresentationReport {
  bool tried_as_is = false;
  bool as_is = false;            // the stream returned codes the input as is
  size_t remeshed_bytes = 0;     // 0 when that stream failed
  double remeshed_psnr_db = 0;
  bool nothing_remeshed = false;  // every component too small: no normal mesh exists
  size_t as_is_bytes = 0;        // 0 when not tried or failed
  double as_is_psnr_db = 0;
  size_t as_is_vertices = 0;     // of that stream: fewer than the input's when simplified
  // Base vertices of the normal-mesh stream compared (another than the remesh
  // given's where the base-size walk found a better one), and the sizes it tried.
  size_t remeshed_base_vertices = 0;
  std::vector<size_t> base_sizes_tried;
  std::optional<RemeshReport> walked_remesh;  // the remesh of that other base
};

struct RepresentationOptions {
  // Whether the input may travel as is: false where the caller asked for a normal
  // mesh of a given shape (levels, base size) or needs one (an atlas).
  bool allow_as_is = false;
  bool repair = false;  // RemeshOptions::repair for the as-is mesh
  // Without a target: a remeshed stream measuring below this PSNR (a .glb's
  // --min-psnr; 0: none) gives way to an as-is stream of higher PSNR at the same
  // lambda, whatever its size.
  double floor_db = 0;
  // The options the remesh given came from, where its base size is the
  // encoder's to choose: with a target, other base sizes are tried
  // (base_size_walk.h). Null: the remesh given is the normal mesh coded.
  const RemeshOptions* remesh = nullptr;
};

// EncodeChoosingLevels(remeshed) (with representation.remesh and a target, the
// best of the base-size walk from it, base_size_walk.h) and, where allowed and
// options.original is set, the input coded as is, where remeshed's own stream's
// bytes leave room for the connectivity and kAsIsMinPositionBits per vertex, or
// it falls short of its target, or nothing was remeshed (then the input as is is
// the only stream); returns the better. With a PSNR target the smaller meeting
// it, with a bpv target the higher PSNR (both: the input as is or simplified,
// whichever of those is best by the same rule). Without a target the remeshed
// stream is measured (if the encode did not): below floor_db the higher PSNR at
// the lambda; above it the as-is stream at the lambda where neither larger nor
// worse, else the as-is stream searched for the remeshed stream's PSNR where no
// larger.
StatusOr<std::vector<uint8_t>> EncodeChoosingRepresentation(const SemiRegularMesh& remeshed,
                                                            const EncodeOptions& options,
                                                            const RepresentationOptions& representation,
                                                            EncodeReport* report, LevelCountReport* levels,
                                                            RepresentationReport* choice);

}  // namespace eqmesh
