/* cli_frames.c — see cli_frames.h. */
#include "cli_frames.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_values.h"
#include "fc_error.h"

fc_code fc_cli_parse_format(const char *option, const char *text, fc_image_format *out, fc_error *err)
{
    static const char *const names[] = {"png", "jpg", "jpeg", "exr", "raw", "h264", NULL};
    static const fc_image_format formats[] = {FC_FORMAT_PNG, FC_FORMAT_JPEG, FC_FORMAT_JPEG, FC_FORMAT_EXR,
                                              FC_FORMAT_RAW, FC_FORMAT_H264};
    int index;
    fc_code code = fc_cli_parse_choice(option, text, names, &index, err);
    if (code == FC_OK)
        *out = formats[index];
    return code;
}

const char *fc_cli_format_extension(fc_image_format format)
{
    switch (format) {
    case FC_FORMAT_PNG: return "png";
    case FC_FORMAT_JPEG: return "jpg";
    case FC_FORMAT_EXR: return "exr";
    case FC_FORMAT_RAW: return "raw";
    case FC_FORMAT_H264: return "h264";
    }
    return "bin";
}

fc_code fc_cli_ensure_dir(const char *dir, fc_error *err)
{
    struct stat st;
    if (stat(dir, &st) == 0 && S_ISDIR(st.st_mode))
        return FC_OK;
    if (mkdir(dir, 0777) != 0)
        return fc_error_set(err, FC_ERR_IO, "cannot create the directory %s: %s", dir, strerror(errno));
    return FC_OK;
}

fc_code fc_cli_ensure_parent_dir(const char *path, fc_error *err)
{
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path)
        return FC_OK;
    char dir[4096];
    size_t len = (size_t)(slash - path);
    if (len >= sizeof dir)
        return fc_error_set(err, FC_ERR_USAGE, "the directory of %s is too long", path);
    memcpy(dir, path, len);
    dir[len] = '\0';
    return fc_cli_ensure_dir(dir, err);
}

fc_code fc_cli_frame_path(char *out, size_t size, const char *dir, const char *prefix, uint64_t number,
                          fc_image_format format, fc_error *err)
{
    int n = snprintf(out, size, "%s/%s_%06llu.%s", dir, prefix, (unsigned long long)number,
                     fc_cli_format_extension(format));
    if (n < 0 || (size_t)n >= size)
        return fc_error_set(err, FC_ERR_USAGE, "the output path in %s is too long", dir);
    return FC_OK;
}
