/* reader_vtkxml_data.h — internal to the VTK XML reader: the bytes of one
 * binary DataArray, wherever VTK put them. A source is either raw bytes (raw
 * appended data) or base64 text (inline "binary" arrays and base64 appended
 * data) decoded as it is read, so that a header and its data encoded as one
 * base64 stream or as two (each padded, as VTK writes compressed arrays) read
 * the same. A block is VTK's header (UInt32 or UInt64 words) and its data, plain
 * or in vtkZLibDataCompressor blocks, and the type names of DataArrays. Both VTK
 * XML readers (particles here, meshes in client/meshes/mesh_vtp.c) read their
 * arrays with it; the XML part they share is reader_vtkxml_xml.h. */
#ifndef FC_READER_VTKXML_DATA_H
#define FC_READER_VTKXML_DATA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "fluidcast_types.h"
#include "reader_cursor.h"

typedef struct fc_vx_source {
    const uint8_t *data;
    size_t size;
    size_t pos;
    bool base64;
    uint8_t pending[3]; /* decoded bytes of the current base64 quad not yet handed out */
    size_t pending_count;
} fc_vx_source;

void fc_vx_source_init(fc_vx_source *s, const uint8_t *data, size_t size, bool base64);

/* The format of a block: header word size, byte order, compression. */
typedef struct fc_vx_encoding {
    bool header64;
    bool big_endian;
    bool compressed;
} fc_vx_encoding;

/* Reads one block from s into a malloc'd *out of exactly `expected` bytes (the
 * array's points x components x value size): the header must say so. `what`
 * names the array in messages ("name: what: ..."). FC_ERR_PARSE for a header
 * that disagrees, data that runs out, bad base64 or zlib data; FC_ERR_NOMEM. */
fc_code fc_vx_read_block(fc_vx_source *s, const fc_vx_encoding *encoding, size_t expected, const char *name,
                         const char *what, uint8_t **out, fc_error *err);

/* A DataArray's type name (Int8 ... UInt64, Float32, Float64) as a scalar type; false for others and NULL. */
bool fc_vx_scalar_type(const char *name, fc_scalar_type *type);

#endif
