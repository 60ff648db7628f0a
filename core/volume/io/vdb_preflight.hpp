#pragma once
// OpenVDB trusts the lengths and counts a .vdb file states: a corrupt string
// length makes it allocate and fill gigabytes, a corrupt child count makes it
// build nodes for minutes. Before OpenVDB opens a file, its header, metadata,
// grid descriptors, each grid's metadata and transform, and its root's tile
// and child counts are walked here and checked against the bytes the file
// holds (the layout of OpenVDB's io::File, format versions 220 and later) and, for float grids, every node and value chunk of the tree (vdb_float_tree.hpp).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/volume/io/vdb_float_tree.hpp"

namespace weft {

// Where the walk found a float or Vec3s grid's leaf buffers, and how their
// values are stored: what a reader needs to decode a leaf itself
// (volume.cpp reads them in parallel from the mapped file).
struct VdbGridLayout {
    std::uint32_t fileVersion = 0, libraryMajor = 0, libraryMinor = 0;
    std::uint32_t compression = 0;  // the grid's io::COMPRESS_* flags
    bool half = false;              // values stored as 16-bit floats
    std::vector<vdbwalk::LeafBufferAt> leaves;  // in the order OpenVDB reads them
    bool unique = true;                         // false: another grid has the name too, and no leaves are kept
    int components = 1;                         // values per voxel: 1 (float) or 3 (vec3s)
};
struct VdbLayout {
    std::uint64_t fileSize = 0;                  // of the file walked: positions hold for that file only
    std::map<std::string, VdbGridLayout> grids;  // by the name the file stores; instances hold no buffers of their own
};

// Throws weft::Error "volume 'PATH': corrupt file (...)" naming the field
// whose length or count the file cannot hold. A file walked before in this
// process (the same path, inode, size and modification time) is not walked
// again; its layout is kept.
std::shared_ptr<const VdbLayout> preflightVdb(const std::string& path);

// The same on bytes in memory (tests and fuzzing); `name` is used in messages.
VdbLayout preflightVdbBytes(const std::string& bytes, const std::string& name);

}  // namespace weft
