#pragma once
// OpenVDB 10 reads a float (or Vec3s) tree's values in chunks whose sizes the file
// states, into buffers sized by the node masks; its bloscFromStream copies
// an uncompressed chunk of the stated length before comparing it with the
// buffer (a fuzzed file wrote 4317 bytes into a 4-byte buffer). The tree is
// walked here in the order OpenVDB reads Tree_float_5_4_3 (RootNode,
// InternalNode and LeafNode readTopology/readBuffers, io::readCompressedValues)
// and every chunk's stated size is checked against what its node expects.
// Tree_vec3s_5_4_3 has the same layout with three floats per value.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/volume/io/vdb_walker.hpp"

namespace weft::vdbwalk {

// A leaf as the walk found it: its origin and where its buffer (the value
// mask, then the values) starts in the file.
struct LeafBufferAt {
    std::array<std::int32_t, 3> origin;
    std::uint64_t pos;
};

struct FloatTreeFormat {
    std::uint32_t version = 0;      // the file's format version
    std::uint32_t compression = 0;  // the grid's io::COMPRESS_* flags
    bool half = false;              // values stored as 16-bit floats (Tree_float_5_4_3_HalfFloat)
    int components = 1;             // floats per value: 1, or 3 for Vec3s
    std::optional<std::uint64_t> topologyEnd;  // where the descriptor says the buffers begin (none in a stream)
    std::vector<LeafBufferAt>* leaves = nullptr;  // when set, every leaf buffer, in the order OpenVDB reads them
};

// Walks from the root's background value to the end of the last leaf buffer.
void walkFloatTree(Walker& w, const FloatTreeFormat& format);

}  // namespace weft::vdbwalk
