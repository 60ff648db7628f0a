#pragma once
// The monitor of every render the weft command runs: the progress line on a
// terminal, and SIGINT/SIGTERM.
//
// While a render runs (a RenderRunning is alive), the first signal
// interrupts it: the render stops at its next row or pass, unwinding removes
// its temporary outputs, and main() then ends the process by that signal
// (endBySignalIfReceived), as the shell and a farm's scheduler expect. At
// any other moment (loading, writing a file, a command that does not
// render), and at a second signal, the temporary outputs are removed and
// the process ends at once.
#include "core/base/run/render_monitor.hpp"

namespace weft {

// Installs the SIGINT and SIGTERM handlers; main() calls it once at start.
void installStopSignalHandlers();

// The command's monitor: polled by every render, draws on a terminal.
RenderMonitor& commandLineMonitor();

// Whether stderr is a terminal (progress lines are drawn only there: farm logs stay clean).
bool stderrIsTerminal();

// Marks a render in progress: a signal meanwhile interrupts it instead of
// ending the process.
class RenderRunning {
public:
    RenderRunning();
    ~RenderRunning();
    RenderRunning(const RenderRunning&) = delete;
    RenderRunning& operator=(const RenderRunning&) = delete;
};

// Ends the process by the signal that interrupted a render, if one did.
void endBySignalIfReceived();

}  // namespace weft
