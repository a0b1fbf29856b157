/* test_bigcopy.c -- big payloads copied by stream stores (util/bigcopy.h):
 * every byte lands, none around the destination changes, whatever the
 * alignment of either side and the length around the threshold; and
 * through the simulator's three copies of a payload (the message's own
 * memory and the receive out of it, a promised buffer, a send by
 * reference settled), the receiver gets the sender's bytes.  The reference
 * is the source itself, compared byte by byte. */
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/simrun.h"
#include "util/bigcopy.h"
#include "util/rng.h"
#include "util/xmem.h"

enum { GUARD = 64 };

static void fill(rng *g, unsigned char *p, size_t n) {
  for (size_t i = 0; i < n; i++) p[i] = (unsigned char)rng_next(g);
}

static void direct(rng *g) {
  static const size_t extra[] = {0, 1, 63, 64, 65, 4096 + 5, (1u << 20) + 3};
  static const size_t off[] = {0, 1, 7, 8, 13, 15};
  size_t big = BIGCOPY_MIN + (1u << 20) + 200;
  unsigned char *src = xmalloc(big + 32), *dst = xmalloc(big + 32 + 2 * GUARD);
  fill(g, src, big + 32);
  int bad = 0, cases = 0;
  for (size_t e = 0; e < sizeof extra / sizeof *extra; e++)
    for (int below = 0; below < 2; below++)
      for (size_t a = 0; a < sizeof off / sizeof *off; a++)
        for (size_t b = 0; b < sizeof off / sizeof *off; b++) {
          if (below && extra[e] >= BIGCOPY_MIN - 1) continue;
          size_t n = below ? BIGCOPY_MIN - 1 - extra[e] : BIGCOPY_MIN + extra[e];
          memset(dst, 0xab, big + 32 + 2 * GUARD);
          unsigned char *d = dst + GUARD + off[b];
          bigcopy(d, src + off[a], n);
          int ok = memcmp(d, src + off[a], n) == 0;
          for (unsigned char *p = dst; p < d; p++) ok &= *p == 0xab;
          for (unsigned char *p = d + n; p < dst + big + 32 + 2 * GUARD; p++) ok &= *p == 0xab;
          bad += !ok, cases++;
        }
  CHECK(bad == 0, "bigcopy: %d of %d copies wrong (a byte lost or one beside them changed)", bad, cases);
  free(src);
  free(dst);
}

/* Rank 0 sends SIZES payloads from odd offsets of its buffer; rank 1
 * receives each one way: at once, into a promised buffer, after a send by
 * reference was settled. */
static const size_t SIZES[] = {BIGCOPY_MIN - 1, BIGCOPY_MIN, BIGCOPY_MIN + 17, (1u << 20) + 3};
enum { NS = sizeof SIZES / sizeof *SIZES };

typedef struct {
  unsigned char *pattern;   /* the bytes sent: pattern + 5 */
  int wrong, bad;
} run;

static void ranks(mp *self, void *ud) {
  run *r = ud;
  size_t most = SIZES[NS - 1];
  if (mp_rank(self) == 0) {
    for (int k = 0; k < NS; k++) {
      r->bad |= mp_send(self, 1, 3 * k, r->pattern + 5, SIZES[k]) != MP_OK;
      r->bad |= mp_send(self, 1, 3 * k + 1, r->pattern + 5, SIZES[k]) != MP_OK;
      mp_ref *ref = NULL;
      r->bad |= mp_send_ref(self, 1, 3 * k + 2, r->pattern + 5, SIZES[k], &ref) != MP_OK;
      mp_settle(self, ref);
    }
    return;
  }
  unsigned char *buf = xmalloc(most + 16);
  for (int k = 0; k < NS; k++) {
    for (int way = 0; way < 3; way++) {
      memset(buf, 0, most + 16);
      mp_promise *p = way == 1 ? mp_promise_make(self, 0, 3 * k + 1, -1, buf + 3, most) : NULL;
      r->bad |= mp_recv(self, 0, 3 * k + way, buf + 3, most, NULL) != MP_OK;
      if (p) mp_promise_drop(self, p, 1);
      r->wrong += memcmp(buf + 3, r->pattern + 5, SIZES[k]) != 0;
    }
  }
  free(buf);
}

static void simulated(rng *g) {
  run r = {xmalloc(SIZES[NS - 1] + 16), 0, 0};
  fill(g, r.pattern, SIZES[NS - 1] + 16);
  sim_config cfg = simrun_config(SIM_NET_IDEAL, 2);
  int rc;
  char err[256];
  sim *s = simrun(&cfg, 2, ranks, &r, &rc, err, sizeof err);
  CHECK(rc == 0 && !r.bad, "the simulated run: %s", rc ? err : "a call failed");
  CHECK(r.wrong == 0, "%d of %d payloads received wrong through the simulator", r.wrong, 3 * NS);
  sim_free(s);
  free(r.pattern);
}

int main(void) {
  rng g;
  rng_seed(&g, 20261202);
  direct(&g);
  simulated(&g);
  return check_done("test_bigcopy");
}
