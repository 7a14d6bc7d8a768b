/* pool.c — the worker pool (see pool.h): pthreads, a generation counter under one mutex; a
 * thread waiting for the next job or for the others' end first spins a short while (a job's
 * end and the next job's start are often microseconds apart: the slab renderer runs one job per
 * slab) before it sleeps on a condition variable. */
#define _POSIX_C_SOURCE 200809L
#include "pool.h"

#include "clock.h"

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

/* how long a waiting thread spins before it sleeps: longer than the gap between two slabs'
 * jobs, short enough not to take a loaded machine's time */
#define SPIN_S 200e-6

struct ics_pool {
  int n;
  pthread_t *th;
  pthread_mutex_t mu;
  pthread_cond_t go, done;
  atomic_ulong gen;
  atomic_int pending;
  int quit;
  void (*fn)(void *, int, int);
  void *ctx;
};

typedef struct {
  ics_pool *p;
  int t;
} worker_arg;

/* 1 when SPIN_S has passed since t0; every 64th call it reads the clock and yields the core to
 * any other runnable thread (a loaded machine) */
static int spun_out(int i, double t0) {
  if (i % 64) return 0;
  sched_yield();
  return ics_clock_s() - t0 > SPIN_S;
}

/* spins until the next job's generation differs from `seen` (1) or SPIN_S has passed (0) */
static int spin_for_job(ics_pool *p, unsigned long seen) {
  double t0 = ics_clock_s();
  for (int i = 1; atomic_load_explicit(&p->gen, memory_order_acquire) == seen; i++)
    if (spun_out(i, t0)) return 0;
  return 1;
}

/* spins until every worker has finished this job (1) or SPIN_S has passed (0) */
static int spin_for_end(ics_pool *p) {
  double t0 = ics_clock_s();
  for (int i = 1; atomic_load_explicit(&p->pending, memory_order_acquire); i++)
    if (spun_out(i, t0)) return 0;
  return 1;
}

static void *worker(void *arg) {
  worker_arg *w = arg;
  ics_pool *p = w->p;
  int t = w->t;
  free(w);
  unsigned long seen = 0;
  for (;;) {
    spin_for_job(p, seen);
    pthread_mutex_lock(&p->mu);
    while (p->gen == seen && !p->quit) pthread_cond_wait(&p->go, &p->mu);
    if (p->quit) {
      pthread_mutex_unlock(&p->mu);
      return NULL;
    }
    seen = p->gen;
    void (*fn)(void *, int, int) = p->fn;
    void *ctx = p->ctx;
    pthread_mutex_unlock(&p->mu);
    fn(ctx, t, p->n);
    if (atomic_fetch_sub(&p->pending, 1) == 1) { /* the last: wake the caller if it sleeps */
      pthread_mutex_lock(&p->mu);
      pthread_cond_signal(&p->done);
      pthread_mutex_unlock(&p->mu);
    }
  }
}

ics_pool *ics_pool_create(int n) {
  if (n <= 0) {
    long c = sysconf(_SC_NPROCESSORS_ONLN);
    n = c > 0 ? (int)c : 1;
  }
  if (n > 256) n = 256;
  ics_pool *p = calloc(1, sizeof *p);
  if (!p) return NULL;
  p->n = n;
  pthread_mutex_init(&p->mu, NULL);
  pthread_cond_init(&p->go, NULL);
  pthread_cond_init(&p->done, NULL);
  p->th = calloc((size_t)n, sizeof *p->th);
  if (!p->th) {
    ics_pool_destroy(p);
    return NULL;
  }
  for (int t = 1; t < n; t++) {
    worker_arg *w = malloc(sizeof *w);
    if (!w) {
      p->n = t;
      ics_pool_destroy(p);
      return NULL;
    }
    w->p = p;
    w->t = t;
    if (pthread_create(&p->th[t], NULL, worker, w)) {
      free(w);
      p->n = t;
      ics_pool_destroy(p);
      return NULL;
    }
  }
  return p;
}

void ics_pool_destroy(ics_pool *p) {
  if (!p) return;
  pthread_mutex_lock(&p->mu);
  p->quit = 1;
  pthread_cond_broadcast(&p->go);
  pthread_mutex_unlock(&p->mu);
  for (int t = 1; t < p->n; t++)
    if (p->th) pthread_join(p->th[t], NULL);
  pthread_mutex_destroy(&p->mu);
  pthread_cond_destroy(&p->go);
  pthread_cond_destroy(&p->done);
  free(p->th);
  free(p);
}

int ics_pool_size(const ics_pool *p) { return p->n; }

void ics_pool_run(ics_pool *p, void (*fn)(void *ctx, int t, int n), void *ctx) {
  if (p->n == 1) {
    fn(ctx, 0, 1);
    return;
  }
  pthread_mutex_lock(&p->mu);
  p->fn = fn;
  p->ctx = ctx;
  p->pending = p->n - 1;
  p->gen++;
  pthread_cond_broadcast(&p->go);
  pthread_mutex_unlock(&p->mu);
  fn(ctx, 0, p->n);
  if (spin_for_end(p)) return;
  pthread_mutex_lock(&p->mu);
  while (p->pending) pthread_cond_wait(&p->done, &p->mu);
  pthread_mutex_unlock(&p->mu);
}
