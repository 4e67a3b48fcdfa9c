/* pipeline_internal.h — what the modules that implement parts of pipeline.h
 * (the foam state) reach for inside a pipeline. Not part of the public API. */
#ifndef FC_PIPELINE_INTERNAL_H
#define FC_PIPELINE_INTERNAL_H

#include "particle_attributes.h"
#include "pipeline.h"

/* The per-particle records of the uploaded frame. */
fc_particle_attributes *fc_pipeline_particle_attributes(fc_pipeline *p);

#endif
