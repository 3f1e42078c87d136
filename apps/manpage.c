/* pelt manpage: the manual page pelt(1) as roff, printed from the same
 * tables as `pelt --help` (apps/commands.c, the flag tables) and the scene
 * key table, so the two cannot drift. The build writes it to pelt.1. */
#include "apps/cli.h"

#include <string.h>

/* Text with roff's special characters escaped; '\n' becomes a space, so
 * the paragraph is filled to the reader's terminal. */
static void text(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '\\') fputs("\\e", f);
        else if (*s == '-') fputs("\\-", f);
        else if (*s == '\n') fputc(' ', f);
        else fputc(*s, f);
    }
}

/* A line of running text; \& keeps a leading '.' or '\'' from being read
 * as a request. */
static void line(FILE *f, const char *s)
{
    if (*s == '.' || *s == '\'') fputs("\\&", f);
    text(f, s);
    fputc('\n', f);
}

static void flag_tag(FILE *f, const cli_flag_doc *d)
{
    fputs(".TP\n", f);
    if (d->alias) {
        fputs("\\fB", f);
        text(f, d->alias);
        fputs("\\fR, ", f);
    }
    fputs("\\fB", f);
    text(f, d->name);
    fputs("\\fR", f);
    if (d->metavar) {
        fputs(" \\fI", f);
        text(f, d->metavar);
        fputs("\\fR", f);
    }
    fputc('\n', f);
    line(f, d->help);
}

/* One section per flag table, named after the commands that take it
 * ("RENDER, BENCH AND COMPARE FLAGS"). */
static void flag_sections(FILE *f)
{
    for (const cli_command *c = cli_commands; c->name; c++) {
        if (!c->flags || c->hidden) continue;
        bool seen = false;
        for (const cli_command *b = cli_commands; b != c; b++)
            if (b->flags == c->flags) seen = true;
        if (seen) continue;
        fputs(".SH \"", f);
        size_t sharing = 0, k = 0; /* "A FLAGS", "A AND B FLAGS", "A, B AND C FLAGS" */
        for (const cli_command *b = c; b->name; b++) sharing += b->flags == c->flags;
        for (const cli_command *b = c; b->name; b++) {
            if (b->flags != c->flags) continue;
            if (k > 0) fputs(k + 1 == sharing ? " AND " : ", ", f);
            k++;
            for (const char *p = b->name; *p; p++) fputc(*p >= 'a' && *p <= 'z' ? *p - 32 : *p, f);
        }
        fputs(" FLAGS\"\n", f);
        cli_flag_doc d;
        for (size_t i = 0; c->flags(i, &d); i++) flag_tag(f, &d);
        flag_tag(f, &(cli_flag_doc){"--help", "-h", NULL, "print the flags of the command", NULL});
    }
}

static const char *const examples[] = {
    "pelt render \\-o torus.png",
    "pelt render \\-\\-mesh bunny.off \\-\\-layers 32 \\-o bunny.png",
    "pelt render scenes/rain.json \\-o rain.mp4",
    "pelt render \\-\\-turntable 90 \\-\\-frames 48 \\-\\-fps 24 \\-o spin_%04d.png",
    "pelt render \\-\\-wind 25,0,0 \\-\\-set fur.length=0.15 \\-o windy.gif",
    "pelt compare scenes/reference/torus.json \\-o side.png",
    "pelt bench \\-\\-layers 16",
    "pelt view scenes/rain.json",
    "xvfb\\-run \\-a pelt view \\-\\-script input.txt \\-\\-screenshot\\-at 2:shot.png",
    "pelt atlas bunny.off \\-o atlas.png",
    "source <(pelt completion bash)",
};

int cmd_manpage(int argc, char **argv)
{
    if (argc > 0) {
        if (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help")) {
            cli_print_help(stdout, cli_find_command("manpage"));
            return 0;
        }
        cli_error("manpage", "unexpected argument '%s'", argv[0]);
        return 2;
    }
    FILE *f = stdout;
    fputs(".\\\" pelt(1), printed by `pelt manpage` from the tables behind `pelt --help`.\n", f);
    fprintf(f, ".TH PELT 1 \"\" \"pelt %s\" \"User Commands\"\n", PELT_VERSION_STRING);
    fputs(".SH NAME\npelt \\- render real\\-time dynamic shell fur over triangle meshes\n", f);

    fputs(".SH SYNOPSIS\n", f);
    for (const cli_command *c = cli_commands; c->name; c++) {
        if (c->hidden) continue;
        fprintf(f, ".B pelt %s\n", c->name);
        if (c->args[0]) line(f, c->args);
        fputs(".br\n", f);
    }

    fputs(".SH DESCRIPTION\n", f);
    line(f, "pelt renders fur over triangle meshes with the shell method (concentric\n"
            "semi-transparent texture layers) and makes it move: it bends under gravity,\n"
            "wind and the mesh's motion, curls, and clumps where water drops land, then\n"
            "dries and curls again. It renders headless through EGL (a GPU, or Mesa's\n"
            "llvmpipe without one), or live in a window (view) to orbit, comb, wet, dry and\n"
            "blow on. A scene file (JSON) describes the mesh, fur, camera,\n"
            "light, forces, rain and animation; flags override its keys.");

    fputs(".SH COMMANDS\n", f);
    for (const cli_command *c = cli_commands; c->name; c++) {
        if (c->hidden) continue;
        fprintf(f, ".TP\n\\fB%s\\fR", c->name);
        if (c->args[0]) {
            fputc(' ', f);
            text(f, c->args);
        }
        fputc('\n', f);
        line(f, c->description);
    }

    flag_sections(f);

    fputs(".SH \"SCENE KEYS\"\n", f);
    line(f, "A scene file is JSON; every key is optional and an empty {} is the default\n"
            "scene. Every key below can also be set with --set KEY=VALUE (a JSON value, or a\n"
            "bare string). The format, key by key, with types and defaults, is\n"
            "docs/scene-format.md in pelt's sources.");
    fputs(".PP\n", f);
    for (size_t i = 0; pelt_scene_key_name(i); i++) {
        if (i) fputs(",\n", f);
        text(f, pelt_scene_key_name(i));
    }
    fputs("\n", f);

    fputs(".SH \"VIDEO OUTPUT\"\n", f);
    line(f, "With -o NAME.mp4 (H.264), NAME.webm (VP9) or NAME.gif, render pipes raw frames\n"
            "into ffmpeg(1), found on PATH (Debian package ffmpeg); pelt links no codec.\n"
            "An odd width or height is padded to even for H.264 and VP9. Without ffmpeg,\n"
            "render says what to install; a PNG sequence (-o NAME_%04d.png) needs nothing.");

    fputs(".SH \"EXIT STATUS\"\n", f);
    line(f, "0 on success; 1 when the work failed (a file could not be read or written, no\n"
            "OpenGL context, ffmpeg failed); 2 for a bad command line or scene file. Every\n"
            "error names the file, key or flag.");

    fputs(".SH ENVIRONMENT\n.TP\n.B DISPLAY\n", f);
    line(f, "the X display view opens its window on; without it view says so and exits 1.");
    fputs(".TP\n.B PATH\n", f);
    line(f, "where render looks for ffmpeg.");
    fputs(".TP\n.B XDG_CACHE_HOME\n", f);
    line(f, "the atlas cache is $XDG_CACHE_HOME/pelt (default ~/.cache/pelt).");

    fputs(".SH EXAMPLES\n.nf\n", f);
    for (size_t i = 0; i < sizeof examples / sizeof examples[0]; i++) fprintf(f, "%s\n", examples[i]);
    fputs(".fi\n", f);

    fputs(".SH \"SEE ALSO\"\n.BR ffmpeg (1)\n", f);
    return ferror(f) ? 1 : 0;
}
