/* Fuzz target: scene JSON through pelt_scene_parse. */
#include "fuzz_common.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    pelt_scene s;
    pelt_error err = {0};
    if (pelt_scene_parse(text, "fuzz/scene.json", &s, &err) == PELT_OK) {
        fuzz_use_scene(&s, 1.5f);
    }
    free(text);
    return 0;
}
