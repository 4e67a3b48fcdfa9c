/* particle_reader.h — turns particle files into the in-memory frame the wire carries.
 * Formats: raw little-endian float32 xyz (.f32), PLY (ascii, binary little/big
 * endian), legacy VTK (ascii and binary POLYDATA / UNSTRUCTURED_GRID), CSV with a
 * header line, Houdini classic BGEO (partio's .bgeo, gzip'd or not), numpy .npy (N, 3) float
 * arrays, VTK XML .vtu/.vtp (ascii, binary, appended raw or base64, zlib-compressed),
 * .pvd collections (by path: the first dataset listed) and HDF5 (libhdf5: SWIFT/GADGET
 * snapshots, PySPH output, H5Part, or any layout named by a dataset path), known by its
 * signature rather than its name. A bad file gets FC_ERR_PARSE (or FC_ERR_IO) with a message naming
 * the file and what is wrong; never a crash. */
#ifndef FC_PARTICLE_READER_H
#define FC_PARTICLE_READER_H

#include <stdbool.h>
#include "fluidcast_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fc_file_format {
    FC_FILE_UNKNOWN = 0,
    FC_FILE_F32,
    FC_FILE_PLY,
    FC_FILE_VTK,
    FC_FILE_CSV,
    FC_FILE_BGEO,
    FC_FILE_NPY,
    FC_FILE_VTK_XML,
    FC_FILE_PVD,
    FC_FILE_HDF5
} fc_file_format;

/* --select: which particles to keep, by one attribute's value. */
enum { FC_SELECT_MAX = 8, FC_SELECT_MAX_VALUES = 16, FC_SELECT_NAME_MAX = 64, FC_SELECT_TEXT_MAX = 160 };

typedef enum fc_select_op {
    FC_SELECT_IN,      /* ATTR=V[,V...]: equal to one of the values */
    FC_SELECT_NOT_IN,  /* ATTR!=V[,V...]: equal to none of them */
    FC_SELECT_LT,      /* ATTR<V */
    FC_SELECT_LE,      /* ATTR<=V */
    FC_SELECT_GT,      /* ATTR>V */
    FC_SELECT_GE       /* ATTR>=V */
} fc_select_op;

typedef struct fc_select {
    char attribute[FC_SELECT_NAME_MAX];  /* matched case-insensitively */
    fc_select_op op;
    uint32_t value_count;
    double values[FC_SELECT_MAX_VALUES];
    char text[FC_SELECT_TEXT_MAX];       /* as given, for messages */
} fc_select;

/* Parses "ATTR=V[,V...]", "ATTR!=V[,V...]", "ATTR<V", "ATTR<=V", "ATTR>V" or "ATTR>=V"
 * ("==" also means "="). FC_ERR_USAGE naming the text for anything else. */
fc_code fc_select_parse(const char *text, fc_select *out, fc_error *err);

/* Float64 positions far from the origin (x ~ 1e7 with a spacing of 1e-3) lose their spacing
 * in float32. A read with a recentring shifts them by the bounds' centre in double before the
 * conversion: the first float64 file read decides (recentre when the centre lies farther from
 * the origin than 100 x the largest extent) and every later read with the same state uses that
 * offset, so a sequence keeps one frame of reference. Float32 files are never shifted. */
typedef struct fc_recentring {
    bool decided;          /* a float64 file was read: applied and offset hold */
    bool applied;          /* positions are file positions - offset */
    double offset[3];
} fc_recentring;

/* How to read a file beyond what its format says: the command line's reader options.
 * A zeroed struct (or NULL) means the defaults. */
typedef struct fc_read_options {
    const char *dataset;   /* HDF5 --dataset: a group, an N x 3 dataset, or "x=PATH,y=PATH,z=PATH"
                            * (docs/formats.md, HDF5); NULL: found by the file's layout */
    bool has_step;         /* H5Part --step: read group Step#step ... */
    uint64_t step;         /* ... instead of the lowest-numbered step */
    /* --select: a particle is kept when all hold. Attributes: x y z, density, vx vy vz, speed, id,
     * radius when the frame has them, and any other per-particle scalar the file names (a CSV column
     * such as DualSPHysics' Type, a PySPH array such as tag, a SWIFT dataset such as Masses); x, y, z
     * in the file's coordinates, before any recentring. An unknown
     * name is an error listing those the file has; a selection that keeps nothing is an error naming it. */
    uint32_t select_count;
    fc_select select[FC_SELECT_MAX];
    fc_recentring *recentring;   /* NULL: float64 positions are converted as they are */
} fc_read_options;

/* From the file name's extension (case-insensitive): .f32 .ply .vtk .csv .npy .vtu .vtp .pvd, .bgeo
 * (also .bgeo.gz, .bhclassic, and .bgeo.sc so that its reader can refuse it clearly), .h5 .hdf5 .hdf
 * .h5part. fc_read_particles trusts the HDF5 signature over any extension. */
fc_file_format fc_file_format_from_path(const char *path);

/* Whether data is an HDF5 file: its signature "\x89HDF\r\n\x1a\n" at offset 0, 512, 1024, 2048, ...
 * (a user block may come first). */
bool fc_is_hdf5(const uint8_t *data, size_t size);

/* Reads `path` (an HDF5 file by its signature, else the format from its extension)
 * into *frame (zeroed first; free with fc_frame_free). Positions always; density,
 * velocity and ids when the file has them. A .pvd collection reads the first DataSet
 * it lists (a .vtu or .vtp, relative to the .pvd's directory). */
fc_code fc_read_particles(const char *path, fc_frame *frame, fc_error *err);
/* Same, with reader options (NULL: the defaults). */
fc_code fc_read_particles_with(const char *path, const fc_read_options *options, fc_frame *frame, fc_error *err);

/* Same, from a buffer in memory; `name` is used in error messages. FC_FILE_PVD is
 * refused here: a collection names other files, which only a path can resolve.
 * FC_FILE_UNKNOWN reads HDF5 when the data has its signature. */
fc_code fc_read_particles_mem(const uint8_t *data, size_t size, fc_file_format format,
                              const char *name, fc_frame *frame, fc_error *err);
fc_code fc_read_particles_mem_with(const uint8_t *data, size_t size, fc_file_format format, const char *name,
                                   const fc_read_options *options, fc_frame *frame, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
