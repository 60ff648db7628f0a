#pragma once
// What a scene file's "render" block may say, as typed values: the technique
// and its parameters, the image size, the samples per pixel and the seed.
// A render request says the same things (and wins over the scene); where the
// files go and how many threads render belong to the request alone
// (core/base/options/render_options.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace weft {

// An image size whose sides are in [1, 65536] once parsed or checked.
struct Resolution {
    int width = 0;
    int height = 0;

    bool valid() const;
    std::string text() const;  // "WxH"
    bool operator==(const Resolution&) const = default;
};

// "WxH" (or "WXH") with W and H in [1, 65536]; nullopt for anything else.
std::optional<Resolution> readResolution(const std::string& text);
// readResolution, or an Error naming the text.
Resolution parseResolution(const std::string& text);
// A resolution built in code, held to the same limits and error as parseResolution.
void requireValid(const Resolution& resolution);

struct SceneRender {
    std::optional<std::string> technique;
    std::vector<std::string> sets;  // "key=value", later ones win
    std::optional<Resolution> resolution;
    std::optional<int> spp;
    std::optional<std::uint64_t> seed;
};

}  // namespace weft
