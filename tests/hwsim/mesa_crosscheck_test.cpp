// Mesa cross-checks: the pass lists of crosscheck_cases.hpp (fixed ones and
// 120 seeded random ones) rendered by llvmpipe and softpipe (weft_mesa_check,
// one process per driver) and by hwsim under the matching profile must give
// equal counts — SAMPLES_PASSED, non-helper program invocations (an atomic
// counter in the program), which pixels were written, and the pipeline
// statistics FRAGMENT_SHADER_INVOCATIONS and CLIPPING_INPUT/OUTPUT_PRIMITIVES
// (both drivers offer ARB_pipeline_statistics_query). If EGL cannot make a
// context the test fails with the reason.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "core/base/error.hpp"
#include "tests/hwsim/case_lines.hpp"
#include "tests/hwsim/crosscheck_hwsim.hpp"
#include "tests/hwsim/mesa_driver.hpp"

namespace weft::crosscheck {
namespace {

struct DriverRun {
    std::string output;
    int status = -1;
};

DriverRun runDriver(const std::string& driver) {
    const std::string cmd = mesaDriverEnv(driver) + std::string(WEFT_MESA_CHECK) + " 2>&1";
    DriverRun run;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return run;
    char buf[512];
    while (fgets(buf, sizeof buf, pipe)) run.output += buf;
    run.status = pclose(pipe);
    return run;
}

void crossCheck(const std::string& driver, const std::string& profileName) {
    const DriverRun run = runDriver(driver);
    ASSERT_EQ(run.status, 0) << "weft_mesa_check could not run on " << driver << ":\n" << run.output;
    ASSERT_NE(run.output.find("RENDERER " + driver), std::string::npos) << "not Mesa's " << driver << ":\n" << run.output;
    ASSERT_EQ(run.output.find("NOSTATS"), std::string::npos) << driver << " lacks pipeline statistics:\n" << run.output;
    const std::map<std::string, Counts> gl = parseCaseLines(run.output);
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
        EXPECT_EQ(h.fsInvocations, g.fsInvocations) << driver << " " << c.name << " FRAGMENT_SHADER_INVOCATIONS";
        EXPECT_EQ(h.clipIn, g.clipIn) << driver << " " << c.name << " CLIPPING_INPUT_PRIMITIVES";
        EXPECT_EQ(h.clipOut, g.clipOut) << driver << " " << c.name << " CLIPPING_OUTPUT_PRIMITIVES";
        ++compared;
    }
    EXPECT_GE(compared, 100);  // the fixed cases and the random pass lists (those needing bounds skip on llvmpipe)
}

TEST(HwsimMesa, LlvmpipeCountsEqualHwsim) { crossCheck("llvmpipe", "mesa-llvmpipe"); }
TEST(HwsimMesa, SoftpipeCountsEqualHwsim) { crossCheck("softpipe", "mesa-softpipe"); }

}  // namespace
}  // namespace weft::crosscheck
