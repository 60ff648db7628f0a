#pragma once
// The entry points of an external plugin: a shared library named
// "<anything>.weft.so" in a folder on WEFT_PLUGIN_PATH (colon-separated).
// It must define both functions with C linkage:
//
//   extern "C" int weft_plugin_abi_version() { return WEFT_PLUGIN_ABI_VERSION; }
//   extern "C" void weft_plugin_register(weft::TechniqueRegistry* registry) {
//       registry->add({"my.technique", "summary", weft::ParamTable(...), factory});
//   }
//
// The host refuses a plugin whose ABI version differs from its own: plugins
// share C++ types with the host, so they must be rebuilt against its headers.
#include "plugins/technique.hpp"

#define WEFT_PLUGIN_ABI_VERSION 3  // 3: TechniqueInfo gained reference and knobs

extern "C" {
typedef int (*weft_plugin_abi_version_fn)();
typedef void (*weft_plugin_register_fn)(weft::TechniqueRegistry*);
}

namespace weft {

// Loads every *.weft.so on WEFT_PLUGIN_PATH once; errors name the file.
void loadExternalPlugins();

}  // namespace weft
