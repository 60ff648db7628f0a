#pragma once
// Runs a function over every pixel in parallel, by rows. Each pixel's result
// depends only on its own coordinates, so images are identical for any
// thread count. Progress advances per row.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/progress.hpp"
#include "core/render_context.hpp"

namespace weft {

// rowFn(y) renders row y completely.
template <class RowFn>
void forEachRow(const RenderSettings& settings, const char* label, RowFn rowFn) {
    Progress progress(label, settings.height, settings.showProgress);
    tbb::parallel_for(tbb::blocked_range<int>(0, settings.height, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            rowFn(y);
            progress.advance();
        }
    });
    progress.finish();
}

}  // namespace weft
