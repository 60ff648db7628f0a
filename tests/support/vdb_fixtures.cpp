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

void writeEmptyVdb(const std::filesystem::path& path) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    openvdb::io::File file(path.string());
    file.write({grid});
    file.close();
}

}  // namespace weft::test
