/* The threads of the per-frame CPU work (core/base/workers.c): every item
 * of a run is done exactly once, parts are whole grains, a pool run at
 * once after it starts does not hang, and a pool torn down mid-life joins. */
#include "support/check.h"

#include "core/base/workers.h"

#include <stdatomic.h>
#include <string.h>

typedef struct tally {
    unsigned char *hits; /* per item: how many times it was done */
    size_t grain;
    atomic_int misaligned; /* parts that began off a grain */
    atomic_int calls;
} tally;

static void count_items(void *ctx, size_t begin, size_t end)
{
    tally *t = ctx;
    if (begin % t->grain != 0) atomic_fetch_add(&t->misaligned, 1);
    atomic_fetch_add(&t->calls, 1);
    for (size_t i = begin; i < end; i++) t->hits[i]++;
}

static void every_item_once_for_every_size_and_thread_count(void)
{
    enum { N = 1000 };
    static unsigned char hits[N];
    const size_t sizes[] = {0, 1, 2, 31, 32, 33, 64, 100, 999, 1000};
    const size_t grains[] = {1, 7, 32};
    for (unsigned threads = 1; threads <= 5; threads++) {
        pelt__workers *w = NULL;
        CHECK(pelt__workers_create(threads, NULL, NULL, &w, NULL) == PELT_OK);
        if (!w) return;
        CHECK(pelt__workers_threads(w) == threads);
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
            for (size_t g = 0; g < sizeof grains / sizeof grains[0]; g++) {
                memset(hits, 0, sizeof hits);
                tally t = {hits, grains[g], 0, 0};
                pelt__workers_run(w, count_items, &t, sizes[s], grains[g]);
                int wrong = 0;
                for (size_t i = 0; i < N; i++) wrong += hits[i] != (i < sizes[s] ? 1 : 0);
                CHECK(wrong == 0);
                CHECK(atomic_load(&t.misaligned) == 0);
                CHECK(atomic_load(&t.calls) <= (int)threads);
                if (wrong) fprintf(stderr, "  %u threads, n %zu, grain %zu: %d items wrong\n", threads,
                                   sizes[s], grains[g], wrong);
            }
        pelt__workers_destroy(w);
    }
}

static void a_run_at_once_after_creation_does_not_hang(void)
{
    /* The threads may not have reached their wait when the first run is
     * published: they must still take it (a hang here fails by timeout). */
    static unsigned char hits[4096];
    for (int k = 0; k < 300; k++) {
        pelt__workers *w = NULL;
        CHECK(pelt__workers_create(3, NULL, NULL, &w, NULL) == PELT_OK);
        memset(hits, 0, sizeof hits);
        tally t = {hits, 16, 0, 0};
        pelt__workers_run(w, count_items, &t, sizeof hits, 16);
        pelt__workers_run(w, count_items, &t, sizeof hits, 16);
        int wrong = 0;
        for (size_t i = 0; i < sizeof hits; i++) wrong += hits[i] != 2;
        CHECK(wrong == 0);
        pelt__workers_destroy(w);
    }
}

static void automatic_count_and_null_pool(void)
{
    pelt__workers *w = NULL;
    CHECK(pelt__workers_create(0, NULL, NULL, &w, NULL) == PELT_OK);
    CHECK(pelt__workers_threads(w) >= 1 && pelt__workers_threads(w) <= PELT__WORKERS_MAX);
    pelt__workers_destroy(w);
    CHECK(pelt__workers_create(1000, NULL, NULL, &w, NULL) == PELT_OK);
    CHECK(pelt__workers_threads(w) == PELT__WORKERS_MAX);
    pelt__workers_destroy(w);
    CHECK(pelt__workers_create(2, NULL, NULL, NULL, NULL) == PELT_ERR_INVALID_ARGUMENT);
    /* No pool: the caller does it all. */
    static unsigned char hits[100];
    tally t = {hits, 1, 0, 0};
    pelt__workers_run(NULL, count_items, &t, 100, 1);
    CHECK(atomic_load(&t.calls) == 1);
    CHECK(hits[0] == 1 && hits[99] == 1);
    CHECK(pelt__workers_threads(NULL) == 1);
    pelt__workers_destroy(NULL);
}

int main(void)
{
    RUN(every_item_once_for_every_size_and_thread_count);
    RUN(a_run_at_once_after_creation_does_not_hang);
    RUN(automatic_count_and_null_pool);
    return check_failures ? 1 : 0;
}
