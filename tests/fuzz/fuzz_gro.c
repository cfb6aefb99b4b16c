/* libFuzzer target: the GRO reader (several frames, --model) and validation. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return vb_fuzz_read(data, size, VB_FMT_GRO);
}
