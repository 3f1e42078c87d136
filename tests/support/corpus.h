/* Debian's libcgal-demo mesh archive as a test corpus: extracted once per
 * test into its own folder, listed in name order. Header-only. */
#ifndef PELT_TEST_CORPUS_H
#define PELT_TEST_CORPUS_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define CGAL_ARCHIVE "/usr/share/doc/libcgal-dev/data.tar.gz"

static inline int corpus_has_suffix(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

static inline int corpus_by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static inline int corpus_available(void)
{
    struct stat sb;
    return stat(CGAL_ARCHIVE, &sb) == 0;
}

/* Extracts data/meshes into `dir` and fills names (each malloc'd: the
 * caller frees them) with the mesh files there, sorted. Returns the count,
 * or -1 when extracting or listing failed. */
static inline long corpus_list(const char *dir, char **names, size_t cap)
{
    char cmd[2048], meshes[1024];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s' && tar -xzf '%s' -C '%s' data/meshes", dir,
             CGAL_ARCHIVE, dir);
    if (system(cmd) != 0) return -1;
    snprintf(meshes, sizeof meshes, "%s/data/meshes", dir);
    DIR *d = opendir(meshes);
    if (!d) return -1;
    size_t count = 0;
    struct dirent *ent;
    while ((ent = readdir(d)) && count < cap) {
        const char *n = ent->d_name;
        if (corpus_has_suffix(n, ".off") || corpus_has_suffix(n, ".ply") ||
            corpus_has_suffix(n, ".stl") || corpus_has_suffix(n, ".obj"))
            names[count++] = strdup(n);
    }
    closedir(d);
    qsort(names, count, sizeof names[0], corpus_by_name);
    return (long)count;
}

#endif
