#include "core/sampling/generators.hpp"

#include <cmath>

#include "core/base/error.hpp"

namespace weft {

const PatternGeneratorRegistry& patternGenerators() {
    static const PatternGeneratorRegistry registry = [] {
        PatternGeneratorRegistry r("pattern");
        registerRegularGenerators(r);
        registerPoissonGenerator(r);
        registerPointDiffusionGenerator(r);
        registerLloydGenerator(r);
        registerNetGenerators(r);
        return r;
    }();
    return registry;
}

const PatternGeneratorInfo& patternGenerator(const std::string& name) {
    if (!patternGenerators().has(name))
        throw Error("unknown pattern '" + name + "' (known: " + patternGenerators().names() + ", interleaved:NxM)");
    return patternGenerators().get(name);
}

std::vector<Vec2> generatePoints(const std::string& name, int count, const std::map<std::string, std::string>& options,
                                 std::uint64_t seed) {
    const PatternGeneratorInfo& info = patternGenerator(name);
    if (count < 1) throw Error("pattern '" + name + "': the point count must be at least 1");
    const ParamSet parsed = info.options.parse(options);
    return info.generate(count, parsed, seed);
}

std::pair<int, int> gridShape(int count) {
    int rows = int(std::sqrt(double(count)));
    while (rows > 1 && count % rows != 0) --rows;
    return {count / rows, rows};
}

double hexagonalDistance(int count) { return std::sqrt(2.0 / (std::sqrt(3.0) * count)); }

}  // namespace weft
