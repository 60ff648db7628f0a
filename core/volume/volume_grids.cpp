#include "core/volume/volume_grids.hpp"

#include <openvdb/io/File.h>
#include <openvdb/tools/GridTransformer.h>
#include <openvdb/tree/LeafManager.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/base/error.hpp"
#include "core/volume/optics/blackbody.hpp"
#include "core/volume/io/vdb_preflight.hpp"
#include "core/volume/volume.hpp"

namespace weft {

namespace {

// Beyond this a radiator's T^4 would leave float range.
constexpr double kHottestKelvin = 1e7;
constexpr float kMaxEmission = 1e30f;

struct EmissionOf {
    const EmissionSettings& s;
    const BlackbodyTable* blackbody;  // null without a temperature grid

    openvdb::Vec3s operator()(float temperature, float emission) const {
        openvdb::Vec3s e(0.0f);
        if (blackbody && std::isfinite(temperature)) {
            const double kelvin = std::min(double(temperature) * s.temperatureScale + s.temperatureOffset, kHottestKelvin);
            if (kelvin > 0) {
                const double radiance = s.blackbodyIntensity * std::pow(kelvin / 1000.0, 4);
                e += blackbody->color(kelvin) * float(radiance);
            }
        }
        if (std::isfinite(emission) && emission > 0) e += toVec3f(s.color * (double(emission) * s.strength));
        for (int c = 0; c < 3; ++c) e[c] = std::isfinite(e[c]) ? std::clamp(e[c], 0.0f, kMaxEmission) : 0.0f;
        return e;
    }
};

}  // namespace

const std::vector<std::string>& gridRoles() {
    static const std::vector<std::string> roles{"density", "temperature", "emission", "velocity", "color"};
    return roles;
}

const std::vector<std::string>& conventionalGridNames(const std::string& role) {
    static const std::map<std::string, std::vector<std::string>> names{
        {"density", {"density"}}, {"temperature", {"temperature", "heat"}}, {"emission", {"emission", "flame", "flames"}},
        {"velocity", {"velocity", "vel", "v"}}, {"color", {"color", "albedo", "Cd"}}};
    static const std::vector<std::string> none;
    const auto it = names.find(role);
    return it == names.end() ? none : it->second;
}

const std::map<std::string, std::string>& gridRoleAliases() {
    static const std::map<std::string, std::string> aliases{{"albedo", "color"}};
    return aliases;
}

openvdb::FloatGrid::Ptr readRoleGrid(const std::string& path, const std::string& gridName, const std::string& role) {
    return readFloatGrid(path, gridName, role);
}

std::map<std::string, std::string> pickConventionalGrids(const std::string& path, const std::string& densityName) {
    initVdb();
    preflightVdb(path);
    openvdb::io::File file(path);
    try {
        file.open(false);
    } catch (const std::exception&) {
        throw Error("volume '" + path + "': not an OpenVDB file");
    }
    std::map<std::string, std::string> picked;
    if (!densityName.empty()) picked["density"] = densityName;
    for (const std::string& role : gridRoles()) {
        if (picked.count(role)) continue;
        for (const std::string& name : conventionalGridNames(role))
            if (file.hasGrid(name)) {
                picked[role] = name;
                break;
            }
    }
    if (!picked.count("density")) picked["density"] = "";  // readFloatGrid's own choice: the first grid
    return picked;
}

template <class GridT>
typename GridT::Ptr inIndexSpaceOf(typename GridT::Ptr grid, const openvdb::math::Transform& target) {
    if (grid->transform() == target) return grid;
    auto out = GridT::create(grid->background());
    out->setName(grid->getName());
    out->setTransform(target.copy());
    openvdb::tools::resampleToMatch<openvdb::tools::BoxSampler>(*grid, *out);
    return out;
}

openvdb::FloatGrid::Ptr inIndexSpaceOf(openvdb::FloatGrid::Ptr grid, const openvdb::math::Transform& target) {
    return inIndexSpaceOf<openvdb::FloatGrid>(std::move(grid), target);
}

openvdb::Vec3SGrid::Ptr buildEmissionGrid(const openvdb::FloatGrid* temperature, const openvdb::FloatGrid* emission,
                                          const EmissionSettings& settings, const openvdb::math::Transform& transform) {
    auto out = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    out->setName("emission");
    out->setTransform(transform.copy());
    if (temperature) out->tree().topologyUnion(temperature->tree());
    if (emission) out->tree().topologyUnion(emission->tree());
    const EmissionOf of{settings, temperature ? &BlackbodyTable::get() : nullptr};
    const auto valueAt = [&](const openvdb::FloatGrid::ConstAccessor* t, const openvdb::FloatGrid::ConstAccessor* e,
                             const openvdb::Coord& c) { return of(t ? t->getValue(c) : 0.0f, e ? e->getValue(c) : 0.0f); };
    // Voxels, leaf by leaf in parallel (each leaf is written by one thread).
    openvdb::tree::LeafManager<openvdb::Vec3STree> leaves(out->tree());
    leaves.foreach([&](openvdb::Vec3STree::LeafNodeType& leaf, std::size_t) {
        std::optional<openvdb::FloatGrid::ConstAccessor> t, e;
        if (temperature) t.emplace(temperature->getConstAccessor());
        if (emission) e.emplace(emission->getConstAccessor());
        for (auto it = leaf.beginValueAll(); it; ++it)
            it.setValue(it.isValueOn() ? valueAt(t ? &*t : nullptr, e ? &*e : nullptr, it.getCoord()) : openvdb::Vec3s(0.0f));
    });
    // Active tiles: one value each, from their first voxel.
    std::optional<openvdb::FloatGrid::ConstAccessor> t, e;
    if (temperature) t.emplace(temperature->getConstAccessor());
    if (emission) e.emplace(emission->getConstAccessor());
    auto tiles = out->tree().beginValueOn();
    tiles.setMaxDepth(openvdb::Vec3STree::ValueOnIter::LEAF_DEPTH - 1);
    for (; tiles; ++tiles) tiles.setValue(valueAt(t ? &*t : nullptr, e ? &*e : nullptr, tiles.getCoord()));
    return out;
}

openvdb::Vec3SGrid::Ptr buildMotionGrid(openvdb::Vec3SGrid::Ptr velocity, const openvdb::math::Transform& density,
                                        const MotionSettings& settings, double& maxMotion) {
    openvdb::Vec3SGrid::Ptr motion =
        velocity->transform() == density ? velocity->deepCopy() : inIndexSpaceOf<openvdb::Vec3SGrid>(velocity, density);
    motion->setName("motion");
    const auto& map = *density.baseMap();
    const double perFrame = settings.velocityScale / settings.fps;
    maxMotion = 0;
    const auto toMotion = [&](const openvdb::Vec3s& v) {
        const openvdb::Vec3d m = map.applyInverseJacobian(openvdb::Vec3d(v)) * perFrame;
        if (!(std::isfinite(m[0]) && std::isfinite(m[1]) && std::isfinite(m[2]))) return openvdb::Vec3s(0.0f);
        // Capped like the reach: a broken simulation's 1e30 must not carry lookups out of integer range.
        const double length = m.length();
        const openvdb::Vec3s out(length > kMaxMotionReach ? m * (kMaxMotionReach / length) : m);
        maxMotion = std::max(maxMotion, double(out.length()));
        return out;
    };
    // Every stored value (active or not: trilinear lookups read both) and
    // the background, which answers everywhere else.
    for (auto it = motion->tree().beginValueAll(); it; ++it) it.setValue(toMotion(*it));
    motion->tree().root().setBackground(toMotion(velocity->background()), /*updateChildNodes=*/false);
    return motion;
}

namespace {

// A colour value as a tint: each channel clamped to [0, 1]; NaN (a broken
// cache) is 1, the untinted medium.
openvdb::Vec3s tintOf(const openvdb::Vec3s& c) {
    openvdb::Vec3s t;
    for (int i = 0; i < 3; ++i) t[i] = std::isnan(c[i]) ? 1.0f : std::clamp(c[i], 0.0f, 1.0f);
    return t;
}

// The grid's values as tints under its own transform: active values
// clamped, every inactive value and the background 1, so that trilinear
// lookups near the active region's edge blend towards untinted, not black.
template <class GridT, class ToVec3>
openvdb::Vec3SGrid::Ptr tintsOf(const GridT& color, ToVec3 toVec3) {
    auto out = openvdb::Vec3SGrid::create(openvdb::Vec3s(1.0f));
    out->setName(color.getName());
    out->setTransform(color.transform().copy());
    out->tree().topologyUnion(color.tree());
    const auto source = color.getConstAccessor();
    for (auto it = out->tree().beginValueAll(); it; ++it)
        it.setValue(it.isValueOn() ? tintOf(toVec3(source.getValue(it.getCoord()))) : openvdb::Vec3s(1.0f));
    return out;
}

}  // namespace

openvdb::Vec3SGrid::Ptr buildColorGrid(const openvdb::GridBase& color, const openvdb::math::Transform& density) {
    openvdb::Vec3SGrid::Ptr tints;
    if (const auto* rgb = dynamic_cast<const openvdb::Vec3SGrid*>(&color)) tints = tintsOf(*rgb, [](const openvdb::Vec3s& v) { return v; });
    else if (const auto* grey = dynamic_cast<const openvdb::FloatGrid*>(&color)) tints = tintsOf(*grey, [](float v) { return openvdb::Vec3s(v); });
    else throw Error("the color grid '" + color.getName() + "' holds " + color.valueType() + " values; color needs a vec3s or float grid");
    tints = inIndexSpaceOf<openvdb::Vec3SGrid>(tints, density);
    tints->setName("color");
    return tints;
}

double motionReachOf(double maxMotion, double shutterOpen, double shutterClose) {
    const double reach = maxMotion * std::max(std::abs(shutterOpen), std::abs(shutterClose));
    return std::isfinite(reach) ? std::min(reach, kMaxMotionReach) : kMaxMotionReach;
}

}  // namespace weft
