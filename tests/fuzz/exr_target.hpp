#pragma once
// Fuzz target: EXR files as `weft diff`, `weft merge` and `weft filter`
// read them (core/image/io/image_io.cpp through the OpenImageIO module), then
// what each command does next with the image: the comparison metrics, the
// tile checks of a merge and the A-Trous filter's channel lookup.
#include "core/image/io/exr_preflight.hpp"
#include "core/image/compare/image_compare.hpp"
#include "core/image/io/image_io.hpp"
#include "core/screen/atrous.hpp"
#include "plugins/host/tile_merge.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

// Headers that declare more than this many pixel values (64 KB of floats) are
// legitimate, but reading them would spend each execution clearing buffers
// instead of parsing: such inputs are checked by the preflight only.
constexpr std::uint64_t kMaxFuzzedPixelValues = 1u << 14;

inline Outcome exrFile(const std::uint8_t* data, std::size_t size) {
    const std::string path = writeScratch("image.exr", asText(data, size));
    ExrDeclared declared;
    const Outcome preflight = guarded([&] { declared = preflightExr(path); });
    if (!preflight.accepted) return preflight;
    if (declared.pixelValues > kMaxFuzzedPixelValues || declared.displayPixels > kMaxFuzzedPixelValues) {
        Outcome o{true, ""};
        o.skipped = true;
        return o;
    }
    const Outcome read = guarded([&] {
        Metadata metadata;
        ImageWindow window;
        Image image = readImage(path, &metadata, &window);
        require(image.data().size() == std::size_t(image.width()) * image.height() * image.channelCount(),
                "pixel count matches the size");
        if (image.channelCount() > 0 && image.width() > 0 && image.height() > 0) compareImages(image, image);
        AtrousSettings settings;
        settings.levels = 2;
        atrousFilterImage(image, "", "N", "P", settings);
    });
    const Outcome merged = guarded([&] { mergeTiles({path}); });
    return merged.accepted ? merged : read;
}

}  // namespace weft::fuzz
