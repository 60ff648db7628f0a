#pragma once
// Trees weft builds over a volume's voxels (a light cache, a ray
// intersector's topology) may use coordinates shifted by whole leaves.
// OpenVDB's root keeps one top node of 32^3 entries (256 KiB, cleared when
// made) per 4096^3 region a tree touches, so a volume around the index
// origin costs eight of them, on one thread; shifted above the origin it
// costs one.
#include <openvdb/openvdb.h>
#include <openvdb/tree/ValueAccessor.h>

namespace weft {

// a / b rounded towards minus infinity (b > 0).
inline int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The multiple of `width` one width below the box's minimum on each axis:
// coordinates of the box less it are at least `width`. Zero for an empty box.
inline openvdb::Coord widthBelow(const openvdb::CoordBBox& box, int width) {
    if (box.empty()) return openvdb::Coord(0);
    return openvdb::Coord((floorDiv(box.min().x(), width) - 1) * width, (floorDiv(box.min().y(), width) - 1) * width,
                          (floorDiv(box.min().z(), width) - 1) * width);
}

// Adds the active voxels and tiles of `from`, moved by `shift` (a multiple
// of 8: leaves stay leaves), to `to`.
template <class Tree>
void addShiftedTopology(const Tree& from, const openvdb::Coord& shift, openvdb::MaskTree& to) {
    openvdb::tree::ValueAccessor<openvdb::MaskTree> acc(to);
    for (auto leaf = from.cbeginLeaf(); leaf; ++leaf)
        if (!leaf->isEmpty()) acc.touchLeaf(leaf->origin() + shift)->setValueMask(leaf->getValueMask());
    auto tile = from.cbeginValueOn();
    tile.setMaxDepth(tile.getLeafDepth() - 1);  // tiles only
    for (; tile; ++tile) {
        const openvdb::CoordBBox box = tile.getBoundingBox();
        to.fill(openvdb::CoordBBox(box.min() + shift, box.max() + shift), true, true);
    }
}

// An empty mask over a grid's voxels moved by `shift`: its transform still
// maps each moved voxel to the world point of the original.
inline openvdb::MaskGrid::Ptr shiftedMask(const openvdb::math::Transform& gridTransform, const openvdb::Coord& shift) {
    openvdb::MaskGrid::Ptr mask = openvdb::MaskGrid::create(false);
    openvdb::math::Transform::Ptr transform = gridTransform.copy();
    transform->preTranslate(-shift.asVec3d());
    mask->setTransform(transform);
    return mask;
}

}  // namespace weft
