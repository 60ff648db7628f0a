// hammersley and lp: (0,m,2)-nets in base 2 when count = 2^m.
//   hammersley  (i / N, radical inverse of i in base 2)
//   lp          (i / N, Larcher-Pillichshammer radical inverse of i)
// Randomisation (scramble=): xor applies a seeded random digital shift to
// both coordinates, owen a seeded nested uniform scramble; both keep the net
// property (every elementary interval of area 1/N holds exactly one point).
// hammersley defaults to none (the classical deterministic set), lp to xor.
#include "core/base/rng.hpp"
#include "core/sampling/generators.hpp"

namespace weft {

std::uint32_t radicalInverse2(std::uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    return ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
}

// Output bit j (1/2^(j+1) place) is the XOR of input bits j, j+1, ... : the
// generator matrix of ones on and above the diagonal.
std::uint32_t larcherPillichshammer(std::uint32_t i) {
    std::uint32_t out = 0, column = 1u << 31;
    for (; i; i >>= 1, column |= column >> 1)
        if (i & 1u) out ^= column;
    return out;
}

// Each bit is flipped by a random bit chosen by the bits above it, so
// equal prefixes share their flips and elementary intervals map to
// elementary intervals.
std::uint32_t owenScramble(std::uint32_t v, std::uint64_t seed) {
    std::uint32_t out = v;
    for (int b = 31; b >= 0; --b) {
        const std::uint64_t prefix = b == 31 ? 0 : (std::uint64_t(v) >> (b + 1)) | (1ull << (31 - b));
        out ^= std::uint32_t(mix64(seed ^ mix64(prefix)) >> 63) << b;
    }
    return out;
}

namespace {

enum class Scramble { None, Xor, Owen };

Scramble scrambleFrom(const std::string& s) { return s == "xor" ? Scramble::Xor : s == "owen" ? Scramble::Owen : Scramble::None; }

std::uint32_t randomise(std::uint32_t v, Scramble s, std::uint64_t key) {
    if (s == Scramble::Xor) return v ^ std::uint32_t(mix64(key) >> 32);
    if (s == Scramble::Owen) return owenScramble(v, key);
    return v;
}

template <class Inverse>
std::vector<Vec2> net(int count, Scramble s, std::uint64_t seed, Inverse inverse) {
    const std::uint64_t keyX = hashCombine(seed, 1), keyY = hashCombine(seed, 2);
    std::vector<Vec2> out(count);
    for (int i = 0; i < count; ++i) {
        const auto x = std::uint32_t((std::uint64_t(i) << 32) / std::uint64_t(count));
        out[i].x = randomise(x, s, keyX) * 0x1p-32;
        out[i].y = randomise(inverse(std::uint32_t(i)), s, keyY) * 0x1p-32;
    }
    return out;
}

ParamSpec scrambleParam(const char* def) {
    return enumParam("scramble", def, {"none", "xor", "owen"},
                     "randomisation that keeps the net property: random digital shift (xor) or nested uniform (owen)");
}

}  // namespace

void registerNetGenerators(PatternGeneratorRegistry& r) {
    r.add({"hammersley", "(i/N, base-2 radical inverse of i): a (0,m,2)-net for N = 2^m",
           ParamTable("pattern hammersley", {scrambleParam("none")}),
           [](int count, const ParamSet& o, std::uint64_t seed) {
               return net(count, scrambleFrom(o.getString("scramble")), seed, radicalInverse2);
           }});
    r.add({"lp", "Larcher-Pillichshammer (0,m,2)-net, scrambled (random digital shift by default)",
           ParamTable("pattern lp", {scrambleParam("xor")}),
           [](int count, const ParamSet& o, std::uint64_t seed) {
               return net(count, scrambleFrom(o.getString("scramble")), seed, larcherPillichshammer);
           }});
}

}  // namespace weft
