#include "core/image/image_codec.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "core/base/error.hpp"

namespace weft {

namespace {

// WEFT_IMAGE_CODEC if set, else weft_oiio.so beside the running executable,
// else beside the shared object this code is in (the Python module, whose
// executable is python3), else the loader's own search (LD_LIBRARY_PATH).
std::vector<std::string> candidatePaths() {
    std::vector<std::string> paths;
    if (const char* env = std::getenv("WEFT_IMAGE_CODEC")) paths.emplace_back(env);
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) paths.push_back((exe.parent_path() / "weft_oiio.so").string());
    Dl_info self{};
    if (dladdr(reinterpret_cast<const void*>(&candidatePaths), &self) && self.dli_fname) {
        const std::string beside = (std::filesystem::path(self.dli_fname).parent_path() / "weft_oiio.so").string();
        if (std::find(paths.begin(), paths.end(), beside) == paths.end()) paths.push_back(beside);
    }
    paths.emplace_back("weft_oiio.so");
    return paths;
}

const ImageCodec* load() {
    std::string tried;
    for (const std::string& path : candidatePaths()) {
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            tried += (tried.empty() ? "" : "; ") + std::string(dlerror());
            continue;
        }
        auto entry = reinterpret_cast<const ImageCodec* (*)()>(dlsym(handle, "weft_image_codec"));
        const ImageCodec* codec = entry ? entry() : nullptr;
        if (codec && codec->abiVersion == kImageCodecAbi) return codec;
        tried += "; " + path + ": not a weft image codec of ABI " + std::to_string(kImageCodecAbi);
    }
    throw Error("cannot load the image codec module weft_oiio.so (" + tried + ")");
}

}  // namespace

const ImageCodec& imageCodec() {
    static std::once_flag once;
    static const ImageCodec* codec = nullptr;
    static std::string failure;
    std::call_once(once, [] {
        try {
            codec = load();
        } catch (const Error& e) {
            failure = e.what();
        }
    });
    if (!codec) throw Error(failure);
    return *codec;
}

}  // namespace weft
