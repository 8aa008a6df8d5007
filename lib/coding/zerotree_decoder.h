// Decoder half of coder 1 (zerotree) in the .eqm container.
//
// The level data of a zerotree stream is ONE embedded payload (zerotree_coder.h)
// holding the coefficients of all J refinements, interleaved by bit plane: it
// travels as level chunk 0, and level chunks 1 .. J-1 are empty (ext_spec A.4).
// Any prefix of the payload that holds its header decodes, to every level, at a
// coarser quality; a shorter one decodes the base only.
//
// Decoding level K < J still decodes the whole payload's coefficients (the planes
// interleave the levels, so it cannot stop early) against the level-J hierarchy,
// then synthesises K refinements, each with the local frames of the decoder's own
// level-j geometry, exactly like the EQ decoder.
#pragma once

#include <cstddef>
#include <cstdint>

#include "coding/decoder.h"
#include "coding/stream_header.h"
#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// Levels a zerotree stream of `size` bytes (a prefix when < s.total_size) can
// give, at most `requested` (0..J).
int ZerotreeLevelsAvailable(const StreamInfo& s, const uint8_t* data, size_t size, int requested);

// Runs the refinements 0 .. levels-1 on *mesh (hierarchy built to level 0 or
// further, refined here to `levels` once the payload header agrees with the
// container's; positions = the decoded level-0 values); size may be a prefix.
Status DecodeZerotreeLevels(const uint8_t* data, size_t size, const StreamInfo& s, const StreamHeader& h,
                            int levels, SemiRegularMesh* mesh);

}  // namespace eqmesh
