/* pipeline.h -- what ./tile does to an input, in memory, with checks: for the
 * robustness tests (truncations, mutations) and the fuzz targets.
 *
 * Each returns 0 when the input was accepted, 1 when it was refused; it
 * aborts (so that a fuzzer or a test sees a crash) when an invariant breaks:
 * a refusal that is not one line naming the input, a stack that does not
 * read back bit for bit after writing, a mesh that is not closed. */
#ifndef PIPELINE_H
#define PIPELINE_H

#include <stddef.h>

/* A DICOM RT structure set: read, every ROI's stack, re-encoded by the
 * test writer and read back equal, stacks tiled and closed (those whose
 * pairs all have at most max_pair = m * n nodes: tiling is the slow part). */
int pipeline_dicom(const unsigned char *buf, size_t len, double max_pair);

/* A .contours stack: read, written and read back equal, tiled and closed
 * (when its pairs have at most max_pair nodes). */
int pipeline_contours(const char *buf, size_t len, double max_pair);

#endif
