/* surface_raster.h — `--surface mesh` renders (fc_settings.surface): the
 * uploaded frame's surface mesh, extracted once per upload and surface
 * settings, rasterised into the depth the screen-space splats would have
 * made (linear view depth of the nearest surface, 0 = no fluid). The passes
 * after the depth (thickness, normals, composite, shadow, meshes) run
 * unchanged on it; the smoothing is skipped, the mesh being smooth already. */
#ifndef FC_SURFACE_RASTER_H
#define FC_SURFACE_RASTER_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "fc_surface_mesh.h"
#include "mesh_buffers.h"
#include "render_target.h"
#include "view.h"

typedef struct fc_surface_raster {
    GLuint depth_program;       /* mesh.vert.glsl + mesh_depth.frag.glsl: the nearest surface's linear depth */
    GLuint thickness_program;   /* mesh.vert.glsl + surface_thickness.frag.glsl: the ray's length inside */
    fc_render_target target;    /* R32F with a depth buffer, copied into the depth pass's target */
    fc_mesh_buffers *buffers;   /* the current mesh on the GPU; NULL: none yet, or no triangles */
    /* What the mesh was extracted for: the cache key. */
    bool valid;
    uint64_t upload;
    float radius, cell;
    uint32_t kernel, smoothing;
} fc_surface_raster;

fc_code fc_surface_raster_create(const char *shader_dir, fc_surface_raster *r, fc_error *err);
void fc_surface_raster_destroy(fc_surface_raster *r);

/* Whether the mesh held is the one of upload `upload` with these settings. */
bool fc_surface_raster_holds(const fc_surface_raster *r, uint64_t upload, const fc_settings *settings);

/* Takes the mesh of upload `upload` with these settings onto the GPU. */
fc_code fc_surface_raster_keep(fc_surface_raster *r, fc_pipeline *p, const fc_surface_mesh *mesh, uint64_t upload,
                               const fc_settings *settings, fc_error *err);

/* The mesh's thickness through `view` (the thickness pass's reduced view)
 * into `thickness` (R32F, resized to the view): the length of each pixel's
 * ray inside the mesh, world units, as the splats' (without their cut at the
 * floor). */
fc_code fc_surface_raster_thickness(fc_surface_raster *r, const fc_view *view, fc_render_target *thickness,
                                    fc_error *err);

/* The mesh's linear depth through `view` into `depth` (R32F, resized to the view; 0 = no fluid). */
fc_code fc_surface_raster_depth(fc_surface_raster *r, const fc_view *view, fc_render_target *depth, fc_error *err);


#endif
