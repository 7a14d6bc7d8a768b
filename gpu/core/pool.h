/* pool.h — a fixed pool of worker threads that runs one job at a time: ics_pool_run(fn, ctx)
 * calls fn(ctx, t, n) on every thread t = 0..n-1 (the caller is thread 0) and returns when all
 * have finished. Work is split by the job itself (rows t, t + n, ... or bands), so results never
 * depend on scheduling. */
#ifndef ICS_RENDER_POOL_H
#define ICS_RENDER_POOL_H

typedef struct ics_pool ics_pool;

/* n <= 0: the number of online processors (at most 256). NULL when out of memory or threads
 * cannot be created (the caller may fall back to n = 1, which creates no thread). */
ics_pool *ics_pool_create(int n);
void ics_pool_destroy(ics_pool *p);
int ics_pool_size(const ics_pool *p);
void ics_pool_run(ics_pool *p, void (*fn)(void *ctx, int t, int n), void *ctx);

#endif
