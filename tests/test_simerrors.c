/* test_simerrors.c -- the simulator's error reports and warnings (a bad
 * rank, a negative compute, messages never read, truncation, a rank that
 * spins), each naming the rank and the call. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "mp/mp.h"
#include "sim/sim.h"
#include "tests/simrun.h"

/* ==== errors and warnings ================================================= */

typedef struct {
  int rc[8];
  unsigned char buf[16];
  mp_status st;
} errs;

static void badrank_main(mp *self, void *ud) {
  errs *e = ud;
  if (mp_rank(self) != 0) return;
  e->rc[0] = mp_send(self, 5, 0, "x", 1);
  e->rc[1] = mp_send(self, -1, 0, "x", 1);
  e->rc[2] = mp_send(self, 1, -2, "x", 1);
  e->rc[3] = mp_recv(self, 7, 0, NULL, 0, NULL);
  e->rc[4] = mp_probe(self, 0, -5, NULL);
  e->rc[5] = mp_compute(self, 1); /* still fine afterwards */
}

static void negcompute_main(mp *self, void *ud) {
  errs *e = ud;
  e->rc[mp_rank(self)] = mp_compute(self, mp_rank(self) == 0 ? -1 : NAN);
  e->rc[2 + mp_rank(self)] = mp_compute(self, 2);
}

static void unread_main(mp *self, void *ud) {
  (void)ud;
  int me = mp_rank(self);
  if (me == 1) {
    mp_send(self, 3, 4, "a", 1);
    mp_send(self, 3, 4, "b", 1);
    mp_send(self, 2, 1, "c", 1);
  }
  char c;
  if (me == 2) mp_recv(self, 1, 1, &c, 1, NULL);
}

static void trunc_main(mp *self, void *ud) {
  errs *e = ud;
  if (mp_rank(self) == 0) {
    unsigned char big[100];
    for (int i = 0; i < 100; i++) big[i] = (unsigned char)i;
    mp_send(self, 1, 9, big, sizeof big);
  } else {
    memset(e->buf, 0xee, sizeof e->buf);
    e->rc[0] = mp_recv(self, 0, 9, e->buf, 10, &e->st);
  }
}

static void spin_main(mp *self, void *ud) {
  errs *e = ud;
  if (mp_rank(self) == 1) {
    mp_recv(self, 0, 0, NULL, 0, NULL);
    return;
  }
  int rc;
  while ((rc = mp_probe(self, 1, 0, NULL)) == 0) {
  }
  e->rc[0] = rc;
}

static void test_errors(void) {
  char err[512];
  int rc;
  sim_config cfg = simrun_config(SIM_NET_BUS, 2);

  errs e;
  memset(&e, 0, sizeof e);
  sim *s = simrun(&cfg, 2, badrank_main, &e, &rc, err, sizeof err);
  CHECK(e.rc[0] == MP_ERANK && e.rc[1] == MP_ERANK, "send to a bad rank: %d %d", e.rc[0], e.rc[1]);
  CHECK(e.rc[2] == MP_EARG, "send with tag -2: %d", e.rc[2]);
  CHECK(e.rc[3] == MP_ERANK && e.rc[4] == MP_EARG, "recv/probe bad args: %d %d", e.rc[3], e.rc[4]);
  CHECK(e.rc[5] == MP_OK, "compute after the errors: %d", e.rc[5]);
  CHECK(rc == -1 && strstr(err, "rank 0: mp_send to rank 5, which does not exist (2 ranks)") &&
            strstr(err, "(5 errors in all)"),
        "bad rank: %s", err);
  CHECK(sim_stats_get(s)->errors == 5, "%lld errors counted", sim_stats_get(s)->errors);
  sim_free(s);

  memset(&e, 0, sizeof e);
  s = simrun(&cfg, 2, negcompute_main, &e, &rc, err, sizeof err);
  CHECK(e.rc[0] == MP_EARG && e.rc[1] == MP_EARG, "negative/NaN compute: %d %d", e.rc[0], e.rc[1]);
  CHECK(e.rc[2] == MP_OK && e.rc[3] == MP_OK, "compute afterwards: %d %d", e.rc[2], e.rc[3]);
  CHECK(rc == -1 && strstr(err, "rank 0: mp_compute(-1)"), "negative compute: %s", err);
  CHECK(sim_rank(s, 0)->finish == 2 * cfg.c, "the bad compute was charged: %.17g",
        sim_rank(s, 0)->finish);
  sim_free(s);

  /* Unread messages: a warning on cfg.warn, counted, and the run succeeds. */
  char *wtext;
  size_t wlen;
  FILE *w = open_memstream(&wtext, &wlen);
  cfg = simrun_config(SIM_NET_BUS, 4);
  cfg.warn = w;
  s = simrun(&cfg, 4, unread_main, NULL, &rc, err, sizeof err);
  fclose(w);
  CHECK(rc == 0, "unread messages are not an error: %s", err);
  CHECK(strcmp(wtext, "sim: warning: rank 3 finished with 2 unread messages (first from rank 1, "
                      "tag 4)\n") == 0,
        "unread warning: '%s'", wtext);
  CHECK(sim_stats_get(s)->warnings == 1 && sim_stats_get(s)->unread == 2 &&
            sim_rank(s, 3)->unread == 2,
        "unread counts: %lld warnings, %lld unread", sim_stats_get(s)->warnings,
        sim_stats_get(s)->unread);
  free(wtext);
  sim_free(s);

  /* The same, quiet: counted, not printed. */
  cfg.warn = NULL;
  s = simrun(&cfg, 4, unread_main, NULL, &rc, err, sizeof err);
  CHECK(rc == 0 && sim_stats_get(s)->warnings == 1, "quiet unread warning not counted");
  sim_free(s);

  /* Truncation: MP_ETRUNC, the first cap bytes, the full length, a warning. */
  cfg = simrun_config(SIM_NET_IDEAL, 2);
  memset(&e, 0, sizeof e);
  s = simrun(&cfg, 2, trunc_main, &e, &rc, err, sizeof err);
  CHECK(e.rc[0] == MP_ETRUNC, "truncating recv returned %d", e.rc[0]);
  CHECK(e.st.len == 100 && e.st.source == 0 && e.st.tag == 9, "truncated status: %zu %d %d",
        e.st.len, e.st.source, e.st.tag);
  CHECK(e.buf[0] == 0 && e.buf[9] == 9 && e.buf[10] == 0xee, "truncated copy: %d %d %d", e.buf[0],
        e.buf[9], e.buf[10]);
  CHECK(rc == 0 && sim_stats_get(s)->warnings == 1 && sim_stats_get(s)->unread == 0,
        "truncation: rc %d, %lld warnings", rc, sim_stats_get(s)->warnings);
  sim_free(s);

  /* Polling probe without ever moving the clock: stopped, not hung. */
  cfg = simrun_config(SIM_NET_BUS, 2);
  memset(&e, 0, sizeof e);
  s = simrun(&cfg, 2, spin_main, &e, &rc, err, sizeof err);
  CHECK(e.rc[0] == MP_ESTOPPED && rc == -1 && strstr(err, "without its clock moving"),
        "probe spin: %d, %s", e.rc[0], err);
  sim_free(s);
}

int main(void) {
  test_errors();
  return check_done("test_simerrors");
}
