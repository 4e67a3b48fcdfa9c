/* reader_vtkxml_xml.c — the XML part both VTK XML readers share (see the header). */
#include "reader_vtkxml_xml.h"

#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"

void fc_vx_fail(fc_vx_xml *x, fc_code code, const char *fmt, ...)
{
    if (x->code != FC_OK)
        return;
    char reason[FC_ERROR_MESSAGE_MAX];
    va_list args;
    va_start(args, fmt);
    vsnprintf(reason, sizeof reason, fmt, args);
    va_end(args);
    x->code = fc_error_set(x->err, code, "%s: line %lu: %s", x->c->name,
                           (unsigned long)XML_GetCurrentLineNumber(x->parser), reason);
    XML_StopParser(x->parser, XML_FALSE);
}

void fc_vx_on_file(fc_vx_xml *x, const char **attrs)
{
    const char *order = fc_vx_attribute(attrs, "byte_order"), *header = fc_vx_attribute(attrs, "header_type");
    const char *compressor = fc_vx_attribute(attrs, "compressor");
    fc_vx_encoding *e = &x->encoding;
    e->big_endian = order != NULL && strcmp(order, "BigEndian") == 0;
    if (order != NULL && !e->big_endian && strcmp(order, "LittleEndian") != 0)
        return fc_vx_fail(x, FC_ERR_PARSE, "byte_order '%.40s' is neither LittleEndian nor BigEndian", order);
    e->header64 = header != NULL && strcmp(header, "UInt64") == 0;
    if (header != NULL && !e->header64 && strcmp(header, "UInt32") != 0)
        return fc_vx_fail(x, FC_ERR_PARSE, "header_type '%.40s' is neither UInt32 nor UInt64", header);
    e->compressed = compressor != NULL && compressor[0] != '\0';
    if (e->compressed && strcmp(compressor, "vtkZLibDataCompressor") != 0)
        return fc_vx_fail(x, FC_ERR_PARSE, "compressor '%.40s' is not supported (only vtkZLibDataCompressor: write "
                                           "with SetCompressorTypeToZLib or none)", compressor);
    x->have_file = true;
}

void fc_vx_on_appended(fc_vx_xml *x, const char **attrs)
{
    const char *encoding = fc_vx_attribute(attrs, "encoding");
    x->have_appended = true;
    x->appended_base64 = encoding == NULL || strcmp(encoding, "base64") == 0;
    if (!x->appended_base64 && strcmp(encoding, "raw") != 0)
        fc_vx_fail(x, FC_ERR_PARSE, "AppendedData encoding '%.30s' is neither raw nor base64", encoding);
}

/* Where appended data starts in a file's bytes: just after the "<AppendedData ...>" start tag; *xml_size is
 * then what expat is given (up to and including that tag). NULL, with *xml_size = size, when there is no such
 * tag or it never closes. */
static const uint8_t *find_appended(const uint8_t *data, size_t size, size_t *xml_size)
{
    static const char tag[] = "<AppendedData";
    *xml_size = size;
    for (size_t i = 0; i + sizeof tag - 1 <= size; i++) {
        const uint8_t *hit = memchr(data + i, '<', size - i);
        if (hit == NULL || (size_t)(hit - data) + sizeof tag - 1 > size)
            return NULL;
        i = (size_t)(hit - data);
        if (memcmp(hit, tag, sizeof tag - 1) != 0)
            continue;
        const uint8_t *close = memchr(hit, '>', size - i);
        if (close == NULL)
            return NULL;
        *xml_size = (size_t)(close + 1 - data); /* up to and including the start tag */
        return close + 1;
    }
    return NULL;
}

static fc_code parse_bytes(fc_vx_xml *x, size_t size, bool complete)
{
    size_t done = 0;
    enum XML_Status status = XML_STATUS_OK;
    do { /* expat takes int lengths: feed large files in pieces */
        size_t piece = size - done > INT_MAX / 2 ? INT_MAX / 2 : size - done;
        status = XML_Parse(x->parser, (const char *)x->c->data + done, (int)piece, complete && done + piece == size);
        done += piece;
    } while (status == XML_STATUS_OK && done < size);
    if (status == XML_STATUS_ERROR && x->code == FC_OK)
        x->code = fc_error_set(x->err, FC_ERR_PARSE, "%s: line %lu: XML: %s", x->c->name,
                               (unsigned long)XML_GetCurrentLineNumber(x->parser),
                               XML_ErrorString(XML_GetErrorCode(x->parser)));
    return x->code;
}

/* The appended bytes start after the '_' that marks them; whitespace may come before it. */
static fc_code skip_to_data(fc_vx_xml *x, const uint8_t **appended, size_t *appended_size)
{
    const uint8_t *p = *appended;
    size_t left = x->c->size - (size_t)(p - x->c->data);
    while (left > 0 && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t'))
        p++, left--;
    if (left == 0 || *p != '_')
        return fc_error_set(x->err, FC_ERR_PARSE, "%s: AppendedData does not start with '_'", x->c->name);
    *appended = p + 1;
    *appended_size = left - 1;
    return FC_OK;
}

fc_code fc_vx_parse(fc_vx_xml *x, XML_StartElementHandler start, XML_EndElementHandler end,
                    XML_CharacterDataHandler text, void *user, const uint8_t **appended, size_t *appended_size)
{
    size_t xml_size = 0;
    *appended = find_appended(x->c->data, x->c->size, &xml_size);
    *appended_size = 0;
    x->parser = XML_ParserCreate(NULL);
    if (x->parser == NULL)
        return fc_error_set(x->err, FC_ERR_NOMEM, "%s: cannot create the XML parser", x->c->name);
    XML_SetUserData(x->parser, user);
    XML_SetElementHandler(x->parser, start, end);
    XML_SetCharacterDataHandler(x->parser, text);
    fc_code code = parse_bytes(x, xml_size, *appended == NULL);
    XML_ParserFree(x->parser);
    x->parser = NULL;
    if (code == FC_OK && !x->have_file)
        code = fc_error_set(x->err, FC_ERR_PARSE, "%s: no VTKFile element", x->c->name);
    if (code == FC_OK && *appended != NULL && !x->have_appended)
        code = fc_error_set(x->err, FC_ERR_PARSE, "%s: AppendedData is not a child of VTKFile", x->c->name);
    if (code == FC_OK && *appended != NULL)
        code = skip_to_data(x, appended, appended_size);
    if (code != FC_OK)
        *appended = NULL, *appended_size = 0;
    return code;
}

const char *fc_vx_attribute(const char **attrs, const char *name)
{
    for (size_t i = 0; attrs[i] != NULL; i += 2)
        if (strcmp(attrs[i], name) == 0)
            return attrs[i + 1];
    return NULL;
}

bool fc_vx_text_append(char **text, size_t *len, size_t *cap, const char *add, size_t n)
{
    if (*len + n > *cap) {
        size_t grown_cap = *cap ? *cap : 256;
        while (grown_cap < *len + n)
            grown_cap *= 2;
        char *grown = realloc(*text, grown_cap);
        if (grown == NULL)
            return false;
        *text = grown;
        *cap = grown_cap;
    }
    memcpy(*text + *len, add, n);
    *len += n;
    return true;
}
