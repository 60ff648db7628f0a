#pragma once
// What identifies a volume to the caches of work derived from it (oracle
// fields, raymarch's empty-space skipper): a frame sequence of a static
// volume and the runs of a sweep load or hold the same volume again and
// again, and the work done on it once serves them all.
//
// A volume read from a file is identified by its path, grid name, size and
// modification time (as the sweep's reference cache does) and its transform,
// so every frame's fresh load of an unchanged file finds it; any other
// volume (procedural, built in code) by its tree, which a cache entry keeps
// alive (keptGrid) so that its address is not reused. The transfer
// function, the emission grid (by a hash of its content: other emission
// settings or grids, another key) and the active box (which a moving
// volume's reach pads) join the key.
#include <string>

#include "core/volume/volume.hpp"

namespace weft {

std::string volumeKey(const Volume& volume);

// What a cache entry keeps alive for a volume identified by its tree; null
// for one identified by its file.
openvdb::FloatGrid::ConstPtr keptGrid(const Volume& volume);

// Appends a number to a key, exactly (17 significant digits) and delimited.
void addKeyNumber(std::string& key, double value);

}  // namespace weft
