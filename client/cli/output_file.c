/* output_file.c — see output_file.h. */
#include "output_file.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "fc_error.h"

fc_code fc_output_format_from_path(const char *path, fc_image_format *out, fc_error *err)
{
    static const struct {
        const char *extension;
        fc_image_format format;
    } known[] = {
        { ".png", FC_FORMAT_PNG }, { ".jpg", FC_FORMAT_JPEG }, { ".jpeg", FC_FORMAT_JPEG },
        { ".exr", FC_FORMAT_EXR },
    };
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (dot && (!slash || dot > slash)) {
        for (size_t i = 0; i < sizeof known / sizeof known[0]; i++) {
            if (strcasecmp(dot, known[i].extension) == 0) {
                *out = known[i].format;
                return FC_OK;
            }
        }
    }
    return fc_error_set(err, FC_ERR_USAGE, "cannot tell the image format of \"%s\": use .png, .jpg, .jpeg or .exr",
                        path);
}

const char *fc_output_format_name(fc_image_format format)
{
    switch (format) {
    case FC_FORMAT_PNG: return "PNG";
    case FC_FORMAT_JPEG: return "JPEG";
    case FC_FORMAT_EXR: return "EXR";
    case FC_FORMAT_RAW: return "RAW";
    case FC_FORMAT_H264: return "H.264";
    }
    return "unknown";
}

fc_code fc_output_write(const char *path, const uint8_t *data, size_t size, fc_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "cannot write %s: %s", path, strerror(errno));
    bool written = fwrite(data, 1, size, f) == size;
    int write_errno = errno;
    if (fclose(f) != 0 && written) {
        written = false;
        write_errno = errno;
    }
    if (!written) {
        remove(path);
        return fc_error_set(err, FC_ERR_IO, "cannot write %s: %s", path, strerror(write_errno));
    }
    return FC_OK;
}
