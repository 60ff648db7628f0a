// A render reports its progress to its monitor and polls it: every
// technique's passes run from 0 to 1 as its monitor sees them, and a monitor
// that answers "interrupted" stops any technique with Cancelled, at its
// first poll or half way through.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "core/base/run/progress.hpp"
#include "core/base/run/render_context.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/technique.hpp"

using namespace weft;

namespace {

class RecordingMonitor : public RenderMonitor {
public:
    explicit RecordingMonitor(int stopAfterPolls = -1) : stopAfter_(stopAfterPolls) {}
    void progress(std::string_view pass, double fraction) override {
        std::lock_guard<std::mutex> lock(mutex_);
        reports.emplace_back(std::string(pass), fraction);
    }
    bool interrupted() override { return polls.fetch_add(1) + 1 > stopAfter_ && stopAfter_ >= 0; }

    std::vector<std::pair<std::string, double>> reports;
    std::atomic<int> polls{0};

private:
    const int stopAfter_;
    std::mutex mutex_;
};

// Each pass's reports lie in [0, 1], never go back between its start (0)
// and its end (1), and the pass ends.
void expectPassesRunFromStartToEnd(const std::vector<std::pair<std::string, double>>& reports, const std::string& who) {
    std::map<std::string, double> last;
    for (const auto& [pass, fraction] : reports) {
        EXPECT_GE(fraction, 0.0) << who << ": " << pass;
        EXPECT_LE(fraction, 1.0) << who << ": " << pass;
        const auto it = last.find(pass);
        if (fraction > 0.0 && it != last.end()) {
            EXPECT_GE(fraction, it->second) << who << ": " << pass << " went back";
        }
        last[pass] = fraction;
    }
    for (const auto& [pass, fraction] : last) EXPECT_EQ(fraction, 1.0) << who << ": " << pass << " never ended";
}

std::string inputFor(const TechniqueInfo& t) {
    switch (t.renders) {
    case Content::None: return "builtin:zoneplate";
    case Content::Volumes: return "builtin:cloud";
    case Content::Meshes: return std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json";
    case Content::VolumesAndMeshes: return std::string(WEFT_SOURCE_DIR) + "/scenes/combined/smoke_in_cornell.json";
    }
    return "";
}

RenderRequest requestFor(const TechniqueInfo& t, RenderMonitor& monitor) {
    RenderRequest r;
    r.input = inputFor(t);
    r.technique = t.name;
    r.resolution = Resolution{40, 32};
    r.spp = 1;
    r.threads = 2;
    r.monitor = &monitor;
    return r;
}

}  // namespace

TEST(Progress, ReportsStartAndEndAndStopsOnceInterrupted) {
    RecordingMonitor watching;
    {
        Progress p("loop", 1000, &watching);
        tbb::parallel_for(0, 1000, [&](int) { p.advance(); });
    }
    ASSERT_GE(watching.reports.size(), 2u);
    EXPECT_EQ(watching.reports.front(), std::make_pair(std::string("loop"), 0.0));
    EXPECT_EQ(watching.reports.back(), std::make_pair(std::string("loop"), 1.0));
    EXPECT_EQ(watching.polls.load(), 1000);

    RecordingMonitor stopping(10);
    Progress p("loop", 1000, &stopping);
    std::atomic<int> done{0};
    EXPECT_THROW(tbb::parallel_for(0, 1000, [&](int) { p.advance(), ++done; }), Cancelled);
    EXPECT_EQ(done.load(), 10);  // the steps after the interrupt never ran

    Timings timings;
    RecordingMonitor stopped(0);
    timings.monitor = &stopped;
    EXPECT_THROW(ScopedTimer(timings, "pass"), Cancelled);  // a pass does not start
    EXPECT_TRUE(timings.entries().empty());
}

TEST(RenderMonitor, EveryTechniqueReportsItsPassesFromStartToEnd) {
    for (const TechniqueInfo* t : techniques().all()) {
        RecordingMonitor monitor;
        const RenderOutcome out = renderToImage(requestFor(*t, monitor));
        EXPECT_EQ(out.image.width(), 40) << t->name;
        EXPECT_FALSE(monitor.reports.empty()) << t->name << " reported no progress";
        EXPECT_GT(monitor.polls.load(), 2) << t->name;
        expectPassesRunFromStartToEnd(monitor.reports, t->name);
    }
}

TEST(RenderMonitor, AnInterruptStopsEveryTechniqueAtItsFirstPollOrHalfWay) {
    for (const TechniqueInfo* t : techniques().all()) {
        RecordingMonitor counting;
        renderToImage(requestFor(*t, counting));
        for (const int stopAfter : {0, counting.polls.load() / 2}) {
            RecordingMonitor stopping(stopAfter);
            EXPECT_THROW(renderToImage(requestFor(*t, stopping)), Cancelled) << t->name << " after " << stopAfter << " polls";
        }
        RecordingMonitor again;  // nothing of the stopped renders stays behind
        EXPECT_NO_THROW(renderToImage(requestFor(*t, again))) << t->name;
    }
}
