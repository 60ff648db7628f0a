// regular, jittered and random point sets on the unit torus.
//   regular   cell centres of a cols x rows grid (cols * rows = count, as square
//             as count allows): the method of dependent tests when repeated
//   jittered  one uniform point in each cell of the same grid (stratified)
//   random    independent uniform points (white noise, the baseline)
#include "core/base/rng.hpp"
#include "core/sampling/generators.hpp"

namespace weft {

namespace {

std::vector<Vec2> gridPoints(int count, std::uint64_t seed, bool jitter) {
    const auto [cols, rows] = gridShape(count);
    Rng rng(seed);
    std::vector<Vec2> out;
    out.reserve(count);
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < cols; ++i) {
            const double u = jitter ? rng.uniformDouble() : 0.5, v = jitter ? rng.uniformDouble() : 0.5;
            out.push_back({(i + u) / cols, (j + v) / rows});
        }
    return out;
}

std::vector<Vec2> randomPoints(int count, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec2> out(count);
    for (Vec2& p : out) p.x = rng.uniformDouble(), p.y = rng.uniformDouble();
    return out;
}

}  // namespace

void registerRegularGenerators(PatternGeneratorRegistry& r) {
    r.add({"regular", "cell centres of a regular grid (method of dependent tests when repeated)",
           ParamTable("pattern regular", {}),
           [](int count, const ParamSet&, std::uint64_t seed) { return gridPoints(count, seed, false); }});
    r.add({"jittered", "one uniform point in each cell of a regular grid (stratified sampling)",
           ParamTable("pattern jittered", {}),
           [](int count, const ParamSet&, std::uint64_t seed) { return gridPoints(count, seed, true); }});
    r.add({"random", "independent uniform points (white noise)", ParamTable("pattern random", {}),
           [](int count, const ParamSet&, std::uint64_t seed) { return randomPoints(count, seed); }});
}

}  // namespace weft
