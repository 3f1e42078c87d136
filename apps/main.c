/* pelt — command-line front end: render, bench, info. */
#include "apps/cli.h"

#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "pelt %s - real-time dynamic shell fur\n"
            "\n"
            "usage: pelt COMMAND [ARGS]\n"
            "\n"
            "commands:\n"
            "  render [SCENE.json] [flags]  render a scene (default: the Table 1 torus) to PNG\n"
            "  bench  [SCENE.json] [flags]  time frames: median, min, max ms per frame\n"
            "  info   MESH                  load and validate a mesh, print what was found\n"
            "  atlas  MESH [-o atlas.png]   build a mesh's atlas, draw patches + direction field\n"
            "\n"
            "Run 'pelt COMMAND --help' for the flags of a command.\n",
            PELT_VERSION_STRING);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version")) {
        printf("pelt %s\n", PELT_VERSION_STRING);
        return 0;
    }
    if (!strcmp(cmd, "render")) return cmd_render(argc - 2, argv + 2);
    if (!strcmp(cmd, "bench")) return cmd_bench(argc - 2, argv + 2);
    if (!strcmp(cmd, "info")) return cmd_info(argc - 2, argv + 2);
    if (!strcmp(cmd, "atlas")) return cmd_atlas(argc - 2, argv + 2);
    fprintf(stderr, "pelt: unknown command '%s'\n\n", cmd);
    usage(stderr);
    return 2;
}
