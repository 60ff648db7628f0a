#include "oracles/oracle.hpp"

#include <algorithm>

namespace weft {

OracleField paddedByReach(const OracleField& field, double reach, double minDistance) {
    if (!(reach > 0)) return field;
    const auto shrink = [&](float d) { return float(std::max(minDistance, double(d) - reach)); };
    OracleField out = field;  // the same rings: only the distances they index shrink
    out.constant = shrink(field.constant);
    for (float& d : out.distances) d = shrink(d);
    return out;
}

RingAccessor OracleField::accessor() const {
    static const RingTree kEmpty(kFarRing);
    return RingAccessor(rings ? *rings : kEmpty);
}

OracleRegistry& oracles() {
    static OracleRegistry registry("oracle");
    return registry;
}

}  // namespace weft
