/* Fuzz target: a mesh file from memory through pelt_mesh_load_memory (pelt's
 * header checks, then assimp, then pelt_mesh_create). One target per
 * format: PELT_FUZZ_NAME is fuzz_mesh_EXT; glTF input that starts with
 * "glTF" is read as GLB. */
#include <pelt/pelt.h>

#include <stdint.h>
#include <stdlib.h>
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
        /* A skinned file's animations pose without fault at any time. */
        pelt_skin_info skin = pelt_mesh_skin_info(mesh);
        float *pose = skin.animations ? malloc(d.vertex_count * 10 * sizeof(float)) : NULL;
        for (size_t a = 0; pose && a < skin.animations && a < 4; a++) {
            static const float times[3] = {0.0f, 0.37f, -5.5f};
            for (int t = 0; t < 3; t++)
                if (pelt_mesh_pose(mesh, a, times[t], pose, pose + 3 * d.vertex_count, pose + 6 * d.vertex_count,
                                   NULL) != PELT_OK)
                    __builtin_trap();
        }
        free(pose);
        pelt_mesh_destroy(mesh);
    }
    return 0;
}
