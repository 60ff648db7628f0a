#pragma once
// A headless GL context through EGL for the programs that drive a real GL
// (weft_mesa_check, weft_gl_probe). Mesa's surfaceless platform first (the
// Gallium driver is chosen by GALLIUM_DRIVER); where that platform is absent
// (a GPU vendor's EGL, e.g. NVIDIA's), the first EGL device
// (EGL_EXT_platform_device). Rendering goes to framebuffer objects: no
// surface is made. Failures print "ERROR reason" and exit 2.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <string>

namespace weft::gl {

[[noreturn]] void fail(const std::string& why);

// A compatibility-profile context of at least the given version (polygon
// stipple is compatibility-only), made current without a surface.
void makeContext(int major, int minor);

bool hasExtension(const char* name);

// "renderer | version" of the current context.
std::string rendererString();

// Compiles one shader; a compile error fails with the driver's log.
GLuint compileShader(GLenum type, const std::string& source);
// Links a vertex and a fragment shader; a link error fails with the log.
GLuint linkProgram(const std::string& vertexSource, const std::string& fragmentSource);

}  // namespace weft::gl
