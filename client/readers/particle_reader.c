/* particle_reader.c — format detection, file loading and dispatch to the format readers. */
#include "particle_reader.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "fc_file.h"
#include "fc_frame.h"
#include "reader_cursor.h"
#include "reader_fields.h"
#include "reader_formats.h"
#include "reader_select.h"

static const struct {
    const char *extension;
    fc_file_format format;
} format_extensions[] = {
    { "f32", FC_FILE_F32 },
    { "ply", FC_FILE_PLY },
    { "vtk", FC_FILE_VTK },
    { "csv", FC_FILE_CSV },
    { "bgeo", FC_FILE_BGEO },
    { "bhclassic", FC_FILE_BGEO },
    { "bgeo.gz", FC_FILE_BGEO },
    { "bgeo.sc", FC_FILE_BGEO },
    { "npy", FC_FILE_NPY },
    { "vtu", FC_FILE_VTK_XML },
    { "vtp", FC_FILE_VTK_XML },
    { "pvd", FC_FILE_PVD },
    { "h5", FC_FILE_HDF5 },
    { "hdf5", FC_FILE_HDF5 },
    { "hdf", FC_FILE_HDF5 },
    { "h5part", FC_FILE_HDF5 },
};

/* Whether the name ends with "." extension, case-insensitively. */
static bool has_extension(const char *base, const char *extension)
{
    size_t n = strlen(base), m = strlen(extension);
    return n > m && base[n - m - 1] == '.' && fc_span_iequals((fc_span){ base + n - m, m }, extension);
}

fc_file_format fc_file_format_from_path(const char *path)
{
    if (path == NULL)
        return FC_FILE_UNKNOWN;
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    for (size_t i = 0; i < sizeof format_extensions / sizeof format_extensions[0]; i++) {
        if (has_extension(base, format_extensions[i].extension))
            return format_extensions[i].format;
    }
    return FC_FILE_UNKNOWN;
}

static fc_code unknown_format(const char *name, fc_error *err)
{
    return fc_error_set(err, FC_ERR_PARSE, "%s: unknown particle file format (expected .f32, .ply, .vtk, .vtu, .vtp, .pvd, .csv, .bgeo, .npy or an HDF5 file)",
                        name);
}

static fc_code read_format(fc_cursor *c, fc_file_format format, fc_frame *frame, fc_error *err)
{
    switch (format) {
    case FC_FILE_F32:
        return fc_read_f32(c, frame, err);
    case FC_FILE_PLY:
        return fc_read_ply(c, frame, err);
    case FC_FILE_VTK:
        return fc_read_vtk(c, frame, err);
    case FC_FILE_CSV:
        return fc_read_csv(c, frame, err);
    case FC_FILE_BGEO:
        return fc_read_bgeo(c, frame, err);
    case FC_FILE_NPY:
        return fc_read_npy(c, frame, err);
    case FC_FILE_VTK_XML:
        return fc_read_vtkxml(c, frame, err);
    case FC_FILE_HDF5:
        /* Checked here, so that libhdf5 (or the command's module of it) only ever sees HDF5. */
        if (!fc_is_hdf5(c->data, c->size))
            return fc_error_set(err, FC_ERR_PARSE, "%s: not an HDF5 file (no \\x89HDF signature)", c->name);
        return fc_read_hdf5(c, frame, err);
    case FC_FILE_PVD:
        return fc_error_set(err, FC_ERR_PARSE, "%s: a .pvd collection names other files: read it by its path, "
                            "or give one of its datasets", c->name);
    case FC_FILE_UNKNOWN:
        break;
    }
    return unknown_format(c->name, err);
}

bool fc_is_hdf5(const uint8_t *data, size_t size)
{
    static const uint8_t signature[8] = { 0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n' };
    if (data == NULL)
        return false;
    /* HDF5 looks at 0, then 512 and every doubling after it (a user block of 512 << k bytes). */
    for (size_t at = 0; at <= size && size - at >= sizeof signature; at = at == 0 ? 512 : 2 * at) {
        if (memcmp(data + at, signature, sizeof signature) == 0)
            return true;
        if (at > SIZE_MAX / 4)
            break;
    }
    return false;
}

/* Recentre when the centre is farther from the origin than this many times the largest extent: float32 then
 * keeps at least 1/(100 x 2^-24) ~ 170000 steps across the data instead of the 2^24 it would have at the origin. */
#define FC_RECENTRE_RATIO 100.0

/* The first float64 read decides the recentring from the bounds of its positions. */
static void decide_recentring(const fc_positions64 *p, fc_recentring *r)
{
    double lo[3], hi[3], centre[3], extent = 0.0, distance = 0.0;
    for (int k = 0; k < 3; k++)
        lo[k] = hi[k] = p->xyz[k];
    for (uint64_t i = 0; i < p->count; i++)
        for (int k = 0; k < 3; k++) {
            double v = p->xyz[3 * i + (uint64_t)k];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    for (int k = 0; k < 3; k++) {
        centre[k] = lo[k] / 2 + hi[k] / 2;
        extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
        distance = fabs(centre[k]) > distance ? fabs(centre[k]) : distance;
    }
    r->decided = true;
    r->applied = distance > FC_RECENTRE_RATIO * extent && distance > 0.0;
    for (int k = 0; k < 3; k++)
        r->offset[k] = r->applied ? centre[k] : 0.0;
}

/* Converts the staged float64 positions to the frame's float32, less the recentring's offset. */
static fc_code finish_positions64(fc_positions64 *p, fc_recentring *r, fc_frame *frame, const char *name,
                                  fc_error *err)
{
    if (p->out_of_memory)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for %llu float64 positions", name,
                            (unsigned long long)frame->count);
    if (p->xyz == NULL || p->count != frame->count)
        return FC_OK;
    if (!r->decided)
        decide_recentring(p, r);
    for (uint64_t i = 0; i < p->count; i++)
        for (int k = 0; k < 3; k++) {
            double v = p->xyz[3 * i + (uint64_t)k] - (r->applied ? r->offset[k] : 0.0);
            if (!(fabs(v) <= FLT_MAX))
                return fc_error_set(err, FC_ERR_PARSE, "%s: particle %llu: %c = %g is beyond float range", name,
                                    (unsigned long long)i, 'x' + k, p->xyz[3 * i + (uint64_t)k]);
            frame->positions[3 * i + (uint64_t)k] = (float)v;
        }
    return FC_OK;
}

fc_code fc_read_particles_mem(const uint8_t *data, size_t size, fc_file_format format,
                              const char *name, fc_frame *frame, fc_error *err)
{
    return fc_read_particles_mem_with(data, size, format, name, NULL, frame, err);
}

/* The cursor's data read as `format`, then the selection of its options
 * applied; never a partial frame. */
static fc_code read_and_select(fc_cursor *c, fc_file_format format, fc_frame *frame, fc_error *err)
{
    if (format == FC_FILE_UNKNOWN && fc_is_hdf5(c->data, c->size))
        format = FC_FILE_HDF5;
    /* Named scalars beyond the frame's attributes are kept only when a selection may need them. */
    fc_read_extras *extras = c->options->select_count > 0 ? calloc(1, sizeof *extras) : NULL;
    if (c->options->select_count > 0 && extras == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", c->name);
    c->extras = extras;
    fc_positions64 positions64 = { NULL, 0, false };
    fc_recentring *recentring = c->options->recentring;
    c->positions64 = recentring != NULL ? &positions64 : NULL;
    fc_code code = read_format(c, format, frame, err);
    if (code == FC_OK && recentring != NULL)
        code = finish_positions64(&positions64, recentring, frame, c->name, err);
    free(positions64.xyz);
    static const double no_offset[3] = { 0.0, 0.0, 0.0 };
    const double *offset = recentring != NULL && recentring->applied ? recentring->offset : no_offset;
    if (code == FC_OK)
        code = fc_select_apply(frame, extras, c->options, offset, c->name, err);
    if (extras != NULL)
        fc_extras_free(extras);
    free(extras);
    if (code != FC_OK)
        fc_frame_free(frame); /* never hand out a partial frame */
    return code;
}

/* Reads `data` as `format`; `adoptable` is data itself when a reader may
 * keep it as a frame's array (then set to NULL), else NULL. */
static fc_code read_mem(const uint8_t *data, size_t size, fc_file_format format, const char *name,
                        const fc_read_options *options, uint8_t **adoptable, fc_frame *frame, fc_error *err)
{
    static const fc_read_options defaults; /* zero: the defaults */
    if (frame == NULL)
        return fc_error_set(err, FC_ERR_USAGE, "fc_read_particles_mem: frame is NULL");
    memset(frame, 0, sizeof *frame);
    if (name == NULL)
        name = "<memory>";
    if (data == NULL && size != 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s: data is NULL but size is %zu", name, size);
    if (size == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: empty file", name);
    fc_cursor c;
    fc_cursor_init(&c, data, size, name);
    c.options = options != NULL ? options : &defaults;
    c.adoptable = *adoptable;
    fc_code code = read_and_select(&c, format, frame, err);
    *adoptable = c.adoptable;
    return code;
}

fc_code fc_read_particles_mem_with(const uint8_t *data, size_t size, fc_file_format format, const char *name,
                                   const fc_read_options *options, fc_frame *frame, fc_error *err)
{
    uint8_t *copy_only = NULL;
    return read_mem(data, size, format, name, options, &copy_only, frame, err);
}

/* The first DataSet of the collection at `path`, as a path: relative names are relative to the .pvd's directory. */
static fc_code pvd_dataset_path(const char *path, char *dataset, size_t dataset_size, fc_error *err)
{
    uint8_t *data = NULL;
    size_t size = 0;
    fc_code code = fc_read_file(path, SIZE_MAX, &data, &size, err);
    if (code != FC_OK)
        return code;
    char file[4096];
    fc_cursor c;
    fc_cursor_init(&c, data, size, path);
    code = size == 0 ? fc_error_set(err, FC_ERR_PARSE, "%s: empty file", path)
                     : fc_pvd_first_dataset(&c, file, sizeof file, err);
    free(data);
    if (code != FC_OK)
        return code;
    const char *slash = strrchr(path, '/');
    int dir_len = file[0] == '/' || slash == NULL ? 0 : (int)(slash + 1 - path);
    if (snprintf(dataset, dataset_size, "%.*s%s", dir_len, path, file) >= (int)dataset_size)
        return fc_error_set(err, FC_ERR_PARSE, "%s: first DataSet's path is too long", path);
    fc_file_format format = fc_file_format_from_path(dataset);
    if (format == FC_FILE_PVD || format == FC_FILE_UNKNOWN)
        return fc_error_set(err, FC_ERR_PARSE, "%s: first DataSet '%s' is not a particle file (.vtu, .vtp, ...)", path,
                            file);
    return FC_OK;
}

/* A .pvd stands for its first dataset; its errors are reported under the .pvd's name too. */
static fc_code read_pvd(const char *path, const fc_read_options *options, fc_frame *frame, fc_error *err)
{
    char dataset[4096 + 256];
    fc_code code = pvd_dataset_path(path, dataset, sizeof dataset, err);
    if (code != FC_OK)
        return code;
    fc_error inner = { FC_OK, "" };
    code = fc_read_particles_with(dataset, options, frame, &inner);
    if (code != FC_OK)
        return fc_error_set(err, code, "%s: its first DataSet: %s", path, inner.message);
    return FC_OK;
}

fc_code fc_read_particles(const char *path, fc_frame *frame, fc_error *err)
{
    return fc_read_particles_with(path, NULL, frame, err);
}

fc_code fc_read_particles_with(const char *path, const fc_read_options *options, fc_frame *frame, fc_error *err)
{
    if (frame == NULL || path == NULL)
        return fc_error_set(err, FC_ERR_USAGE, "fc_read_particles: path and frame must not be NULL");
    memset(frame, 0, sizeof *frame);
    fc_file_format format = fc_file_format_from_path(path);
    if (format == FC_FILE_PVD)
        return read_pvd(path, options, frame, err);
    uint8_t *data = NULL;
    size_t size = 0;
    fc_code code = fc_read_file(path, SIZE_MAX, &data, &size, err);
    if (code != FC_OK)
        return code;
    /* HDF5 files carry many names (.h5, .hdf5, .snap, .0, none): the signature decides. */
    if (fc_is_hdf5(data, size))
        format = FC_FILE_HDF5;
    /* data is malloc'd: a reader may keep it as the frame's positions (then it is not freed here). */
    uint8_t *adoptable = data;
    code = format == FC_FILE_UNKNOWN ? unknown_format(path, err)
                                     : read_mem(data, size, format, path, options, &adoptable, frame, err);
    free(adoptable);
    return code;
}
