#pragma once
// Analytic 2D test images with exact pixel integrals, so that aliasing and
// error are measured against the truth, not eyeballed. Coordinates are
// continuous pixels ((0,0) the top-left corner); each scene scales with the
// image size. Values are grey in [0, 1].
//   zoneplate  0.5 + 0.5 cos(k r^2), local frequency 2 cycles/pixel at r = W/2;
//              exact box integrals are separable 1D (Fresnel) integrals
//   grating    0.5 + 0.5 cos(2 pi f . x), f = (1.37, 0.29) cycles/pixel: one
//              tone above every sampling rate below 9 spp; exact (sinc)
//   checker    a checkerboard plane in perspective up to a far edge, sky 0.5
//              beyond; exact by clipping projected squares to the pixel
//   siemens    Siemens star of 36 wedges about the centre; exact by clipping
//   lines      12 thin lines at 6 degrees (fewer below 48 rows), 0.1 to 1.5
//              pixels wide; exact
//   disc       a disc moving right during the shutter (t in [0, 1)); its
//              time-averaged coverage of a point is closed form, its pixel
//              integral exact in x and adaptive Simpson in y (to 1e-10)
#include <string>
#include <vector>

namespace weft {

enum class AnalyticScene { ZonePlate, Grating, Checker, Siemens, Lines, Disc };

const char* analyticSceneNames();  // "zoneplate|grating|checker|siemens|lines|disc"
bool isAnalyticSceneName(const std::string& name);
AnalyticScene analyticSceneFromName(const std::string& name);

class AnalyticImage {
public:
    AnalyticImage(AnalyticScene scene, int width, int height);

    // Point sample at image position (x, y) and shutter time t.
    double value(double x, double y, double t) const;
    // The exact mean over pixel (px, py) (and over the shutter for the disc).
    double pixelIntegral(int px, int py) const;
    // disc: the fraction of the shutter during which (x, y) is covered.
    double timeCoverage(double x, double y) const;

private:
    double checkerValue(double x, double y) const;
    double checkerIntegral(int px, int py) const;
    double discRowIntegral(double y, double x0, double x1) const;
    double discIntegral(int px, int py) const;

    AnalyticScene scene_;
    int w_, h_;
    double cx_, cy_;
    double zoneK_;                                    // zone plate
    double gratingFx_ = 1.37, gratingFy_ = 0.29;     // grating
    double horizon_, focal_, square_, farY_;         // checker
    int wedges_ = 36;                                 // siemens
    std::vector<double> lineOffset_, lineWidth_;      // lines
    double lineAngle_;
    double discR_, discX0_, discX1_;                  // disc
};

}  // namespace weft
