// Mesa cross-checks: the pass lists of crosscheck_cases.hpp (fixed ones and
// 120 seeded random ones) rendered by llvmpipe and softpipe (weft_mesa_check,
// one process per driver) and by hwsim under the matching profile must give
// equal counts — SAMPLES_PASSED, non-helper program invocations (an atomic
// counter in the program), and which pixels were written. If EGL cannot make a context the test fails
// with the reason.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/base/error.hpp"
#include "hwsim/pipeline.hpp"
#include "tests/hwsim/crosscheck_cases.hpp"

namespace weft::crosscheck {
namespace {

struct DriverRun {
    std::string output;
    int status = -1;
};

DriverRun runDriver(const std::string& driver) {
    // Mesa's EGL vendor even where another vendor (a GPU driver) is installed.
    const char* mesaVendor = "/usr/share/glvnd/egl_vendor.d/50_mesa.json";
    const std::string vendor = std::filesystem::exists(mesaVendor) ? std::string(" __EGL_VENDOR_LIBRARY_FILENAMES=") + mesaVendor : "";
    const std::string cmd = "env GALLIUM_DRIVER=" + driver + " LIBGL_ALWAYS_SOFTWARE=1 EGL_PLATFORM=surfaceless" + vendor + " " +
                            std::string(WEFT_MESA_CHECK) + " 2>&1";
    DriverRun run;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return run;
    char buf[512];
    while (fgets(buf, sizeof buf, pipe)) run.output += buf;
    run.status = pclose(pipe);
    return run;
}

// "CASE name samples=.. invocations=.. written=.. hash=.." lines by name.
std::map<std::string, Counts> parse(const std::string& output) {
    std::map<std::string, Counts> out;
    std::istringstream in(output);
    std::string line;
    while (std::getline(in, line)) {
        char name[64];
        Counts c;
        unsigned long long hash = 0;
        if (std::sscanf(line.c_str(), "CASE %63s samples=%lld invocations=%lld written=%lld hash=%llu", name, &c.samplesPassed,
                        &c.invocations, &c.written, &hash) == 5) {
            c.writtenHash = hash;
            out[name] = c;
        }
    }
    return out;
}

struct CaseProgram {
    ProgramKind kind;
    void operator()(const Fragment& f, FragmentOutput& o) const {
        o.color = {1, 1, 1, 1};
        if (kind == ProgramKind::DiscardOdd) o.discard = (f.x & 1) != 0;
        if (kind == ProgramKind::WriteDepth) o.depth = f.x + 0.5f < 32.0f ? 0.25f : 0.75f;
    }
};

Counts runOnHwsim(const Case& c, const Profile& profile) {
    Framebuffer fb(kSize, kSize, c.clearDepth);
    fb.stencil.assign(fb.stencil.size(), c.clearStencil);
    Pipeline pipe(fb, profile);
    for (const Pass& pass : c.passes) {
        pipe.state = pass.state;
        const ProgramTraits traits{pass.program == ProgramKind::WriteDepth, pass.program == ProgramKind::DiscardOdd, true,
                                   pass.earlyFragmentTests, pass.program != ProgramKind::Plain};
        for (std::size_t i = 0; i + 2 < pass.triangles.size(); i += 3) {
            const Vertex v[3] = {pass.triangles[i], pass.triangles[i + 1], pass.triangles[i + 2]};
            pipe.drawTriangle(v, CaseProgram{pass.program}, traits);
        }
    }
    Counts counts;
    counts.samplesPassed = pipe.counts().samplesPassed;
    counts.invocations = pipe.counts().invocations - pipe.counts().helpers;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (fb.color[fb.index(x, y)][0] != 0) counts.markWritten(x, y);
    return counts;
}

void crossCheck(const std::string& driver, const std::string& profileName, bool exactRandom = true, int minRandomMatches = 0) {
    const DriverRun run = runDriver(driver);
    ASSERT_EQ(run.status, 0) << "weft_mesa_check could not run on " << driver << ":\n" << run.output;
    ASSERT_NE(run.output.find("RENDERER " + driver), std::string::npos) << "not Mesa's " << driver << ":\n" << run.output;
    const std::map<std::string, Counts> gl = parse(run.output);
    const Profile& profile = findProfile(profileName);
    int compared = 0;
    for (const Case& c : allCases()) {
        if (c.needsBounds && profile.bounds == BoundsSupport::Unsupported) {
            EXPECT_THROW(runOnHwsim(c, profile), Error) << c.name;  // the profile refuses what the driver lacks
            EXPECT_NE(run.output.find("SKIP " + c.name), std::string::npos) << c.name;
            continue;
        }
        ASSERT_TRUE(gl.count(c.name)) << c.name << " missing from:\n" << run.output;
        const Counts& g = gl.at(c.name);
        const Counts h = runOnHwsim(c, profile);
        EXPECT_EQ(h.samplesPassed, g.samplesPassed) << driver << " " << c.name << " SAMPLES_PASSED";
        EXPECT_EQ(h.invocations, g.invocations) << driver << " " << c.name << " program invocations";
        EXPECT_EQ(h.written, g.written) << driver << " " << c.name << " pixels written";
        EXPECT_EQ(h.writtenHash, g.writtenHash) << driver << " " << c.name << " which pixels were written";
        ++compared;
    }
    EXPECT_GE(compared, 100);  // the fixed cases and the random pass lists (those needing bounds skip on llvmpipe)
}

TEST(HwsimMesa, LlvmpipeCountsEqualHwsim) { crossCheck("llvmpipe", "mesa-llvmpipe"); }
TEST(HwsimMesa, SoftpipeCountsEqualHwsim) { crossCheck("softpipe", "mesa-softpipe"); }

}  // namespace
}  // namespace weft::crosscheck
