#pragma once
// A small, fast, seedable generator (xoshiro256**, Blackman & Vigna 2018) seeded through
// SplitMix64, so that any tuple of integers (seed, case, incidence, block, ...) names one stream.
#include <cstdint>
#include <cstring>
#include <initializer_list>

namespace gonio {

inline std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// The bits of a double, to key a stream by the uniforms a sampler was given (so that a sampler
// needing more randomness than it was given is still a function of its arguments).
inline std::uint64_t bits_of(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

class Rng {
  public:
    // The stream is a pure function of the keys: the same keys give the same numbers anywhere.
    Rng(std::initializer_list<std::uint64_t> keys) {
        std::uint64_t h = 0x6a09e667f3bcc909ull;
        for (std::uint64_t k : keys) {
            h ^= k + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
            std::uint64_t t = h;
            h = splitmix64(t);
        }
        for (auto& s : s_) s = splitmix64(h);
    }
    std::uint64_t next_u64() {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }
    // Uniform double in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

  private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t s_[4];
};

} // namespace gonio
