/* egl_context.c — a headless OpenGL 4.5 core context through EGL, with no
 * window system: a GPU through EGL_EXT_platform_device, or Mesa's surfaceless
 * platform (llvmpipe). Function pointers come from libepoxy. */
#include "egl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "gpu_diagnosis.h"

/* EGL_EXT_device_drm_render_node, newer than Debian 12's libepoxy headers. */
#ifndef EGL_DRM_RENDER_NODE_FILE_EXT
#define EGL_DRM_RENDER_NODE_FILE_EXT 0x3377
#endif

/* More EGL devices than any machine has; eglQueryDevicesEXT reports the real count. */
#define MAX_EGL_DEVICES 32
#define REQUIRED_GL_VERSION 45   /* epoxy_gl_version() encoding of 4.5 */

struct fc_gl_context {
    EGLDisplay display;
    EGLContext context;
    bool robust;            /* created with reset notification: glGetGraphicsResetStatus can report a loss */
    char egl_vendor[128];
    char renderer[256];
    char version[256];
    char fallback[320];     /* why --gpu auto took the software platform; "" otherwise */
    char device[256];       /* fc_gl_context_device */
    char notes[2048];       /* fc_gl_context_notes */
};

static void add_note(fc_gl_context *ctx, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void add_note(fc_gl_context *ctx, const char *format, ...)
{
    size_t used = strlen(ctx->notes);
    if (used + 1 >= sizeof ctx->notes)
        return;
    va_list args;
    va_start(args, format);
    vsnprintf(ctx->notes + used, sizeof ctx->notes - used, format, args);
    va_end(args);
    used = strlen(ctx->notes);
    if (used + 1 < sizeof ctx->notes)
        snprintf(ctx->notes + used, sizeof ctx->notes - used, "\n");
}

fc_code fc_gpu_choice_parse(const char *text, fc_gpu_choice *out, fc_error *err)
{
    if (!text || !out)
        return fc_error_set(err, FC_ERR_USAGE, "gpu choice: missing text or output");
    if (strcmp(text, "auto") == 0) {
        *out = (fc_gpu_choice){FC_GPU_AUTO, 0};
        return FC_OK;
    }
    if (strcmp(text, "software") == 0) {
        *out = (fc_gpu_choice){FC_GPU_SOFTWARE, 0};
        return FC_OK;
    }
    bool cuda = strncmp(text, "cuda:", 5) == 0;
    const char *number = cuda ? text + 5 : text;
    char *end = NULL;
    errno = 0;
    long index = strtol(number, &end, 10);
    if (number[0] < '0' || number[0] > '9' || *end != '\0' || errno != 0 || index > INT_MAX)
        return fc_error_set(err, FC_ERR_USAGE,
                            "gpu choice '%s': expected \"auto\", \"software\", an EGL device number or cuda:N",
                            text);
    *out = (fc_gpu_choice){cuda ? FC_GPU_CUDA : FC_GPU_INDEX, (int)index};
    return FC_OK;
}

static const char *egl_error_name(EGLint code)
{
    switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT: return "EGL_BAD_DEVICE_EXT";
    }
    return "unknown EGL error";
}

/* Whether the space-separated extension list contains `name` as a whole word. */
static bool has_extension(const char *list, const char *name)
{
    size_t len = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)) != NULL; p += len) {
        bool starts = p == list || p[-1] == ' ';
        bool ends = p[len] == ' ' || p[len] == '\0';
        if (starts && ends)
            return true;
    }
    return false;
}

static bool has_client_extension(const char *name)
{
    /* EGL_NO_DISPLAY queries the client (platform) extensions. */
    return has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), name);
}

static fc_code egl_failure(fc_error *err, const char *tried, const char *step)
{
    return fc_error_set(err, FC_ERR_GL, "EGL: %s: %s failed (%s)", tried, step, egl_error_name(eglGetError()));
}

/* The devices EGL enumerates; *count = 0 when enumeration is unavailable. */
static void query_devices(EGLDeviceEXT devices[MAX_EGL_DEVICES], EGLint *count)
{
    *count = 0;
    if (!has_client_extension("EGL_EXT_device_enumeration") || !has_client_extension("EGL_EXT_device_query") ||
        !has_client_extension("EGL_EXT_platform_device"))
        return;
    if (!eglQueryDevicesEXT(MAX_EGL_DEVICES, devices, count))
        *count = 0;
}

static bool is_software_device(EGLDeviceEXT device)
{
    return has_extension(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

/* The names a robust context is asked for with: robust buffer access, and a
 * context that is lost on a GPU reset and says so through
 * glGetGraphicsResetStatus. EGL 1.5 spells them one way,
 * EGL_EXT_create_context_robustness another; false when the display has
 * neither. names: access, reset strategy, lose-on-reset. */
static bool robustness_names(EGLDisplay display, EGLint egl_major, EGLint egl_minor, EGLint names[3])
{
    if (egl_major > 1 || (egl_major == 1 && egl_minor >= 5)) {
        names[0] = EGL_CONTEXT_OPENGL_ROBUST_ACCESS;
        names[1] = EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY;
        names[2] = EGL_LOSE_CONTEXT_ON_RESET;
        return true;
    }
    if (has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_EXT_create_context_robustness")) {
        names[0] = EGL_CONTEXT_OPENGL_ROBUST_ACCESS_EXT;
        names[1] = EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT;
        names[2] = EGL_LOSE_CONTEXT_ON_RESET_EXT;
        return true;
    }
    return false;
}

/* A robust 4.5 core context where the driver grants one (a lost context can
 * then be noticed and replaced), else a plain one. */
static EGLContext create_gl45(EGLDisplay display, EGLint egl_major, EGLint egl_minor, bool *robust)
{
    enum { ROBUSTNESS_AT = 6 };   /* where the robustness pairs go; EGL_NONE there ends the list before them */
    EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4,
        EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_NONE, EGL_TRUE,
        EGL_NONE, EGL_NONE,
        EGL_NONE};
    EGLint names[3];
    *robust = robustness_names(display, egl_major, egl_minor, names);
    if (*robust) {
        attributes[ROBUSTNESS_AT] = names[0];
        attributes[ROBUSTNESS_AT + 2] = names[1];
        attributes[ROBUSTNESS_AT + 3] = names[2];
        EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context != EGL_NO_CONTEXT)
            return context;
        *robust = false;
        attributes[ROBUSTNESS_AT] = EGL_NONE;
    }
    return eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
}

/* Initialises `display`, then creates a 4.5 core context without config or
 * surface and makes it current. `tried` names the platform for messages. */
static fc_code create_on_display(EGLDisplay display, const char *tried, fc_gl_context *ctx, fc_error *err)
{
    if (display == EGL_NO_DISPLAY)
        return egl_failure(err, tried, "eglGetPlatformDisplayEXT");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
        return egl_failure(err, tried, "eglInitialize");
    const char *extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!has_extension(extensions, "EGL_KHR_no_config_context") ||
        !has_extension(extensions, "EGL_KHR_surfaceless_context"))
        return fc_error_set(err, FC_ERR_GL,
                            "EGL: %s: display lacks EGL_KHR_no_config_context or EGL_KHR_surfaceless_context",
                            tried);
    if (!eglBindAPI(EGL_OPENGL_API))
        return egl_failure(err, tried, "eglBindAPI(EGL_OPENGL_API)");
    bool robust = false;
    EGLContext context = create_gl45(display, major, minor, &robust);
    if (context == EGL_NO_CONTEXT)
        return egl_failure(err, tried, "eglCreateContext(OpenGL 4.5 core)");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        fc_code code = egl_failure(err, tried, "eglMakeCurrent(no surface)");
        eglDestroyContext(display, context);
        return code;
    }
    ctx->display = display;
    ctx->context = context;
    ctx->robust = robust;
    return FC_OK;
}

/* The device's CUDA number (EGL_NV_device_cuda), -1 when it has none. */
static int cuda_number(EGLDeviceEXT device)
{
    EGLAttrib value = -1;
    if (!has_extension(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS), "EGL_NV_device_cuda") ||
        !eglQueryDeviceAttribEXT(device, EGL_CUDA_DEVICE_NV, &value) || value < 0 || value > INT_MAX)
        return -1;
    return (int)value;
}

/* The device's DRM file, preferring the render node; NULL when the driver does not say. */
static const char *drm_file(EGLDeviceEXT device)
{
    const char *extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
    const char *file = NULL;
    if (has_extension(extensions, "EGL_EXT_device_drm_render_node"))
        file = eglQueryDeviceStringEXT(device, EGL_DRM_RENDER_NODE_FILE_EXT);
    if (!file && has_extension(extensions, "EGL_EXT_device_drm"))
        file = eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT);
    return file;
}

static void describe_device(EGLDeviceEXT device, int index, char *out, size_t size)
{
    const char *file = drm_file(device);
    int cuda = cuda_number(device);
    int n = snprintf(out, size, "EGL device %d%s%s", index, file ? ", " : "", file ? file : "");
    if (cuda >= 0 && n > 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, ", CUDA %d", cuda);
}

static fc_code create_on_device(EGLDeviceEXT device, int index, fc_gl_context *ctx, fc_error *err)
{
    char tried[256];
    describe_device(device, index, tried, sizeof tried);
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, NULL);
    fc_code code = create_on_display(display, tried, ctx, err);
    if (code == FC_OK)
        snprintf(ctx->device, sizeof ctx->device, "%s", tried);
    return code;
}

static fc_code create_surfaceless(fc_gl_context *ctx, fc_error *err)
{
    const char *tried = "Mesa surfaceless platform";
    if (!has_client_extension("EGL_MESA_platform_surfaceless"))
        return fc_error_set(err, FC_ERR_GL, "EGL: %s: EGL_MESA_platform_surfaceless not supported", tried);
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    fc_code code = create_on_display(display, tried, ctx, err);
    if (code == FC_OK)
        snprintf(ctx->device, sizeof ctx->device, "%s (no device)", tried);
    return code;
}

/* Why auto found no hardware device to render on, for the operator: no
 * enumeration at all, only software devices, or the first hardware device's
 * failure (a device the driver lists but the container's cgroup hides fails here). */
static void describe_fallback(char *out, size_t size, EGLint count, EGLint hardware, const fc_error *device_err)
{
    if (count == 0)
        snprintf(out, size, "no GPU EGL device: EGL enumerates no devices (no EGL_EXT_device_enumeration)");
    else if (hardware == 0)
        snprintf(out, size, "no GPU EGL device: %d EGL device(s), all software", (int)count);
    else
        snprintf(out, size, "no GPU EGL device usable: %s", device_err->message);
}

/* The first hardware device that yields a context, passing over (with a
 * note each, fc_gl_context_notes) those whose eglInitialize or context
 * fails: cgroups hide GPUs the driver still lists. Else the surfaceless
 * platform, recording why in ctx->fallback. When both fail, the message
 * names both attempts. */
static fc_code create_auto(fc_gl_context *ctx, fc_error *err)
{
    EGLDeviceEXT devices[MAX_EGL_DEVICES];
    EGLint count = 0, hardware = 0;
    query_devices(devices, &count);
    fc_error device_err = {FC_OK, "no hardware EGL device"};
    for (EGLint i = 0; i < count; i++) {
        if (is_software_device(devices[i]))
            continue;
        hardware++;
        if (create_on_device(devices[i], (int)i, ctx, &device_err) == FC_OK)
            return FC_OK;
        add_note(ctx, "--gpu auto: skipping %s", device_err.message);
    }
    describe_fallback(ctx->fallback, sizeof ctx->fallback, count, hardware, &device_err);
    fc_error software_err;
    if (create_surfaceless(ctx, &software_err) == FC_OK)
        return FC_OK;
    return fc_error_set(err, FC_ERR_GL, "no OpenGL 4.5 context: %s; %s", device_err.message,
                        software_err.message);
}

static fc_code create_indexed(int index, fc_gl_context *ctx, fc_error *err)
{
    EGLDeviceEXT devices[MAX_EGL_DEVICES];
    EGLint count = 0;
    query_devices(devices, &count);
    if (index < 0 || index >= count)
        return fc_error_set(err, FC_ERR_GL, "EGL device %d does not exist: %d EGL device(s) enumerated", index,
                            (int)count);
    return create_on_device(devices[index], index, ctx, err);
}

/* The EGL device that is CUDA device `cuda` (EGL_CUDA_DEVICE_NV), so the
 * number Slurm or Kubernetes hands a job picks the GPU CUDA would. */
static fc_code create_cuda(int cuda, fc_gl_context *ctx, fc_error *err)
{
    EGLDeviceEXT devices[MAX_EGL_DEVICES];
    EGLint count = 0;
    query_devices(devices, &count);
    char seen[256] = "";
    size_t used = 0;
    for (EGLint i = 0; i < count; i++) {
        int number = cuda_number(devices[i]);
        if (number == cuda)
            return create_on_device(devices[i], (int)i, ctx, err);
        if (number >= 0 && used < sizeof seen)
            used += (size_t)snprintf(seen + used, sizeof seen - used, "%s%d", used ? ", " : "", number);
    }
    if (used > 0)
        return fc_error_set(err, FC_ERR_GL, "--gpu cuda:%d: no EGL device is CUDA device %d (the EGL devices are CUDA %s)",
                            cuda, cuda, seen);
    char causes[1024];
    fc_gpu_diagnose(causes, sizeof causes);
    return fc_error_set(err, FC_ERR_GL,
                        "--gpu cuda:%d: none of the %d EGL device(s) reports a CUDA device number "
                        "(EGL_NV_device_cuda): no NVIDIA EGL driver. Likely cause: %s",
                        cuda, (int)count, causes);
}

static void copy_string(char *dst, size_t size, const char *src)
{
    snprintf(dst, size, "%s", src ? src : "unknown");
}

/* Records the strings a caller reports, after checking the context really is 4.5:
 * drivers may hand out a lower version than requested. */
static fc_code describe_context(fc_gl_context *ctx, fc_error *err)
{
    copy_string(ctx->egl_vendor, sizeof ctx->egl_vendor, eglQueryString(ctx->display, EGL_VENDOR));
    copy_string(ctx->renderer, sizeof ctx->renderer, (const char *)glGetString(GL_RENDERER));
    copy_string(ctx->version, sizeof ctx->version, (const char *)glGetString(GL_VERSION));
    if (epoxy_gl_version() < REQUIRED_GL_VERSION)
        return fc_error_set(err, FC_ERR_GL, "OpenGL 4.5 core required, %s offers %s", ctx->renderer,
                            ctx->version);
    return FC_OK;
}

fc_code fc_gl_context_create(const fc_gpu_choice *choice, fc_gl_context **out, fc_error *err)
{
    if (!choice || !out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_gl_context_create: missing choice or output");
    *out = NULL;
    fc_gl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the GL context");
    fc_code code;
    switch (choice->mode) {
    case FC_GPU_AUTO: code = create_auto(ctx, err); break;
    case FC_GPU_SOFTWARE: code = create_surfaceless(ctx, err); break;
    case FC_GPU_INDEX: code = create_indexed(choice->index, ctx, err); break;
    case FC_GPU_CUDA: code = create_cuda(choice->index, ctx, err); break;
    default: code = fc_error_set(err, FC_ERR_USAGE, "unknown gpu mode %d", (int)choice->mode); break;
    }
    if (code == FC_OK)
        code = describe_context(ctx, err);
    if (code != FC_OK) {
        fc_gl_context_destroy(ctx);
        return code;
    }
    *out = ctx;
    return FC_OK;
}

void fc_gl_context_destroy(fc_gl_context *ctx)
{
    if (!ctx)
        return;
    if (ctx->context != EGL_NO_CONTEXT) {
        if (eglGetCurrentContext() == ctx->context)
            eglMakeCurrent(ctx->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(ctx->display, ctx->context);
    }
    /* No eglTerminate: a platform display is one object per process, so
     * terminating it would destroy the contexts other owners still use. */
    free(ctx);
}

fc_code fc_gl_context_make_current(fc_gl_context *ctx, fc_error *err)
{
    if (!ctx)
        return fc_error_set(err, FC_ERR_USAGE, "fc_gl_context_make_current: no context");
    if (!eglMakeCurrent(ctx->display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->context))
        return fc_error_set(err, FC_ERR_GL, "eglMakeCurrent failed (%s)", egl_error_name(eglGetError()));
    return FC_OK;
}

const char *fc_gl_context_egl_vendor(const fc_gl_context *ctx)
{
    return ctx->egl_vendor;
}

const char *fc_gl_context_renderer(const fc_gl_context *ctx)
{
    return ctx->renderer;
}

const char *fc_gl_context_version(const fc_gl_context *ctx)
{
    return ctx->version;
}

const char *fc_gl_context_fallback(const fc_gl_context *ctx)
{
    return ctx->fallback;
}

const char *fc_gl_context_device(const fc_gl_context *ctx)
{
    return ctx->device;
}

const char *fc_gl_context_notes(const fc_gl_context *ctx)
{
    return ctx->notes;
}

bool fc_gl_context_robust(const fc_gl_context *ctx)
{
    return ctx->robust;
}

fc_gl_reset fc_gl_context_reset_status(const fc_gl_context *ctx)
{
    /* Without reset notification GL answers GL_NO_ERROR whatever happened. */
    if (!ctx->robust)
        return FC_GL_NO_RESET;
    switch (glGetGraphicsResetStatus()) {
    case GL_NO_ERROR: return FC_GL_NO_RESET;
    case GL_GUILTY_CONTEXT_RESET: return FC_GL_RESET_GUILTY;
    case GL_INNOCENT_CONTEXT_RESET: return FC_GL_RESET_INNOCENT;
    default: return FC_GL_RESET_UNKNOWN;
    }
}

const char *fc_gl_reset_name(fc_gl_reset reset)
{
    switch (reset) {
    case FC_GL_NO_RESET: return "no";
    case FC_GL_RESET_GUILTY: return "guilty";
    case FC_GL_RESET_INNOCENT: return "innocent";
    case FC_GL_RESET_UNKNOWN: break;
    }
    return "unknown";
}
