/* cli_values.c — see cli_values.h. */
#include "cli_values.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

/* Parses a float at the start of text; *end is where it stopped. False when no
 * number is there or it is out of float range / not finite. */
static bool scan_float(const char *text, const char **end, float *out)
{
    char *stop;
    errno = 0;
    float value = strtof(text, &stop);
    *end = stop;
    if (stop == text || errno == ERANGE || !isfinite(value))
        return false;
    *out = value;
    return true;
}

/* Parses decimal digits only (strtoul would accept signs and spaces). */
static bool scan_uint(const char *text, const char **end, uint32_t *out)
{
    uint64_t value = 0;
    const char *p = text;
    while (*p >= '0' && *p <= '9') {
        value = value * 10 + (uint64_t)(*p - '0');
        if (value > UINT32_MAX)
            return false;
        p++;
    }
    *end = p;
    if (p == text)
        return false;
    *out = (uint32_t)value;
    return true;
}

fc_code fc_cli_parse_float(const char *option, const char *text, float *out, fc_error *err)
{
    const char *end;
    if (!scan_float(text, &end, out) || *end != '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a finite number, not \"%s\"", option, text);
    return FC_OK;
}

fc_code fc_cli_parse_uint(const char *option, const char *text, uint32_t min, uint32_t max,
                          uint32_t *out, fc_error *err)
{
    const char *end;
    uint32_t value;
    if (!scan_uint(text, &end, &value) || *end != '\0' || value < min || value > max)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a whole number in %u..%u, not \"%s\"", option,
                            (unsigned)min, (unsigned)max, text);
    *out = value;
    return FC_OK;
}

fc_code fc_cli_parse_vec3(const char *option, const char *text, float out[3], fc_error *err)
{
    const char *p = text;
    for (int i = 0; i < 3; i++) {
        const char *end;
        char expected_after = i < 2 ? ',' : '\0';
        if (!scan_float(p, &end, &out[i]) || *end != expected_after)
            return fc_error_set(err, FC_ERR_USAGE, "%s needs X,Y,Z (three finite numbers), not \"%s\"", option,
                                text);
        p = end + 1;
    }
    return FC_OK;
}

/* "x", "+x", "-x", ... as a unit vector; false for anything else. */
static bool scan_signed_axis(const char *text, float out[3])
{
    float sign = 1.0f;
    if (*text == '+' || *text == '-')
        sign = *text++ == '-' ? -1.0f : 1.0f;
    if (text[0] < 'x' || text[0] > 'z' || text[1] != '\0')
        return false;
    for (int k = 0; k < 3; k++)
        out[k] = k == text[0] - 'x' ? sign : 0.0f;
    return true;
}

fc_code fc_cli_parse_up(const char *option, const char *text, float out[3], fc_error *err)
{
    if (scan_signed_axis(text, out))
        return FC_OK;
    fc_error why;
    if (fc_cli_parse_vec3(option, text, out, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs x, y, z, -x, -y, -z or X,Y,Z, not \"%s\"", option, text);
    return FC_OK;
}

fc_code fc_cli_parse_size(const char *option, const char *text, uint32_t *width, uint32_t *height,
                          fc_error *err)
{
    const char *end;
    uint32_t w, h;
    if (!scan_uint(text, &end, &w) || (*end != 'x' && *end != 'X') || !scan_uint(end + 1, &end, &h) ||
        *end != '\0' || w == 0 || h == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs WIDTHxHEIGHT (e.g. 1280x720), not \"%s\"", option, text);
    *width = w;
    *height = h;
    return FC_OK;
}

fc_code fc_cli_parse_choice(const char *option, const char *text, const char *const *choices,
                            int *out, fc_error *err)
{
    for (int i = 0; choices[i]; i++) {
        if (strcmp(text, choices[i]) == 0) {
            *out = i;
            return FC_OK;
        }
    }
    char list[128] = "";
    for (int i = 0; choices[i]; i++) {
        size_t used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", choices[i]);
    }
    return fc_error_set(err, FC_ERR_USAGE, "%s needs one of %s, not \"%s\"", option, list, text);
}
