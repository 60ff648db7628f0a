#include "oracles/oracle.hpp"

#include <algorithm>

namespace weft {

OracleField paddedByReach(const OracleField& field, double reach, double minDistance) {
    if (!(reach > 0)) return field;
    const auto shrink = [&](float d) { return float(std::max(minDistance, double(d) - reach)); };
    OracleField out;
    out.constant = shrink(field.constant);
    out.shift = field.shift;
    if (!field.distance) return out;
    openvdb::FloatGrid::Ptr grid = field.distance->deepCopy();
    for (auto v = grid->tree().beginValueAll(); v; ++v) v.setValue(shrink(*v));  // voxels and tiles, on or off
    grid->tree().root().setBackground(shrink(grid->background()), /*updateChildNodes=*/false);  // its values were all shrunk above
    out.distance = grid;
    return out;
}

OracleRegistry& oracles() {
    static OracleRegistry registry("oracle");
    return registry;
}

}  // namespace weft
