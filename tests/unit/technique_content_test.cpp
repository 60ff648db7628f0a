// What a technique renders: a scene holding content it cannot render is
// refused with one line naming what it would drop and the techniques that
// render it all (no registered technique drops volumes any more, so a
// mesh-only one is made here).
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "plugins/technique.hpp"

using namespace weft;

TEST(TechniqueContent, AMeshOnlyTechniqueRefusesAVolumeAndNamesTheTechniquesThatRenderBoth) {
    Scene scene;
    scene.source = "mixed.json";
    scene.volumes.emplace_back(), scene.meshes.emplace_back();
    TechniqueInfo info{"test.meshes_only", "renders meshes only", ParamTable("test.meshes_only", {}), nullptr};
    info.renders = Content::Meshes;
    try {
        checkTechniqueContent(info, scene);
        FAIL() << "accepted a volume it cannot render";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("test.meshes_only renders meshes, and the scene 'mixed.json' also has 1 volume it would drop"), std::string::npos) << what;
        for (const char* able : {"lighting.adaptive_indirect", "lighting.vpl_deferred", "mesh.pathtrace", "volume.singlescatter"})
            EXPECT_NE(what.find(able), std::string::npos) << able << ": " << what;
    }
    info.renders = Content::VolumesAndMeshes;
    EXPECT_NO_THROW(checkTechniqueContent(info, scene));
}
