#include "core/base/files/module_loader.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "core/base/error.hpp"

namespace weft {

namespace {

std::vector<std::string> candidatePaths(const std::string& fileName, const char* envVar) {
    std::vector<std::string> paths;
    if (const char* env = std::getenv(envVar)) paths.emplace_back(env);
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) paths.push_back((exe.parent_path() / fileName).string());
    Dl_info self{};
    if (dladdr(reinterpret_cast<const void*>(&candidatePaths), &self) && self.dli_fname) {
        const std::string beside = (std::filesystem::path(self.dli_fname).parent_path() / fileName).string();
        if (std::find(paths.begin(), paths.end(), beside) == paths.end()) paths.push_back(beside);
    }
    paths.push_back(fileName);
    return paths;
}

}  // namespace

const void* loadModule(const std::string& fileName, const char* envVar, const char* entry,
                       const std::function<bool(const void*)>& accepts) {
    std::string tried;
    for (const std::string& path : candidatePaths(fileName, envVar)) {
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            tried += (tried.empty() ? "" : "; ") + std::string(dlerror());
            continue;
        }
        auto function = reinterpret_cast<const void* (*)()>(dlsym(handle, entry));
        const void* module = function ? function() : nullptr;
        if (module && accepts(module)) return module;
        tried += (tried.empty() ? "" : "; ") + path + ": not the weft module this build expects";
    }
    throw Error("cannot load the module " + fileName + " (" + tried + ")");
}

}  // namespace weft
