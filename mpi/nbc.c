/* nbc.c -- the nonblocking collectives' requests and progress (nbc.h). */
#include "mpi/nbc.h"

#include <stdio.h>
#include <stdlib.h>

#include "mpi/core.h"

/* A started collective: its schedule and the program's request. */
typedef struct nbc {
  struct nbc *next;
  coll_sched *s;
  MPI_Request req;
} nbc;

/* The rank's live ones, in the order they started. */
typedef struct {
  nbc *head, *tail;
} list;

static void list_release(void *ud) {   /* the rank's end: the schedules go with their own part */
  list *l = ud;
  for (nbc *e = l->head, *n; e; e = n) {
    n = e->next;
    free(e);
  }
  free(l);
}

static list *rank_list(void) {
  list *l = st_part(ST_PART_NBC);
  if (!l) {
    if (!(l = calloc(1, sizeof *l))) {
      fprintf(stderr, "tilesim: a nonblocking collective: out of memory\n");
      abort();
    }
    st_part_set(ST_PART_NBC, l, list_release);
  }
  return l;
}

/* e's schedule is at its end: its request completes, it goes, and so does
 * its hold on the communicator (held: it was). */
static void finish(nbc *e, int held) {
  MPI_Comm comm = coll_sched_group(e->s)->comm;
  coll_req_complete(e->req, coll_sched_error(e->s));
  coll_sched_free(e->s);
  free(e);
  if (held) comm_release(comm);
}

/* The engine completed a watched request: step every live schedule that can
 * go on, in start order (one that finishes is taken out). */
static void progress(void) {
  list *l = st_part(ST_PART_NBC);
  if (!l) return;
  nbc **pp = &l->head, *prev = NULL;
  while (*pp) {
    nbc *e = *pp;
    if (!coll_sched_step(e->s)) {
      prev = e;
      pp = &e->next;
      continue;
    }
    *pp = e->next;
    if (l->tail == e) l->tail = prev;
    finish(e, 1);
  }
  if (!l->head) coll_set_progress(progress, 0);
}

void nbc_start(coll_sched *s, const char *fn, MPI_Comm comm, int root, MPI_Request *req) {
  MPI_Request h = coll_req(fn, comm, root);
  *req = h;
  nbc *e = malloc(sizeof *e);
  if (!e) {
    fprintf(stderr, "tilesim: %s: out of memory\n", fn);
    abort();
  }
  e->next = NULL;
  e->s = s;
  e->req = h;
  if (coll_sched_step(s)) {   /* nothing to wait for */
    finish(e, 0);
    return;
  }
  comm_hold(comm);
  list *l = rank_list();
  if (l->tail)
    l->tail->next = e;
  else
    l->head = e;
  l->tail = e;
  coll_set_progress(progress, 1);
}
