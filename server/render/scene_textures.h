/* scene_textures.h — the layout of fc_scene_textures (pipeline.h), for the
 * passes that sample them. */
#ifndef FC_SCENE_TEXTURES_H
#define FC_SCENE_TEXTURES_H

#include <epoxy/gl.h>

#include "pipeline.h"

struct fc_scene_textures {
    GLuint background;        /* 2D texture, linear RGB(A), first row = the image's top; 0 = built-in scene */
    float background_aspect;  /* width / height of the background image */
    GLuint environment_map;   /* cube map, linear RGB(A); 0 = procedural sky */
};

#endif
