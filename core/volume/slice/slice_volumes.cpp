#include "core/volume/slice/slice_volumes.hpp"

namespace weft {

const Counter kEmissionTables{"preintegration.emission_tables", "pre-integration tables that hold emission weights (emitting scenes only)"};

namespace {

bool sameTransferFunction(const TransferFunction& a, const TransferFunction& b) {
    if (a.rangeMin() != b.rangeMin() || a.rangeMax() != b.rangeMax() || a.points().size() != b.points().size()) return false;
    for (std::size_t i = 0; i < a.points().size(); ++i) {
        const TfPoint &p = a.points()[i], &q = b.points()[i];
        if (p.s != q.s || p.color != q.color || p.extinction != q.extinction) return false;
    }
    return true;
}

}  // namespace

std::vector<SliceVolume> makeSliceVolumes(const std::vector<Volume>& volumes) {
    std::vector<SliceVolume> out(volumes.size());
    const auto& ref = volumes.front().grid->transform();
    for (std::size_t k = 0; k < volumes.size(); ++k) {
        SliceVolume& v = out[k];
        v.volume = &volumes[k];
        v.tables = int(k);
        if (k == 0) continue;
        v.reference = false;
        const auto& own = volumes[k].grid->transform();
        auto map = [&](const Vec3d& p) { return own.worldToIndex(ref.indexToWorld(p)); };
        v.origin = map(Vec3d(0, 0, 0));
        for (int a = 0; a < 3; ++a) v.axis[a] = map(Vec3d(a == 0, a == 1, a == 2)) - v.origin;
        v.lengthScale = volumes.front().voxelLength() / volumes[k].voxelLength();
        for (std::size_t j = 0; j < k; ++j)
            if (out[j].lengthScale == v.lengthScale && sameTransferFunction(volumes[j].tf, volumes[k].tf)) {
                v.tables = out[j].tables;
                break;
            }
    }
    return out;
}

SliceTables::SliceTables(const std::vector<SliceVolume>& volumes, double spacing, int maxSlices, int resolution,
                         PreintPrecision precision)
    : sets_(volumes.size()) {
    std::vector<bool> emits(volumes.size(), false);  // a set shared by an emitting volume holds emission weights
    for (const SliceVolume& v : volumes) emits[v.tables] = emits[v.tables] || v.volume->emission != nullptr;
    for (const SliceVolume& v : volumes)
        if (!sets_[v.tables])
            sets_[v.tables] = std::make_unique<SegmentTables>(v.volume->tf, spacing * v.lengthScale, maxSlices, resolution, precision,
                                                              emits[v.tables]);
}

bool sceneEmits(const std::vector<SliceVolume>& volumes) {
    for (const SliceVolume& v : volumes)
        if (v.volume->emission) return true;
    return false;
}

int SliceTables::builtCount() const {
    int n = 0;
    for (const auto& s : sets_) n += s ? s->builtCount() : 0;
    return n;
}

std::int64_t SliceTables::entriesBuilt() const {
    std::int64_t n = 0;
    for (const auto& s : sets_) n += s ? s->entriesBuilt() : 0;
    return n;
}

int SliceTables::emissionBuiltCount() const {
    int n = 0;
    for (const auto& s : sets_) n += s && s->withEmission() ? s->builtCount() : 0;
    return n;
}

}  // namespace weft
