/* Fuzz target: scene JSON through pelt_scene_parse. */
#include <pelt/pelt.h>

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
        float wind[3], model[16];
        pelt_scene_wind_at(&s, 1.5f, wind);
        pelt_scene_model_at(&s, 1.5f, model);
        pelt_scene_free(&s);
    }
    free(text);
    return 0;
}
