#include "hwsim/raster.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/error.hpp"

namespace weft::hwsim {

namespace {

std::int64_t snap(float v) { return std::llround(double(v) * kSubpixel); }

// Whether a directed edge (dx, dy) of a counter-clockwise primitive owns the
// centres on it. The interior lies left of the edge: a rightward horizontal
// edge is a bottom edge, an upward edge is a right edge.
bool ownsEdge(std::int64_t dx, std::int64_t dy, FillRule rule) {
    const bool top = rule == FillRule::TopLeft || rule == FillRule::TopRight;
    const bool left = rule == FillRule::TopLeft || rule == FillRule::BottomLeft;
    if (dy == 0) return dx < 0 ? top : !top;
    return dy < 0 ? left : !left;
}

void clipBox(PrimitiveSetup& s, double minX, double minY, double maxX, double maxY, int width, int height) {
    s.x0 = std::max(0, int(std::floor(minX)));
    s.y0 = std::max(0, int(std::floor(minY)));
    s.x1 = std::min(width, int(std::ceil(maxX)) + 1);
    s.y1 = std::min(height, int(std::ceil(maxY)) + 1);
}

}  // namespace

PrimitiveSetup setupTriangle(const Vertex v[3], FillRule rule, int width, int height) {
    PrimitiveSetup s;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y) || !std::isfinite(v[i].z)) return s;  // covers nothing
        if (std::fabs(v[i].x) > kMaxCoordinate || std::fabs(v[i].y) > kMaxCoordinate)
            throw Error("hwsim: vertex (" + std::to_string(v[i].x) + ", " + std::to_string(v[i].y) +
                        ") outside the rasterizer's range of +-" + std::to_string(int(kMaxCoordinate)) + " pixels");
    }
    std::int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i) X[i] = snap(v[i].x), Y[i] = snap(v[i].y);
    const std::int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
    if (area == 0) return s.zeroArea = true, s;  // empty box
    int order[3] = {0, 1, 2};
    if (area < 0) std::swap(order[1], order[2]);  // make it counter-clockwise
    s.edges.count = 3;
    for (int e = 0; e < 3; ++e) {
        const int i = order[e], j = order[(e + 1) % 3];
        const std::int64_t dx = X[j] - X[i], dy = Y[j] - Y[i];
        s.edges.a[e] = -dy;
        s.edges.b[e] = dx;
        s.edges.c[e] = dy * X[i] - dx * Y[i];
        s.edges.owns[e] = ownsEdge(dx, dy, rule);
    }
    // Depth plane through the snapped vertices.
    const double x0 = double(X[0]) / kSubpixel, y0 = double(Y[0]) / kSubpixel;
    const double x1 = double(X[1]) / kSubpixel - x0, y1 = double(Y[1]) / kSubpixel - y0;
    const double x2 = double(X[2]) / kSubpixel - x0, y2 = double(Y[2]) / kSubpixel - y0;
    const double z1 = double(v[1].z) - v[0].z, z2 = double(v[2].z) - v[0].z;
    const double det = x1 * y2 - x2 * y1;
    s.dzdx = (z1 * y2 - z2 * y1) / det;
    s.dzdy = (x1 * z2 - x2 * z1) / det;
    s.z0 = double(v[0].z) - s.dzdx * x0 - s.dzdy * y0;
    if (v[0].z == v[1].z && v[1].z == v[2].z) s.z0 = v[0].z, s.dzdx = s.dzdy = 0;  // constant depth stays exact
    const double minX = std::min({X[0], X[1], X[2]}) / double(kSubpixel), maxX = std::max({X[0], X[1], X[2]}) / double(kSubpixel);
    const double minY = std::min({Y[0], Y[1], Y[2]}) / double(kSubpixel), maxY = std::max({Y[0], Y[1], Y[2]}) / double(kSubpixel);
    clipBox(s, minX, minY, maxX, maxY, width, height);
    return s;
}

namespace {

struct ScanEdge {
    float dx, dy, dxdy, sx, sy;
    int lines;
};

ScanEdge scanEdge(const Vertex& from, const Vertex& to, float fromX, float fromY, float toY) {
    ScanEdge e;
    e.dx = to.x - from.x;
    e.dy = to.y - from.y;
    e.sy = std::ceil(fromY);
    e.lines = int(std::ceil(toY - e.sy));
    e.dxdy = e.dy != 0.0f ? e.dx / e.dy : 0.0f;
    e.sx = fromX + (e.sy - fromY) * e.dxdy;
    return e;
}

// The rows of one half of the triangle between two edges, clipped to the target.
void scanHalf(ScanEdge& left, ScanEdge& right, int lines, int width, int height, SpanRows& rows) {
    const int sy = int(left.sy);
    const int start = std::max(sy, 0) - sy, finish = std::min(sy + lines, height) - sy;
    for (int y = start; y < finish; ++y) {
        const int l = std::max(int(left.sx + float(y) * left.dxdy), 0);
        const int r = std::min(int(right.sx + float(y) * right.dxdy), width);
        const std::size_t row = std::size_t(sy + y - rows.y0);
        if (l < r && row < rows.left.size()) rows.left[row] = l, rows.right[row] = r;
    }
    left.sx += float(lines) * left.dxdy, right.sx += float(lines) * right.dxdy;
    left.sy += float(lines), right.sy += float(lines);
}

// Indices of the vertices from bottom to top, ties kept in softpipe's order.
void sortByY(const Vertex v[3], int& lo, int& mid, int& hi) {
    const float y0 = v[0].y, y1 = v[1].y, y2 = v[2].y;
    if (y0 <= y1) {
        if (y1 <= y2) lo = 0, mid = 1, hi = 2;
        else if (y2 <= y0) lo = 2, mid = 0, hi = 1;
        else lo = 0, mid = 2, hi = 1;
    } else {
        if (y0 <= y2) lo = 1, mid = 0, hi = 2;
        else if (y2 <= y1) lo = 2, mid = 1, hi = 0;
        else lo = 1, mid = 2, hi = 0;
    }
}

}  // namespace

PrimitiveSetup setupTriangleSpans(const Vertex v[3], int width, int height, SpanRows& rows) {
    PrimitiveSetup s = setupTriangle(v, FillRule::BottomRight, width, height);  // validation and depth plane
    rows.reset(0, height);
    s.spans = &rows;
    if (s.empty()) return s;
    int lo, mid, hi;
    sortByY(v, lo, mid, hi);
    const Vertex &a = v[lo], &b = v[mid], &c = v[hi];
    const float area = (c.x - a.x) * (b.y - a.y) - (b.x - a.x) * (c.y - a.y);
    if (!std::isfinite(1.0f / area)) return s.x1 = s.x0, s.zeroArea = true, s;
    const float ax = a.x + 0.5f, bx = b.x + 0.5f, ay = a.y - 0.5f, by = b.y - 0.5f, cy = c.y - 0.5f;
    ScanEdge major = scanEdge(a, c, ax, ay, cy), bottom = scanEdge(a, b, ax, ay, by), top = scanEdge(b, c, bx, by, cy);
    if (1.0f / area < 0) {
        scanHalf(major, bottom, bottom.lines, width, height, rows);
        scanHalf(major, top, top.lines, width, height, rows);
    } else {
        scanHalf(bottom, major, bottom.lines, width, height, rows);
        scanHalf(top, major, top.lines, width, height, rows);
    }
    s.x0 = width, s.x1 = 0, s.y0 = height, s.y1 = 0;  // the box of the spans
    for (int y = 0; y < height; ++y)
        if (rows.left[y] < rows.right[y])
            s.x0 = std::min(s.x0, rows.left[y]), s.x1 = std::max(s.x1, rows.right[y]), s.y0 = std::min(s.y0, y), s.y1 = y + 1;
    return s;
}

PrimitiveSetup setupRect(int x0, int y0, int x1, int y1, float z, int width, int height) {
    PrimitiveSetup s;
    s.x0 = std::max(0, x0), s.y0 = std::max(0, y0), s.x1 = std::min(width, x1), s.y1 = std::min(height, y1);
    s.edges.count = 0;  // every centre of the clipped box is inside
    s.z0 = z;
    return s;
}

}  // namespace weft::hwsim
