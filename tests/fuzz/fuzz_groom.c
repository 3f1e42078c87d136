/* Fuzz target: groom files through pelt_fur_load_groom_memory, onto a
 * small torus (the corpus holds grooms saved from the same torus). */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pelt_fur *fur = fuzz_torus_fur();
    pelt_error err = {0};
    if (pelt_fur_load_groom_memory(fur, data, size, "fuzz.groom.ply", &err) == PELT_OK)
        pelt_fur_reset_groom(fur);
    return 0;
}
