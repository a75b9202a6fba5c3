/* Fuzz harness for the .rob action file reader (include/lsc/files.h): the
 * input is a whole file. Properties: fuzz_files.h. */
#include "fuzz_files.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_files(LSC_FILE_ROB, data, size);
}
