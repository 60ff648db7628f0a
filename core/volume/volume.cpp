#include "core/volume/volume.hpp"

#include <openvdb/io/File.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/tree/LeafManager.h>
#include <openvdb/tools/Count.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/volume/grid/topology_dilation.hpp"
#include "core/volume/io/vdb_leaf_reader.hpp"
#include "core/volume/io/vdb_preflight.hpp"

namespace weft {

double Volume::voxelLength() const {
    const Vec3d v = grid->transform().voxelSize();
    return std::cbrt(v.x() * v.y() * v.z());
}

openvdb::FloatGrid::ConstPtr placeGrid(const openvdb::FloatGrid::ConstPtr& grid, const openvdb::math::Mat4d& objectToWorld) {
    // A shallow copy (the tree is shared, read-only); only its transform is new.
    openvdb::FloatGrid::Ptr placed = openvdb::ConstPtrCast<openvdb::FloatGrid>(grid->copy());
    openvdb::math::Transform::Ptr xf = grid->transform().copy();
    xf->postMult(objectToWorld);
    placed->setTransform(xf);
    return placed;
}

openvdb::FloatGrid::ConstPtr indexSpaceGrid(const openvdb::FloatGrid& grid) {
    openvdb::FloatGrid::Ptr copy = openvdb::ConstPtrCast<openvdb::FloatGrid>(grid.copy());
    copy->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
    return copy;
}

openvdb::FloatGrid::ConstPtr occupancyIndexGrid(const Volume& volume, openvdb::FloatGrid::Ptr visible) {
    if (!volume.emission && !volume.motion) return visible ? visible : indexSpaceGrid(*volume.grid);
    openvdb::FloatGrid::Ptr both = visible ? visible : volume.grid->deepCopy();
    if (volume.emission) both->tree().topologyUnion(volume.emission->tree());
    if (volume.motion && volume.motionReach > 0)  // one 26-neighbour dilation per voxel reached (Chebyshev <= Euclidean)
        dilateTopology(both->tree(), int(std::ceil(volume.motionReach)), openvdb::tools::NN_FACE_EDGE_VERTEX,
                       openvdb::tools::EXPAND_TILES);
    both->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
    return both;
}

openvdb::CoordBBox Volume::indexBox() const {
    openvdb::CoordBBox box = activeBox;
    if (box.empty()) return box;  // expanding the empty box would overflow
    box.expand(1);
    return box;
}

BBoxd worldBoxOf(const openvdb::math::Transform& xf, const Vec3d& lo, const Vec3d& hi) {
    BBoxd box;
    for (int corner = 0; corner < 8; ++corner)
        box.expand(xf.indexToWorld(Vec3d((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(), (corner & 4) ? hi.z() : lo.z())));
    return box;
}

BBoxd Volume::worldBox() const {
    if (empty()) return BBoxd();  // an empty box: nothing to frame or to hit
    const openvdb::CoordBBox ib = indexBox();
    return worldBoxOf(grid->transform(), ib.min().asVec3d() - Vec3d(0.5), ib.max().asVec3d() + Vec3d(0.5));
}

namespace {

// Reads every leaf buffer of a grid opened with delayed loading, in
// parallel (each reads its own bytes of the mapped file: vdb_leaf_reader.hpp),
// instead of one seek and read system call after another as OpenVDB's plain
// read does.
void loadLeavesInParallel(const openvdb::GridBase::Ptr& base, const std::string& path, const VdbLayout* file, const std::string& name) {
    // OpenVDB shows an unnamed grid as "[0]" (a second "density" as
    // "density[1]"); the file and the walk hold its unique name, the name
    // and a separator byte before the number.
    const std::string stored = openvdb::io::GridDescriptor::stringAsUniqueName(name);
    const VdbGridLayout* layout = nullptr;
    if (file)
        if (const auto it = file->grids.find(stored); it != file->grids.end()) layout = &it->second;
    // A leaf that fails to decode is left as it was (vdb_leaf_reader.cpp
    // decodes into a leaf of its own), so the grid is destroyed safely.
    loadLeaves(base, path, file, layout);
}

// The grid `gridName` of a .vdb whose value type `accepts` takes;
// gridName empty: "density" if present, else the first grid. `needs` words
// the type error ("float grids", "a float grid").
openvdb::GridBase::Ptr readGridOf(const std::string& path, const std::string& gridName, const std::string& role, const std::string& needs,
                                  bool (*accepts)(const openvdb::GridBase&)) {
    initVdb();
    requireRegularFile(path, "volume");
    const std::shared_ptr<const VdbLayout> layout = preflightVdb(path);  // lengths and counts OpenVDB would trust
    openvdb::io::File file(path);
    file.setCopyMaxBytes(0);  // map the file itself, no private copy in the temp folder: it is read whole below
    try {
        file.open(true);  // delayed loading: leaves are read from the mapped file, in parallel below
    } catch (const std::exception&) {  // OpenVDB's own text can hold raw bytes of the file
        throw Error("volume '" + path + "': not an OpenVDB file");
    }
    std::string names, chosen;
    for (auto it = file.beginName(); it != file.endName(); ++it) {
        names += (names.empty() ? "" : ", ") + it.gridName();
        if (gridName.empty() && (chosen.empty() || it.gridName() == "density")) chosen = it.gridName();
    }
    if (!gridName.empty()) chosen = gridName;
    const std::string what = (role.empty() ? "grid '" : "the " + role + " grid '") + chosen + "'";
    if (chosen.empty() || !file.hasGrid(chosen))
        throw Error("volume '" + path + "': no grid named '" + chosen + "'" + (role.empty() ? "" : " for " + role) +
                    " (grids: " + (names.empty() ? "none" : names) + ")");
    // The type and transform come first: the preflight walks only float
    // and vec3s trees of linear transforms, so no other tree is handed to OpenVDB.
    openvdb::GridBase::Ptr header;
    try {
        header = file.readGridMetadata(chosen);
    } catch (const std::exception&) {
        throw Error("volume '" + path + "': " + what + " cannot be read: the file is corrupt or cut short");
    }
    if (!accepts(*header))
        throw Error("volume '" + path + "': " + what + " holds " + header->valueType() + " values; " +
                    (role.empty() ? "weft renders " + needs : role + " needs " + needs));
    if (!role.empty() && header->getGridClass() == openvdb::GRID_LEVEL_SET)
        throw Error("volume '" + path + "': " + what + " is a level set; " + role + " needs a fog volume (convert it with vdb_tool or OpenVDB's sdfToFogVolume)");
    if (!header->transform().isLinear()) throw Error("volume '" + path + "': " + what + " has a non-linear (frustum) transform, which weft does not support");
    openvdb::GridBase::Ptr base;
    try {
        base = file.readGrid(chosen);
        loadLeavesInParallel(base, path, layout.get(), chosen);
    } catch (const Error& e) {  // the leaf reader's own reason
        throw Error("volume '" + path + "': " + what + " cannot be read: " + e.what() + " (the file is corrupt)");
    } catch (const std::bad_alloc&) {
        throw Error("volume '" + path + "': " + what + " does not fit in memory (or its header is corrupt)");
    } catch (const std::exception&) {
        throw Error("volume '" + path + "': " + what + " cannot be read: the file is corrupt or cut short");
    }
    if (!base || !accepts(*base)) throw Error("volume '" + path + "': " + what + " cannot be read: the file is corrupt");
    return base;
}

template <class GridT>
bool isA(const openvdb::GridBase& grid) {
    return grid.isType<GridT>();
}

bool isColor(const openvdb::GridBase& grid) { return isA<openvdb::FloatGrid>(grid) || isA<openvdb::Vec3SGrid>(grid); }

}  // namespace

openvdb::FloatGrid::Ptr readFloatGrid(const std::string& path, const std::string& gridName, const std::string& role) {
    return openvdb::gridPtrCast<openvdb::FloatGrid>(
        readGridOf(path, gridName, role, role.empty() ? "float grids" : "a float grid", &isA<openvdb::FloatGrid>));
}

openvdb::Vec3SGrid::Ptr readVec3Grid(const std::string& path, const std::string& gridName, const std::string& role) {
    return openvdb::gridPtrCast<openvdb::Vec3SGrid>(readGridOf(path, gridName, role, "a vec3s grid", &isA<openvdb::Vec3SGrid>));
}

openvdb::GridBase::Ptr readFloatOrVec3Grid(const std::string& path, const std::string& gridName, const std::string& role) {
    return readGridOf(path, gridName, role, "a vec3s or float grid", &isColor);
}

void computeStatistics(Volume& volume) {
    volume.activeBox = volume.grid->evalActiveVoxelBoundingBox();
    if (volume.emission) volume.activeBox.expand(volume.emission->evalActiveVoxelBoundingBox());  // an empty box expands to the other
    if (volume.grid->activeVoxelCount() == 0 && volume.grid->tree().activeTileCount() == 0) {
        volume.valueMin = volume.valueMax = volume.grid->background();
        return;
    }
    const auto range = openvdb::tools::minMax(volume.grid->tree());
    volume.valueMin = range.min();
    volume.valueMax = range.max();
    if (std::isfinite(volume.valueMin) && std::isfinite(volume.valueMax)) return;
    // NaN or Inf voxels (a broken simulation) must not make the range useless.
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (auto it = volume.grid->cbeginValueOn(); it; ++it)
        if (std::isfinite(*it)) lo = std::min(lo, *it), hi = std::max(hi, *it);
    volume.valueMin = lo <= hi ? lo : 0.0f;
    volume.valueMax = lo <= hi ? hi : 0.0f;
}

}  // namespace weft
