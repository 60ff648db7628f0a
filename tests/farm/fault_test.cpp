// A render killed with SIGKILL never leaves a file at its output name: the
// EXR is written under a temporary name and renamed when complete. The kill
// lands at several points: while the temporary file is being written, while
// it waits before the rename (a test hook holds it there), and at fractions
// of a normal render's run time.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/support/test_support.hpp"

using namespace weft::test;
namespace fs = std::filesystem;

namespace {

// Starts `weft render ...` writing `output`; returns its pid.
pid_t startRender(const fs::path& output, const char* pauseMs) {
    const pid_t pid = fork();
    if (pid == 0) {
        if (pauseMs) setenv("WEFT_TEST_PAUSE_BEFORE_RENAME_MS", pauseMs, 1);
        const std::string out = output.string();
        execl(WEFT_BIN, WEFT_BIN, "render", "builtin:cloud", "--res", "96x96", "--spp", "2", "--threads", "1", "-o",
              out.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

bool tempFileIn(const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".weft-tmp-") != std::string::npos) return true;
    return false;
}

// Waits (bounded) until a temporary output shows up, true when it did.
bool waitForTemp(const fs::path& dir, pid_t pid) {
    for (int i = 0; i < 20000; ++i) {
        if (tempFileIn(dir)) return true;
        if (waitpid(pid, nullptr, WNOHANG) == pid) return false;
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    return false;
}

void killAndReap(pid_t pid) {
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
}

TEST(FarmFaults, KillDuringTheEXRWriteLeavesNoFileAtTheOutputName) {
    // 0 ms: as soon as the temporary file exists (the writer has it open);
    // later: while the finished temporary file waits for its rename.
    for (int afterMs : {0, 1, 5, 50, 400}) {
        TempDir dir;
        const fs::path out = dir / "frame.exr";
        const pid_t pid = startRender(out, "1000");
        ASSERT_TRUE(waitForTemp(dir.path(), pid)) << "no temporary output appeared";
        std::this_thread::sleep_for(std::chrono::milliseconds(afterMs));
        killAndReap(pid);
        EXPECT_FALSE(fs::exists(out)) << "killed " << afterMs << " ms into the write";
    }
}

TEST(FarmFaults, TermAndIntRemoveTheTemporaryOutput) {
    for (int sig : {SIGTERM, SIGINT}) {
        TempDir dir;
        const fs::path out = dir / "frame.exr";
        const pid_t pid = startRender(out, "5000");
        ASSERT_TRUE(waitForTemp(dir.path(), pid)) << "no temporary output appeared";
        kill(pid, sig);
        int status = 0;
        waitpid(pid, &status, 0);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "ends as the signal would end it";
        EXPECT_FALSE(tempFileIn(dir.path())) << "signal " << sig << " left the temporary file";
        EXPECT_FALSE(fs::exists(out));
    }
}

// A signal while the render runs stops it at its next row: weft says so,
// writes nothing and still ends by the signal, so the shell or the farm's
// scheduler sees what happened. A signal that lands while weft still loads
// ends it at once instead; the delay grows until one lands in the render.
TEST(FarmFaults, TermAndIntDuringTheRenderStopItAndWriteNothing) {
    for (int sig : {SIGTERM, SIGINT}) {
        bool stoppedInRender = false;
        for (int delayMs = 500; delayMs <= 8000 && !stoppedInRender; delayMs *= 2) {
            TempDir dir;
            const fs::path out = dir / "frame.exr", err = dir / "stderr.txt";
            const pid_t pid = fork();
            if (pid == 0) {
                if (!freopen(err.c_str(), "w", stderr)) _exit(127);
                execl(WEFT_BIN, WEFT_BIN, "render", "builtin:cloud", "--res", "512x512", "--spp", "256", "--threads", "1", "-o",
                      out.c_str(), static_cast<char*>(nullptr));
                _exit(127);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(delayMs));
            kill(pid, sig);
            int status = 0;
            waitpid(pid, &status, 0);
            EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "ends as the signal would end it";
            EXPECT_FALSE(fs::exists(out));
            EXPECT_FALSE(tempFileIn(dir.path()));
            stoppedInRender = readBytes(err).find("the render stopped and wrote nothing") != std::string::npos;
        }
        EXPECT_TRUE(stoppedInRender) << "signal " << sig << " never stopped a running render";
    }
}

TEST(FarmFaults, StaleTemporaryOutputOfADeadProcessIsRemoved) {
    TempDir dir;
    // pids never reach 999999999 (Linux's pid_max is at most 2^22): its writer is gone.
    writeText(dir / ".frame.weft-tmp-999999999.exr", "left by a killed render");
    writeText(dir / ".other.weft-tmp-999999999.exr", "another output's: not ours to remove");
    const auto r = runWeft("render builtin:sphere --res 8x8 -o " + (dir / "frame.exr").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_FALSE(fs::exists(dir / ".frame.weft-tmp-999999999.exr"));
    EXPECT_TRUE(fs::exists(dir / ".other.weft-tmp-999999999.exr"));
    EXPECT_TRUE(fs::exists(dir / "frame.exr"));
}

TEST(FarmFaults, KillAtAnyTimeLeavesNothingOrTheCompleteFrame) {
    TempDir ref;
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t whole = startRender(ref / "whole.exr", nullptr);
    waitpid(whole, nullptr, 0);
    const double runMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(fs::exists(ref / "whole.exr"));
    for (double fraction : {0.2, 0.5, 0.8, 0.95, 1.0}) {
        TempDir dir;
        const fs::path out = dir / "frame.exr";
        const pid_t pid = startRender(out, nullptr);
        std::this_thread::sleep_for(std::chrono::microseconds(long(fraction * runMs * 1000)));
        killAndReap(pid);
        if (fs::exists(out)) {  // the kill came after the rename: the frame must be whole
            const auto r = runWeft("check " + out.string());
            EXPECT_EQ(r.status, 0) << r.output;
            EXPECT_EQ(readBytes(out), readBytes(ref / "whole.exr"));
        }
    }
}

}  // namespace
