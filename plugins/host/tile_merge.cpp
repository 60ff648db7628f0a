#include "plugins/host/tile_merge.hpp"

#include <algorithm>
#include <climits>
#include <map>

#include "core/base/error.hpp"
#include "core/base/options/frames.hpp"
#include "core/volume/io/header_text.hpp"
#include "plugins/host/render_job.hpp"

namespace weft {

namespace {

struct Tile {
    std::string path;
    Image image;
    Metadata metadata;
    ImageWindow window;
    int index = 0, count = 0;
    int fullWidth = 0, fullHeight = 0;
};

std::string valueOf(const Metadata& md, const std::string& key) {
    for (const auto& [k, v] : md)
        if (k == key) return v;
    return "";
}

bool placementOrCounter(const std::string& key) {
    return key.rfind("weft:tile", 0) == 0 || key.rfind("weft:counter:", 0) == 0 || key == "weft:complete";
}

Tile readTile(const std::string& path) {
    Tile t;
    t.path = path;
    t.image = readImage(path, &t.metadata, &t.window);
    if (valueOf(t.metadata, "weft:complete") != "1")
        throw Error("merge: '" + path + "' is not a complete weft render (no weft:complete attribute)");
    const std::string spec = valueOf(t.metadata, "weft:tile");
    if (spec.empty()) throw Error("merge: '" + path + "' is not a tile (no weft:tile attribute; render it with --tile i/n)");
    const TileSpec tile = parseTileSpec(spec);
    t.index = tile.index, t.count = tile.count;
    const Resolution full = parseResolution(valueOf(t.metadata, "weft:tile:full_resolution"));
    t.fullWidth = full.width, t.fullHeight = full.height;
    return t;
}

// Same render: same count, resolution, channels and every non-placement attribute.
void checkSameRender(const Tile& a, const Tile& b) {
    const auto fail = [&](const std::string& what) {
        throw Error("merge: tiles '" + a.path + "' and '" + b.path + "' are from different renders (" + what + ")");
    };
    if (a.count != b.count) fail("tile counts " + std::to_string(a.count) + " and " + std::to_string(b.count));
    if (a.fullWidth != b.fullWidth || a.fullHeight != b.fullHeight) fail("full resolutions differ");
    if (a.image.channelNames() != b.image.channelNames()) fail("channels differ");
    std::map<std::string, std::string> ma, mb;
    for (const auto& [k, v] : a.metadata)
        if (!placementOrCounter(k)) ma[k] = v;
    for (const auto& [k, v] : b.metadata)
        if (!placementOrCounter(k)) mb[k] = v;
    for (const auto& [k, v] : ma)
        if (!mb.count(k) || mb[k] != v) fail(k + " '" + v + "' vs '" + (mb.count(k) ? mb[k] : std::string("(none)")) + "'");
    for (const auto& [k, v] : mb)
        if (!ma.count(k)) fail(k + " only in the second");
}

void checkPlacement(const Tile& t) {
    const RowBand band = tileRows(t.fullHeight, t.index, t.count);
    if (t.window.x != 0 || t.window.y != band.begin || t.image.width() != t.fullWidth ||
        t.image.height() != band.end - band.begin)
        throw Error("merge: '" + t.path + "' holds rows " + std::to_string(t.window.y) + ".." +
                    std::to_string(t.window.y + t.image.height() - 1) + " but tile " + std::to_string(t.index) + "/" +
                    std::to_string(t.count) + " is rows " + std::to_string(band.begin) + ".." + std::to_string(band.end - 1));
}

std::vector<Tile> readCheckedSet(const std::vector<std::string>& paths) {
    if (paths.empty()) throw Error("merge: no tiles given");
    std::vector<Tile> tiles;
    for (const std::string& p : paths) tiles.push_back(readTile(p));
    std::map<int, std::string> byIndex;
    for (const Tile& t : tiles) {
        checkSameRender(tiles.front(), t);
        checkPlacement(t);
        if (auto [it, fresh] = byIndex.emplace(t.index, t.path); !fresh)
            throw Error("merge: tile " + std::to_string(t.index) + "/" + std::to_string(t.count) + " given twice ('" +
                        it->second + "' and '" + t.path + "')");
    }
    std::string missing;
    for (int i = 1; i <= tiles.front().count; ++i)
        if (!byIndex.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    if (!missing.empty())
        throw Error("merge: incomplete set: missing tile(s) " + missing + " of " + std::to_string(tiles.front().count));
    return tiles;
}

// A counter attribute as a non-negative count; anything else is a corrupt tile.
long long counterValue(const Tile& t, const std::string& key, const std::string& value) {
    long long n = 0;
    if (!parseWhole(value, n) || n < 0)
        throw Error("merge: '" + t.path + "': attribute " + key + " is not a count (corrupt tile)");
    return n;
}

Metadata mergedMetadata(const std::vector<Tile>& tiles) {
    std::map<std::string, long long> counters;
    for (const Tile& t : tiles)
        for (const auto& [k, v] : t.metadata)
            if (k.rfind("weft:counter:", 0) == 0) {
                const long long n = counterValue(t, k, v);
                counters[k] = n > LLONG_MAX - counters[k] ? LLONG_MAX : counters[k] + n;
            }
    Metadata md;
    for (const auto& [k, v] : tiles.front().metadata) {
        if (k.rfind("weft:counter:", 0) == 0) md.emplace_back(k, std::to_string(counters[k]));
        else if (!placementOrCounter(k)) md.emplace_back(k, v);
    }
    md.emplace_back("weft:merged_tiles", std::to_string(tiles.size()));
    md.emplace_back("weft:complete", "1");
    return md;
}

}  // namespace

MergedFrame mergeTiles(const std::vector<std::string>& paths) {
    const std::vector<Tile> tiles = readCheckedSet(paths);
    const Tile& first = tiles.front();
    MergedFrame out{Image(first.fullWidth, first.fullHeight, first.image.channelNames()), mergedMetadata(tiles)};
    for (const Tile& t : tiles)
        std::copy(t.image.data().begin(), t.image.data().end(),
                  out.image.data().begin() + std::ptrdiff_t(std::size_t(t.window.y) * t.fullWidth * t.image.channelCount()));
    return out;
}

}  // namespace weft
