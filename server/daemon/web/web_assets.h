/* web_assets.h — the web viewer's files (the repository's web/ folder), built
 * into the daemon by web/embed_web.cmake so that it serves them without any
 * file at run time. */
#ifndef FC_DAEMON_WEB_ASSETS_H
#define FC_DAEMON_WEB_ASSETS_H

#include <stddef.h>

typedef struct fc_web_asset {
    const char *path;           /* "/index.html", "/viewer.js", ... */
    const char *content_type;   /* "text/html; charset=utf-8", ... */
    const unsigned char *data;
    size_t size;
} fc_web_asset;

/* The asset served at an URL path ("/" is "/index.html"); NULL for none. */
const fc_web_asset *fc_web_asset_find(const char *path);

#endif
