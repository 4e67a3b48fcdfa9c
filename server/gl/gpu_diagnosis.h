/* gpu_diagnosis.h — why a process sees no usable GPU: the usual causes on
 * clusters and in containers, read from the environment and /dev, worded for
 * the operator who has to fix them. */
#ifndef FC_GPU_DIAGNOSIS_H
#define FC_GPU_DIAGNOSIS_H

#include <stddef.h>

/* One or more likely causes, separated by "; ", into out (always terminated). */
void fc_gpu_diagnose(char *out, size_t size);

#endif
