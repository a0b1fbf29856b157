/* fuzz_contours.c -- libFuzzer target: the .contours reader and what ./tile
 * does with a stack (tests/pipeline.c: every refusal one line, the stack
 * written and read back equal, small stacks tiled and closed).
 * make fuzz builds and runs it on tests/fuzz/corpus_contours/. */
#include <stddef.h>
#include <stdint.h>

#include "tests/pipeline.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  pipeline_contours((const char *)data, size, 2500);
  return 0;
}
