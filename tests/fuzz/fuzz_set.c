/* Fuzz target: --set values through pelt_scene_set. Each line of the input
 * is one KEY=VALUE (as after --set), applied in turn to one scene; a line
 * without '=' sets the key numbered by its first byte to the rest. */
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
    size_t keys = 0;
    while (pelt_scene_key_name(keys)) keys++;
    pelt_scene s;
    pelt_scene_defaults(&s);
    char *line = text;
    while (line) {
        char *next = strchr(line, '\n');
        if (next) *next++ = '\0';
        pelt_error err = {0};
        char *eq = strchr(line, '=');
        if (eq) {
            *eq = '\0';
            pelt_scene_set(&s, line, eq + 1, &err);
        } else if (*line) {
            pelt_scene_set(&s, pelt_scene_key_name((unsigned char)*line % keys), line + 1, &err);
        }
        line = next;
    }
    fuzz_use_scene(&s, 2.0f);
    free(text);
    return 0;
}
