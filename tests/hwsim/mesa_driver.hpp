#pragma once
// The command prefix that runs a GL program of ours (weft_mesa_check,
// weft_gl_probe) on one of Mesa's software drivers, headless: the Gallium
// driver, the surfaceless EGL platform, and Mesa's EGL vendor even where
// another vendor (a GPU driver) is installed.
#include <filesystem>
#include <string>

namespace weft::crosscheck {

inline std::string mesaDriverEnv(const std::string& driver) {
    const char* mesaVendor = "/usr/share/glvnd/egl_vendor.d/50_mesa.json";
    const std::string vendor = std::filesystem::exists(mesaVendor) ? std::string(" __EGL_VENDOR_LIBRARY_FILENAMES=") + mesaVendor : "";
    return "env GALLIUM_DRIVER=" + driver + " LIBGL_ALWAYS_SOFTWARE=1 EGL_PLATFORM=surfaceless" + vendor + " ";
}

}  // namespace weft::crosscheck
