#pragma once
// Reading the leaf buffers of a grid OpenVDB opened with delayed loading.
// OpenVDB 10 loads a delay-loaded leaf by checking the file's modification
// time (a stat system call per leaf: 7,041 for the aneurism) before it
// decodes the leaf's bytes. Where the preflight walk found each leaf's bytes
// (vdb_preflight.hpp), they are decoded here straight from the mapped file,
// in parallel, with OpenVDB's own LeafNode::readBuffers. A grid the walk
// cannot place leaf by leaf is refused: OpenVDB's own delayed load trusts
// the file's sizes before it checks them (a corrupt file overflowed its buffer).
#include <openvdb/openvdb.h>

#include <cstddef>
#include <string>

#include "core/volume/io/vdb_preflight.hpp"

namespace weft {

// Loads every leaf buffer of `grid` (a float or Vec3s grid of the file at
// `path`, read with delayed loading); file and layout: the walk's record of
// the file and of that grid, or null. Returns how many leaves it decoded.
// Throws weft::Error saying why when the walk's record cannot place every
// leaf (no record, two grids of the name, the file changed since the walk,
// a leaf elsewhere than the walk found it), and what OpenVDB throws for
// bytes that do not decode.
std::size_t loadLeaves(const openvdb::GridBase::Ptr& grid, const std::string& path, const VdbLayout* file, const VdbGridLayout* layout);

}  // namespace weft
