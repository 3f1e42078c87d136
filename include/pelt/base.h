/* pelt — status codes, error detail and small shared types. */
#ifndef PELT_BASE_H
#define PELT_BASE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One list, expanded into the enum and the name table (X-macro). */
#define PELT_STATUS_LIST(X)                                                    \
    X(PELT_OK, "ok")                                                           \
    X(PELT_ERR_INVALID_ARGUMENT, "invalid argument")                           \
    X(PELT_ERR_IO, "file could not be read or written")                        \
    X(PELT_ERR_FORMAT, "malformed input")                                      \
    X(PELT_ERR_OUT_OF_MEMORY, "out of memory")                                 \
    X(PELT_ERR_NO_CONTEXT, "no OpenGL context could be made")                  \
    X(PELT_ERR_GL, "OpenGL error")                                             \
    X(PELT_ERR_UNSUPPORTED, "unsupported")

typedef enum pelt_status {
#define PELT__ENUM(name, text) name,
    PELT_STATUS_LIST(PELT__ENUM)
#undef PELT__ENUM
    PELT_STATUS_COUNT
} pelt_status;

/* Detail of a failure: the status and a readable message that names the
 * file, key or value at fault. Every fallible call takes an optional
 * pelt_error* (NULL is allowed) and fills it on failure. */
typedef struct pelt_error {
    pelt_status status;
    char message[512];
} pelt_error;

/* Short fixed description of a status ("malformed input"). */
const char *pelt_status_text(pelt_status status);

/* Allocation hooks (as cgltf and sokol have them). Zero-initialised means
 * malloc/free. An object made with hooks keeps them and frees everything it
 * owns through them, so alloc and free must pair up. alloc returns NULL
 * when out of memory; free accepts NULL. */
typedef struct pelt_allocator {
    void *(*alloc)(size_t size, void *user);
    void (*free)(void *ptr, void *user);
    void *user;
} pelt_allocator;

typedef enum pelt_log_level {
    PELT_LOG_ERROR = 0,
    PELT_LOG_WARNING,
    PELT_LOG_INFO
} pelt_log_level;

/* Where warnings go (a degenerate triangle dropped, a mesh's uvs not used,
 * a ray that missed). Zero-initialised means silence: the library never
 * prints. Errors also come back in pelt_error. */
typedef struct pelt_logger {
    void (*func)(pelt_log_level level, const char *message, void *user);
    void *user;
} pelt_logger;

/* Both hooks, as the create descs take them. */
typedef struct pelt_hooks {
    pelt_allocator allocator;
    pelt_logger logger;
} pelt_hooks;

#ifdef __cplusplus
}
#endif
#endif
