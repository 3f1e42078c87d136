/* pelt completion bash: a bash completion script printed from the same
 * tables as `pelt --help` (commands, flags, their value words) and the
 * scene key table (for --set KEY=). The build writes it for installation. */
#include "apps/cli.h"

#include <string.h>

/* Every flag of a table that takes a value of `kind` ("file", "word",
 * "other"), as a case pattern "-o|--output|..."; false if there is none. */
static bool value_flags(FILE *f, cli_flag_list flags, const char *kind)
{
    bool any = false;
    cli_flag_doc d;
    for (size_t i = 0; flags(i, &d); i++) {
        if (!d.metavar) continue;
        bool file = strstr(d.metavar, "FILE") || strstr(d.metavar, "DIR");
        bool word = d.values != NULL;
        if (!strcmp(kind, "file") ? !file || word
            : !strcmp(kind, "word") ? !word
                                    : file || word || !strcmp(d.name, "--set"))
            continue;
        fprintf(f, "%s%s", any ? "|" : "        ", d.name);
        if (d.alias) fprintf(f, "|%s", d.alias);
        any = true;
    }
    return any;
}

static void command_case(FILE *f, const cli_command *c)
{
    fprintf(f, "    %s)\n", c->name);
    cli_flag_doc d;
    if (c->flags) {
        fputs("        case $prev in\n", f);
        for (size_t i = 0; c->flags(i, &d); i++) {
            if (!d.values) continue;
            bool file = strstr(d.metavar, "FILE") != NULL;
            fprintf(f, "        %s%s%s) _pelt_words \"%s\"; %sreturn ;;\n", d.name,
                    d.alias ? "|" : "", d.alias ? d.alias : "", d.values,
                    file ? "_pelt_files '*'; " : "");
        }
        for (size_t i = 0; c->flags(i, &d); i++)
            if (!strcmp(d.name, "--set")) fputs("        --set) _pelt_keys; return ;;\n", f);
        if (value_flags(f, c->flags, "file")) fputs(") _pelt_files '*'; return ;;\n", f);
        if (value_flags(f, c->flags, "other")) fputs(") return ;;\n", f);
        fputs("        esac\n", f);
        fputs("        if [[ $cur == -* ]]; then\n            _pelt_words \"", f);
        for (size_t i = 0; c->flags(i, &d); i++)
            fprintf(f, "%s%s%s%s", i ? " " : "", d.name, d.alias ? " " : "", d.alias ? d.alias : "");
        fputs(" --help -h\"\n            return\n        fi\n", f);
    } else {
        fputs("        [[ $cur == -* ]] && { _pelt_words \"--help -h\"; return; }\n", f);
    }
    if (c->arg_words) fprintf(f, "        _pelt_words \"%s\"\n", c->arg_words);
    if (c->arg_files) fprintf(f, "        _pelt_files '%s'\n", c->arg_files);
    fputs("        ;;\n", f);
}

int cmd_completion(int argc, char **argv)
{
    const cli_command *self = cli_find_command("completion");
    if (argc > 0 && (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help"))) {
        cli_print_help(stdout, self);
        return 0;
    }
    if (argc != 1 || strcmp(argv[0], "bash")) {
        cli_error("completion", "expected the shell: pelt completion bash (the one shell so far)");
        return 2;
    }
    FILE *f = stdout;
    fprintf(f,
            "# bash completion for pelt %s, printed by `pelt completion bash` from the\n"
            "# tables behind `pelt --help`. Installed as\n"
            "# share/bash-completion/completions/pelt; or: source <(pelt completion bash)\n\n",
            PELT_VERSION_STRING);
    fputs("_pelt_scene_keys=\"", f);
    for (size_t i = 0; pelt_scene_key_name(i); i++)
        fprintf(f, "%s%s", i ? " " : "", pelt_scene_key_name(i));
    fputs("\"\n\n", f);
    fputs("_pelt_words() { COMPREPLY+=($(compgen -W \"$1\" -- \"$cur\")); }\n"
          "_pelt_files() {\n"
          "    compopt -o filenames 2>/dev/null\n"
          "    local IFS=$'\\n'\n"
          "    COMPREPLY+=($(compgen -d -- \"$cur\"))\n"
          "    if [[ $1 == '*' ]]; then COMPREPLY+=($(compgen -f -- \"$cur\"))\n"
          "    else COMPREPLY+=($(compgen -f -X \"!$1\" -- \"$cur\")); fi\n"
          "}\n"
          "_pelt_keys() {\n"
          "    compopt -o nospace 2>/dev/null\n"
          "    COMPREPLY+=($(compgen -S = -W \"$_pelt_scene_keys\" -- \"$cur\"))\n"
          "}\n\n",
          f);
    fputs("_pelt() {\n"
          "    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}\n"
          "    COMPREPLY=()\n"
          "    if ((COMP_CWORD == 1)); then\n"
          "        _pelt_words \"",
          f);
    for (const cli_command *c = cli_commands; c->name; c++)
        if (!c->hidden) fprintf(f, "%s ", c->name);
    fputs("--help --version\"\n"
          "        return\n"
          "    fi\n"
          "    case ${COMP_WORDS[1]} in\n",
          f);
    for (const cli_command *c = cli_commands; c->name; c++)
        if (!c->hidden) command_case(f, c);
    fputs("    esac\n"
          "}\n"
          "complete -F _pelt pelt\n",
          f);
    return ferror(f) ? 1 : 0;
}
