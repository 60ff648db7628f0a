#include "core/volume/optics/segment_tables.hpp"

#include "core/base/error.hpp"

namespace weft {

SegmentTables::SegmentTables(const TransferFunction& tf, double spacing, int maxSlices, int resolution,
                             PreintPrecision precision, bool withEmission)
    : tf_(tf), spacing_(spacing), resolution_(resolution), precision_(precision), withEmission_(withEmission),
      once_(new tbb::collaborative_once_flag[maxSlices + 1]), tables_(maxSlices + 1) {}

const PreintegrationTable& SegmentTables::forSlices(int slices) {
    if (slices < 1 || slices >= int(tables_.size()))
        throw Error("internal: segment of " + std::to_string(slices) + " slices outside the table range");
    tbb::collaborative_call_once(once_[slices], [&] {
        tables_[slices] = std::make_unique<PreintegrationTable>(tf_, std::vector<double>{spacing_ * slices}, resolution_, precision_, withEmission_);
    });
    return *tables_[slices];
}

std::int64_t SegmentTables::entriesBuilt() const {
    std::int64_t n = 0;
    for (const auto& t : tables_) n += t ? t->entriesBuilt() : 0;
    return n;
}

int SegmentTables::builtCount() const {
    int n = 0;
    for (const auto& t : tables_) n += t != nullptr;
    return n;
}

}  // namespace weft
