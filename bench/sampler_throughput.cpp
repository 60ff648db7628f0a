// Trilinear samples per second on one thread: OpenVDB's GridSampler with
// BoxSampler (what every volume technique used) against weft's LeafSampler
// (core/volume/leaf_sampler.hpp), side by side on the same rays: parallel
// rays along z through the grid's active box, a sample every half voxel.
// Prints both rates, their ratio and whether every sample was identical.
//
//   build/bin/weft_sampler_throughput [FILE.vdb [GRID]]   (default data/smoke_small.vdb)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/volume/leaf_sampler.hpp"
#include "core/volume/volume.hpp"

namespace {

struct Pass {
    double seconds = 0, sum = 0;
    std::int64_t samples = 0;
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a of every sample's bits
};

template <class Sampler>
Pass march(Sampler& sampler, const openvdb::CoordBBox& box) {
    Pass p;
    const auto t0 = std::chrono::steady_clock::now();
    for (int x = box.min().x(); x <= box.max().x(); x += 2)
        for (int y = box.min().y(); y <= box.max().y(); y += 2)
            for (double z = box.min().z() - 1.0; z <= box.max().z() + 1.0; z += 0.5) {
                const float v = sampler.isSample(openvdb::Vec3d(x + 0.37, y + 0.61, z));
                std::uint32_t bits;
                std::memcpy(&bits, &v, 4);
                p.hash = (p.hash ^ bits) * 1099511628211ull;
                p.sum += v;
                ++p.samples;
            }
    p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return p;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string path = argc > 1 ? argv[1] : std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
    const auto grid = weft::readFloatGrid(path, argc > 2 ? argv[2] : "");
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    const auto acc = grid->getConstAccessor();
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler> box_sampler(acc, grid->transform());
    weft::LeafSampler leaf_sampler(acc, grid->transform());
    march(leaf_sampler, box);  // warm caches for both
    Pass box_pass, leaf_pass;
    for (int round = 0; round < 3; ++round) {  // best of three each, interleaved: the same machine load
        const Pass b = march(box_sampler, box), l = march(leaf_sampler, box);
        if (round == 0 || b.seconds < box_pass.seconds) box_pass = b;
        if (round == 0 || l.seconds < leaf_pass.seconds) leaf_pass = l;
    }
    std::printf("trilinear samples, one thread, %s (%lld samples per pass)\n", path.c_str(), (long long)box_pass.samples);
    std::printf("  OpenVDB GridSampler<BoxSampler>  %7.1f M/s\n", box_pass.samples / box_pass.seconds / 1e6);
    std::printf("  weft LeafSampler                 %7.1f M/s   %.2fx\n", leaf_pass.samples / leaf_pass.seconds / 1e6,
                box_pass.seconds / leaf_pass.seconds);
    std::printf("  samples identical: %s\n", box_pass.hash == leaf_pass.hash ? "yes" : "NO");
    return box_pass.hash == leaf_pass.hash ? 0 : 1;
}
