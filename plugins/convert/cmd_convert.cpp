// weft convert IN -o OUT.vdb: a dense volume becomes a sparse float .vdb
// that `weft render` reads like any other. IN is a headerless raw file
// (.raw, .raw.gz: --dims and --type describe it) or a file that describes
// itself: NRRD (.nrrd, .nhdr), NumPy (.npy) or VTK legacy image data (.vtk).
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Count.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/volume/io/raw_samples.hpp"
#include "core/volume/io/volume_import.hpp"
#include "plugins/host/command.hpp"

namespace weft {

namespace {

const char* const kConvertHelp =
    "turn a dense volume into a sparse .vdb: headerless raw (.raw, .raw.gz, with --dims and --type), "
    "NRRD (.nrrd, .nhdr; raw or gzip), NumPy (.npy) or VTK legacy STRUCTURED_POINTS (.vtk)";

struct ConvertCommand {
    std::string input, output;
    ImportOptions options;
};

void checkVdbOutput(const std::string& path) {
    if (std::filesystem::path(path).extension() != ".vdb")
        throw Error("output '" + path + "': must end in .vdb");
    checkOutputPath(path, "output");
}

// Temp name then rename: a failed write leaves any existing file as it was.
// Written through a stream of our own, whose every write and close is
// checked (io::File checks only its open: a full disk left a truncated file).
void writeVdb(const openvdb::FloatGrid::Ptr& grid, const std::string& path) {
    AtomicOutput out(path);
    std::ofstream os(out.tempPath(), std::ios::binary);
    if (!os) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    errno = 0;
    try {
        openvdb::io::Stream(os).write(openvdb::GridPtrVec{grid});
    } catch (const std::exception& e) {
        throw Error("cannot write '" + path + "': " + (errno ? std::strerror(errno) : e.what()));
    }
    os.close();
    if (!os) throw Error("cannot write '" + path + "': " + (errno ? std::strerror(errno) : "write failed"));
    out.commit();
}

std::string vecText(const openvdb::Vec3d& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%g,%g,%g", v.x(), v.y(), v.z());
    return buf;
}

// Where the volume sits, when it is not the default (origin 0, axis-aligned, background 0).
std::string placementText(const RawVolumeSpec& spec) {
    std::string text;
    if (spec.origin != openvdb::Vec3d(0.0)) text += ", origin " + vecText(spec.origin);
    if (!spec.direction.eq(openvdb::Mat3d::identity(), 0.0)) text += ", rotated or sheared axes";
    if (spec.background != 0.0) {
        char buf[48];
        std::snprintf(buf, sizeof buf, ", background %g", spec.background);
        text += buf;
    }
    return text;
}

void printSummary(const ConvertCommand& c, const VolumeImport& im, const openvdb::FloatGrid& grid, double seconds) {
    const openvdb::Index64 active = grid.activeVoxelCount();
    std::string range = "none";
    if (active > 0) {
        const auto mm = openvdb::tools::minMax(grid.tree());
        char buf[64];
        std::snprintf(buf, sizeof buf, "%g..%g", mm.min(), mm.max());
        range = buf;
    }
    const RawVolumeSpec& spec = im.spec;
    std::printf("%s: %s %dx%dx%d %s -> %llu active voxels, values %s, voxel size %s%s, grid '%s' -> %s (%.2f s)\n",
                c.input.c_str(), im.format.c_str(), spec.dims.x(), spec.dims.y(), spec.dims.z(), rawTypeName(spec.type),
                (unsigned long long)active, range.c_str(), vecText(spec.spacing).c_str(), placementText(spec).c_str(),
                spec.gridName.c_str(), c.output.c_str(), seconds);
}

void runConvert(const ConvertCommand& c) {
    const auto start = std::chrono::steady_clock::now();
    checkVdbOutput(c.output);
    const VolumeImport im = planImport(c.input, c.options);
    refuseInputAsOutput(c.output, "output");  // its data files are known now
    const openvdb::FloatGrid::Ptr grid = readVolumeSamples(im.data, im.spec);
    writeVdb(grid, c.output);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    printSummary(c, im, *grid, seconds);
}

// An option that may be absent: its text when given (even empty).
struct Optional {
    CLI::Option* option;
    std::string* text;
    std::optional<std::string> get() const { return option->count() ? std::optional<std::string>(*text) : std::nullopt; }
};

const CommandRegistrar registrar{{"convert", 30, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("convert", kConvertHelp);
    auto c = std::make_shared<ConvertCommand>();
    auto texts = std::make_shared<std::array<std::string, 7>>();
    auto& t = *texts;
    cmd->add_option("input", c->input,
                    "the volume; samples x fastest, then y, then z; gzip when a raw file's name ends in .gz; a C-ordered "
                    ".npy array of shape (Z,Y,X) or a Fortran-ordered one of shape (X,Y,Z)")->required();
    const std::array<Optional, 7> given{{
        {cmd->add_option("--dims", t[0], "samples along x,y,z, e.g. 256,256,256 (raw files; a header states them)"), &t[0]},
        {cmd->add_option("--type", t[1], std::string("sample type: ") + rawTypeNames() +
                                             " (raw files; values are kept as numbers, integers beyond 2^24 round to float)"), &t[1]},
        {cmd->add_option("--spacing", t[2], "voxel size sx,sy,sz in world units (default 1,1,1)"), &t[2]},
        {cmd->add_option("--endian", t[3], "byte order of multi-byte samples: little|big (default little)"), &t[3]},
        {cmd->add_option("--origin", t[4], "world position x,y,z of voxel (0,0,0) (default 0,0,0)"), &t[4]},
        {cmd->add_option("--direction", t[5], "3x3 matrix, 9 numbers row by row, whose columns are the world directions "
                                              "of the x, y, z axes: world = origin + direction * diag(spacing) * index "
                                              "(default identity)"), &t[5]},
        {cmd->add_option("--background", t[6], "samples equal to it are inactive and it is the grid's background "
                                               "(default 0; e.g. -1000 for CT in Hounsfield units)"), &t[6]},
    }};
    cmd->add_option("--grid", c->options.grid, "name of the grid in the .vdb")->capture_default_str();
    cmd->add_option("-o,--output", c->output, "output .vdb (written atomically)")->required();
    cmd->callback([c, texts, given] {
        ImportOptions& o = c->options;
        o.dims = given[0].get();
        o.type = given[1].get();
        o.spacing = given[2].get();
        o.endian = given[3].get();
        o.origin = given[4].get();
        o.direction = given[5].get();
        o.background = given[6].get();
        runConvert(*c);
    });
}}};

}  // namespace

}  // namespace weft
