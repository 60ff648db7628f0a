#pragma once
// A small bounding-volume hierarchy over the world boxes of a scene's
// volumes, so that a ray visits only the volumes whose boxes it crosses:
// a scene of many caches (a fire of fifty pieces, a crowd of clouds) costs
// per ray what the few volumes it meets cost, not what all of them do.
// Median splits on the longest axis of the box centres; leaves hold up to
// two volumes. Queries return indices in ascending order, so what a ray
// meets, and in which order it is summed, never depends on the tree.
#include <cstdint>
#include <vector>

#include "core/scene/camera.hpp"
#include "core/volume/volume.hpp"

namespace weft {

class VolumeBvh {
public:
    VolumeBvh() = default;
    // Boxes with min > max (empty volumes) are never met.
    explicit VolumeBvh(std::vector<BBoxd> boxes);
    // Over the world boxes of the volumes, indexed as they are.
    static VolumeBvh of(const std::vector<Volume>& volumes);

    // Every box that origin + t * dir meets for some t in [0, tMax]
    // (dir need not be unit; t counts in its lengths), ascending.
    void query(const Vec3d& origin, const Vec3d& dir, double tMax, std::vector<std::uint32_t>& out) const;
    std::size_t size() const { return boxes_.size(); }
    std::size_t nodeCount() const { return nodes_.size(); }

private:
    struct Node {
        BBoxd box;
        std::uint32_t first = 0, count = 0;  // leaf: its range of order_
        std::uint32_t right = 0;             // inner node: the second child (the first follows it)
    };
    std::uint32_t build(std::uint32_t first, std::uint32_t count);

    std::vector<BBoxd> boxes_;
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

// Whether origin + t * dir meets box for some t in [0, tMax] (slab test).
bool rayMeetsBox(const BBoxd& box, const Vec3d& origin, const Vec3d& dir, double tMax);

}  // namespace weft
