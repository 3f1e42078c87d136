/* pelt — command-line front end: the subcommands of apps/commands.c. */
#include "apps/cli.h"

#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "pelt %s - real-time dynamic shell fur\n"
            "\n"
            "usage: pelt COMMAND [ARGS]\n"
            "\n"
            "commands:\n",
            PELT_VERSION_STRING);
    for (const cli_command *c = cli_commands; c->name; c++) {
        if (c->hidden) continue;
        char left[64];
        snprintf(left, sizeof left, "%s %s", c->name, c->args);
        fprintf(f, "  %-28s %s\n", left, c->summary);
    }
    fprintf(f, "\nRun 'pelt COMMAND --help' for the flags of a command; 'man pelt' for all.\n");
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
    const cli_command *c = cli_find_command(cmd);
    if (c) return c->run(argc - 2, argv + 2);
    fprintf(stderr, "pelt: unknown command '%s'\n\n", cmd);
    usage(stderr);
    return 2;
}
