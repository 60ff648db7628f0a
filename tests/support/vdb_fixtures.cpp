#include "tests/support/vdb_fixtures.hpp"

#include <openvdb/io/File.h>

#include "core/volume/volume.hpp"

namespace weft::test {

void writeProceduralVdb(const std::filesystem::path& path, const std::string& kind, int res, const std::string& gridName) {
    auto grid = makeProceduralGrid(kind, res, 1);
    grid->setName(gridName);
    openvdb::io::File file(path.string());
    file.write({grid});
    file.close();
}

void writeSlabVdb(const std::filesystem::path& path, int nxy, int nz, double voxel, const std::vector<std::string>& alsoNamed) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    grid->fill(openvdb::CoordBBox(openvdb::Coord(-nxy / 2, -nxy / 2, 0), openvdb::Coord(nxy / 2 - 1, nxy / 2 - 1, nz - 1)), 1.0f, true);
    grid->tree().voxelizeActiveTiles();
    openvdb::GridPtrVec grids{grid};
    for (const std::string& name : alsoNamed) {
        grids.push_back(grid->deepCopy());
        grids.back()->setName(name);
    }
    openvdb::io::File file(path.string());
    file.write(grids);
    file.close();
}

void writeEmptyVdb(const std::filesystem::path& path) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    openvdb::io::File file(path.string());
    file.write({grid});
    file.close();
}

}  // namespace weft::test
