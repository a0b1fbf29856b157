/* pingpong.c -- latency and bandwidth of the machine between ranks 0 and 1.
 *
 *   cc pingpong.c $(pkg-config --cflags --libs tilesim) -o pingpong
 *   ./pingpong --procs 2 --net ideal -- 100 0 8 1024 65536
 *
 * For each message size B (default 0, 8, 1024, 65536 bytes), rank 0 sends
 * B bytes to rank 1 and rank 1 sends them back, K times (default 100).
 * Rank 0 prints a line per size: the round trip, the one-way time (half of
 * it) and the bandwidth B / one-way.  On --net ideal a round trip takes
 * exactly 2 (m + B per_byte); on a topology, with the ranks h links apart,
 * 2 (m + h hop_latency + B per_byte) (cut-through, an idle network).  Other
 * ranks, if any, have nothing to do.
 *
 * The payload's last byte carries the round number, and rank 1 checks it:
 * the line "pingpong: checked" says every message came intact and in order
 * (the same on every backend; the times are simulated or wall-clock). */
#include <stdio.h>
#include <stdlib.h>

#include <tilesim/tilesim.h>

enum { MAX_SIZES = 32 };

typedef struct {
  int rounds;
  int nsizes;
  long sizes[MAX_SIZES];
} pingpong_args;

static void pingpong(mp *self, void *ud) {
  const pingpong_args *a = ud;
  int me = mp_rank(self);
  if (me > 1 || mp_size(self) < 2) return;
  long most = 1;
  for (int i = 0; i < a->nsizes; i++)
    if (a->sizes[i] > most) most = a->sizes[i];
  unsigned char *buf = calloc(1, (size_t)most);
  if (!buf) mp_abort(self, 1, "pingpong: out of memory");
  int bad = 0;
  for (int i = 0; i < a->nsizes; i++) {
    size_t len = (size_t)a->sizes[i];
    double t0 = mp_time(self);
    for (int k = 0; k < a->rounds; k++) {
      if (me == 0) {
        if (len) buf[len - 1] = (unsigned char)k;
        mp_send(self, 1, i, buf, len);
        mp_recv(self, 1, i, buf, len, NULL);
      } else {
        mp_status st;
        mp_recv(self, 0, i, buf, len, &st);
        if (st.len != len || (len && buf[len - 1] != (unsigned char)k)) bad++;
        mp_send(self, 0, i, buf, len);
      }
    }
    if (me == 0) {
      double rt = (mp_time(self) - t0) / a->rounds, one = rt / 2;
      char b1[32], b2[32];
      printf("pingpong: %ld bytes: round trip %s s, one way %s s, %.6g bytes/s\n", a->sizes[i],
             tilesim_fmt_double(rt, b1, sizeof b1), tilesim_fmt_double(one, b2, sizeof b2),
             one > 0 ? (double)len / one : 0.0);
    }
  }
  if (me == 1) {
    if (bad) mp_abort(self, 1, "pingpong: a message came back wrong");
    printf("pingpong: checked %d sizes x %d round trips\n", a->nsizes, a->rounds);
  }
  free(buf);
}

int main(int argc, char **argv) {
  tilesim_machine *m;
  int status = tilesim_args(&argc, &argv, &m);
  if (!m) return status;
  pingpong_args a = {100, 4, {0, 8, 1024, 65536}};   /* after --: [K [SIZE...]] */
  if (argc > 1) a.rounds = atoi(argv[1]);
  if (argc > 2) a.nsizes = 0;
  for (int i = 2; i < argc && a.nsizes < MAX_SIZES; i++) a.sizes[a.nsizes++] = atol(argv[i]);
  int ok = a.rounds >= 1 && argc - 2 <= MAX_SIZES;
  for (int i = 0; i < a.nsizes; i++) ok &= a.sizes[i] >= 0 && a.sizes[i] <= (1L << 30);
  if (!ok) {
    fprintf(stderr, "pingpong: arguments after --: [K [SIZE...]]: K >= 1, up to %d sizes of 0 to 2^30 bytes\n",
            MAX_SIZES);
    tilesim_machine_free(m);
    return 2;
  }
  return tilesim_exec(m, 0, pingpong, &a);
}
