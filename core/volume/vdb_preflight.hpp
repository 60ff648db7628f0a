#pragma once
// OpenVDB trusts the lengths and counts a .vdb file states: a corrupt string
// length makes it allocate and fill gigabytes, a corrupt child count makes it
// build nodes for minutes. Before OpenVDB opens a file, its header, metadata,
// grid descriptors, each grid's metadata and transform, and its root's tile
// and child counts are walked here and checked against the bytes the file
// holds (the layout of OpenVDB's io::File, format versions 220 and later) and, for float grids, every node and value chunk of the tree (vdb_float_tree.hpp).
#include <cstdint>
#include <string>

namespace weft {

// Throws weft::Error "volume 'PATH': corrupt file (...)" naming the field
// whose length or count the file cannot hold.
void preflightVdb(const std::string& path);

// The same on bytes in memory (tests and fuzzing); `name` is used in messages.
void preflightVdbBytes(const std::string& bytes, const std::string& name);

}  // namespace weft
