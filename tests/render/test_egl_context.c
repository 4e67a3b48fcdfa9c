/* test_egl_context.c — headless context creation: the software path works and
 * reports llvmpipe with GL 4.5; it is robust where the driver allows (llvmpipe
 * does), so a GPU reset can be noticed through glGetGraphicsResetStatus, which
 * the daemon asks after every render; a device number that does not exist
 * fails with FC_ERR_GL and a message; gpu choices parse strictly. */
#include <epoxy/gl.h>
#include <string.h>

#include "egl_context.h"
#include "test_util.h"

/* A software context, made current; NULL (the failure checked and told) when there is none. */
static fc_gl_context *software_context(void)
{
    fc_gpu_choice software = {FC_GPU_SOFTWARE, 0};
    fc_gl_context *ctx = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_gl_context_create(&software, &ctx, &err), FC_OK);
    if (!ctx)
        fprintf(stderr, "software context: %s\n", err.message);
    return ctx;
}

static void test_software_context(void)
{
    fc_gl_context *ctx = software_context();
    if (!ctx)
        return;
    fc_error err = {0};
    CHECK_MSG(strstr(fc_gl_context_renderer(ctx), "llvmpipe") != NULL, "renderer %s", fc_gl_context_renderer(ctx));
    CHECK_MSG(strncmp(fc_gl_context_version(ctx), "4.5", 3) == 0 || fc_gl_context_version(ctx)[0] > '4',
              "version %s", fc_gl_context_version(ctx));
    CHECK_MSG(strstr(fc_gl_context_version(ctx), "Core") != NULL, "version %s", fc_gl_context_version(ctx));
    CHECK(strlen(fc_gl_context_egl_vendor(ctx)) > 0);
    CHECK_MSG(fc_gl_context_fallback(ctx)[0] == '\0', "software asked for, yet a fallback: %s",
              fc_gl_context_fallback(ctx));
    CHECK_CODE(fc_gl_context_make_current(ctx, &err), FC_OK);
    fc_gl_context_destroy(ctx);
}

/* A fresh context reports no reset, and GL itself confirms the robust flags. */
static void test_robust_context(void)
{
    fc_gl_context *ctx = software_context();
    if (!ctx)
        return;
    CHECK(fc_gl_context_robust(ctx));
    GLint flags = 0, strategy = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    glGetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
    CHECK_MSG(flags & GL_CONTEXT_FLAG_ROBUST_ACCESS_BIT, "GL_CONTEXT_FLAGS 0x%x", (unsigned)flags);
    CHECK_MSG(strategy == GL_LOSE_CONTEXT_ON_RESET, "GL_RESET_NOTIFICATION_STRATEGY 0x%x", (unsigned)strategy);
    CHECK_CODE(fc_gl_context_reset_status(ctx), FC_GL_NO_RESET);
    fc_gl_context_destroy(ctx);

    CHECK(strcmp(fc_gl_reset_name(FC_GL_RESET_GUILTY), "guilty") == 0);
    CHECK(strcmp(fc_gl_reset_name(FC_GL_RESET_INNOCENT), "innocent") == 0);
    CHECK(strcmp(fc_gl_reset_name(FC_GL_RESET_UNKNOWN), "unknown") == 0);
}

/* AUTO takes a hardware device when there is one and software otherwise:
 * either way it yields a 4.5 core context, and it says why when it took
 * llvmpipe (the daemon logs that). */
static void test_auto_context(void)
{
    fc_gpu_choice automatic = {FC_GPU_AUTO, 0};
    fc_gl_context *ctx = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_gl_context_create(&automatic, &ctx, &err), FC_OK);
    if (ctx) {
        CHECK_MSG(strstr(fc_gl_context_version(ctx), "Core") != NULL, "version %s", fc_gl_context_version(ctx));
        const char *fallback = fc_gl_context_fallback(ctx);
        if (strstr(fc_gl_context_renderer(ctx), "llvmpipe"))
            CHECK_MSG(strncmp(fallback, "no GPU EGL device", 17) == 0, "llvmpipe, and the reason is '%s'", fallback);
        else
            CHECK_MSG(fallback[0] == '\0', "%s, yet a fallback: %s", fc_gl_context_renderer(ctx), fallback);
    }
    fc_gl_context_destroy(ctx);
}

/* Both contexts share the process's one EGL display: destroying the first
 * must leave the second usable. */
static void test_two_contexts(void)
{
    fc_gpu_choice software = {FC_GPU_SOFTWARE, 0};
    fc_gl_context *first = NULL, *second = NULL;
    CHECK_CODE(fc_gl_context_create(&software, &first, NULL), FC_OK);
    CHECK_CODE(fc_gl_context_create(&software, &second, NULL), FC_OK);
    fc_gl_context_destroy(first);
    CHECK_CODE(fc_gl_context_make_current(second, NULL), FC_OK);
    fc_gl_context_destroy(second);
}

static void test_missing_device(void)
{
    fc_gpu_choice missing = {FC_GPU_INDEX, 99};
    fc_gl_context *ctx = (fc_gl_context *)&missing;   /* must be reset to NULL */
    fc_error err = {0};
    CHECK_CODE(fc_gl_context_create(&missing, &ctx, &err), FC_ERR_GL);
    CHECK(ctx == NULL);
    CHECK(err.code == FC_ERR_GL);
    CHECK_MSG(strstr(err.message, "99") != NULL, "message: %s", err.message);
}

static void test_choice_parsing(void)
{
    fc_gpu_choice choice;
    CHECK_CODE(fc_gpu_choice_parse("auto", &choice, NULL), FC_OK);
    CHECK(choice.mode == FC_GPU_AUTO);
    CHECK_CODE(fc_gpu_choice_parse("software", &choice, NULL), FC_OK);
    CHECK(choice.mode == FC_GPU_SOFTWARE);
    CHECK_CODE(fc_gpu_choice_parse("3", &choice, NULL), FC_OK);
    CHECK(choice.mode == FC_GPU_INDEX && choice.index == 3);
    fc_error err = {0};
    CHECK_CODE(fc_gpu_choice_parse("-1", &choice, &err), FC_ERR_USAGE);
    CHECK(strstr(err.message, "-1") != NULL);
    CHECK_CODE(fc_gpu_choice_parse("", &choice, NULL), FC_ERR_USAGE);
    CHECK_CODE(fc_gpu_choice_parse("2x", &choice, NULL), FC_ERR_USAGE);
    CHECK_CODE(fc_gpu_choice_parse("Auto", &choice, NULL), FC_ERR_USAGE);
}

int main(void)
{
    test_software_context();
    test_robust_context();
    test_auto_context();
    test_two_contexts();
    test_missing_device();
    test_choice_parsing();
    return test_result();
}
