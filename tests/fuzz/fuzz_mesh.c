/* Fuzz target: a mesh file from memory through pelt_mesh_load_memory (pelt's
 * header checks, then assimp, then pelt_mesh_create). One target per
 * format: PELT_FUZZ_NAME is fuzz_mesh_EXT; glTF input that starts with
 * "glTF" is read as GLB. */
#include <pelt/pelt.h>

#include <stdint.h>
#include <string.h>

#ifndef PELT_FUZZ_NAME
#error "PELT_FUZZ_NAME names the target (fuzz_mesh_obj, ...)"
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *target = PELT_FUZZ_NAME;
    const char *ext = target + strlen("fuzz_mesh_");
    if (!strcmp(ext, "gltf") && size >= 4 && !memcmp(data, "glTF", 4)) ext = "glb";
    char name[32] = "fuzz.";
    strncat(name, ext, sizeof name - strlen(name) - 1);
    pelt_mesh *mesh = NULL;
    pelt_error err = {0};
    if (pelt_mesh_load_memory(data, size, name, &mesh, &err) == PELT_OK) {
        pelt_mesh_data d = pelt_mesh_get_data(mesh);
        if (d.vertex_count == 0 || d.triangle_count == 0) __builtin_trap(); /* never an empty mesh */
        pelt_mesh_destroy(mesh);
    }
    return 0;
}
