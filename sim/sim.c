/* sim.c -- the discrete-event simulator: the machine, its run (sim_run's
 * main loop, the deadlock report), its statistics.  Its ranks' calls are
 * calls.c's. */
#include "sim/sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/calls.h"
#include "sim/profile.h"
#include "util/wallclock.h"
#include "util/xmem.h"

/* ==== the machine ========================================================= */

sim *sim_new(const sim_config *cfg, int nranks, char *err, size_t errlen) {
  if (nranks < 1) {
    snprintf(err, errlen, "sim: %d ranks: need at least 1", nranks);
    return NULL;
  }
  topo *tp;
  int procs;
  if (sim_config_check(cfg, nranks, &tp, &procs, err, errlen) != 0) return NULL;
  sim *s = xcalloc(1, sizeof *s);
  s->cfg = *cfg;
  s->cfg.procs = procs;
  if (tp) {
    s->cfg.net = SIM_NET_TOPOLOGY;
    s->topo = tp;
    s->links = links_new(tp, cfg->m, cfg->hop_latency, cfg->per_byte, cfg->store_forward);
  }
  s->n = nranks;
  s->place = xmallocarray((size_t)nranks, sizeof *s->place);
  for (int r = 0; r < nranks; r++) s->place[r] = cfg->place ? cfg->place[r] : r % cfg->procs;
  s->cfg.place = s->place;
  s->cpu = cpu_model_on(&cfg->cpu);
  s->seen = xcalloc((size_t)cfg->procs, 1);
  s->ranks = xcalloc((size_t)nranks, sizeof *s->ranks);
  for (int r = 0; r < nranks; r++) {
    rank *k = &s->ranks[r];
    k->base = (struct mp){.ops = &sim_ops, .rank = r, .size = nranks};
    k->s = s;
    k->proc = s->place[r];
    k->st.proc = k->proc;
    k->wake = INFINITY;
  }
  s->busy = xcalloc((size_t)procs, sizeof *s->busy);
  s->nic = xcalloc((size_t)procs, sizeof *s->nic);
  s->q = evq_new(nranks);
  s->st.ranks = nranks;
  s->st.procs = procs;
  s->log = (mp_log){.name = "sim", .warn = cfg->warn, .st = &s->st.run};
  return s;
}

links *sim_links(sim *s) { return s->links; }

void sim_trace(sim *s, FILE *csv, FILE *json) {
  s->tcsv = csv;
  s->tjson = json;
}

void sim_trace_count(sim *s, int csv, int json) {
  s->count_csv = csv;
  s->count_json = json;
}

void sim_progress(sim *s, void (*tick)(void *ud, double t, long long events), void *ud) {
  s->tick = tick;
  s->tick_ud = ud;
}

void sim_trace_limit(sim *s, unsigned long long limit) {
  s->limited = 1;
  s->trace_limit = limit;
}

int sim_trace_over(const sim *s) { return trace_over(s->tr); }

void sim_trace_size(const sim *s, unsigned long long *csv, unsigned long long *json) {
  trace_size(s->tr, csv, json);
}

/* Every rank runs this on its own stack. */
static coro *rank_main(void *ud) {
  rank *r = ud;
  sim *s = r->s;
  mp_enter(&r->base, s->procs[r->base.rank].main, s->procs[r->base.rank].ud);
  r->state = R_DONE;
  r->st.done = 1;
  r->st.finish = r->now;
  if (r->now > s->st.makespan) s->st.makespan = r->now;
  if (s->tr) trace_finish(s->tr, r->base.rank, r->proc, r->now);
  s->live--;
  s->st.switches++;
  double t;
  int id = evq_pop(s->q, &t);
  if (id < 0) return s->main;
  XASSERT(t >= s->gtime);
  s->gtime = t;
  return s->ranks[id].co;
}

/* Every live rank waits in recv and nothing is on its way: say who waits for
 * what, and stop the run. */
static void report_deadlock(sim *s) {
  mp_deadlock d;
  mp_deadlock_begin(&d, "deadlock at t=%.9g:", s->gtime);
  for (int i = 0; i < s->n; i++) {
    rank *r = &s->ranks[i];
    if (r->state != R_BLOCKED) continue;
    r->deadlocked = 1;
    mp_deadlock_rank(&d, &r->base, r->wait_src, r->wait_tag);
  }
  s->st.deadlock = 1;
  s->stopped = 1;
  char *text = mp_deadlock_end(&d);
  mp_fail_text(&s->log, text, 1); /* always quoted: it is often the consequence of the others */
  free(text);
}

/* Count and report what was sent and never received; free it. */
static void sweep_unread(sim *s) {
  for (int i = 0; i < s->n; i++) {
    rank *r = &s->ranks[i];
    if (!r->box.head) continue;
    long long count = 0;
    for (msg *m = r->box.head; m; m = m->next) count++;
    r->st.unread = count;
    s->st.unread += count;
    mp_warn(&s->log, "rank %d finished with %lld unread message%s (first from rank %d, tag %d)", i, count,
         count == 1 ? "" : "s", r->box.head->src, r->box.head->tag);
    box_clear(&r->box, &s->msgs);
  }
}

int sim_run(sim *s, const mp_proc *procs, char *err, size_t errlen) {
  if (s->ran) {
    snprintf(err, errlen, "sim_run: this machine has run already");
    return -1;
  }
  s->ran = 1;
  for (int i = 0; i < s->n; i++) {
    if (!procs[i].main) {
      snprintf(err, errlen, "sim_run: rank %d has no main function", i);
      return -1;
    }
  }
  double w0 = wallclock();
  mp *outer = mp_self();   /* restored whenever a rank gives way to sim_run */
  s->procs = procs;
  s->tr = s->count_csv || s->count_json ? trace_new_count(s->count_csv, s->count_json)
          : s->limited                    ? trace_new_limited(s->tcsv, s->tjson, s->trace_limit)
                                          : trace_new(s->tcsv, s->tjson);
  s->main = coro_main_new();
  char cerr[256];
  int made = 0;
  s->stacks = coro_stacks_new(s->n, s->cfg.stack, cerr, sizeof cerr);
  if (!s->stacks) mp_fail(&s->log, "sim_run: %s", cerr);
  for (; s->stacks && made < s->n; made++) {
    rank *r = &s->ranks[made];
    r->co = coro_new_on(s->stacks, rank_main, r, cerr, sizeof cerr);
    if (!r->co) {
      mp_fail(&s->log, "sim_run: rank %d: %s", made, cerr);
      break;
    }
    coro_stack(r->co, &r->base.stack_lo, &r->base.stack_size);
    r->base.stack_guard = coro_guard(r->co);
  }
  if (made == s->n) {
    if (s->tr) trace_begin(s->tr, s->n, s->place, s->cfg.procs);
    for (int i = 0; i < s->n; i++) s->ranks[i].base.traced = s->tr != NULL;
    for (int i = 0; i < s->n; i++) evq_set(s->q, i, 0.0, s->seq++);
    s->live = s->n;
    for (;;) {
      double t;
      int id = evq_pop(s->q, &t);
      if (id >= 0) {
        XASSERT(t >= s->gtime);
        s->gtime = t;
        s->st.switches++;
        coro_switch(s->main, s->ranks[id].co);
        mp_set_self(outer);
        continue;
      }
      if (s->live == 0) break;
      /* Nothing can act and ranks are alive: all of them wait in recv. */
      if (!s->stopped) report_deadlock(s);
      int woken = 0;
      for (int i = 0; i < s->n; i++) {
        if (s->ranks[i].state != R_BLOCKED) continue;
        evq_set(s->q, i, s->gtime, s->seq++);
        woken++;
      }
      XASSERT(woken > 0);
    }
    sweep_unread(s);
    s->st.pooled = s->msgs.pooled;
    if (s->tr && trace_end(s->tr, cerr, sizeof cerr) != 0) mp_fail(&s->log, "sim_run: %s", cerr);
  }
  /* Ranks whose stacks share guard pages (coro.h) may have overflowed
   * where only a check sees it: the run fails naming them. */
  for (long i = coro_stacks_overflowed(s->stacks, 0); i >= 0; i = coro_stacks_overflowed(s->stacks, i + 1))
    mp_fail(&s->log, "rank %ld overflowed its stack of %zu KiB (--stack sets it)", i, s->ranks[i].base.stack_size >> 10);
  for (int i = 0; i < made; i++) {
    coro_free(s->ranks[i].co);
    s->ranks[i].co = NULL;
  }
  coro_stacks_free(s->stacks);
  s->stacks = NULL;
  coro_free(s->main);
  s->main = NULL;
  s->st.wall_s = wallclock() - w0;
  return mp_log_report(&s->log, err, errlen);
}

const sim_rank_stats *sim_rank(const sim *s, int i) {
  XASSERT(i >= 0 && i < s->n);
  return &s->ranks[i].st;
}

const sim_stats *sim_stats_get(const sim *s) { return &s->st; }

void sim_free(sim *s) {
  if (!s) return;
  for (int i = 0; i < s->n; i++) {
    rank *r = &s->ranks[i];
    coro_free(r->co);
    box_clear(&r->box, &s->msgs);
    free(r->chans.t);
  }
  mstore_free(&s->msgs);
  coro_stacks_free(s->stacks);
  coro_free(s->main);
  trace_free(s->tr);
  evq_free(s->q);
  free(s->ranks);
  free(s->place);
  free(s->busy);
  free(s->nic);
  links_free(s->links);
  topo_free(s->topo);
  free(s->seen);
  mp_log_free(&s->log);
  free(s);
}
