// Output files that appear whole or not at all.
//
// Every file eqmesh writes goes through WriteFileAtomically: the bytes go to a
// temporary file beside the target, which is renamed over the target only once
// it is complete. A failed or killed run therefore never leaves a half-written
// output, and an existing file is replaced in one step (rename(2) is atomic
// within a directory). No fsync: the guarantee is against our own failures, not
// against power loss, and fsync would cost more than the write on some disks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace eqmesh {

// Writes `size` bytes to `path` atomically (see above). On any error the
// temporary file is removed and `path` is untouched. The new file gets the
// usual 0666 & ~umask permissions.
Status WriteFileAtomically(const std::string& path, const uint8_t* data, size_t size);
Status WriteFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes);

// True when both paths name the same existing file (through links too): the
// tools refuse to write their output over their input.
bool IsSameFile(const std::string& a, const std::string& b);

}  // namespace eqmesh
