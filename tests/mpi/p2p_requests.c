/* p2p_requests.c -- nonblocking and persistent requests, checked by
 * themselves on any number of ranks >= 2: Isend/Irecv with Wait, Waitall,
 * Waitany and Waitsome (each request completed once), the Test family
 * (a request that cannot be done yet tests false, and nothing changes),
 * MPI_Request_free, MPI_REQUEST_NULL and inactive requests (the empty
 * status), persistent requests started again and again, and a posted
 * receive keeping its place ahead of a later blocking one. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* The empty status of MPI 3.1 section 3.7.3. */
static int req_empty(const MPI_Status *st) {
  int count = -1;
  MPI_Get_count(st, MPI_INT, &count);
  return st->MPI_SOURCE == MPI_ANY_SOURCE && st->MPI_TAG == MPI_ANY_TAG && count == 0;
}

/* Around the ring both ways at once: two Irecvs, two Isends, Waitall. */
static void req_ring(mtest *t) {
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int out[2] = {t->rank, -t->rank}, in[2] = {-1, -1};
  MPI_Request r[4];
  MPI_Status st[4];
  MPI_Irecv(&in[0], 1, MPI_INT, left, 1, MPI_COMM_WORLD, &r[0]);
  MPI_Irecv(&in[1], 1, MPI_INT, right, 2, MPI_COMM_WORLD, &r[1]);
  MPI_Isend(&out[0], 1, MPI_INT, right, 1, MPI_COMM_WORLD, &r[2]);
  MPI_Isend(&out[1], 1, MPI_INT, left, 2, MPI_COMM_WORLD, &r[3]);
  MPI_Waitall(4, r, st);
  MCHECK(t, in[0] == left && in[1] == -right, "ring: %d %d", in[0], in[1]);
  MCHECK(t, st[0].MPI_SOURCE == left && st[1].MPI_SOURCE == right && st[1].MPI_TAG == 2, "ring statuses");
  int nulls = 1;
  for (int i = 0; i < 4; i++) nulls &= r[i] == MPI_REQUEST_NULL;
  MCHECK(t, nulls, "ring: requests not nulled");
}

/* Rank 0 receives one message from every other rank, completing them with
 * Waitany, then again with Waitsome: every index exactly once, its status
 * naming its source; with nothing left, MPI_UNDEFINED. */
static void req_any_some(mtest *t) {
  int n = t->size - 1;
  for (int round = 0; round < 2; round++) {
    if (t->rank != 0) {
      int v = 100 * round + t->rank;
      MPI_Send(&v, 1, MPI_INT, 0, 10 + round, MPI_COMM_WORLD);
      continue;
    }
    int *in = malloc((size_t)n * sizeof *in), *hit = calloc((size_t)n, sizeof *hit);
    int *idx = malloc((size_t)n * sizeof *idx);
    MPI_Request *r = malloc((size_t)n * sizeof *r);
    MPI_Status *st = malloc((size_t)n * sizeof *st);
    for (int i = 0; i < n; i++) MPI_Irecv(&in[i], 1, MPI_INT, i + 1, 10 + round, MPI_COMM_WORLD, &r[i]);
    int done = 0, bad = 0;
    while (done < n) {
      if (round == 0) {
        int k = -1;
        MPI_Status s1;
        MPI_Waitany(n, r, &k, &s1);
        int ok = k >= 0 && k < n && !hit[k] && s1.MPI_SOURCE == k + 1 && in[k] == k + 1 && r[k] == MPI_REQUEST_NULL;
        if (!ok) printf("p2p_requests: waitany: index %d source %d\n", k, s1.MPI_SOURCE);
        bad += !ok;
        if (k >= 0 && k < n) hit[k]++;
        done++;
      } else {
        int out = -1;
        MPI_Waitsome(n, r, &out, idx, st);
        if (out < 1 || out > n - done) {
          printf("p2p_requests: waitsome: %d done of %d left\n", out, n - done);
          bad++;
          break;
        }
        for (int j = 0; j < out; j++) {
          int k = idx[j];
          int ok = k >= 0 && k < n && !hit[k] && st[j].MPI_SOURCE == k + 1 && in[k] == 100 + k + 1;
          if (!ok) printf("p2p_requests: waitsome: index %d source %d\n", k, st[j].MPI_SOURCE);
          bad += !ok;
          if (k >= 0 && k < n) hit[k]++;
        }
        done += out;
      }
    }
    MCHECK(t, bad == 0, "%s: %d requests completed wrongly", round ? "waitsome" : "waitany", bad);
    int k = 0, out = 0;
    MPI_Status s1;
    if (round == 0) {
      MPI_Waitany(n, r, &k, &s1);
      MCHECK(t, k == MPI_UNDEFINED && req_empty(&s1), "waitany on nothing: %d", k);
    } else {
      MPI_Waitsome(n, r, &out, idx, st);
      MCHECK(t, out == MPI_UNDEFINED, "waitsome on nothing: %d", out);
    }
    free(in);
    free(hit);
    free(idx);
    free(r);
    free(st);
  }
}

/* Rank 1 posts two receives; rank 0 sends the second's message only after
 * rank 1 says so, so until then Testall is false (and changes nothing),
 * Testany and Testsome can only find the first. */
static void req_tests(mtest *t) {
  if (t->rank == 0) {
    int a = 1, b = 2, go;
    MPI_Send(&a, 1, MPI_INT, 1, 20, MPI_COMM_WORLD);
    MPI_Recv(&go, 1, MPI_INT, 1, 21, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Send(&b, 1, MPI_INT, 1, 22, MPI_COMM_WORLD);
    MPI_Send(&a, 1, MPI_INT, 1, 23, MPI_COMM_WORLD);
    MPI_Recv(&go, 1, MPI_INT, 1, 24, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Send(&b, 1, MPI_INT, 1, 25, MPI_COMM_WORLD);
    return;
  }
  if (t->rank != 1) return;
  int a = 0, b = 0, flag = 1, go = 0;
  MPI_Request r[2];
  MPI_Status st[2];
  MPI_Irecv(&a, 1, MPI_INT, 0, 20, MPI_COMM_WORLD, &r[0]);
  MPI_Irecv(&b, 1, MPI_INT, 0, 22, MPI_COMM_WORLD, &r[1]);
  MPI_Testall(2, r, &flag, st);
  MCHECK(t, flag == 0 && r[0] != MPI_REQUEST_NULL && r[1] != MPI_REQUEST_NULL, "testall before go: %d", flag);
  /* The first completes by itself: test it until it does. */
  flag = 0;
  MPI_Status s1;
  while (!flag) MPI_Test(&r[0], &flag, &s1);
  MCHECK(t, a == 1 && r[0] == MPI_REQUEST_NULL && s1.MPI_TAG == 20, "test: %d", a);
  int k = -2;
  MPI_Testany(2, r, &k, &flag, &s1);
  MCHECK(t, flag == 0 && k == MPI_UNDEFINED, "testany before go: flag %d index %d", flag, k);
  MPI_Send(&go, 1, MPI_INT, 0, 21, MPI_COMM_WORLD);
  flag = 0;
  while (!flag) MPI_Testall(2, r, &flag, st);
  MCHECK(t, b == 2 && r[1] == MPI_REQUEST_NULL && req_empty(&st[0]) && st[1].MPI_TAG == 22,
         "testall after go: %d", b);
  /* Testany and Testsome the same way. */
  MPI_Irecv(&a, 1, MPI_INT, 0, 25, MPI_COMM_WORLD, &r[0]);
  MPI_Irecv(&b, 1, MPI_INT, 0, 23, MPI_COMM_WORLD, &r[1]);
  flag = 0;
  while (!flag) MPI_Testany(2, r, &k, &flag, &s1);
  MCHECK(t, k == 1 && s1.MPI_TAG == 23 && r[1] == MPI_REQUEST_NULL, "testany: index %d", k);
  int out = 0, idx[2];
  MPI_Testsome(2, r, &out, idx, st);
  MCHECK(t, out == 0, "testsome before go: %d", out);
  MPI_Send(&go, 1, MPI_INT, 0, 24, MPI_COMM_WORLD);
  while (out == 0) MPI_Testsome(2, r, &out, idx, st);
  MCHECK(t, out == 1 && idx[0] == 0 && st[0].MPI_TAG == 25 && a == 2, "testsome: %d done, index %d", out, idx[0]);
  MPI_Testany(2, r, &k, &flag, &s1);
  MCHECK(t, flag == 1 && k == MPI_UNDEFINED, "testany on nothing: flag %d index %d", flag, k);
}

/* MPI_REQUEST_NULL and freed requests. */
static void req_null_free(mtest *t) {
  MPI_Request r = MPI_REQUEST_NULL;
  MPI_Status st;
  int flag = 0;
  MPI_Wait(&r, &st);
  MCHECK(t, req_empty(&st), "wait on MPI_REQUEST_NULL");
  MPI_Test(&r, &flag, &st);
  MCHECK(t, flag == 1 && req_empty(&st), "test on MPI_REQUEST_NULL");
  /* A freed send still goes; a freed receive still takes its message (it
   * was posted first), so the later receive gets the next one. */
  if (t->rank == 0) {
    int v[2] = {31, 32};
    MPI_Isend(&v[0], 1, MPI_INT, 1, 30, MPI_COMM_WORLD, &r);
    MPI_Request_free(&r);
    MCHECK(t, r == MPI_REQUEST_NULL, "freed send not nulled");
    MPI_Send(&v[1], 1, MPI_INT, 1, 30, MPI_COMM_WORLD);
    int done;
    MPI_Recv(&done, 1, MPI_INT, 1, 33, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  } else if (t->rank == 1) {
    int first = 0, second = 0;
    MPI_Irecv(&first, 1, MPI_INT, 0, 30, MPI_COMM_WORLD, &r);
    MPI_Request_free(&r);
    MPI_Recv(&second, 1, MPI_INT, 0, 30, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MCHECK(t, second == 32, "after a freed receive: %d (32 due)", second);
    MPI_Send(&second, 1, MPI_INT, 0, 33, MPI_COMM_WORLD);
  }
}

/* Persistent requests around the ring, started five times with new data
 * each time; an inactive one waits and tests as the empty status. */
static void req_persistent(mtest *t) {
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int out = 0, in = -1;
  MPI_Request r[2];
  MPI_Status st[2];
  MPI_Recv_init(&in, 1, MPI_INT, left, 40, MPI_COMM_WORLD, &r[0]);
  MPI_Send_init(&out, 1, MPI_INT, right, 40, MPI_COMM_WORLD, &r[1]);
  MPI_Wait(&r[0], &st[0]);
  MCHECK(t, r[0] != MPI_REQUEST_NULL && req_empty(&st[0]), "inactive persistent wait");
  for (int i = 0; i < 5; i++) {
    out = 1000 * i + t->rank;
    if (i % 2) {
      MPI_Startall(2, r);
    } else {
      MPI_Start(&r[0]);
      MPI_Start(&r[1]);
    }
    MPI_Waitall(2, r, st);
    MCHECK(t, in == 1000 * i + left && st[0].MPI_SOURCE == left && r[0] != MPI_REQUEST_NULL,
           "persistent round %d: %d", i, in);
  }
  int flag = 0;
  MPI_Test(&r[1], &flag, &st[1]);
  MCHECK(t, flag == 1 && req_empty(&st[1]), "inactive persistent test");
  MPI_Request_free(&r[0]);
  MPI_Request_free(&r[1]);
  MCHECK(t, r[0] == MPI_REQUEST_NULL && r[1] == MPI_REQUEST_NULL, "persistent free");
}

/* A receive from any source posted before a blocking receive from a named
 * one: the named source's first message goes to the first receive. */
static void req_posted_first(mtest *t) {
  int last = t->size - 1;
  if (t->rank == last) {
    int v[2] = {51, 52};
    MPI_Send(&v[0], 1, MPI_INT, 0, 50, MPI_COMM_WORLD);
    MPI_Send(&v[1], 1, MPI_INT, 0, 50, MPI_COMM_WORLD);
  }
  if (t->rank != 0) return;
  int a = 0, b = 0;
  MPI_Request r;
  MPI_Status st;
  MPI_Irecv(&a, 1, MPI_INT, MPI_ANY_SOURCE, 50, MPI_COMM_WORLD, &r);
  MPI_Recv(&b, 1, MPI_INT, last, 50, MPI_COMM_WORLD, &st);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  MCHECK(t, a == 51 && b == 52, "posted first: %d %d (51 52 due)", a, b);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {req_ring, req_any_some, req_tests, req_null_free, req_persistent, req_posted_first, NULL};
  return mtest_main(&argc, &argv, "p2p_requests", 2, 0, checks);
}
