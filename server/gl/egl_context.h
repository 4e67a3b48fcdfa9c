/* egl_context.h — a headless OpenGL 4.5 core context through EGL, with no display:
 * a GPU through EGL_EXT_platform_device, or Mesa's surfaceless platform (llvmpipe). */
#ifndef FC_EGL_CONTEXT_H
#define FC_EGL_CONTEXT_H

#include <stdbool.h>

#include "fluidcast_types.h"

typedef enum fc_gpu_mode {
    FC_GPU_AUTO = 0,      /* first hardware EGL device that initialises; else software, saying why */
    FC_GPU_SOFTWARE,      /* Mesa surfaceless (llvmpipe) */
    FC_GPU_INDEX,         /* EGL device number `index` as enumerated by eglQueryDevicesEXT */
    FC_GPU_CUDA           /* the EGL device whose EGL_CUDA_DEVICE_NV is `index` (NVIDIA, EGL_NV_device_cuda) */
} fc_gpu_mode;

typedef struct fc_gpu_choice {
    fc_gpu_mode mode;
    int index;
} fc_gpu_choice;

/* Parses "auto", "software", an EGL device number or "cuda:N". */
fc_code fc_gpu_choice_parse(const char *text, fc_gpu_choice *out, fc_error *err);

typedef struct fc_gl_context fc_gl_context;

/* Creates the context and makes it current on the calling thread: a robust
 * one (lost on a GPU reset, which fc_gl_context_reset_status then reports)
 * where the driver grants it, else a plain one. FC_ERR_GL with the EGL error
 * and what was tried when no context can be made. */
fc_code fc_gl_context_create(const fc_gpu_choice *choice, fc_gl_context **out, fc_error *err);
void fc_gl_context_destroy(fc_gl_context *ctx);
fc_code fc_gl_context_make_current(fc_gl_context *ctx, fc_error *err);

const char *fc_gl_context_egl_vendor(const fc_gl_context *ctx);
const char *fc_gl_context_renderer(const fc_gl_context *ctx);   /* GL_RENDERER */
const char *fc_gl_context_version(const fc_gl_context *ctx);    /* GL_VERSION */
/* Which device the context is on: "EGL device 0, /dev/dri/renderD128, CUDA 0"
 * (the DRM file and CUDA number where the driver tells), or "Mesa surfaceless
 * platform (no device)". */
const char *fc_gl_context_device(const fc_gl_context *ctx);
/* What --gpu auto passed over, one warning a line ("" when none): the GPU
 * devices whose eglInitialize or context creation failed, each with why.
 * Why it then fell back to llvmpipe is fc_gl_context_fallback; the likely
 * cause, gpu_diagnosis.h. */
const char *fc_gl_context_notes(const fc_gl_context *ctx);

/* Why FC_GPU_AUTO fell back to Mesa's surfaceless platform (llvmpipe), e.g.
 * "no GPU EGL device: 1 EGL device(s), all software"; "" when it did not
 * (a hardware device, or FC_GPU_SOFTWARE / FC_GPU_INDEX asked for). */
const char *fc_gl_context_fallback(const fc_gl_context *ctx);

/* Whether the context was created robust, with reset notification. */
bool fc_gl_context_robust(const fc_gl_context *ctx);

/* What glGetGraphicsResetStatus says of the context (current on the calling
 * thread): whether the GPU was reset since it was created, and whose fault
 * that was. A context that is not robust always reports FC_GL_NO_RESET. Once
 * reset, a context stays unusable: destroy it and create another. */
typedef enum fc_gl_reset {
    FC_GL_NO_RESET = 0,
    FC_GL_RESET_GUILTY,      /* this context caused it */
    FC_GL_RESET_INNOCENT,    /* something else on the GPU did */
    FC_GL_RESET_UNKNOWN      /* the driver cannot tell */
} fc_gl_reset;
fc_gl_reset fc_gl_context_reset_status(const fc_gl_context *ctx);
/* "guilty", "innocent", "unknown" (and "no" for FC_GL_NO_RESET). */
const char *fc_gl_reset_name(fc_gl_reset reset);

#endif
