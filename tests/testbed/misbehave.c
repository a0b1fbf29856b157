/* misbehave.c -- a user's program that goes wrong on purpose, one way per
 * argument after --, for tests/cli_testbed.sh (built like an example,
 * against the library's installed headers):
 *   deadlock   every rank waits for the next one's message
 *   badrank    rank 1 sends to a rank that does not exist
 *   badtag     rank 1 sends with a negative tag
 *   abort      rank 2 computes a unit, then aborts with code 3
 *   exit       rank 1 leaves through mp_exit before its last send; rank 0
 *              still gets every message sent before
 *   args       rank 0 prints the program's own arguments (tilesim_argv)
 *   sleep      each rank sleeps rank seconds, then computes 1 unit
 *   deep KIB   rank 1 writes KIB KiB of its stack, a KiB a level (an
 *              overflow, given a smaller --stack) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <tilesim/tilesim.h>

static void deadlock(mp *self) {
  int v, n = mp_size(self);
  mp_recv(self, (mp_rank(self) + 1) % n, 7, &v, sizeof v, NULL);
}

static void badcall(mp *self, int tag, int dst) {
  int v = 1;
  if (mp_rank(self) == 1) printf("misbehave: send returned %d\n", mp_send(self, dst, tag, &v, sizeof v));
}

static void exits(mp *self) {
  int v = 5;
  if (mp_rank(self) == 1) {
    mp_send(self, 0, 1, &v, sizeof v);
    mp_exit(self);
  }
  if (mp_rank(self) == 0) {
    mp_recv(self, 1, 1, &v, sizeof v, NULL);
    printf("misbehave: got %d\n", v);
  }
}

/* kib levels of a KiB of stack each, every byte written. */
static long dive(int kib) {
  volatile unsigned char buf[1024];
  for (size_t i = 0; i < sizeof buf; i++) buf[i] = (unsigned char)kib;
  return (kib > 1 ? dive(kib - 1) : 0) + buf[(unsigned)kib % sizeof buf];
}

static void rank_main(mp *self, void *ud) {
  (void)ud;
  int argc;
  char **argv = tilesim_argv(&argc);
  const char *what = argc > 1 ? argv[1] : "";
  if (strcmp(what, "deadlock") == 0) deadlock(self);
  else if (strcmp(what, "badrank") == 0) badcall(self, 0, mp_size(self) + 5);
  else if (strcmp(what, "badtag") == 0) badcall(self, -4, 0);
  else if (strcmp(what, "exit") == 0) exits(self);
  else if (strcmp(what, "abort") == 0) {
    if (mp_rank(self) == 2) {
      mp_compute(self, 1);
      mp_abort(self, 3, "rank 2 gives up");
    }
    int v;
    mp_recv(self, MP_ANY, MP_ANY, &v, sizeof v, NULL);
  } else if (strcmp(what, "sleep") == 0) {
    mp_sleep(self, mp_rank(self));
    mp_compute(self, 1);
  } else if (strcmp(what, "deep") == 0 && argc > 2) {
    if (mp_rank(self) == 1 && dive(atoi(argv[2])) < 0) printf("misbehave: never\n");
  } else if (strcmp(what, "args") == 0 && mp_rank(self) == 0) {
    for (int i = 0; i < argc; i++) printf("misbehave: argv[%d] = %s\n", i, i == 0 ? "(name)" : argv[i]);
  }
}

int main(int argc, char **argv) { return tilesim_main(argc, argv, rank_main, NULL); }
