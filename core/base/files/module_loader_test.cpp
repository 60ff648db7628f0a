// Modules load from beside the executable; a missing or foreign one is a
// one-line error naming every path tried.
#include <gtest/gtest.h>

#include "core/base/files/module_loader.hpp"
#include "core/image/io/image_codec.hpp"
#include "core/mesh/mesh_codec.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

TEST(ModuleLoader, FindsTheCodecModulesBesideTheExecutable) {
    EXPECT_EQ(imageCodec().abiVersion, kImageCodecAbi);
    EXPECT_EQ(meshCodec().abiVersion, kMeshCodecAbi);
}

TEST(ModuleLoader, AMissingModuleNamesThePathsTried) {
    const std::string error = test::errorOf([] { loadModule("weft_no_such_module.so", "WEFT_NO_SUCH_MODULE", "entry", [](const void*) { return true; }); });
    EXPECT_NE(error.find("cannot load the module weft_no_such_module.so"), std::string::npos) << error;
    EXPECT_NE(error.find("/weft_no_such_module.so"), std::string::npos) << error;  // the path beside the executable
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(ModuleLoader, AModuleOfAnotherAbiIsRefused) {
    const std::string error = test::errorOf([] { loadModule("weft_oiio.so", "WEFT_NO_SUCH_MODULE", "weft_image_codec", [](const void*) { return false; }); });
    EXPECT_NE(error.find("not the weft module this build expects"), std::string::npos) << error;
}

}  // namespace
}  // namespace weft
