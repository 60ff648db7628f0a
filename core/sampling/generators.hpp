#pragma once
// Point-set generators on the unit torus, registered by name. Each one is a
// small unit in its own file with an option table (validated and documented
// like technique parameters) and a function count, options, seed -> points.
// The registry is filled by explicit calls (core is a static library, so
// self-registering objects there would be dropped by the linker).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/options/params.hpp"
#include "core/base/registry.hpp"
#include "core/sampling/pattern_set.hpp"

namespace weft {

struct PatternGeneratorInfo {
    std::string name;
    std::string summary;
    ParamTable options;
    // count points in [0, 1)^2, a pure function of (count, options, seed).
    std::function<std::vector<Vec2>(int count, const ParamSet& options, std::uint64_t seed)> generate;
};

using PatternGeneratorRegistry = NamedRegistry<PatternGeneratorInfo>;
const PatternGeneratorRegistry& patternGenerators();
// The named generator; an unknown name is an error listing the known ones.
const PatternGeneratorInfo& patternGenerator(const std::string& name);

// count points of the named generator, options given as key=value text.
std::vector<Vec2> generatePoints(const std::string& name, int count, const std::map<std::string, std::string>& options,
                                 std::uint64_t seed);

// One registration function per generator file.
void registerRegularGenerators(PatternGeneratorRegistry& r);  // regular, jittered, random
void registerPoissonGenerator(PatternGeneratorRegistry& r);
void registerPointDiffusionGenerator(PatternGeneratorRegistry& r);
void registerLloydGenerator(PatternGeneratorRegistry& r);
void registerNetGenerators(PatternGeneratorRegistry& r);  // hammersley, lp

// Factor count = cols * rows with cols the divisor closest to sqrt(count), cols >= rows.
std::pair<int, int> gridShape(int count);

// Dart-throwing Poisson-disk points with a minimum toroidal distance of
// relativeRadius times the hexagonal-packing distance for count points.
// useGrid picks the grid-accelerated test (the default) over the plain one
// that checks every accepted point; both accept exactly the same darts.
struct PoissonResult {
    std::vector<Vec2> points;
    double radius = 0;  // the minimum distance actually guaranteed
    std::int64_t darts = 0;
};
PoissonResult poissonDartThrowing(int count, double relativeRadius, std::uint64_t seed, bool useGrid);

// Hexagonal-packing nearest-neighbour distance of count points on the unit torus.
double hexagonalDistance(int count);

// Radical inverses as 32-bit fractions: base 2 (van der Corput) and
// Larcher-Pillichshammer.
std::uint32_t radicalInverse2(std::uint32_t i);
std::uint32_t larcherPillichshammer(std::uint32_t i);
// Nested uniform (Owen) scrambling of a 32-bit fraction, keyed by seed.
std::uint32_t owenScramble(std::uint32_t v, std::uint64_t seed);

}  // namespace weft
