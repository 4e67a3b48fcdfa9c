/* fc_colormap_tables.h — the generated tables behind fc_colormap.h. */
#ifndef FC_COLORMAP_TABLES_H
#define FC_COLORMAP_TABLES_H

#include "fc_colormap.h"

extern const float fc_colormap_tables[FC_COLORMAP_COUNT][FC_COLORMAP_ENTRIES][3];

#endif
