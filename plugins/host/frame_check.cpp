#include "plugins/host/frame_check.hpp"

#include <filesystem>

#include "core/image/io/image_io.hpp"

namespace weft {

std::string frameState(const std::string& path) {
    if (!std::filesystem::exists(path)) return "missing";
    Metadata md;
    try {
        readImage(path, &md);  // reads every pixel: a truncated file fails here
    } catch (const std::exception& e) {
        std::string why = e.what();
        for (char& c : why)
            if (c == '\n' || c == '\t') c = ' ';
        return "corrupt: " + why;
    }
    for (const auto& [k, v] : md)
        if (k == "weft:complete" && v == "1") return "ok";
    return "corrupt: no weft:complete attribute";
}

}  // namespace weft
