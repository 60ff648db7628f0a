#pragma once
// What a scene will take in memory once loaded, estimated before anything
// loads: a .vdb's leaf counts from its preflight walk (vdb_preflight.hpp),
// a procedural volume's resolution, a mesh file's size. A scene above the
// limit is refused at once instead of being refused after it has loaded
// (10,000 procedural volumes once passed 14 GB before the check ran).
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"

namespace weft {

// loadScene, refused with one line before loading when the estimate is
// above limitBytes (0: no limit).
Scene loadSceneWithin(const std::string& input, std::optional<double> aspect, const std::string& gridName, std::optional<int> frame,
                      double limitBytes);

// What a scene file's volumes and meshes take once loaded: volumeFile and
// meshFile turn the file names it holds into paths. A file named by several
// volumes counts once, as it loads once. What cannot be estimated (a
// missing file) counts 0: the loader then reports it with its position.
double sceneFileLoadBytes(const nlohmann::json& root, const std::function<std::string(const std::string&)>& volumeFile,
                          const std::function<std::string(const std::string&)>& meshFile);

// Bytes a .vdb's grids take once read (every grid of the file).
double vdbLoadBytes(const std::string& path);
// Bytes a mesh file takes once read and placed in the BVH (an upper estimate from its size).
double meshLoadBytes(const std::string& path);
// Bytes of a procedural volume of res^3 voxels (a fire has a temperature grid too).
double proceduralLoadBytes(int res, const std::string& kind);

// Throws "<what> needs about X GiB to load, above the Y GiB limit ..." when bytes > limitBytes > 0.
void requireLoadWithin(double bytes, double limitBytes, const std::string& what);

}  // namespace weft
