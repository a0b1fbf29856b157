/* state.h -- one rank's MPI state: communicators, groups, requests, the
 * matching engine's queues (private to the point-to-point part of the MPI
 * layer: mpi/state.c, engine.c, err.c, init.c, pt2pt.c, request.c, comm.c,
 * group.c, coll_transport.c).
 *
 * A rank's state hangs on its mp handle (mp_user) from MPI_Init to
 * MPI_Finalize: nothing of it is global, so ranks that run as coroutines
 * (the simulator) or threads share nothing.  st_get() finds it in two loads
 * and a thread-local read. */
#ifndef TSMPI_STATE_H
#define TSMPI_STATE_H

#include <stddef.h>

#include "mpi/dtype.h"
#include "mp/mp.h"
#include "mpi/mpi.h"
#include "mpi/core.h"

/* ==== handles ============================================================= */

/* mpi.h: kind << 24 | index; created objects have bit 23 set. */
enum {
  H_KIND_SHIFT = 24,
  H_CREATED = 0x800000,
  H_SLOT_MASK = 0x7fffff
};
#define H_KIND(h) ((unsigned)(h) >> H_KIND_SHIFT)
enum { HK_COMM = 1, HK_GROUP = 2, HK_ERRH = 5, HK_REQ = 6, HK_INFO = 7, HK_MSG = 10 };

/* ==== contexts and the envelope =========================================== */

/* A message's mp tag holds its envelope (no header bytes travel):
 *
 *   bit 30 29 | 28 ........ 18 | 17 ............ 0
 *       kind  |   context      |   MPI tag
 *
 * kind: K_DATA (an eager message), K_SYNC (an MPI_Ssend's: its receiver
 * answers with a K_ACK when the receive starts), K_ACK (that answer, with
 * the message's context and tag).  Every communicator has a pair of
 * contexts, 2k for point-to-point and 2k + 1 for its collectives; k is the
 * same on every rank of it (comm.c).  CTX_PAIRS pairs: a rank can be in at
 * most that many communicators at once, MPI_COMM_WORLD and MPI_COMM_SELF
 * included. */
enum {
  ENV_TAG_BITS = 18,
  ENV_CTX_BITS = 11,
  ENV_KIND_SHIFT = ENV_TAG_BITS + ENV_CTX_BITS,
  ST_TAG_UB = (1 << ENV_TAG_BITS) - 1,   /* MPI_TAG_UB: 262143 */
  CTX_PAIRS = 1 << (ENV_CTX_BITS - 1),     /* 1024 */
  K_DATA = 0,
  K_SYNC = 1,
  K_ACK = 2
};

static inline int st_env_encode(int kind, int ctx, int tag) {
  return kind << ENV_KIND_SHIFT | ctx << ENV_TAG_BITS | tag;
}
static inline int st_env_kind(int mptag) { return mptag >> ENV_KIND_SHIFT; }
static inline int st_env_ctx(int mptag) { return (mptag >> ENV_TAG_BITS) & ((1 << ENV_CTX_BITS) - 1); }
static inline int st_env_tag(int mptag) { return mptag & ST_TAG_UB; }

/* Tags the communicator constructors use on the parent's collective
 * context, above the collectives' own (core.h: COLL_TAG_MAX). */
enum { TAG_CTXID = COLL_TAG_MAX + 1, TAG_CTXID_BCAST, TAG_SPLIT, TAG_SPLIT_BCAST, TAG_INTER, TAG_INTER_BCAST };
/* MPI_Comm_create_group's, by the program's tag (tag % TAG_GROUP_N): a pair
 * each, so that groups made at once with different tags keep apart. */
enum { TAG_GROUP_N = 64, TAG_GROUP = ST_TAG_UB + 1 - 2 * TAG_GROUP_N };

/* ==== groups and communicators ============================================ */

/* An ordered set of ranks, shared (counted) by groups and communicators. */
typedef struct {
  int refs;
  int n;
  int *world;   /* world[i]: the MPI_COMM_WORLD rank of rank i; NULL: i itself */
  int *sw;      /* the world ranks sorted, and ... */
  int *sr;      /* ... sr[k] the rank of sw[k] (NULL with world NULL) */
} st_ranks;

/* An intracommunicator's g and size are its group; an
 * intercommunicator's are the remote group's, which its point-to-point
 * ranks name (so that sends, receives and statuses need nothing else),
 * and lg is its local group; rank is always the calling rank's in its own
 * group.  Use st_comm_lsize and st_comm_lgroup for the local side. */
typedef struct {
  int live;            /* 0: a free slot */
  int pair;            /* context pair: ctx 2 * pair, collectives 2 * pair + 1 */
  int rank, size;      /* the calling rank's rank in it, and its size */
  st_ranks *g;
  MPI_Errhandler eh;   /* predefined, or a handler of the rank's (errh.c): counted */
  char name[MPI_MAX_OBJECT_NAME];   /* MPI_Comm_set_name's */
  char words[32];      /* comm_get_name's answer */
  MPI_Comm h;          /* its own handle */
  int inter;           /* an intercommunicator */
  int low;             /* intercommunicators: the local leader's world rank is below
                          the remote leader's (its group comes first when merged) */
  st_ranks *lg;       /* intercommunicators: the local group (counted) */
  MPI_Comm local;      /* intercommunicators: an intracommunicator of the local
                          group, with a context pair of its own, for the
                          collectives' local steps (hidden from the program) */
  int hidden;          /* such a local communicator */
  unsigned hints;      /* the info hints it keeps (info.c: INFO_HINT_*) */
  unsigned nbc_seq;    /* nonblocking collectives started on it (comm_nbc_tag) */
  struct ptopo *topo;   /* its process topology (topo.h), counted, or NULL */
  int holds;           /* nonblocking collectives on it going on (comm_hold) */
  int freed;           /* MPI_Comm_free'd while held: gone for the program, and
                          ended when the last hold goes */
} st_comm;

static inline int st_comm_lsize(const st_comm *c) { return c->inter ? c->lg->n : c->size; }
static inline st_ranks *st_comm_lgroup(const st_comm *c) { return c->inter ? c->lg : c->g; }

/* ==== requests ============================================================ */

enum { RQ_SEND, RQ_RECV, RQ_KIND, RQ_COLL };   /* RQ_KIND: a kind of its own (q->ops, core.h);
                                                RQ_COLL: a nonblocking collective (coll_req) */
enum { SM_STANDARD, SM_SYNC, SM_BUFFERED, SM_READY };
enum { RS_INACTIVE, RS_ACTIVE, RS_DONE };

typedef struct st_req st_req;
struct st_req {
  st_req *next, *prev;    /* the posted queue (receives), the sync list (sends),
                              the free list */
  int slot;                /* its handle's slot; -1: not in the table (a blocking
                              call's request on the stack) */
  unsigned char kind;      /* RQ_* */
  unsigned char mode;      /* SM_* (sends) */
  unsigned char state;     /* RS_* */
  unsigned char persistent;/* made by MPI_*_init */
  unsigned char freed;     /* MPI_Request_free while active: goes when done */
  unsigned char used;      /* in the table and not freed */
  unsigned char held;      /* holds dt (dtype_hold) until freed */
  unsigned char watch;     /* a nonblocking collective's step: when done, the
                              rank's progress function runs (coll_p2p_watch) */
  /* the call's arguments */
  void *buf;
  int count;
  MPI_Datatype dt;
  int peer;                /* rank in comm, MPI_ANY_SOURCE or MPI_PROC_NULL */
  int tag;                 /* MPI tag or MPI_ANY_TAG */
  MPI_Comm comm;
  int pair;                /* comm's context pair, for messages */
  const char *fn;          /* the MPI call that made it, for messages */
  size_t msglen;           /* receives: the length of the message taken */
  size_t sendlen;          /* sends: the message's length */
  /* matching */
  int wpeer;               /* peer's world rank, or MP_ANY */
  int ctx;                 /* its context */
  size_t cap;              /* receives: the buffer's bytes (count * type size) */
  void *contig;            /* receives: where those bytes lie if the type is
                              contiguous there, else NULL (unpacked) */
  st_ranks *g;            /* active receives: comm's ranks (counted), to name
                              the source in the status */
  /* RQ_KIND: its kind and its state (core.h: req_start) */
  const req_kind *ops;
  void *ext;
  /* the message path (engine.h: what is copied when) */
  unsigned char byref;     /* sends: the message goes by reference (mp_send_ref) */
  mp_ref *ref;             /* a send by reference not yet settled */
  void *tmp;               /* a non-contiguous send's packed copy, until settled */
  mp_promise *prom;        /* a posted receive's promise of its buffer */
  /* the result */
  MPI_Status st;
};

/* ==== unexpected messages ================================================= */

typedef struct st_msg st_msg;
struct st_msg {
  st_msg *next, *prev;
  int src;                 /* world rank */
  int kind, ctx, tag;      /* the envelope */
  size_t len;
  mp_msg *h;               /* the message, held (mp_recv_msg) until read */
  MPI_Comm comm;           /* a matched probe's (MPI_Mprobe) communicator */
};

/* ==== the rank ============================================================ */

enum { ST_LIVE = 1, ST_FINALIZED = 2 };

typedef struct st_rank st_rank;
struct st_rank {
  int state;               /* ST_LIVE */
  mp *self;
  int wrank, wsize;        /* in MPI_COMM_WORLD */
  int thread_level;        /* what MPI_Init_thread provided */
  /* communicators: MPI_COMM_WORLD, MPI_COMM_SELF, then created ones by slot */
  st_comm world, selfc;
  st_comm **comms;
  int ncomms;
  unsigned char pairs[CTX_PAIRS / 8];   /* context pairs in use: bit set */
  /* groups by slot (MPI_GROUP_EMPTY is predefined) */
  st_ranks **groups;
  int ngroups;
  st_ranks *empty;        /* MPI_GROUP_EMPTY */
  /* requests by slot, and the free ones */
  st_req **reqs;
  int nreqs;
  st_req *freereq;
  /* the matching engine (engine.c) */
  st_req *posted, *posted_tail;   /* receives posted and not matched, in order */
  int posted_plain;                /* ... of those, the ones without a promise */
  st_msg *unexp, *unexp_tail;     /* messages taken off mp and not matched, in order */
  long nunexp;
  st_req *sync, *sync_tail;       /* synchronous sends waiting for their ack */
  mp_ref *held_ref;                /* a blocking call's send by reference, and its */
  void *held_tmp;                  /* packed copy, until settled (eng_hold) */
  int attr[8];             /* MPI_Comm_get_attr's values, by predefined key */
  /* matched probes' messages by slot (MPI_Mprobe), and the free slots */
  st_msg **msgs;
  int nmsgs;
  /* a rank that polls without its clock moving (spin.h) */
  long spins;
  double spin_t;
  /* requests of a kind of their own not yet freed, and whether their
   * progress runs now (engine.c: eng_advance_all) */
  int nkinds;
  int advancing;
  /* MPI_Buffer_attach */
  void *bbuf;
  int bsize;
  /* the nonblocking collectives' progress (coll_set_progress) */
  void (*progress)(void);
  int progress_due;        /* a watched request completed since it last ran */
  int in_progress;         /* it runs */
  /* the other parts' slots (core.h) */
  void *part[ST_PARTS];
  void (*release[ST_PARTS])(void *);
  /* attribute keys and attributes (attr.c), error handlers and the
   * program's error classes and codes (errh.c), info objects (info.c) */
  struct attr_table *attrs;
  struct errh_table *errs;
  struct info_table *infos;
  int argc;                /* what MPI_Init was given (0 and NULL if nothing), */
  char **argv;             /* for MPI_INFO_ENV, made when first asked for */
};

/* The calling rank's state: NULL before MPI_Init, after MPI_Finalize and
 * outside a rank. */
st_rank *st_get(void);

/* What mp_user holds after MPI_Finalize, and after the rank was stopped
 * inside an MPI call (its state released): marks, not states (init.c's). */
extern const char init_marks[2];
#define INIT_MARK_FINALIZED ((void *)&init_marks[0])
#define INIT_MARK_STOPPED ((void *)&init_marks[1])

/* The state for call fn, or the run ends: outside a rank, before MPI_Init or
 * after MPI_Finalize (a clear message, exit status 1: st_need_fail). */
_Noreturn void st_need_fail(const char *fn);
static inline st_rank *st_need(const char *fn) {
  void *u = mp_self_user();
  if (u && u != INIT_MARK_FINALIZED && u != INIT_MARK_STOPPED) return u;
  st_need_fail(fn);
}

/* The rank ends here (the run was stopped: an MPI_Abort, a deadlock): its
 * state is released and mp_exit never returns. */
_Noreturn void st_stopped(st_rank *R);

/* Release everything of the rank's state (MPI_Finalize, a stopped run). */
void st_release(st_rank *R);

/* Communicator comm of R, or NULL (freed, null, not a communicator). */
st_comm *st_comm_get(st_rank *R, MPI_Comm comm);

/* The same for call fn on a communicator its caller has checked: a bad one
 * is a bug of the layer (the run ends). */
st_comm *st_comm_must(st_rank *R, MPI_Comm comm, const char *fn);

/* The rank in c of world rank w, or -1 if w is not in c. */
int st_comm_rank_of(const st_comm *c, int w);

/* Requests: a new one in the table (zeroed but for its slot), the one a
 * handle names (NULL if none), its handle, and its end (out of the table, or
 * just freed for one on the stack; a send by reference settled; a kind of
 * its own's free called, whose error class is returned). */
st_req *st_req_new(st_rank *R);
st_req *st_req_get(st_rank *R, MPI_Request h);
static inline MPI_Request st_req_handle(const st_req *q) {
  return (MPI_Request)(HK_REQ << H_KIND_SHIFT | H_CREATED | q->slot);
}
int st_req_free(st_rank *R, st_req *q);

/* Matched probes' messages (MPI_Mprobe): a handle for m, and the message a
 * handle names, taken out of the table (NULL: none). */
MPI_Message st_msg_handle(st_rank *R, st_msg *m);
st_msg *st_msg_take(st_rank *R, MPI_Message h);

/* A blocking call's request, on its stack (the fill functions of pt2pt.h
 * set the rest; no zeroing of the whole struct on the fast path). */
static inline void st_req_stack(st_req *q) {
  q->slot = -1;
  q->used = q->held = 0;
}

/* A communicator's context pair as a name for messages: "MPI_COMM_WORLD",
 * "MPI_COMM_SELF", "communicator N" (buf: at least 32 bytes). */
const char *st_pair_name(int pair, char *buf);

/* The world rank of rank r of c (0 <= r < c->size). */
static inline int st_world_of(const st_comm *c, int r) { return c->g->world ? c->g->world[r] : r; }

/* Groups' ranks: a new set of n ranks (world NULL: the identity), counted. */
st_ranks *st_ranks_new(int n, const int *world);
void st_ranks_drop(st_ranks *g);
int st_ranks_find(const st_ranks *g, int w);   /* rank of world rank w, or -1 */

#endif
