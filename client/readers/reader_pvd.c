/* reader_pvd.c — ParaView's .pvd collections: an XML list of datasets, one per
 * time step (<VTKFile type="Collection"><Collection><DataSet timestep=".."
 * file=".."/>...). fluidcast renders one frame, so a .pvd stands for the first
 * DataSet it lists; particle_reader.c resolves and reads that file. */
#include "reader_formats.h"

#include <expat.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include "fc_error.h"

typedef struct pvd_state {
    const fc_cursor *c;
    fc_error *err;
    fc_code code;
    XML_Parser parser;
    unsigned depth;
    bool is_collection;
    bool found;
    char *file;
    size_t file_size;
} pvd_state;

static void pvd_fail(pvd_state *s, const char *reason, const char *detail)
{
    if (s->code != FC_OK)
        return;
    s->code = fc_error_set(s->err, FC_ERR_PARSE, "%s: line %lu: %s%.60s", s->c->name,
                           (unsigned long)XML_GetCurrentLineNumber(s->parser), reason, detail);
    XML_StopParser(s->parser, XML_FALSE);
}

static const char *attribute(const XML_Char **attributes, const char *name)
{
    for (size_t i = 0; attributes[i] != NULL; i += 2) {
        if (strcmp(attributes[i], name) == 0)
            return attributes[i + 1];
    }
    return NULL;
}

static void XMLCALL on_start(void *user, const XML_Char *name, const XML_Char **attrs)
{
    pvd_state *s = user;
    unsigned depth = s->depth++;
    if (depth == 0) {
        const char *type = attribute(attrs, "type");
        if (strcmp(name, "VTKFile") != 0 || type == NULL || strcmp(type, "Collection") != 0)
            pvd_fail(s, "not a .pvd collection (expected <VTKFile type=\"Collection\">)", "");
        s->is_collection = true;
        return;
    }
    if (depth != 2 || s->found || strcmp(name, "DataSet") != 0)
        return;
    const char *file = attribute(attrs, "file");
    if (file == NULL || file[0] == '\0')
        return pvd_fail(s, "DataSet without a file attribute", "");
    if (strlen(file) >= s->file_size)
        return pvd_fail(s, "DataSet file name too long: ", file);
    snprintf(s->file, s->file_size, "%s", file);
    s->found = true;
    XML_StopParser(s->parser, XML_FALSE); /* the first one is all we read */
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    pvd_state *s = user;
    (void)name;
    s->depth--;
}

fc_code fc_pvd_first_dataset(fc_cursor *c, char *file, size_t file_size, fc_error *err)
{
    pvd_state s = { c, err, FC_OK, XML_ParserCreate(NULL), 0, false, false, file, file_size };
    if (s.parser == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: cannot create the XML parser", c->name);
    XML_SetUserData(s.parser, &s);
    XML_SetElementHandler(s.parser, on_start, on_end);
    enum XML_Status status = XML_STATUS_OK;
    if (c->size > INT_MAX)
        s.code = fc_error_set(err, FC_ERR_PARSE, "%s: %zu bytes is too large for a .pvd collection", c->name, c->size);
    else
        status = XML_Parse(s.parser, (const char *)c->data, (int)c->size, XML_TRUE);
    if (s.code == FC_OK && status == XML_STATUS_ERROR && !s.found)
        s.code = fc_error_set(err, FC_ERR_PARSE, "%s: line %lu: XML: %s", c->name,
                              (unsigned long)XML_GetCurrentLineNumber(s.parser),
                              XML_ErrorString(XML_GetErrorCode(s.parser)));
    if (s.code == FC_OK && !s.found)
        s.code = fc_error_set(err, FC_ERR_PARSE, "%s: the collection lists no DataSet", c->name);
    XML_ParserFree(s.parser);
    return s.code;
}
