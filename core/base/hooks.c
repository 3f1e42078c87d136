#include "core/base/hooks.h"

#include "core/base/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void *pelt__alloc(const pelt_allocator *a, size_t size)
{
    if (size == 0) size = 1;
    if (a && a->alloc) return a->alloc(size, a->user);
    return malloc(size);
}

void *pelt__alloc_zero(const pelt_allocator *a, size_t count, size_t size)
{
    if (size != 0 && count > (size_t)-1 / size) return NULL;
    size_t bytes = count * size;
    void *p = pelt__alloc(a, bytes);
    if (p) memset(p, 0, bytes ? bytes : 1);
    return p;
}

void *pelt__calloc(size_t count, size_t size) { return pelt__alloc_zero(NULL, count, size); }

void pelt__free(const pelt_allocator *a, void *ptr)
{
    if (!ptr) return;
    if (a && a->free)
        a->free(ptr, a->user);
    else
        free(ptr);
}

void pelt__log(const pelt_logger *l, pelt_log_level level, const char *fmt, ...)
{
    if (!l || !l->func) return;
    char message[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    l->func(level, message, l->user);
}

pelt_status pelt__hooks_check(const pelt_hooks *h, const char *desc, pelt_error *err)
{
    if (h && !h->allocator.alloc != !h->allocator.free)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "%s.hooks.allocator: set both alloc and free, or neither", desc);
    return PELT_OK;
}
