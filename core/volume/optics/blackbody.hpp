#pragma once
// The colour of a Planckian (black-body) radiator: its spectral radiance
// integrated against the CIE 1931 observer (cie1931.hpp), normalised to
// luminance Y = 1 and brought to the scene's linear space through
// OpenColorIO (the config's cie_xyz_d65_interchange role). Colours out of
// the scene space's gamut (the reddest temperatures in Rec.709) are clipped
// at 0 per channel, so emission is never negative.
#include <vector>

#include "core/scene/camera.hpp"

namespace weft {

// Temperatures whose chromaticity is tabulated; colder and hotter ones take
// the nearest end's (at 800 K a radiator is already a dim red; past 40000 K
// the chromaticity barely moves).
constexpr double kBlackbodyColdestK = 800, kBlackbodyHottestK = 40000;

// CIE 1931 XYZ of a radiator at `kelvin` (clamped to the range above),
// normalised to Y = 1: the 5 nm table summed exactly.
Vec3d blackbodyXyz(double kelvin);

// The same in the scene's linear space, by a table even in mireds
// (1e6 / kelvin), where the chromaticity is smooth; built once, shared.
class BlackbodyTable {
public:
    static const BlackbodyTable& get();  // throws weft::Error when the OCIO config has no XYZ role
    Vec3f color(double kelvin) const;

private:
    BlackbodyTable();
    std::vector<Vec3f> rgb_;
};

}  // namespace weft
