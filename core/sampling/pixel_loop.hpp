#pragma once
// Runs a function over every pixel in parallel, by rows. Each pixel's result
// depends only on its own coordinates, so images are identical for any
// thread count. Progress advances per row. Only the settings' row band is
// visited (all rows unless a tile is being rendered).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/base/progress.hpp"
#include "core/base/render_context.hpp"

namespace weft {

// rowFn(y) renders row y completely.
template <class RowFn>
void forEachRow(const RenderSettings& settings, const char* label, RowFn rowFn) {
    const int end = settings.rowEnd < 0 ? settings.height : std::min(settings.rowEnd, settings.height);
    const int begin = std::clamp(settings.rowBegin, 0, end);
    Progress progress(label, end - begin, settings.showProgress);
    tbb::parallel_for(tbb::blocked_range<int>(begin, end, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            rowFn(y);
            progress.advance();
        }
    });
    progress.finish();
}

}  // namespace weft
