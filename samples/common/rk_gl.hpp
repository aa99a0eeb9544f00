// raykit samples — rk_gl.hpp: a headless OpenGL 4.5 core context through EGL, plus the few GL
// helpers the samples and GPU tests share (program building with raykit includes resolved, SSBO
// round trips, an RGBA8 framebuffer read back).
//
// Copy it into an engine as a starting point; it is not part of the raykit::raykit target because
// it needs EGL and OpenGL. Platform order: EGL_EXT_platform_device (a real GPU first, then any
// device), EGL_MESA_platform_surfaceless (Mesa llvmpipe), then the default display. Set
// RAYKIT_EGL_PLATFORM=device|surfaceless|default to force one.
#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raykit/shader_source.hpp"

namespace rkgl {

class HeadlessContext {
public:
    HeadlessContext() = default;
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;
    ~HeadlessContext()
    {
        if (display_ != EGL_NO_DISPLAY) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
            eglTerminate(display_);
        }
    }

    /// Creates and makes current an OpenGL 4.5 core context. Returns false with error() set.
    bool create()
    {
        const char* force = std::getenv("RAYKIT_EGL_PLATFORM");
        const std::string want = force ? force : "";
        const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        const std::string ext = client_ext ? client_ext : "";
        auto get_platform_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));

        if ((want.empty() || want == "device") && ext.find("EGL_EXT_platform_device") != std::string::npos &&
            get_platform_display) {
            auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
            auto query_device_string =
                reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
            EGLDeviceEXT devices[16];
            EGLint count = 0;
            if (query_devices && query_devices(16, devices, &count)) {
                // Hardware devices first, software (llvmpipe) last.
                for (int pass = 0; pass < 2 && context_ == EGL_NO_CONTEXT; ++pass) {
                    for (EGLint i = 0; i < count && context_ == EGL_NO_CONTEXT; ++i) {
                        const char* dext = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : "";
                        const bool software = dext && std::strstr(dext, "EGL_MESA_device_software");
                        if ((pass == 0) == software) continue;
                        try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device");
                    }
                }
            }
        }
        if (context_ == EGL_NO_CONTEXT && (want.empty() || want == "surfaceless") &&
            ext.find("EGL_MESA_platform_surfaceless") != std::string::npos && get_platform_display) {
            try_display(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                        "surfaceless");
        }
        if (context_ == EGL_NO_CONTEXT && (want.empty() || want == "default")) {
            try_display(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default");
        }
        if (context_ == EGL_NO_CONTEXT) {
            if (error_.empty()) error_ = "no EGL platform available (client extensions: " + ext + ")";
            return false;
        }
        return true;
    }

    const std::string& error() const { return error_; }
    const std::string& platform() const { return platform_; }
    std::string renderer() const
    {
        const GLubyte* r = glGetString(GL_RENDERER);
        const GLubyte* v = glGetString(GL_VERSION);
        return std::string(r ? reinterpret_cast<const char*>(r) : "?") + " | " +
               (v ? reinterpret_cast<const char*>(v) : "?") + " | EGL platform " + platform_;
    }

private:
    void try_display(EGLDisplay dpy, const char* name)
    {
        if (dpy == EGL_NO_DISPLAY) return;
        EGLint major = 0, minor = 0;
        if (!eglInitialize(dpy, &major, &minor)) {
            error_ += std::string("eglInitialize failed on the ") + name + " platform; ";
            return;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            error_ += std::string("no desktop OpenGL on the ") + name + " platform; ";
            eglTerminate(dpy);
            return;
        }
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint num = 0;
        eglChooseConfig(dpy, config_attribs, &config, 1, &num);
        const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLContext ctx = eglCreateContext(dpy, num > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
        if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            error_ += std::string("no OpenGL 4.5 core surfaceless context on the ") + name + " platform; ";
            if (ctx != EGL_NO_CONTEXT) eglDestroyContext(dpy, ctx);
            eglTerminate(dpy);
            return;
        }
        display_ = dpy;
        context_ = ctx;
        platform_ = name;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    std::string error_;
    std::string platform_;
};

/// True when running under CI: the CI environment variable is set to anything but "", "0" or
/// "false" (CI services set CI=true; some set CI=1).
inline bool in_ci()
{
    const char* ci = std::getenv("CI");
    if (!ci) return false;
    const std::string v(ci);
    return !(v.empty() || v == "0" || v == "false" || v == "False" || v == "FALSE");
}

/// The exit code of a program that found no OpenGL 4.5 context: 77 (ctest's "skipped") normally,
/// 1 (failed) under CI, where a missing device must never pass as a skip. Prints why.
inline int no_context_exit(const char* program, const std::string& error)
{
    const bool ci = in_ci();
    std::fprintf(stderr, "%s: %s: no headless OpenGL 4.5 context: %s\n", program, ci ? "FAIL (under CI)" : "SKIP", error.c_str());
    return ci ? 1 : 77;
}

/// A shader's text with its includes resolved and `defines` injected after #version
/// (raykit::resolve_shader; `dir` is searched first, then include_dirs). The samples use
/// exceptions, raykit does not: a resolver error becomes std::runtime_error here.
inline std::string resolved_shader(const std::string& source, const std::string& name, const std::string& dir,
                                   const std::vector<std::string>& include_dirs,
                                   const std::vector<raykit::ShaderDefine>& defines = {})
{
    raykit::ShaderSourceOptions opt;
    opt.include_dirs = include_dirs;
    opt.defines = defines;
    raykit::ShaderSource out;
    raykit::Status st;
    if (!raykit::resolve_shader(source, name, dir, opt, out, st)) throw std::runtime_error(st.message);
    return out.text;
}

/// The file at `path`, resolved as resolved_shader does (its own folder searched first).
inline std::string shader_file(const std::string& path, const std::vector<std::string>& include_dirs,
                               const std::vector<raykit::ShaderDefine>& defines = {})
{
    raykit::Status st;
    std::string text = raykit::load_shader_file(path, include_dirs, defines, nullptr, &st);
    if (!st) throw std::runtime_error(st.message);
    return text;
}

/// Compiles and links a program from (stage, source) pairs; throws std::runtime_error with the
/// driver's log (and the failing source's numbered lines nearby) on failure.
inline GLuint build_program(const std::vector<std::pair<GLenum, std::string>>& stages)
{
    GLuint program = glCreateProgram();
    std::vector<GLuint> shaders;
    for (const auto& st : stages) {
        GLuint sh = glCreateShader(st.first);
        const char* src = st.second.c_str();
        glShaderSource(sh, 1, &src, nullptr);
        glCompileShader(sh);
        GLint ok = 0;
        glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[8192];
            glGetShaderInfoLog(sh, sizeof log, nullptr, log);
            glDeleteShader(sh);
            glDeleteProgram(program);
            throw std::runtime_error(std::string("shader compile failed:\n") + log);
        }
        glAttachShader(program, sh);
        shaders.push_back(sh);
    }
    glLinkProgram(program);
    for (GLuint sh : shaders) glDeleteShader(sh);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[8192];
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw std::runtime_error(std::string("program link failed:\n") + log);
    }
    return program;
}

/// Creates an immutable SSBO holding `bytes` bytes (initialised from `data` when not null).
inline GLuint make_buffer(size_t bytes, const void* data)
{
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
    return buf;
}

/// Reads back a buffer's first `count` floats.
inline std::vector<float> read_floats(GLuint buf, size_t count)
{
    std::vector<float> out(count);
    glGetNamedBufferSubData(buf, 0, static_cast<GLsizeiptr>(count * sizeof(float)), out.data());
    return out;
}

/// An RGBA8 colour framebuffer of width x height, bound for drawing while alive.
class Framebuffer {
public:
    Framebuffer(int width, int height) : width_(width), height_(height)
    {
        glCreateTextures(GL_TEXTURE_2D, 1, &tex_);
        glTextureStorage2D(tex_, 1, GL_RGBA8, width, height);
        glCreateFramebuffers(1, &fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, tex_, 0);
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("incomplete framebuffer");
        }
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, width, height);
    }
    ~Framebuffer()
    {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &fbo_);
        glDeleteTextures(1, &tex_);
    }
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    /// Pixels top row first (ready for stbi_write_png).
    std::vector<unsigned char> read_rgba8() const
    {
        std::vector<unsigned char> px(static_cast<size_t>(width_) * static_cast<size_t>(height_) * 4u);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        std::vector<unsigned char> flipped(px.size());
        const size_t row = static_cast<size_t>(width_) * 4u;
        for (int y = 0; y < height_; ++y) {
            std::memcpy(&flipped[static_cast<size_t>(y) * row], &px[static_cast<size_t>(height_ - 1 - y) * row], row);
        }
        return flipped;
    }

private:
    int width_, height_;
    GLuint tex_ = 0, fbo_ = 0;
};

}  // namespace rkgl
