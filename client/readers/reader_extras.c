/* reader_extras.c — see reader_extras.h. */
#include "reader_extras.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"

double *fc_extras_add(fc_read_extras *x, fc_span name, uint64_t count, const char *file, fc_error *err,
                      fc_code *code)
{
    *code = FC_OK;
    if (x->size == FC_EXTRAS_MAX || name.len == 0 || name.len >= FC_EXTRA_NAME_MAX)
        return NULL;
    char copy[FC_EXTRA_NAME_MAX];
    memcpy(copy, name.ptr, name.len);
    copy[name.len] = '\0';
    if (fc_extras_find(x, copy) != NULL)
        return NULL;
    double *values = count <= SIZE_MAX / sizeof *values ? malloc((size_t)count * sizeof *values) : NULL;
    if (values == NULL) {
        *code = fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for attribute '%s' of %llu particles", file, copy,
                             (unsigned long long)count);
        return NULL;
    }
    for (uint64_t i = 0; i < count; i++)
        values[i] = NAN;
    memcpy(x->names[x->size], copy, name.len + 1);
    x->values[x->size++] = values;
    return values;
}

const double *fc_extras_find(const fc_read_extras *x, const char *name)
{
    for (size_t i = 0; i < x->size; i++)
        if (fc_span_iequals((fc_span){ x->names[i], strlen(x->names[i]) }, name))
            return x->values[i];
    return NULL;
}

void fc_extras_free(fc_read_extras *x)
{
    for (size_t i = 0; i < x->size; i++)
        free(x->values[i]);
    memset(x, 0, sizeof *x);
}
