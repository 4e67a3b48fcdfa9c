/* cli_read_options.c — see cli_read_options.h. */
#include "cli_read_options.h"

#include <string.h>

#include "fc_error.h"

static fc_code set_step(fc_read_options *o, const char *name, const char *value, fc_error *err)
{
    uint64_t step = 0;
    const char *p = value;
    for (; *p >= '0' && *p <= '9' && step <= UINT64_MAX / 10 - 1; p++)
        step = step * 10 + (uint64_t)(*p - '0');
    if (p == value || *p != '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a step number (H5Part's Step#N), not %s", name, value);
    o->has_step = true;
    o->step = step;
    return FC_OK;
}

fc_code fc_cli_set_read_option(fc_read_options *o, const char *name, const char *value, fc_error *err)
{
    if (strcmp(name, "--dataset") == 0) {
        if (value[0] == '\0')
            return fc_error_set(err, FC_ERR_USAGE, "%s needs an HDF5 path", name);
        o->dataset = value;
        return FC_OK;
    }
    if (strcmp(name, "--step") == 0)
        return set_step(o, name, value, err);
    if (strcmp(name, "--select") == 0) {
        if (o->select_count == FC_SELECT_MAX)
            return fc_error_set(err, FC_ERR_USAGE, "at most %d --select options", FC_SELECT_MAX);
        fc_code code = fc_select_parse(value, &o->select[o->select_count], err);
        if (code == FC_OK)
            o->select_count++;
        return code;
    }
    return fc_error_set(err, FC_ERR_USAGE, "%s is not a reader option", name);
}

void fc_cli_print_recentring(const fc_recentring *r)
{
    if (r->applied)
        printf("recentred: float64 positions far from the origin, shifted by -(%.17g, %.17g, %.17g) before float32 "
               "(--eye/--target and --select x/y/z stay in the file's coordinates)\n",
               r->offset[0], r->offset[1], r->offset[2]);
}

void fc_cli_recentre_point(const fc_recentring *r, float point[3])
{
    for (int k = 0; r->applied && k < 3; k++)
        point[k] = (float)((double)point[k] - r->offset[k]);
}

void fc_cli_print_read_options_help(FILE *to, bool step_is_stride)
{
    fputs("particle files:\n"
          "  --dataset PATH          HDF5: where the particles are, when the file is not\n"
          "                          a SWIFT/GADGET snapshot (PartType0), PySPH output\n"
          "                          (particles/*/arrays) or H5Part (Step#N): a group\n"
          "                          holding Coordinates or x, y, z (and the optional\n"
          "                          arrays), an N x 3 dataset of positions, or\n"
          "                          x=PATH,y=PATH,z=PATH (three 1-D datasets)\n",
          to);
    fputs(step_is_stride ? "                          (H5Part: each file's lowest Step#N group)\n"
                         : "  --step N                H5Part: read group Step#N (default: the lowest N)\n",
          to);
    fputs("  --select ATTR=V[,V...]  keep only the particles whose attribute is one of the\n"
          "  --select 'ATTR<V'       values, or compares so (also <=, >, >=, !=);\n"
          "                          repeatable, all must hold. ATTR: x, y, z, density,\n"
          "                          vx, vy, vz, speed, id, radius, or any other column or\n"
          "                          array the file has (DualSPHysics: --select Type=3\n"
          "                          keeps the fluid, dropping the boundary particles)\n"
          "Float64 positions far from the origin (centre beyond 100 x the extent) are\n"
          "recentred on the first file's bounds before float32, and the offset printed.\n"
          "\n",
          to);
}
