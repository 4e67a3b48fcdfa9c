/* test_hardening_gl_robust.c — the headless context is created robust where
 * the driver allows (llvmpipe does): a GPU reset can then be noticed through
 * glGetGraphicsResetStatus, which the daemon asks after every render. A fresh
 * context reports no reset, and GL itself confirms the robust flags. */
#include <epoxy/gl.h>
#include <string.h>

#include "gl/egl_context.h"
#include "test_util.h"

int main(void)
{
    fc_gpu_choice software = {FC_GPU_SOFTWARE, 0};
    fc_gl_context *ctx = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_gl_context_create(&software, &ctx, &err), FC_OK);
    if (!ctx) {
        fprintf(stderr, "software context: %s\n", err.message);
        return test_result();
    }
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
    return test_result();
}
