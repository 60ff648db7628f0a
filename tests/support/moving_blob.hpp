#pragma once
// The velocity-blur test scene: a soft blob translating by its velocity
// grid, and the static blob under a camera moving the other way (the same
// relative motion). Each technique family dresses the blob its own way
// (a transfer function, or a medium and a light).
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/volume/volume.hpp"
#include "tests/support/test_support.hpp"

namespace weft::test {

constexpr double kBlobVoxel = 1.0 / 32;
constexpr double kBlobFps = 24;

// A soft Gaussian blob (sigma 4 voxels, peak `peak`) at the origin and a
// velocity grid "vel" of constant `velocity` (world units per second: its
// background, so every lookup sees it). `fill` sets some voxels of the
// velocity grid to it as well (values a simulation stores).
inline void writeBlob(const std::filesystem::path& path, const openvdb::Vec3s& velocity, float peak = 0.5f, bool fill = false) {
    initVdb();
    auto density = openvdb::FloatGrid::create(0.0f);
    density->setName("density");
    density->setTransform(openvdb::math::Transform::createLinearTransform(kBlobVoxel));
    auto acc = density->getAccessor();
    for (int x = -12; x <= 12; ++x)
        for (int y = -12; y <= 12; ++y)
            for (int z = -12; z <= 12; ++z) {
                const double r2 = x * x + y * y + z * z;
                if (r2 <= 144) acc.setValue(openvdb::Coord(x, y, z), float(peak * std::exp(-r2 / 32.0)));
            }
    auto vel = openvdb::Vec3SGrid::create(velocity);
    vel->setName("vel");
    vel->setTransform(density->transform().copy());
    if (fill) vel->denseFill(openvdb::CoordBBox(openvdb::Coord(-4), openvdb::Coord(4)), velocity, true);
    openvdb::io::File file(path.string());
    file.write({density, vel});
    file.close();
}

// How the blob looks: keys added to its volume object, and to the scene.
struct BlobLook {
    std::string volume;  // e.g. "\"transfer_function\": {...}"
    std::string scene;   // e.g. "\"lights\": [...]"; "" for none
};

// Emission-absorption: a warm transfer function.
inline BlobLook transferFunctionLook() {
    return {R"("transfer_function": {"range": [0, 1], "points": [{"s": 0, "color": [1, 0.8, 0.6], "extinction": 0},
                                                                  {"s": 1, "color": [1, 0.8, 0.6], "extinction": 0.3}]})",
            ""};
}

// Scattering: a grey medium under a directional light from above.
inline BlobLook scatteringLook() {
    return {R"("medium": {"absorb": [0.05, 0.05, 0.05], "scatter": [0.4, 0.3, 0.2]})",
            R"("lights": [{"type": "directional", "direction": [0.2, -1, -0.4], "intensity": 4}])"};
}

inline std::string sceneKeys(const BlobLook& look) { return look.scene.empty() ? "" : ", " + look.scene; }

// The blob with its velocity, camera fixed, shutter [0, 1] (one-sided, so
// that motion one way and the other do not give the same picture).
inline std::string movingBlobScene(const TempDir& dir, const BlobLook& look, const std::string& shutter = "[0, 1]",
                                   const std::string& extra = "", int fov = 16) {
    writeText(dir / "moving.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": )" + std::to_string(fov) +
                                       R"(, "shutter": )" + shutter +
                                       R"(}, "volumes": [{"file": "blob.vdb", "grids": {"velocity": "vel"}, "motion": {"fps": 24})" + extra +
                                       ", " + look.volume + "}]" + sceneKeys(look) + "}");
    return (dir / "moving.json").string();
}

// The static blob and a camera keyed at frames -1 and 1 moving by
// -velocity / fps per frame (frame 0 rendered): the same relative motion.
inline std::string movingCameraBlobScene(const TempDir& dir, const BlobLook& look, double velocityX) {
    const double d = velocityX / kBlobFps;
    const std::string a = std::to_string(d), b = std::to_string(-d);
    writeText(dir / "camera.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 16, "shutter": [0, 1], "keys": [
                                         {"frame": -1, "eye": [)" + a + R"(, 0, 3], "target": [)" + a + R"(, 0, 0]},
                                         {"frame": 1, "eye": [)" + b + R"(, 0, 3], "target": [)" + b + R"(, 0, 0]}]},
                                       "volumes": [{"file": "blob.vdb", )" + look.volume + "}]" + sceneKeys(look) + "}");
    return (dir / "camera.json").string();
}

}  // namespace weft::test
