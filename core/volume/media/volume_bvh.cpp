#include "core/volume/media/volume_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft {

namespace {

constexpr std::uint32_t kLeafSize = 2;

BBoxd unionOf(const std::vector<BBoxd>& boxes, const std::uint32_t* ids, std::uint32_t n) {
    BBoxd b = boxes[ids[0]];
    for (std::uint32_t i = 1; i < n; ++i) b.expand(boxes[ids[i]]);
    return b;
}

int longestCentreAxis(const std::vector<BBoxd>& boxes, const std::uint32_t* ids, std::uint32_t n) {
    BBoxd c(boxes[ids[0]].getCenter(), boxes[ids[0]].getCenter());
    for (std::uint32_t i = 1; i < n; ++i) c.expand(boxes[ids[i]].getCenter());
    const Vec3d e = c.extents();
    return e[0] >= e[1] ? (e[0] >= e[2] ? 0 : 2) : (e[1] >= e[2] ? 1 : 2);
}

}  // namespace

bool rayMeetsBox(const BBoxd& box, const Vec3d& origin, const Vec3d& dir, double tMax) {
    for (int a = 0; a < 3; ++a)
        if (std::isnan(origin[a]) || std::isnan(dir[a])) return false;
    double t0 = 0, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0) {  // parallel to the slab: inside it or never
            if (origin[a] < box.min()[a] || origin[a] > box.max()[a]) return false;
            continue;
        }
        const double inv = 1.0 / dir[a];
        double n = (box.min()[a] - origin[a]) * inv, f = (box.max()[a] - origin[a]) * inv;
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n), t1 = std::min(t1, f);
        if (!(t0 <= t1)) return false;  // also false on NaN
    }
    return true;
}

VolumeBvh::VolumeBvh(std::vector<BBoxd> boxes) : boxes_(std::move(boxes)) {
    for (std::uint32_t i = 0; i < boxes_.size(); ++i)
        if (boxes_[i].min()[0] <= boxes_[i].max()[0] && boxes_[i].min()[1] <= boxes_[i].max()[1] &&
            boxes_[i].min()[2] <= boxes_[i].max()[2])
            order_.push_back(i);
    if (!order_.empty()) build(0, std::uint32_t(order_.size()));
}

VolumeBvh VolumeBvh::of(const std::vector<Volume>& volumes) {
    std::vector<BBoxd> boxes;
    for (const Volume& v : volumes) boxes.push_back(v.worldBox());
    return VolumeBvh(std::move(boxes));
}

std::uint32_t VolumeBvh::build(std::uint32_t first, std::uint32_t count) {
    const std::uint32_t index = std::uint32_t(nodes_.size());
    nodes_.push_back({unionOf(boxes_, &order_[first], count), first, count, 0});
    if (count <= kLeafSize) return index;
    const int axis = longestCentreAxis(boxes_, &order_[first], count);
    const std::uint32_t half = count / 2;
    auto byCentre = [&](std::uint32_t a, std::uint32_t b) {
        const double ca = boxes_[a].getCenter()[axis], cb = boxes_[b].getCenter()[axis];
        return ca < cb || (ca == cb && a < b);  // ties by index: the same tree every time
    };
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count, byCentre);
    nodes_[index].count = 0;  // inner
    build(first, half);
    const std::uint32_t right = build(first + half, count - half);
    nodes_[index].right = right;
    return index;
}

void VolumeBvh::query(const Vec3d& origin, const Vec3d& dir, double tMax, std::vector<std::uint32_t>& out) const {
    out.clear();
    if (nodes_.empty()) return;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (!rayMeetsBox(n.box, origin, dir, tMax)) continue;
        if (n.count > 0) {
            for (std::uint32_t i = 0; i < n.count; ++i)
                if (n.count == 1 || rayMeetsBox(boxes_[order_[n.first + i]], origin, dir, tMax)) out.push_back(order_[n.first + i]);
            continue;
        }
        const std::uint32_t self = std::uint32_t(&n - nodes_.data());
        stack[top++] = n.right, stack[top++] = self + 1;
    }
    std::sort(out.begin(), out.end());
}

}  // namespace weft
