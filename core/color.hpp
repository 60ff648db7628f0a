#pragma once
// Colour management through OpenColorIO. weft renders scene-linear Rec.709;
// previews go through a display transform. With $OCIO set, the studio's
// config (its default display and view) is used; otherwise a small built-in
// config: linear Rec.709 -> sRGB display (IEC 61966-2-1 curve).
#include <memory>
#include <string>

namespace weft {

class DisplayTransform {
public:
    virtual ~DisplayTransform() = default;
    // In place, interleaved RGB, count pixels.
    virtual void apply(float* rgb, int count) const = 0;
    virtual std::string description() const = 0;
};

// The process-wide display transform (built once, thread-safe to use).
const DisplayTransform& displayTransform();

}  // namespace weft
