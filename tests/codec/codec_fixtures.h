// Synthetic semi-regular meshes for the codec tests (no shared data needed).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "coding/encoder.h"
#include "mesh/semi_regular.h"

namespace eqmesh::testing {

// Icosahedron base refined `levels` times, every vertex on a bumpy sphere
// r = 1 + 0.1 sin(3x) cos(2y) (so details are non-zero and mostly normal).
SemiRegularMesh MakeBumpySphere(int levels);

// The same with a small tetrahedron in kept_exactly.
SemiRegularMesh MakeBumpySphereWithKept(int levels);

// The bumpy sphere with the edges of its first base face tagged as creases (a
// closed chain of three: the stream carries a crease chunk).
SemiRegularMesh MakeBumpySphereWithCreases(int levels);

// The options of the golden stream (tests/codec/data/README.md).
EncodeOptions GoldenOptions();
std::string GoldenPath();

// A mesh coded as is: no levels, its base a bumpy icosphere refined three times
// (642 vertices), so the base chunk takes the positions-after layout with surface
// frames; the as-is golden stream encodes it with GoldenOptions().
SemiRegularMesh MakeAsIsSphere();
std::string AsIsGoldenPath();

std::vector<uint8_t> ReadBytes(const std::string& path);
void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes);

double MaxVertexError(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

// Decodes `bytes` with every max_level from 0 to one past the finest and expects
// the vertex and face counts of that level of `mesh` (kept_exactly included).
void ExpectEachMaxLevelGivesItsCounts(const std::vector<uint8_t>& bytes, const SemiRegularMesh& mesh);

}  // namespace eqmesh::testing

namespace eqmesh::testing {
// max over a of the distance to the nearest point of b (brute force, small sets):
// the decoder numbers vertices in the base chunk's order, so tests compare sets.
double MaxNearestDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b);
// Bounding-box diagonal of a point set.
double Diagonal(const std::vector<Vec3>& points);
}  // namespace eqmesh::testing
