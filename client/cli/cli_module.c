/* cli_module.c — see cli_module.h. */
#include "cli_module.h"

#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"

#ifndef FC_MODULE_RELDIR
#define FC_MODULE_RELDIR "../lib/fluidcast"
#endif

/* The directory of the running executable, without the trailing slash. */
static fc_code executable_dir(char dir[FC_MODULE_PATH_MAX], fc_error *err)
{
    ssize_t len = readlink("/proc/self/exe", dir, FC_MODULE_PATH_MAX);
    if (len < 0)
        return fc_error_set(err, FC_ERR_IO, "cannot find the fluidcast executable (/proc/self/exe): %s",
                            strerror(errno));
    if (len >= FC_MODULE_PATH_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "the fluidcast executable's path is too long");
    dir[len] = '\0';
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = '\0';
    return FC_OK;
}

fc_code fc_cli_module_path(const char *file, char path[FC_MODULE_PATH_MAX], fc_error *err)
{
    const char *override = getenv(FC_MODULE_DIR_ENV);
    int len;
    if (override && override[0]) {
        len = snprintf(path, FC_MODULE_PATH_MAX, "%s/%s", override, file);
    } else {
        char dir[FC_MODULE_PATH_MAX];
        fc_code code = executable_dir(dir, err);
        if (code != FC_OK)
            return code;
        len = snprintf(path, FC_MODULE_PATH_MAX, "%s/%s/%s", dir, FC_MODULE_RELDIR, file);
    }
    if (len < 0 || len >= FC_MODULE_PATH_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "the path of %s is too long", file);
    return FC_OK;
}

/* dlerror()'s message, or a fallback when it has none. */
static const char *dl_reason(void)
{
    const char *reason = dlerror();
    return reason ? reason : "no reason given";
}

fc_code fc_cli_module_open(const char *file, const char *symbol, uint32_t abi, const char *purpose,
                           fc_cli_module *m, fc_error *err)
{
    memset(m, 0, sizeof *m);
    fc_code code = fc_cli_module_path(file, m->path, err);
    if (code != FC_OK)
        return code;
    /* RTLD_LOCAL: the module's libraries stay out of the command's symbol
     * scope. RTLD_NODELETE: never unmapped (see fc_cli_module_close). */
    m->handle = dlopen(m->path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!m->handle)
        return fc_error_set(err, FC_ERR_IO, "%s needs the module %s, which cannot be loaded: %s", purpose, file,
                            dl_reason());
    dlerror();
    const uint32_t *version = dlsym(m->handle, symbol);
    if (!version)
        code = fc_error_set(err, FC_ERR_IO, "%s needs the module %s, which is broken (%s): %s", purpose, m->path,
                            symbol, dl_reason());
    else if (*version != abi)
        code = fc_error_set(err, FC_ERR_IO,
                            "%s needs the module %s, which is from another version of fluidcast "
                            "(interface %u, this fluidcast needs %u)",
                            purpose, m->path, (unsigned)*version, (unsigned)abi);
    if (code != FC_OK) {
        fc_cli_module_close(m);
        return code;
    }
    m->api = version;
    return FC_OK;
}

void fc_cli_module_close(fc_cli_module *m)
{
    if (m->handle)
        dlclose(m->handle);
    m->handle = NULL;
    m->api = NULL;
}
