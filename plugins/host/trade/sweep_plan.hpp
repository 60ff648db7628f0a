#pragma once
// What a sweep renders: the combinations of the values each --vary gives,
// per technique group. `--technique T --vary k=a,b --technique U --vary ...`
// makes one group per technique; a --vary before the first --technique
// belongs to every group (or to the scene's own technique when there is no
// --technique). Keys spp, seed and res set those render options; any other
// key is a parameter of the group's technique (--set key=value).
#include <optional>
#include <string>
#include <vector>

#include "core/base/options/render_options.hpp"

namespace weft {

struct Scene;

struct SweepAxis {
    std::string key;
    std::vector<std::string> values;
};

struct SweepGroup {
    std::optional<std::string> technique;  // none: the scene's (or the default)
    std::vector<SweepAxis> axes;
};

struct SweepRun {
    int index = 0;                                            // 0-based, in plan order
    std::string technique;                                    // as rendered
    std::vector<std::pair<std::string, std::string>> varied;  // the group's axes' values, in axis order
    RenderRequest request;                                    // the base request with `varied` applied
    int width = 0, height = 0;                                // the image it renders (scene and request)
};

// "key=a,b,c" -> its axis. A missing '=', an empty key or value is an error.
SweepAxis parseVary(const std::string& text);

// Every combination of every group, in group order, the last axis fastest.
// Each run's request is checked the way a render checks it (render options
// through their table, the technique's parameters through its table, the
// content of `scene`), so a bad key or value fails here, before anything
// renders, with one line naming the --vary and the value.
std::vector<SweepRun> planSweep(const RenderRequest& base, const std::vector<SweepGroup>& groups, const Scene& scene);

// "step=0.5 spp=4", how a run is named in tables and plots.
std::string runLabel(const SweepRun& run);

}  // namespace weft
