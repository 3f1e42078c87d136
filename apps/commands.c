/* The table of pelt's subcommands: `pelt --help`, `pelt CMD --help`, the
 * manual page (apps/manpage.c) and shell completion (apps/completion.c)
 * all print from it. */
#include "apps/cli.h"

#include <string.h>

/* The browser build (docs/web.md) has the viewer alone: its table holds
 * view, so its --help and flag errors read as on the desktop. */
const cli_command cli_commands[] = {
#if !defined(__EMSCRIPTEN__)
    {"render", "[SCENE.json] [flags]",
     "render a scene (default: the Table 1 torus) to PNG or video",
     "Renders the scene (default: the paper's Table 1 torus, 800x600)\n"
     "headless to a PNG, a PNG sequence (-o out_%04d.png) or a video: -o out.mp4,\n"
     "out.webm or out.gif pipes the frames into ffmpeg (Debian package ffmpeg).\n"
     "Flags override keys of the scene file. On a terminal an animation shows\n"
     "its progress: frames, frames per second and the time left.",
     cli_scene_flag, cmd_render, "*.json", NULL, false},
    {"bench", "[SCENE.json] [flags]", "time frames: median, min, max ms per frame",
     "Renders frames after a warm-up, glFinish after each, and prints the median,\n"
     "minimum and maximum milliseconds per frame for each part of the frame.\n"
     "Takes the flags of render.",
     cli_scene_flag, cmd_bench, "*.json", NULL, false},
    {"compare", "[SCENE.json] [flags]", "the shell picture against the strand reference, measured",
     "Renders the scene twice from the same state (the same fur, the same frame):\n"
     "with shells and fins, and as the strand reference (the same hairs drawn as\n"
     "geometry), plus the skin alone for its outline. Prints one figure a line:\n"
     "ssim (luminance at half size, 1 = the same), mae (mean R, G, B error, 0..255),\n"
     "silhouette_px and the fur's coverage in those bands outside the skin for\n"
     "shells and strands, stripe_energy_ratio (the shells' spacing across the rim,\n"
     "shells over strands), outline_grain (the step along the outline outside the\n"
     "skin: hairs crossing it against a smooth band), luminance_shells and\n"
     "luminance_strands. -o writes\n"
     "shells | strands | difference (x4) as one PNG. Takes the flags of render;\n"
     "an animation compares its last frame. docs/reference.md says how to read it.",
     cli_scene_flag, cmd_compare, "*.json", NULL, false},
#endif
    {"view", "[SCENE.json] [flags]", "the scene in a window: orbit, comb, wet, dry, blow, live",
     "Opens the scene of render (the same file and flags) in a window with an OpenGL\n"
     "3.3 core context; the fur moves with the real frame time. Left drag uses the\n"
     "tool (water, hair dryer, comb, length: keys 1-4; 0 orbits), right drag orbits,\n"
     "middle drag pans, the wheel zooms; H shows every key. -o names the screenshots\n"
     "of the P key, --save-groom the groom of Ctrl+S; --script replays timed input,\n"
     "--screenshot-at saves the window, --frames ends a run. Needs a display\n"
     "(DISPLAY; under Xvfb: xvfb-run -a pelt view ...).",
     cli_view_flag, cmd_view, "*.json", NULL, false},
#if !defined(__EMSCRIPTEN__)
    {"info", "MESH", "load and validate a mesh, print what was found",
     "Loads a mesh (OBJ, PLY, OFF, STL, glTF/GLB...), validates it\n"
     "and prints its counts, bounds and what validation changed.",
     NULL, cmd_info, "*", NULL, false},
    {"atlas", "MESH [flags]", "build a mesh's atlas, draw patches + direction field",
     "Builds the surface atlas of MESH (a file, or torus / sphere / square) and draws\n"
     "its patches and hair direction field to a PNG; prints the atlas statistics.",
     cli_atlas_flag, cmd_atlas, "*", "torus sphere square", false},
    {"completion", "bash", "print the bash completion script",
     "Prints a bash completion script for pelt's commands, flags and scene keys.\n"
     "Try it with: source <(pelt completion bash)",
     NULL, cmd_completion, NULL, "bash", false},
    {"manpage", "", "print the manual page pelt(1) as roff",
     "Prints the manual page pelt(1) as roff; the build writes it to pelt.1.",
     NULL, cmd_manpage, NULL, NULL, true},
#endif
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, false},
};

const cli_command *cli_find_command(const char *name)
{
    for (const cli_command *c = cli_commands; c->name; c++)
        if (!strcmp(c->name, name)) return c;
    return NULL;
}

/* "-o, --output FILE" */
static void flag_left(const cli_flag_doc *d, char *out, size_t size)
{
    snprintf(out, size, "%s%s%s%s%s", d->alias ? d->alias : "", d->alias ? ", " : "", d->name,
             d->metavar ? " " : "", d->metavar ? d->metavar : "");
}

void cli_print_help(FILE *f, const cli_command *c)
{
    fprintf(f, "usage: pelt %s%s%s\n\n%s\n\n", c->name, c->args[0] ? " " : "", c->args,
            c->description);
    static const cli_flag_doc help = {"--help", "-h", NULL, "this help", NULL};
    cli_flag_doc d;
    size_t width = strlen("-h, --help");
    char left[96];
    for (size_t i = 0; c->flags && c->flags(i, &d); i++) {
        flag_left(&d, left, sizeof left);
        if (strlen(left) > width) width = strlen(left);
    }
    fprintf(f, "flags:\n");
    for (size_t i = 0;; i++) {
        bool last = !c->flags || !c->flags(i, &d);
        if (last) d = help;
        flag_left(&d, left, sizeof left);
        fprintf(f, "  %-*s  %s\n", (int)width, left, d.help);
        if (last) break;
    }
}
