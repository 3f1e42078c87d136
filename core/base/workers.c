/* A pool of POSIX threads that split one loop with the caller
 * (core/base/workers.h). A run publishes its loop under the lock, bumps
 * the generation and wakes the threads; each takes its own part, and the
 * last one to finish wakes the caller, which has done part 0 meanwhile. */
#include "core/base/workers.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

/* Browsers run wasm on one thread unless the build asks for more. */
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define PELT__HAVE_THREADS 0
#else
#define PELT__HAVE_THREADS 1
#endif

typedef struct worker {
    struct pelt__workers *pool;
    unsigned part; /* 1..started: part 0 is the caller's */
    pthread_t thread;
} worker;

struct pelt__workers {
    pelt_allocator alloc;
    unsigned started; /* threads besides the caller */
    worker workers[PELT__WORKERS_MAX - 1];

    pthread_mutex_t lock;
    pthread_cond_t wake; /* a run was published, or quit */
    pthread_cond_t done; /* pending reached 0 */
    uint64_t generation; /* runs published so far */
    unsigned pending;    /* threads still on this run */
    bool quit;

    /* The run being done, set under the lock before the generation moves. */
    pelt__work_fn fn;
    void *ctx;
    size_t n, grain;
};

/* Items [begin, end) of part `part` of `parts`: whole grains, spread
 * evenly, the rest of n in the last. */
static void part_range(size_t n, size_t grain, unsigned part, unsigned parts, size_t *begin, size_t *end)
{
    size_t grains = (n + grain - 1) / grain;
    size_t g0 = grains * part / parts, g1 = grains * (part + 1) / parts;
    *begin = g0 * grain < n ? g0 * grain : n;
    *end = g1 * grain < n ? g1 * grain : n;
}

static void *worker_main(void *arg)
{
    worker *self = arg;
    pelt__workers *w = self->pool;
    /* Runs published before this thread first takes the lock are still
     * its to do: it was counted in their `pending`. */
    uint64_t seen = 0;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (!w->quit && w->generation == seen) pthread_cond_wait(&w->wake, &w->lock);
        if (w->quit) break;
        seen = w->generation;
        pelt__work_fn fn = w->fn;
        void *ctx = w->ctx;
        size_t begin, end;
        part_range(w->n, w->grain, self->part, w->started + 1, &begin, &end);
        pthread_mutex_unlock(&w->lock);
        if (begin < end) fn(ctx, begin, end);
        pthread_mutex_lock(&w->lock);
        if (--w->pending == 0) pthread_cond_signal(&w->done);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

static unsigned online_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (unsigned)n : 1u;
}

pelt_status pelt__workers_create(unsigned threads, const pelt_allocator *alloc, const pelt_logger *log,
                                 pelt__workers **out, pelt_error *err)
{
    const char *fn = "pelt__workers_create";
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    const bool automatic = threads == 0;
    if (automatic) threads = PELT__HAVE_THREADS ? online_cores() : 1u;
    if (threads > PELT__WORKERS_MAX) threads = PELT__WORKERS_MAX;

    pelt__workers *w = pelt__alloc_zero(alloc, 1, sizeof *w);
    if (!w) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);
    if (alloc) w->alloc = *alloc;
    if (pthread_mutex_init(&w->lock, NULL) != 0) goto no_sync;
    if (pthread_cond_init(&w->wake, NULL) != 0) {
        pthread_mutex_destroy(&w->lock);
        goto no_sync;
    }
    if (pthread_cond_init(&w->done, NULL) != 0) {
        pthread_cond_destroy(&w->wake);
        pthread_mutex_destroy(&w->lock);
        goto no_sync;
    }
    for (unsigned i = 0; i + 1 < threads; i++) {
        worker *k = &w->workers[w->started];
        k->pool = w;
        k->part = w->started + 1;
        if (pthread_create(&k->thread, NULL, worker_main, k) != 0) break;
        w->started++;
    }
    if (w->started + 1 < threads && !automatic)
        pelt__log(log, PELT_LOG_WARNING, "%u threads asked for, %u started: the rest of the work runs on fewer",
                  threads, w->started + 1);
    *out = w;
    return PELT_OK;

no_sync:
    /* Without a lock no thread can be told what to do: the caller alone. */
    w->started = 0;
    w->quit = true; /* marks the lock as never made, for destroy */
    *out = w;
    return PELT_OK;
}

void pelt__workers_destroy(pelt__workers *w)
{
    if (!w) return;
    if (!w->quit) {
        pthread_mutex_lock(&w->lock);
        w->quit = true;
        pthread_cond_broadcast(&w->wake);
        pthread_mutex_unlock(&w->lock);
        for (unsigned i = 0; i < w->started; i++) pthread_join(w->workers[i].thread, NULL);
        pthread_cond_destroy(&w->done);
        pthread_cond_destroy(&w->wake);
        pthread_mutex_destroy(&w->lock);
    }
    pelt_allocator alloc = w->alloc;
    pelt__free(&alloc, w);
}

unsigned pelt__workers_threads(const pelt__workers *w) { return w ? w->started + 1 : 1u; }

void pelt__workers_run(pelt__workers *w, pelt__work_fn fn, void *ctx, size_t n, size_t grain)
{
    if (n == 0) return;
    if (grain == 0) grain = 1;
    if (!w || w->started == 0 || n <= grain) {
        fn(ctx, 0, n);
        return;
    }
    pthread_mutex_lock(&w->lock);
    w->fn = fn;
    w->ctx = ctx;
    w->n = n;
    w->grain = grain;
    w->pending = w->started;
    w->generation++;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);

    size_t begin, end;
    part_range(n, grain, 0, w->started + 1, &begin, &end);
    if (begin < end) fn(ctx, begin, end);

    pthread_mutex_lock(&w->lock);
    while (w->pending > 0) pthread_cond_wait(&w->done, &w->lock);
    pthread_mutex_unlock(&w->lock);
}
