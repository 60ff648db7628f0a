// weft convert IN.raw[.gz] --dims X,Y,Z --type u8|u16|f32 -o OUT.vdb: a
// headerless dense volume becomes a sparse fog-volume .vdb that `weft render`
// reads like any other.
#include <openvdb/io/File.h>
#include <openvdb/tools/Count.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/base/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/volume/raw_volume.hpp"
#include "plugins/host/command.hpp"

namespace weft {

namespace {

struct ConvertOptions {
    std::string input, output;
    std::string dims, type, spacing = "1,1,1", endian = "little", grid = "density";
};

// Every option is checked before the input is read, so a typo costs nothing.
RawVolumeSpec specFrom(const ConvertOptions& o) {
    RawVolumeSpec spec;
    spec.dims = parseRawDims(o.dims);
    spec.type = parseRawType(o.type);
    spec.spacing = parseRawSpacing(o.spacing);
    spec.byteOrder = parseByteOrder(o.endian);
    spec.gridName = o.grid;
    rawByteCount(spec);  // overflow and absurd sizes
    return spec;
}

void checkVdbOutput(const std::string& path) {
    if (std::filesystem::path(path).extension() != ".vdb")
        throw Error("output '" + path + "': must end in .vdb");
    checkOutputPath(path, "output");
}

// Temp name then rename: a failed write leaves any existing file as it was.
void writeVdb(const openvdb::FloatGrid::Ptr& grid, const std::string& path) {
    AtomicOutput out(path);
    openvdb::io::File file(out.tempPath());
    file.write(openvdb::GridPtrVec{grid});
    file.close();
    out.commit();
}

std::string vecText(const openvdb::Vec3d& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%g,%g,%g", v.x(), v.y(), v.z());
    return buf;
}

void printSummary(const ConvertOptions& o, const RawVolumeSpec& spec, const openvdb::FloatGrid& grid, double seconds) {
    const openvdb::Index64 active = grid.activeVoxelCount();
    std::string range = "none";
    if (active > 0) {
        const auto mm = openvdb::tools::minMax(grid.tree());
        char buf[64];
        std::snprintf(buf, sizeof buf, "%g..%g", mm.min(), mm.max());
        range = buf;
    }
    std::printf("%s: %dx%dx%d %s -> %llu active voxels, values %s, voxel size %s, grid '%s' -> %s (%.2f s)\n",
                o.input.c_str(), spec.dims.x(), spec.dims.y(), spec.dims.z(), rawTypeName(spec.type),
                (unsigned long long)active, range.c_str(), vecText(spec.spacing).c_str(), spec.gridName.c_str(),
                o.output.c_str(), seconds);
}

void runConvert(const ConvertOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    const RawVolumeSpec spec = specFrom(o);
    checkVdbOutput(o.output);
    const openvdb::FloatGrid::Ptr grid = readRawVolume(o.input, spec);
    writeVdb(grid, o.output);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    printSummary(o, spec, *grid, seconds);
}

const CommandRegistrar registrar{{"convert", 30, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("convert", "turn a headerless dense volume (.raw, .raw.gz) into a sparse .vdb");
    auto o = std::make_shared<ConvertOptions>();
    cmd->add_option("input", o->input, "raw samples, x fastest then y then z; gzip when the name ends in .gz")->required();
    cmd->add_option("--dims", o->dims, "samples along x,y,z, e.g. 256,256,256")->required();
    cmd->add_option("--type", o->type, "sample type: u8|u16|f32 (values are kept as numbers)")->required();
    cmd->add_option("--spacing", o->spacing, "voxel size sx,sy,sz in world units")->capture_default_str();
    cmd->add_option("--endian", o->endian, "byte order of u16/f32 samples: little|big")->capture_default_str();
    cmd->add_option("--grid", o->grid, "name of the grid in the .vdb")->capture_default_str();
    cmd->add_option("-o,--output", o->output, "output .vdb (written atomically)")->required();
    cmd->callback([o] { runConvert(*o); });
}}};

}  // namespace

}  // namespace weft
