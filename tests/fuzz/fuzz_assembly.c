/* libFuzzer target: mmCIF biological assemblies (--assembly 1 or 2, by the
 * first byte): the _pdbx_struct_assembly_gen / _pdbx_struct_oper_list
 * categories, operator expressions and the exact moves. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb_read_options opt;
    memset(&opt, 0, sizeof opt);
    opt.format = VB_FMT_MMCIF;
    vb_fuzz_options(data, size, &opt);
    opt.model = 0;
    opt.assembly = size > 0 ? 1 + ((data[0] >> 5) & 1) : 1;
    return vb_fuzz_read_with(data, size, &opt);
}
