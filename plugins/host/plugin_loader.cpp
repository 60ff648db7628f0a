#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <sstream>

#include "plugins/plugin_api.hpp"

namespace fs = std::filesystem;

namespace weft {

namespace {

void loadOne(const fs::path& file) {
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw Error("plugin '" + file.string() + "': " + dlerror());
    auto version = reinterpret_cast<weft_plugin_abi_version_fn>(dlsym(handle, "weft_plugin_abi_version"));
    auto reg = reinterpret_cast<weft_plugin_register_fn>(dlsym(handle, "weft_plugin_register"));
    if (!version || !reg)
        throw Error("plugin '" + file.string() + "': missing weft_plugin_abi_version or weft_plugin_register");
    if (const int v = version(); v != WEFT_PLUGIN_ABI_VERSION)
        throw Error("plugin '" + file.string() + "': built for plugin ABI " + std::to_string(v) + ", this weft speaks " +
                    std::to_string(WEFT_PLUGIN_ABI_VERSION) + "; rebuild it against this weft");
    reg(&techniques());  // the library stays loaded for the life of the process
}

}  // namespace

void loadExternalPlugins() {
    static std::once_flag once;
    std::call_once(once, [] {
        const char* path = std::getenv("WEFT_PLUGIN_PATH");
        if (!path) return;
        std::stringstream dirs(path);
        for (std::string dir; std::getline(dirs, dir, ':');) {
            if (dir.empty() || !fs::is_directory(dir)) continue;
            std::vector<fs::path> files;
            for (const auto& entry : fs::directory_iterator(dir)) {
                const std::string name = entry.path().filename().string();
                if (name.size() > 8 && name.compare(name.size() - 8, 8, ".weft.so") == 0) files.push_back(entry.path());
            }
            std::sort(files.begin(), files.end());  // deterministic order
            for (const auto& f : files) loadOne(f);
        }
    });
}

}  // namespace weft
