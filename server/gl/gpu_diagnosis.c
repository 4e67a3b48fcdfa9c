/* gpu_diagnosis.c — the likely causes of "no GPU", in the order an operator
 * meets them: the NVIDIA container toolkit's capabilities, the NVIDIA EGL
 * driver missing beside its device files, DRM render nodes absent or not
 * accessible to this user. */
#include "gpu_diagnosis.h"

#include <dirent.h>
#include <grp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct causes {
    char *out;
    size_t size, used;
} causes;

static void add_cause(causes *c, const char *text)
{
    if (c->used >= c->size)
        return;
    int n = snprintf(c->out + c->used, c->size - c->used, "%s%s", c->used ? "; " : "", text);
    if (n > 0)
        c->used += (size_t)n;
}

/* The container toolkit injects the NVIDIA EGL driver only with "graphics" (or "all"). */
static void check_nvidia_capabilities(causes *c)
{
    const char *caps = getenv("NVIDIA_DRIVER_CAPABILITIES");
    if (!caps || strstr(caps, "graphics") || strstr(caps, "all"))
        return;
    char text[256];
    snprintf(text, sizeof text,
             "NVIDIA_DRIVER_CAPABILITIES=%s lacks 'graphics' (no EGL driver injected; use graphics,utility)",
             caps);
    add_cause(c, text);
}

static void check_nvidia_egl(causes *c)
{
    struct stat st;
    if (stat("/dev/nvidiactl", &st) != 0)
        return;
    if (stat("/usr/share/glvnd/egl_vendor.d/10_nvidia.json", &st) != 0 &&
        stat("/etc/glvnd/egl_vendor.d/10_nvidia.json", &st) != 0)
        add_cause(c, "/dev/nvidiactl exists but no NVIDIA EGL vendor file (glvnd egl_vendor.d/10_nvidia.json)");
    else if (access("/dev/nvidiactl", R_OK | W_OK) != 0)
        add_cause(c, "/dev/nvidiactl is not readable and writable by this user");
}

/* "renderD128 (group render)": who may open a render node. */
static void describe_node(const char *path, char *out, size_t size)
{
    struct stat st;
    const struct group *g = stat(path, &st) == 0 ? getgrgid(st.st_gid) : NULL;
    snprintf(out, size, "uid %d may not open %s (add it to group '%s')", (int)getuid(), path, g ? g->gr_name : "?");
}

static void check_dri(causes *c)
{
    DIR *dir = opendir("/dev/dri");
    if (!dir) {
        add_cause(c, "no /dev/dri (no GPU driver loaded, or a container without --device /dev/dri)");
        return;
    }
    int nodes = 0, usable = 0;
    const struct dirent *e;
    while ((e = readdir(dir)) != NULL) {
        if (strncmp(e->d_name, "renderD", 7) != 0)
            continue;
        char path[300], text[512];
        snprintf(path, sizeof path, "/dev/dri/%s", e->d_name);
        nodes++;
        if (access(path, R_OK | W_OK) == 0) {
            usable++;
            continue;
        }
        describe_node(path, text, sizeof text);
        add_cause(c, text);
    }
    closedir(dir);
    if (nodes == 0)
        add_cause(c, "/dev/dri has no render node (renderD*)");
    else if (usable == nodes && c->used == 0)
        add_cause(c, "/dev/dri/renderD* are accessible but offer no EGL device (driver without "
                     "EGL_EXT_platform_device, or cgroups hide the GPU)");
}

void fc_gpu_diagnose(char *out, size_t size)
{
    causes c = {out, size, 0};
    if (size > 0)
        out[0] = '\0';
    check_nvidia_capabilities(&c);
    check_nvidia_egl(&c);
    check_dri(&c);
}
