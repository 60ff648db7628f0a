#pragma once
// weft's optional modules: shared objects beside the executable that link
// a heavy library (OpenImageIO, Assimp) which only some commands need, so
// that a process loads it the first time it needs it instead of resolving
// its symbols at every start-up.
#include <functional>
#include <mutex>
#include <string>

#include "core/base/error.hpp"

namespace weft {

// Opens the module `fileName` and returns what its extern "C" function
// `entry` (no arguments, returning `const void*`: called through exactly
// that type) returns, the first one `accepts` (the caller's ABI
// check). Tried in order: the path in environment variable `envVar` if set,
// fileName beside the running executable, beside the shared object this
// code is in (the Python module, whose executable is python3), then the
// loader's own search (LD_LIBRARY_PATH). Throws weft::Error naming every
// path tried and why it failed.
const void* loadModule(const std::string& fileName, const char* envVar, const char* entry,
                       const std::function<bool(const void*)>& accepts);

// A module's table of functions (a struct whose first member is `int
// abiVersion`), loaded once per process, thread-safe; every call after a
// failed load throws the same error.
template <class Codec>
const Codec& moduleCodec(const char* fileName, const char* envVar, const char* entry, int abi) {
    static std::once_flag once;
    static const Codec* codec = nullptr;
    static std::string failure;
    std::call_once(once, [&] {
        try {
            codec = static_cast<const Codec*>(loadModule(fileName, envVar, entry, [abi](const void* m) {
                return static_cast<const Codec*>(m)->abiVersion == abi;
            }));
        } catch (const Error& e) {
            failure = e.what();
        }
    });
    if (!codec) throw Error(failure);
    return *codec;
}

}  // namespace weft
