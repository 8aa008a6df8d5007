// SampleRng: the fixed-seed generator behind every sampled measurement.
//
// SplitMix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014; constants as in Vigna's public-domain reference).
// We implement it ourselves and convert to doubles ourselves because the
// std:: distributions are allowed to differ between standard libraries, and a
// PSNR must not change with the compiler. Streams for parallel blocks come from
// hashing (seed, stream, block), so results do not depend on thread count.
#pragma once

#include <cstdint>

namespace eqmesh {

class SampleRng {
 public:
  explicit SampleRng(uint64_t seed) : state_(seed) {}

  // Independent generator for one (seed, stream, block) triple.
  static SampleRng ForBlock(uint64_t seed, uint64_t stream, uint64_t block) {
    SampleRng mix(seed ^ (0x9e3779b97f4a7c15ULL * (stream + 1)));
    const uint64_t a = mix.Next();
    SampleRng mix2(a ^ (0xd1b54a32d192ed03ULL * (block + 1)));
    return SampleRng(mix2.Next());
  }

  uint64_t Next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  // Uniform in [0, 1): the top 53 bits, exactly representable.
  double NextDouble() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

}  // namespace eqmesh
