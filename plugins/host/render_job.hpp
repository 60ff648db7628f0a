#pragma once
// One render from the command line (or a pipeline) to files: load the scene,
// pick and validate the technique, render, and write EXR + preview + stats,
// each atomically. Every check that can fail on user input runs before the
// render starts, so bad input never costs render time or leaves files.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "core/image/io/image_io.hpp"
#include "core/base/run/render_context.hpp"
#include "core/base/options/render_options.hpp"

namespace weft {

struct RenderOutcome {
    Image image;          // the whole frame, or the tile's rows only
    ImageWindow window;   // where image lies in the frame
    Metadata metadata;  // what went into the EXR header
    CounterMap counters;
    std::vector<std::pair<std::string, double>> timingsMs;
};

// Checks what does not depend on the scene or the frame (the ranges of
// values a request built in code may hold, memory, and --set against the
// technique's table when the technique is known without loading the scene);
// throws on the first problem.
void validateRequest(const RenderRequest& request);

// Renders without writing anything (tests and chains use this directly);
// afterLoad runs once the scene has loaded, before the technique starts.
RenderOutcome renderToImage(const RenderRequest& request, const std::function<void()>& afterLoad = {});

// The two halves of renderToImage, for callers that render one scene many
// times (weft sweep): the scene as the request loads it (framed for its
// resolution's aspect), and a render of an already loaded scene. The
// caller has run validateRequest and set the thread count.
struct Scene;
struct LoadedScene {
    std::shared_ptr<const Scene> scene;
    double loadMs = 0;  // reported as the "load" timing of each render
};
std::optional<double> requestAspect(const RenderRequest& request);
// --threads as a count: 0 means every core.
int effectiveThreads(int requested);
LoadedScene loadRequestScene(const RenderRequest& request);
RenderOutcome renderLoadedScene(const RenderRequest& request, const LoadedScene& loaded);

// The request as it renders on `scene` (effectiveRender) and its parsed
// technique parameters, after every check a render makes before it starts
// (parameters, content, motion blur, memory): throws the render's error.
struct CheckedRender {
    EffectiveRender effective;
    ParamSet params;
};
CheckedRender checkRender(const RenderRequest& request, const Scene& scene);

// Renders and writes the requested files (the EXR only when output is set);
// returns what was rendered, for operations chained after it.
RenderOutcome runRender(const RenderRequest& request);

// One request per frame: names with a frame wildcard (input, output,
// preview, stats) expanded, frame set. Several frames need a wildcard in
// every output name, or they would overwrite each other: an Error says so.
std::vector<RenderRequest> requestsForFrames(const RenderRequest& request, const std::vector<int>& frames);

// Renders each request in turn, then hands its outcome to `after` (chained
// steps); a failing one prints its error (naming the frame) and the others
// go on. Returns how many failed.
using AfterRender = std::function<void(const RenderRequest&, RenderOutcome&)>;
int runRenders(const std::vector<RenderRequest>& requests, const AfterRender& after = {});

}  // namespace weft
