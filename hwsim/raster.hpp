#pragma once
// Scan conversion: which pixel centres a convex primitive covers. Vertices
// are snapped to 1/256 pixel (8 sub-pixel bits, as Mesa's rasterizers do)
// and every edge is an exact 64-bit integer edge function, so shared edges
// are decided consistently: a centre exactly on an edge belongs to the
// primitive only on the edges the fill rule names (GL lets the
// implementation choose; profiles say which).
#include <cstdint>
#include <vector>

namespace weft::hwsim {

struct Vertex {
    float x, y, z;  // window coordinates; z in [0, 1]
};

// Which edges own the centres exactly on them, in GL window coordinates
// (y up): a horizontal edge is a top or bottom edge, any other a left or
// right edge.
enum class FillRule : std::uint8_t { TopLeft, TopRight, BottomLeft, BottomRight };

constexpr int kSubpixelBits = 8;
constexpr std::int64_t kSubpixel = 1 << kSubpixelBits;
// Window coordinates beyond this are refused (GL would have clipped them):
// edge functions of snapped coordinates then stay far inside 64 bits.
constexpr float kMaxCoordinate = 1 << 20;

// Up to four edges E(px, py) = a*px + b*py + c over sub-pixel coordinates;
// a pixel centre is inside when every E > 0, or E == 0 on an owning edge.
struct EdgeSet {
    int count = 0;
    std::int64_t a[4]{}, b[4]{}, c[4]{};
    bool owns[4]{};
    // Whether the centre of pixel (x, y) is covered.
    bool covers(int x, int y) const {
        const std::int64_t px = std::int64_t(x) * kSubpixel + kSubpixel / 2, py = std::int64_t(y) * kSubpixel + kSubpixel / 2;
        for (int i = 0; i < count; ++i) {
            const std::int64_t e = a[i] * px + b[i] * py + c[i];
            if (e < 0 || (e == 0 && !owns[i])) return false;
        }
        return true;
    }
};

enum class TileCoverage { None, Partial, Full };

// Whether the pixel centres of [x0, x1) x [y0, y1) are all outside one edge,
// all strictly inside every edge, or mixed: edge functions are linear, so
// their extremes over the centres lie at the corner centres.
inline TileCoverage classifyTile(const EdgeSet& e, int x0, int y0, int x1, int y1) {
    const std::int64_t px0 = std::int64_t(x0) * kSubpixel + kSubpixel / 2, px1 = std::int64_t(x1 - 1) * kSubpixel + kSubpixel / 2;
    const std::int64_t py0 = std::int64_t(y0) * kSubpixel + kSubpixel / 2, py1 = std::int64_t(y1 - 1) * kSubpixel + kSubpixel / 2;
    bool full = true;
    for (int i = 0; i < e.count; ++i) {
        const std::int64_t lo = e.a[i] * (e.a[i] > 0 ? px0 : px1) + e.b[i] * (e.b[i] > 0 ? py0 : py1) + e.c[i];
        const std::int64_t hi = e.a[i] * (e.a[i] > 0 ? px1 : px0) + e.b[i] * (e.b[i] > 0 ? py1 : py0) + e.c[i];
        if (hi < 0 || (hi == 0 && !e.owns[i])) return TileCoverage::None;
        if (lo <= 0) full = false;
    }
    return full ? TileCoverage::Full : TileCoverage::Partial;
}

// Per-row coverage [left, right) of a primitive scanned as spans (the
// float scanline mode of Mesa's softpipe), rows y0 .. y0 + left.size() - 1.
struct SpanRows {
    int y0 = 0;
    std::vector<int> left, right;
    void reset(int firstRow, int rows) {
        y0 = firstRow;
        left.assign(std::size_t(rows), 0);
        right.assign(std::size_t(rows), 0);
    }
};

// A primitive ready to scan: its edges, the pixel bounding box clipped to
// the target (x1, y1 exclusive), and its depth plane z = z0 + dzdx*cx + dzdy*cy
// at pixel centres (cx, cy).
struct PrimitiveSetup {
    EdgeSet edges;
    const SpanRows* spans = nullptr;  // when set, coverage comes from the spans instead of the edges
    bool covers(int x, int y) const {
        if (!spans) return edges.covers(x, y);
        const std::size_t row = std::size_t(y - spans->y0);
        return row < spans->left.size() && x >= spans->left[row] && x < spans->right[row];
    }
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    double z0 = 0, dzdx = 0, dzdy = 0;
    int primitive = 0;      // index within its draw call (gl_PrimitiveID)
    bool zeroArea = false;  // a triangle of zero area (after snapping): some setups drop it from their statistics
    bool empty() const { return x0 >= x1 || y0 >= y1; }
    float depthAt(int x, int y) const { return float(z0 + dzdx * (x + 0.5) + dzdy * (y + 0.5)); }
};

// A triangle (either winding; zero area covers nothing) inside a width x height target.
PrimitiveSetup setupTriangle(const Vertex v[3], FillRule rule, int width, int height);
// The same triangle scanned the way Mesa's softpipe scans it: pixel centres
// shifted to integers, rows from ceil(y_min) to ceil(y_max) (bottom edge in,
// top out), and per row the pixels from trunc(x_left) to trunc(x_right)
// (right edge in, left out), edge positions stepped in single precision
// from the vertices sorted by y — so centres within rounding of an edge fall
// as softpipe's float arithmetic puts them. `rows` receives the spans.
PrimitiveSetup setupTriangleSpans(const Vertex v[3], int width, int height, SpanRows& rows);
// A screen-aligned rectangle [x0, x1) x [y0, y1) at constant depth, scanned as
// one primitive (as a viewport-covering triangle clipped to it would be).
PrimitiveSetup setupRect(int x0, int y0, int x1, int y1, float z, int width, int height);

}  // namespace weft::hwsim
