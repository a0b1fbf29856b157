/* fuzz_dicom.c -- libFuzzer target: the DICOM RT structure set reader and
 * what ./tile does with each ROI (tests/pipeline.c: every refusal one line,
 * ROIs re-encoded and read back equal, small stacks tiled and closed).
 * make fuzz builds and runs it on tests/fuzz/corpus_dicom/. */
#include <stddef.h>
#include <stdint.h>

#include "tests/pipeline.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  pipeline_dicom(data, size, 2500);
  return 0;
}
