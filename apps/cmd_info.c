/* pelt info: load and validate a mesh, print what was found. */
#include "apps/cli.h"

#include <string.h>

int cmd_info(int argc, char **argv)
{
    if (argc >= 1 && (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help"))) {
        cli_print_help(stdout, cli_find_command("info"));
        return 0;
    }
    if (argc != 1) {
        cli_error("info", "expected one mesh file (see pelt info --help)");
        return 2;
    }
    pelt_mesh *m = NULL;
    pelt_error err = {0};
    if (pelt_mesh_load(argv[0], &m, &err) != PELT_OK) {
        cli_error("info", "%s", err.message);
        return 1;
    }
    pelt_mesh_stats s = pelt_mesh_get_stats(m);
    float lo[3], hi[3];
    pelt_mesh_bounds(m, lo, hi);
    printf("%s\n  vertices   %zu\n  triangles  %zu\n  dropped    %zu degenerate\n"
           "  normals    %s\n  uvs        %s\n  bounds     (%g, %g, %g) .. (%g, %g, %g)\n",
           argv[0], s.vertex_count, s.triangle_count, s.dropped_degenerate,
           s.computed_normals ? "computed" : "from file",
           s.fallback_uvs ? "none in file (fallback mapping)" : "from file", (double)lo[0],
           (double)lo[1], (double)lo[2], (double)hi[0], (double)hi[1], (double)hi[2]);
    pelt_skin_info sk = pelt_mesh_skin_info(m);
    if (sk.nodes) {
        printf("  skeleton   %zu bones, %zu nodes, %zu skinned vertices\n", sk.bones, sk.nodes,
               sk.skinned_vertices);
        printf("  animations %zu\n", sk.animations);
        for (size_t i = 0; i < sk.animations; i++) {
            pelt_animation_info a;
            if (pelt_mesh_animation(m, i, &a))
                printf("    %zu  '%s'  %.3f s, %u animated nodes\n", i, a.name, (double)a.duration, a.channels);
        }
    }
    pelt_mesh_destroy(m);
    return 0;
}
