#pragma once
// Fuzz target: .vdb files as `weft render smoke.vdb` reads them
// (core/volume/volume.cpp): the grid read, its statistics, the default
// transfer function and the framing camera.
#include "core/scene/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

inline Outcome vdbFile(const std::uint8_t* data, std::size_t size) {
    const std::string path = writeScratch("volume.vdb", asText(data, size));
    return guarded([&] {
        const Scene scene = loadScene(path);
        require(scene.volumes.size() == 1, "a bare .vdb gives one volume");
        const Volume& v = scene.volumes.front();
        require(!(v.valueMin > v.valueMax), "value range ordered");
    });
}

}  // namespace weft::fuzz
