// Recorded GPUs: every case weft_mesa_check recorded on a real GPU
// (tests/hwsim/recorded/, see its README) replayed by hwsim under that GPU's
// profile must give the recorded counts exactly — SAMPLES_PASSED, non-helper
// invocations, which pixels were written and, where the recording has them,
// the pipeline statistics. No GPU is needed: the file is the measurement.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/base/error.hpp"
#include "tests/hwsim/case_lines.hpp"
#include "tests/hwsim/crosscheck_hwsim.hpp"

namespace weft::crosscheck {
namespace {

struct Recording {
    const char* file;      // in tests/hwsim/recorded/
    const char* profile;   // hwsim profile that must reproduce it
    const char* renderer;  // expected in its RENDERER line
    bool statistics;       // recorded with fs_invocations, clip_in, clip_out
};

const Recording kRecordings[] = {
    {"nvidia-h200-580.159.04.txt", "nvidia-h200", "NVIDIA H200", false},
    {"nvidia-h200-580.159.04-stats.txt", "nvidia-h200", "NVIDIA H200", true},
};

std::string readRecording(const std::string& file) {
    std::ifstream in(std::filesystem::path(WEFT_SOURCE_DIR) / "tests" / "hwsim" / "recorded" / file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// How many of a recording's cases hwsim reproduces under a profile; every
// mismatching field is reported when `report` is set.
int reproduced(const std::map<std::string, Counts>& recorded, const Profile& profile, bool report) {
    int equal = 0;
    for (const Case& c : allCases()) {
        if (!recorded.count(c.name)) continue;
        const Counts& g = recorded.at(c.name);
        Counts h;
        try {
            h = runOnHwsim(c, profile);
        } catch (const Error& e) {
            if (report) ADD_FAILURE() << c.name << ": " << e.what();
            continue;
        }
        const bool stats = g.fsInvocations >= 0;
        const bool same = h.samplesPassed == g.samplesPassed && h.invocations == g.invocations && h.written == g.written &&
                          h.writtenHash == g.writtenHash &&
                          (!stats || (h.fsInvocations == g.fsInvocations && h.clipIn == g.clipIn && h.clipOut == g.clipOut));
        equal += same;
        if (same || !report) continue;
        ADD_FAILURE() << c.name << " recorded / hwsim: samples " << g.samplesPassed << " / " << h.samplesPassed << ", invocations "
                      << g.invocations << " / " << h.invocations << ", written " << g.written << " / " << h.written << ", hash "
                      << g.writtenHash << " / " << h.writtenHash << ", fs_invocations " << g.fsInvocations << " / " << h.fsInvocations
                      << ", clip_in " << g.clipIn << " / " << h.clipIn << ", clip_out " << g.clipOut << " / " << h.clipOut;
    }
    return equal;
}

TEST(HwsimRecorded, EveryRecordedCaseIsReproducedByItsProfile) {
    std::set<std::string> known;
    for (const Case& c : allCases()) known.insert(c.name);
    for (const Recording& r : kRecordings) {
        SCOPED_TRACE(r.file);
        const std::string text = readRecording(r.file);
        ASSERT_NE(text.find(std::string("RENDERER ") + r.renderer), std::string::npos) << "not a recording of " << r.renderer;
        const std::map<std::string, Counts> recorded = parseCaseLines(text);
        int withStatistics = 0;
        for (const auto& [name, counts] : recorded) {
            EXPECT_TRUE(known.count(name)) << name << " is no case of crosscheck_cases.hpp";
            withStatistics += counts.fsInvocations >= 0 && counts.clipIn >= 0 && counts.clipOut >= 0;
        }
        EXPECT_EQ(recorded.size(), known.size()) << "a recording holds every case";
        EXPECT_EQ(withStatistics, r.statistics ? int(recorded.size()) : 0);
        EXPECT_EQ(reproduced(recorded, findProfile(r.profile), true), int(recorded.size()));
    }
}

// The recording decides between profiles: the ones made for other
// implementations miss cases of it.
TEST(HwsimRecorded, OtherProfilesDoNotReproduceTheH200) {
    const std::map<std::string, Counts> recorded = parseCaseLines(readRecording("nvidia-h200-580.159.04-stats.txt"));
    ASSERT_FALSE(recorded.empty());
    for (const char* other : {"ideal", "modern-desktop", "mesa-softpipe"})
        EXPECT_LT(reproduced(recorded, findProfile(other), false), int(recorded.size())) << other;
}

}  // namespace
}  // namespace weft::crosscheck
