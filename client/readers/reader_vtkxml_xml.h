/* reader_vtkxml_xml.h — internal to the VTK XML readers: what both of them
 * (particles in reader_vtkxml.c, meshes in client/meshes/mesh_vtp.c) need of a
 * file's XML part, parsed by expat. The first error, with its XML line, stops
 * the parse; the VTKFile element's encoding and the AppendedData element are
 * read the same way for both; raw appended bytes are not XML, so expat sees a
 * file only up to the AppendedData start tag and the bytes after its '_' are
 * handed back for the arrays to be read from by offset. */
#ifndef FC_READER_VTKXML_XML_H
#define FC_READER_VTKXML_XML_H

#include <expat.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "fluidcast_types.h"
#include "reader_cursor.h"
#include "reader_vtkxml_data.h"

/* A reader's document embeds one; zero it, then set c and err. */
typedef struct fc_vx_xml {
    const fc_cursor *c;         /* the file: its name for messages, its bytes */
    fc_error *err;
    fc_code code;               /* the first error; FC_OK until then */
    XML_Parser parser;          /* while fc_vx_parse runs */
    bool have_file;             /* a VTKFile element was read (fc_vx_on_file) */
    fc_vx_encoding encoding;    /* VTKFile's header_type, byte_order and compressor */
    bool have_appended;         /* an AppendedData element was read (fc_vx_on_appended) */
    bool appended_base64;       /* its encoding: base64 (VTK's default) or raw */
} fc_vx_xml;

/* Records the first error as "name: line N: reason" and stops the parser (from inside expat's handlers). */
void fc_vx_fail(fc_vx_xml *x, fc_code code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* The VTKFile element's byte_order, header_type and compressor (only vtkZLibDataCompressor) into x->encoding,
 * and have_file; its type is the reader's to check. */
void fc_vx_on_file(fc_vx_xml *x, const char **attrs);

/* The AppendedData element: its encoding, raw or base64. */
void fc_vx_on_appended(fc_vx_xml *x, const char **attrs);

/* Parses x->c's XML with the reader's handlers (`user` is their user data), then checks that it had a VTKFile
 * and, where the bytes hold appended data, an AppendedData element starting with '_': *appended and
 * *appended_size are the bytes after it (NULL and 0 for a file without). FC_ERR_PARSE with the line for XML
 * that is not well formed, the handlers' first error, FC_ERR_NOMEM. */
fc_code fc_vx_parse(fc_vx_xml *x, XML_StartElementHandler start, XML_EndElementHandler end,
                    XML_CharacterDataHandler text, void *user, const uint8_t **appended, size_t *appended_size);

/* The value of attribute `name` in expat's name/value list (NULL-terminated), or NULL. */
const char *fc_vx_attribute(const char **attrs, const char *name);

/* Appends n bytes of a DataArray's character data to a growing buffer (*text, *len, *cap; doubling from 256).
 * false when memory runs out (the buffer is left as it was). */
bool fc_vx_text_append(char **text, size_t *len, size_t *cap, const char *add, size_t n);

#endif
