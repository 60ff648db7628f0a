#pragma once
// The tiles of a float tree whose value passes a test, as boxes. Each
// internal node's own table is read (in parallel over the nodes): the
// tree's value iterator costs far more per entry, and a production grid's
// internal nodes hold millions of (mostly background) tile entries.
#include <cstddef>
#include <vector>

#include <openvdb/openvdb.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace weft {

namespace detail {

template <class Node, class Keep>
void addTilesWhere(const Node& node, bool activeOnly, const Keep& keep, std::vector<openvdb::CoordBBox>& out) {
    const auto add = [&](const auto& it) {
        if (keep(*it)) out.push_back(openvdb::CoordBBox::createCube(it.getCoord(), int(Node::ChildNodeType::DIM)));
    };
    if (activeOnly)
        for (auto it = node.cbeginValueOn(); it; ++it) add(it);
    else
        for (auto it = node.cbeginValueAll(); it; ++it) add(it);
}

}  // namespace detail

// Active tiles only, or every tile; keep(value) must be safe to call from several threads.
template <class Keep>
std::vector<openvdb::CoordBBox> tilesWhere(const openvdb::FloatTree& tree, bool activeOnly, const Keep& keep) {
    using Upper = openvdb::FloatTree::RootNodeType::ChildNodeType;
    using Lower = Upper::ChildNodeType;
    std::vector<const Lower*> lower;
    std::vector<const Upper*> upper;
    tree.getNodes(lower);
    tree.getNodes(upper);
    std::vector<std::vector<openvdb::CoordBBox>> found(lower.size() + upper.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, found.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (i < lower.size()) detail::addTilesWhere(*lower[i], activeOnly, keep, found[i]);
            else detail::addTilesWhere(*upper[i - lower.size()], activeOnly, keep, found[i]);
        }
    });
    std::vector<openvdb::CoordBBox> tiles;
    detail::addTilesWhere(tree.root(), activeOnly, keep, tiles);
    for (const auto& f : found) tiles.insert(tiles.end(), f.begin(), f.end());
    return tiles;
}

}  // namespace weft
