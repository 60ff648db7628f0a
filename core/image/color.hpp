#pragma once
// Colour management through OpenColorIO. weft renders scene-linear Rec.709;
// previews go through a display transform. With $OCIO set, the studio's
// config (its default display and view) is used; otherwise a small built-in
// config: lin_rec709 (the scene_linear role), acescg (linear AP1 primaries,
// ACEScg) and srgb_display (IEC 61966-2-1 curve); its display is sRGB.
#include <memory>
#include <string>

namespace weft {

class DisplayTransform {
public:
    virtual ~DisplayTransform() = default;
    // The display's 8-bit values of count interleaved scene-linear RGB
    // pixels. The pixels reach OpenColorIO as half floats, which lets it
    // apply the transform through tables (a tenth of the time of float
    // input; a value lands one step of 255 off in under 1% of cases); NaN
    // and Inf show as the display's black.
    virtual void encode8(const float* rgb, unsigned char* out, int count) const = 0;
    virtual std::string description() const = 0;
};

// The process-wide display transform (built once, thread-safe to use).
const DisplayTransform& displayTransform();

class Image;

// A conversion between two colour spaces of the active config, applied to
// the R, G, B channels of an image (alpha and other channels kept). Colours
// are un-premultiplied by alpha around the conversion where 0 < alpha < 1,
// so non-linear encodings see the surface colour; non-finite results are 0.
class ColorConversion {
public:
    virtual ~ColorConversion() = default;
    virtual void apply(Image& image) const = 0;
};

// CIE XYZ (D65 white at Y = 1) to the config's scene_linear, in place
// (interleaved, count colours), through its cie_xyz_d65_interchange role;
// an Error when the config has none.
void xyzToSceneLinear(float* xyz, int count);

// An Error naming the colour space (and listing the config's) when one is unknown.
std::unique_ptr<ColorConversion> colorConversion(const std::string& from, const std::string& to);

}  // namespace weft
