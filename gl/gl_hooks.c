/* The renderer's allocator and logger: the desc's hooks, or malloc/free and
 * silence. (core/base will get its own; these are gl's.) */
#include "gl/gpu.h"

#include <stdint.h>
#include <stdlib.h>

void *pelt__gl_alloc(const pelt_hooks *h, size_t count, size_t size)
{
    if (size && count > SIZE_MAX / size) return NULL;
    size_t bytes = count * size;
    if (h->allocator.alloc) return h->allocator.alloc(bytes, h->allocator.user);
    return malloc(bytes);
}

void pelt__gl_free(const pelt_hooks *h, void *ptr)
{
    if (!ptr) return;
    if (h->allocator.free)
        h->allocator.free(ptr, h->allocator.user);
    else
        free(ptr);
}

void pelt__gl_log(const pelt_hooks *h, pelt_log_level level, const char *message)
{
    if (h->logger.func) h->logger.func(level, message, h->logger.user);
}
