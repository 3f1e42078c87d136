/* Replays fuzz inputs without libFuzzer: each argument is a file or a
 * folder of files (README.md and dot files skipped), each file is read
 * into a buffer of exactly its size and passed to LLVMFuzzerTestOneInput.
 * The first argument is the corpus and must not be empty; the others
 * (crash files found so far) may be. Built with the project's compiler,
 * so CTest runs every target's corpus under its sanitizers. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: cannot open '%s'\n", path);
        return 0;
    }
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *buf = malloc(n > 0 ? (size_t)n : 1);
    size_t got = buf && n >= 0 ? fread(buf, 1, (size_t)n, f) : 0;
    fclose(f);
    if (!buf || got != (size_t)n) {
        fprintf(stderr, "replay: cannot read '%s'\n", path);
        free(buf);
        return 0;
    }
    LLVMFuzzerTestOneInput(buf, got);
    free(buf);
    return 1;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Replays a file or every file of a folder in name order; the count. */
static int replay(const char *path, int *bad)
{
    struct stat sb;
    if (stat(path, &sb) != 0) {
        fprintf(stderr, "replay: '%s' does not exist\n", path);
        (*bad)++;
        return 0;
    }
    if (!S_ISDIR(sb.st_mode)) {
        if (!replay_file(path)) (*bad)++;
        return 1;
    }
    DIR *d = opendir(path);
    if (!d) {
        (*bad)++;
        return 0;
    }
    char **names = NULL;
    size_t count = 0, cap = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.' || !strcmp(e->d_name, "README.md")) continue;
        if (count == cap) {
            cap = cap ? 2 * cap : 64;
            names = realloc(names, cap * sizeof *names);
        }
        names[count++] = strdup(e->d_name);
    }
    closedir(d);
    if (count) qsort(names, count, sizeof *names, by_name);
    int done = 0;
    for (size_t i = 0; i < count; i++) {
        char file[4096];
        snprintf(file, sizeof file, "%s/%s", path, names[i]);
        if (!replay_file(file)) (*bad)++;
        done++;
        free(names[i]);
    }
    free(names);
    return done;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s CORPUS [CRASH_FILES...]\n", argv[0]);
        return 2;
    }
    int bad = 0;
    for (int i = 1; i < argc; i++) {
        int n = replay(argv[i], &bad);
        printf("replayed %d input%s from %s\n", n, n == 1 ? "" : "s", argv[i]);
        if (i == 1 && n == 0) {
            fprintf(stderr, "replay: the corpus %s is empty\n", argv[1]);
            return 1;
        }
    }
    return bad ? 1 : 0;
}
