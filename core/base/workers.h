/* A few threads that share a loop over independent items with the
 * caller's thread: the strand step's strands, the fins' frame. The threads
 * are started once, when the owner is created, and wait between runs, so a
 * run allocates nothing and costs a wake-up, not a thread start. */
#ifndef PELT_BASE_WORKERS_H
#define PELT_BASE_WORKERS_H

#include "pelt/base.h"

#include <stddef.h>

/* The most threads a pool uses, the caller's included. */
#define PELT__WORKERS_MAX 16

/* Works on the items [begin, end) of a run. */
typedef void (*pelt__work_fn)(void *ctx, size_t begin, size_t end);

typedef struct pelt__workers pelt__workers;

/* A pool of `threads` threads in all, the caller's included: 0 = one per
 * online core (at most PELT__WORKERS_MAX), 1 = the caller alone (no thread
 * is started). Where threads cannot be started (a browser build without
 * them, a process at its limit) it keeps the ones it got, down to the
 * caller alone, and says so through `log`; that is not an error. Only
 * running out of memory for the pool itself fails. */
pelt_status pelt__workers_create(unsigned threads, const pelt_allocator *alloc, const pelt_logger *log,
                                 pelt__workers **out, pelt_error *err);
/* Stops and joins the threads. NULL is allowed. */
void pelt__workers_destroy(pelt__workers *w);

/* Threads a run uses, the caller's included (1 for NULL). */
unsigned pelt__workers_threads(const pelt__workers *w);

/* Calls fn over [0, n) split into one contiguous part per thread, each
 * part a multiple of `grain` items except the last, and returns when every
 * part is done. The parts run at once, so fn must only write what its own
 * items own. With NULL `w`, one thread, or n <= grain: fn(ctx, 0, n) on
 * the caller's thread. Not reentrant: one run at a time per pool. */
void pelt__workers_run(pelt__workers *w, pelt__work_fn fn, void *ctx, size_t n, size_t grain);

#endif
