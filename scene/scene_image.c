/* Images a scene names, decoded with stb_image after a check of the size
 * their header declares (scene_image.h). */
#include "scene/scene_image.h"

#include "core/base/error.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stb_image.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A binary PNM (P5 grey, P6 RGB) must hold the pixels its header declares:
 * Debian's stb reads past the end of a short 16-bit one. Returns the bytes
 * declared and held through *need and *have; false when short. */
static bool pnm_complete(const uint8_t *data, size_t size, unsigned long long *need, size_t *have)
{
    *need = 0, *have = 0;
    if (size < 2 || data[0] != 'P' || (data[1] != '5' && data[1] != '6')) return true;
    unsigned long long v[3] = {0, 0, 0};
    size_t at = 2;
    for (int k = 0; k < 3; k++) {
        for (;;) { /* white space and # comments */
            while (at < size && isspace(data[at])) at++;
            if (at < size && data[at] == '#')
                while (at < size && data[at] != '\n') at++;
            else
                break;
        }
        if (at == size || !isdigit(data[at])) return true; /* stb refuses it */
        while (at < size && isdigit(data[at]) && v[k] < (1ull << 32)) v[k] = 10 * v[k] + (data[at++] - '0');
    }
    at++; /* the one white space before the pixels */
    *need = v[0] * v[1] * (data[1] == '6' ? 3u : 1u) * (v[2] > 255 ? 2u : 1u);
    *have = at < size ? size - at : 0;
    return *need <= *have;
}

pelt_status pelt__scene_decode_image(const char *key, const char *name, const uint8_t *data,
                                     size_t size, int channels, uint8_t **px, int *w, int *h,
                                     pelt_error *err)
{
    *px = NULL;
    int n;
    if (size > INT_MAX || !stbi_info_from_memory(data, (int)size, w, h, &n))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: '%s' is not a readable image (%s)", key, name,
                          size > INT_MAX ? "larger than 2 GiB" : stbi_failure_reason());
    /* stb would try to allocate what a forged header declares. */
    if (*w < 1 || *h < 1 || *w > PELT__IMAGE_MAX_SIDE || *h > PELT__IMAGE_MAX_SIDE ||
        (long long)*w * *h > PELT__IMAGE_MAX_PIXELS)
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "%s: '%s' declares %d x %d pixels; at most %d per side and %lld in all", key,
                          name, *w, *h, PELT__IMAGE_MAX_SIDE, (long long)PELT__IMAGE_MAX_PIXELS);
    unsigned long long need;
    size_t have;
    if (!pnm_complete(data, size, &need, &have))
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "%s: '%s' is truncated: its PNM header declares %llu bytes of pixels, it holds %zu",
                          key, name, need, have);
    *px = stbi_load_from_memory(data, (int)size, w, h, &n, channels);
    if (!*px)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: '%s' is not a readable image (%s)", key, name,
                          stbi_failure_reason());
    return PELT_OK;
}

pelt_status pelt__scene_load_image(const char *key, const char *path, int channels, uint8_t **px,
                                   int *w, int *h, pelt_error *err)
{
    *px = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return pelt__fail(err, PELT_ERR_IO, "%s: cannot open '%s': %s", key, path, strerror(errno));
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    uint8_t *data = NULL;
    if (size > 0 && size <= INT_MAX && fseek(f, 0, SEEK_SET) == 0) data = malloc((size_t)size);
    bool read = data && fread(data, 1, (size_t)size, f) == (size_t)size;
    int e = errno;
    fclose(f);
    pelt_status st;
    if (size == 0) st = pelt__fail(err, PELT_ERR_FORMAT, "%s: '%s' is empty", key, path);
    else if (!read) st = pelt__fail(err, PELT_ERR_IO, "%s: cannot read '%s': %s", key, path,
                                    size > INT_MAX ? "larger than 2 GiB" : strerror(e));
    else st = pelt__scene_decode_image(key, path, data, (size_t)size, channels, px, w, h, err);
    free(data);
    return st;
}
