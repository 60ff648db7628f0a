#pragma once
// A hardware profile: what the API leaves to the implementation and the
// model cannot know — which tests run before the fragment program and when
// that is lost, how finely the program is scheduled, and which features
// exist. Profiles are JSON data files (hwsim/profiles/*.json, compiled into
// the binary); hwsim/profiles/README.md documents every field.
#include <string>
#include <vector>

#include "hwsim/cost_model.hpp"
#include "hwsim/raster.hpp"

namespace weft::hwsim {

// Where stippled fragments die: at scan conversion; as a kill at the start of
// the program (it runs, the fragment is gone before its body); after the program.
enum class StipplePosition { Rasterizer, ProgramStart, Late };
enum class EarlyTests { PerPixel, CoarseOnly, None };  // depth/stencil/bounds tests before the program
enum class BoundsSupport { Early, WithDepthTest, Late, Unsupported };  // WithDepthTest: early exactly when depth is
enum class DiscardRule { Never, Always, WithStencilWrites, WithDepthOrStencilWrites };
enum class ShadingGranularity { Pixel, Quad };

struct Profile {
    std::string name;
    std::string description;
    std::string sources;  // where the behaviour is documented or reported
    FillRule fillRule = FillRule::TopLeft;  // who owns centres exactly on an edge
    bool floatSpans = false;               // scan triangles as softpipe does (float spans), not by edge functions
    StipplePosition stipple = StipplePosition::Rasterizer;
    EarlyTests earlyTests = EarlyTests::PerPixel;
    int coarseTile = 0;                 // hierarchical Z/stencil tile side (pixels), 0: none
    bool coarseStencil = false;         // tiles are culled on stencil as well as depth
    BoundsSupport bounds = BoundsSupport::Early;
    bool boundsChangeForcesLate = false;       // new bounds within a frame lose the early bounds test
    bool directionChangeDisablesCoarse = false;  // LESS <-> GREATER within a frame loses coarse culling until a clear
    DiscardRule discardForcesLate = DiscardRule::Never;  // otherwise: test early, write after the program
    bool sideEffectsForceLate = true;   // programs with memory side effects run before the tests (GL rule)
    bool stippleMirroredWithPosition = false;  // (softpipe) stipple rows mirrored in y when the program reads its position
    bool earlyNeedsDepthTest = false;    // no early tests (stencil, bounds) unless the depth test is on
    bool emptyQuadsStillRun = false;     // with stencil on, a quad emptied by early stencil/depth still runs (4 lanes counted)
    bool queryCountsAtEarlyTests = true; // with early_fragment_tests, SAMPLES_PASSED counts before a discard (GL spec)
    ShadingGranularity shading = ShadingGranularity::Pixel;
    int branchBlockW = 1, branchBlockH = 1;  // pixels executing one program in lock step (dynamic branching)
    bool lockStepWholeBlock = false;          // a block that runs costs all its lanes, not only its shaded quads
    bool polygonStipple = true;               // feature present
    CostModel cost;                           // predicted times (cost_model.hpp)
    // FRAGMENT_SHADER_INVOCATIONS: w x h for each screen-aligned block of that
    // size in which a primitive runs the program; [1, 1] counts each
    // non-helper run, [2, 2] each quad.
    int statsStampW = 1, statsStampH = 1;
    bool statsCountedAtScan = false;  // stamps with covered pixels inside the scissor (before stipple and every test) count
    bool clippingOutputSkipsZeroArea = false;  // CLIPPING_OUTPUT_PRIMITIVES leaves out zero-area triangles

    // Throws weft::Error naming the profile and the missing feature.
    void require(bool featurePresent, const std::string& feature, const std::string& who) const;
};

// Parses one profile file's text; errors name the file, the key and the valid values.
Profile parseProfile(const std::string& jsonText, const std::string& fileName);
// The profiles compiled into the binary, sorted by name.
const std::vector<Profile>& builtinProfiles();
// A built-in profile by name, or a path to a .json file.
const Profile& findProfile(const std::string& nameOrPath);

}  // namespace weft::hwsim
