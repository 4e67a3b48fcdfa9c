/* test_mask_paths.c — the composite's mask comes from one of two paths
 * (background_pass.h): where the driver has ARB_shader_stencil_export the
 * background pass writes the fluid's depth and stencil itself; where it has
 * not (NVIDIA's driver), the composite runs its own full-screen mask pass.
 * llvmpipe has the extension, so without this test the second path would run
 * only with opaque meshes. Mesa's MESA_EXTENSION_OVERRIDE takes the extension
 * away, as that driver lacks it; Mesa reads it once per process, so the test
 * runs itself a second time with it set (`--write FILE`: the same renders,
 * their bytes to FILE) and checks that
 *  - the first process lays the mask in the background pass and the second
 *    does not (else the override did not take: skipped, 77), and
 *  - both paths give the same 8-bit and float images bit for bit: default
 *    look, shadow off, surface noise, a glass mesh, two cameras (the ball
 *    over the floor from the side, and from above with the floor behind). */
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

extern char **environ;

#define WIDTH 96
#define HEIGHT 72
#define LATTICE 0.0625f
#define STEPS 5
#define RADIUS 0.05f
#define RENDERS 10   /* 5 looks x 2 cameras; each an 8-bit and a float image */

/* A glass pane (two triangles) in front of the ball. */
static fc_mesh_buffers *glass_pane(render_fixture *f)
{
    static float vertices[12] = {-0.6f, -0.5f, 0.1f, 0.6f, -0.5f, 0.1f, 0.6f, -0.5f, 0.9f, -0.6f, -0.5f, 0.9f};
    static uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    fc_mesh mesh = {.vertex_count = 4, .triangle_count = 2, .vertices = vertices, .indices = indices,
                    .opacity = 0.3f};
    fc_mesh_buffers *buffers = NULL;
    fc_error err = {0};
    CHECK_MSG(fc_mesh_buffers_create(f->pipeline, &mesh, &buffers, &err) == FC_OK, "mesh buffers: %s", err.message);
    return buffers;
}

static fc_camera view(int which)
{
    fc_camera cam = {.target = {0.0f, 0.0f, 0.4f}, .up = {0.0f, 0.0f, 1.0f}, .fov_y_deg = 40.0f, .width = WIDTH,
                     .height = HEIGHT};
    float side[3] = {0.4f, -3.0f, 0.9f}, above[3] = {0.3f, -0.8f, 3.0f};
    memcpy(cam.eye, which == 0 ? side : above, sizeof side);
    return cam;
}

/* Render k of RENDERS, 8-bit (`want_u8`) or float; false after a CHECK. */
static bool render(render_fixture *f, const fc_scene_mesh *glass, int k, int want_u8, fc_image *out)
{
    fc_settings s;
    fc_settings_default(&s);
    s.radius = RADIUS;
    s.shadow = 1;
    int look = k / 2;
    if (look == 1)
        s.shadow = 0;
    if (look == 2)
        s.noise = 0.3f;
    fc_render_scene scene = {.meshes = look == 3 ? glass : NULL, .mesh_count = look == 3 ? 1 : 0};
    if (look == 4)
        s.exposure = 1.0f;
    fc_camera cam = view(k % 2);
    fc_error err = {0};
    fc_code code = fc_pipeline_render_with(f->pipeline, &cam, &s, &scene, FC_AOV_COLOR, want_u8, out, NULL, &err);
    CHECK_MSG(code == FC_OK, "render %d: %s", k, err.message);
    return code == FC_OK;
}

/* Every render's 8-bit then float bytes, in order, through `put`. */
static bool render_all(render_fixture *f, bool (*put)(void *ctx, int k, const fc_image *img), void *ctx)
{
    uint64_t count = 0;
    float *positions = lattice_ball(STEPS, LATTICE, 0.5f, &count);   /* above the floor z = 0 */
    fc_mesh_buffers *buffers = positions ? glass_pane(f) : NULL;
    fc_frame frame = {.count = count, .positions = positions};
    fc_error err = {0};
    bool ok = buffers && fc_pipeline_upload(f->pipeline, &frame, NULL, &err) == FC_OK;
    CHECK_MSG(ok, "upload: %s", err.message);
    fc_scene_mesh glass = {.buffers = buffers, .color = {0.7f, 0.85f, 1.0f}, .opacity = 0.3f};
    glass.transform[0] = glass.transform[5] = glass.transform[10] = 1.0f;   /* 3x4: identity */
    for (int k = 0; ok && k < RENDERS; k++)
        for (int want_u8 = 1; ok && want_u8 >= 0; want_u8--) {
            fc_image img = {0};
            ok = render(f, &glass, k, want_u8, &img) && put(ctx, 2 * k + !want_u8, &img);
            fc_image_free(&img);
        }
    fc_mesh_buffers_destroy(buffers);
    free(positions);
    return ok;
}

static bool write_image(void *ctx, int k, const fc_image *img)
{
    (void)k;
    return fwrite(img->pixels, 1, fc_image_size(img), ctx) == fc_image_size(img);
}

typedef struct compare {
    FILE *other;      /* the second process's bytes */
    int differing;    /* images that differ */
} compare;

static bool compare_image(void *ctx, int k, const fc_image *img)
{
    compare *c = ctx;
    size_t size = fc_image_size(img);
    unsigned char *theirs = malloc(size);
    bool read = theirs && fread(theirs, 1, size, c->other) == size;
    CHECK_MSG(read, "image %d: the second process wrote fewer bytes", k);
    if (read && memcmp(theirs, img->pixels, size) != 0) {
        c->differing++;
        CHECK_MSG(false, "image %d (look %d, camera %d, %s): the mask pass and the background's mask differ", k,
                  k / 4, k / 2 % 2, k % 2 ? "float" : "8-bit");
    }
    free(theirs);
    return read;
}

/* The second process: the extension overridden away, its renders to `path`. */
static int write_renders(const char *path)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    FILE *out = fopen(path, "wb");
    bool ok = out && fputc(fc_pipeline_background_writes_mask(f.pipeline) ? 'M' : 'P', out) != EOF &&
              render_all(&f, write_image, out);
    if (out && fclose(out) != 0)
        ok = false;
    fixture_close(&f);
    return ok ? 0 : 1;
}

static int run_overridden(const char *self, const char *path)
{
    if (setenv("MESA_EXTENSION_OVERRIDE", "-GL_ARB_shader_stencil_export", 1) != 0)
        return -1;
    char *argv[] = {(char *)self, "--write", (char *)path, NULL};
    pid_t pid;
    int status = 0;
    int spawned = posix_spawn(&pid, self, NULL, NULL, argv, environ);
    unsetenv("MESA_EXTENSION_OVERRIDE");
    if (spawned != 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
        return -1;
    return WEXITSTATUS(status);
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--write") == 0)
        return write_renders(argv[2]);
    char path[] = "/tmp/fc_mask_paths_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) {
        perror("mkstemp");
        return 1;
    }
    close(fd);
    int child = run_overridden("/proc/self/exe", path);
    FILE *other = fopen(path, "rb");
    int path_char = other ? fgetc(other) : EOF;
    render_fixture f;
    bool opened = child == 0 && path_char != EOF && fixture_open(&f);
    CHECK_MSG(child == 0, "the run without ARB_shader_stencil_export failed (exit %d)", child);
    if (opened) {
        bool here = fc_pipeline_background_writes_mask(f.pipeline);
        if (!here || path_char != 'P') {
            printf("the driver %s ARB_shader_stencil_export%s: one mask path only, skipped\n",
                   here ? "has" : "lacks", path_char == 'M' ? " even with MESA_EXTENSION_OVERRIDE" : "");
            fixture_close(&f);
            fclose(other);
            unlink(path);
            return 77;
        }
        compare c = {.other = other};
        render_all(&f, compare_image, &c);
        CHECK_MSG(fgetc(other) == EOF, "the second process wrote more images than this one");
        printf("%d images compared (%d looks x 2 cameras, 8-bit and float), %d differ\n", 2 * RENDERS,
               RENDERS / 2, c.differing);
        fixture_close(&f);
    }
    if (other)
        fclose(other);
    unlink(path);
    return test_result();
}
