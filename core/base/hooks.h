/* The allocator and logger hooks of pelt_hooks (include/pelt/base.h): what
 * an object calls to allocate, free and warn, so a caller's hooks reach
 * every allocation the object owns. Zero hooks mean malloc/free and
 * silence. */
#ifndef PELT_BASE_HOOKS_H
#define PELT_BASE_HOOKS_H

#include "pelt/base.h"

/* size bytes through the allocator (malloc when it has no alloc), or NULL. */
void *pelt__alloc(const pelt_allocator *a, size_t size);
/* count * size zeroed bytes, NULL when out of memory or when the product
 * overflows. */
void *pelt__alloc_zero(const pelt_allocator *a, size_t count, size_t size);
/* pelt__alloc_zero without hooks, for memory freed with free(): objects
 * that take no hooks (meshes) and scratch inside one call. */
void *pelt__calloc(size_t count, size_t size);
/* Frees what pelt__alloc / pelt__alloc_zero returned; NULL is allowed. */
void pelt__free(const pelt_allocator *a, void *ptr);

/* Formats one message and hands it to the logger; nothing without one. */
void pelt__log(const pelt_logger *l, pelt_log_level level, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* PELT_ERR_INVALID_ARGUMENT, naming `desc`, for an allocator with only
 * one of alloc and free: it would pair a foreign alloc with free(). */
pelt_status pelt__hooks_check(const pelt_hooks *h, const char *desc, pelt_error *err);

#endif
