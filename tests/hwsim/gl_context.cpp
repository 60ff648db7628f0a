#include "tests/hwsim/gl_context.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace weft::gl {

void fail(const std::string& why) {
    std::printf("ERROR %s\n", why.c_str());
    std::fflush(stdout);
    std::exit(2);
}

namespace {

template <class Fn>
Fn eglProc(const char* name) {
    return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

bool clientHas(const char* extension) {
    const char* all = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    return all && std::strstr(all, extension);
}

// Mesa's surfaceless display, else the first device's; EGL_NO_DISPLAY if neither.
EGLDisplay headlessDisplay() {
    auto getDisplay = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!getDisplay) fail("EGL has no eglGetPlatformDisplayEXT (EGL_EXT_platform_base)");
    if (clientHas("EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
    }
    auto queryDevices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    if (!clientHas("EGL_EXT_platform_device") || !queryDevices) return EGL_NO_DISPLAY;
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (!queryDevices(8, devices, &count)) return EGL_NO_DISPLAY;
    for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = getDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
    }
    return EGL_NO_DISPLAY;
}

// A config for GL rendering (some EGLs lack EGL_KHR_no_config_context).
EGLConfig anyGlConfig(EGLDisplay display) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n = 0;
    if (!eglChooseConfig(display, attribs, &config, 1, &n) || n < 1) return nullptr;
    return config;
}

}  // namespace

void makeContext(int major, int minor) {
    EGLDisplay display = headlessDisplay();
    if (display == EGL_NO_DISPLAY)
        fail("no headless EGL display (neither Mesa's surfaceless platform nor an EGL device; is libegl-mesa0 installed?)");
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
    const char* displayExtensions = eglQueryString(display, EGL_EXTENSIONS);
    const bool noConfig = displayExtensions && std::strstr(displayExtensions, "EGL_KHR_no_config_context");
    EGLContext ctx = eglCreateContext(display, noConfig ? EGL_NO_CONFIG_KHR : anyGlConfig(display), EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT)
        fail("eglCreateContext (GL " + std::to_string(major) + "." + std::to_string(minor) +
             " compatibility) failed, EGL error 0x" + std::to_string(eglGetError()));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) fail("eglMakeCurrent without a surface failed");
}

bool hasExtension(const char* name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
    return false;
}

std::string rendererString() {
    return std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + " | " +
           reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

namespace {

// Fails with the driver's log of `object` unless its compile or link status is set.
void requireStatus(GLint ok, GLuint object, void (*infoLog)(GLuint, GLsizei, GLsizei*, GLchar*), const char* what) {
    if (ok) return;
    char log[2048];
    infoLog(object, sizeof log, nullptr, log);
    fail(std::string(what) + ": " + log);
}

}  // namespace

GLuint compileShader(GLenum type, const std::string& source) {
    GLuint s = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    requireStatus(ok, s, glGetShaderInfoLog, "shader compile");
    return s;
}

GLuint linkProgram(const std::string& vertexSource, const std::string& fragmentSource) {
    GLuint prog = glCreateProgram();
    glAttachShader(prog, compileShader(GL_VERTEX_SHADER, vertexSource));
    glAttachShader(prog, compileShader(GL_FRAGMENT_SHADER, fragmentSource));
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    requireStatus(ok, prog, glGetProgramInfoLog, "program link");
    return prog;
}

}  // namespace weft::gl
