/* par.h -- the paper's parallel master/slave algorithm (sections 4, 5, 7, 8),
 * written once against the message-passing interface (mp.h), so that it runs
 * unmodified on the simulator, on POSIX threads and on MPI.  This header
 * holds what master and slave share: the protocol's tags and message kinds,
 * the options, the counters, and message packing.
 *
 * Ranks.  Rank 0 is the master; ranks 1..S are the slaves.  (P processors:
 * P = 1 puts the master and one slave on one processor; P >= 2 gives the
 * master one processor and P-1 slaves one each.)
 *
 * The protocol, for one pair of contours (par_master.c, par_slave.c):
 *
 *   master                                slaves
 *   POINTS -> every slave                 build the tile weights
 *   TASK PATH s=0, no bounds -> all       findonepath: each anti-diagonal of
 *                                         the band split into contiguous runs
 *                                         (N_i formula; at least d nodes each);
 *                                         BOUNDARY costs between neighbours;
 *                                         bits kept by whoever computed a node
 *   <- PIECE (columns, edge weights)      backtrack: the owner of the terminal
 *      until the start node is in         node starts, BACK passes control to
 *   BACK(terminate) -> the group          the owner of the next node
 *   BOUND mu(0) -> all (as T and B)
 *   then, for each group (lo, hi, slaves):
 *     2+ slaves: TASK PATH s=mid          as above, inside the band between
 *                                         the group's bounds T = mu(lo) and
 *                                         B = mu(hi); then the master splits
 *                                         the group (half or size), sends
 *                                         mu(mid) as the new B to one half and
 *                                         as the new T to the other (BOUND)
 *     1 slave:   TASK LOCAL               the whole band by the serial
 *                <- RESULT                divide and conquer; only its best path
 *   TASK REPORT -> all, <- STATS          counters, then the next pair or QUIT
 *
 * Idle slaves receive only from the master (source 0), and a slave waiting
 * in the backtrack phase only tag BACK (continue at a node, or terminate), so
 * a BOUNDARY sent early by a group-mate of its next task waits its turn.
 * Every decision (band, split, owners, allocation) is computed the same way
 * everywhere, from the same integers: nobody is asked who owns what. */
#ifndef PAR_H
#define PAR_H

#include <stddef.h>
#include <stdint.h>

#include "mp/mp.h"
#include "algo/split.h"
#include "algo/weights.h"

/* Tags (the simulator counts sends per tag, 0..15). */
enum {
  PAR_TAG_POINTS = 1,   /* pair header, then the points */
  PAR_TAG_TASK = 2,     /* PATH, LOCAL, REPORT, QUIT */
  PAR_TAG_BOUND = 3,    /* a bounding path: T, B or both */
  PAR_TAG_BOUNDARY = 4, /* costs on a run boundary, slave to slave */
  PAR_TAG_BACK = 5,     /* backtrack: continue at (t, c), or terminate (t < 0) */
  PAR_TAG_PIECE = 6,    /* a piece of a path, slave to master */
  PAR_TAG_RESULT = 7,   /* a one-slave group's best path */
  PAR_TAG_STATS = 8     /* a slave's counters (not counted themselves) */
};

enum { PAR_TASK_PATH = 1, PAR_TASK_LOCAL, PAR_TASK_REPORT, PAR_TASK_QUIT };
/* In POINTS' kind field: the header carries the shadow's weight after
 * zr, zc (par_pair.shadow); without it the paper's bytes stay. */
enum { PAR_SHADOW = 0x100 };
enum { PAR_AS_T = 1, PAR_AS_B = 2, PAR_AS_BOTH = 3 };   /* how a BOUND is taken */

/* Message kinds in the report (section 7.2 counts the boundary ones). */
typedef enum {
  PAR_BOUNDARY,    /* run-boundary costs between slaves */
  PAR_BACKTRACK,   /* BACK (continue) and PIECE */
  PAR_BOUNDS,      /* BOUND: T and B */
  PAR_CONTROL,     /* POINTS, TASK (PATH, LOCAL), terminate, RESULT; the
                      end-of-pair REPORT, STATS and QUIT are not counted */
  PAR_KINDS
} par_kind;

const char *par_kind_name(par_kind k);   /* "boundary", "backtrack", ... */

typedef struct {
  uint64_t msgs[PAR_KINDS];    /* messages sent, by kind */
  uint64_t bytes[PAR_KINDS];   /* their bytes */
  uint64_t nodes;              /* node evaluations (charged: one unit each) */
  uint64_t units;              /* node units charged with mp_compute (slaves) */
  uint64_t book;               /* the master's bookkeeping units: one per column
                                  of a path it assembles, copies or measures
                                  (par_master_charge), charged at opt.book */
  uint64_t paths;              /* paths computed */
  double idle;                 /* slaves: seconds waiting in receives from a
                                  pair's points to its report (mp_time) */
} par_counts;

void par_counts_add(par_counts *into, const par_counts *c);

/* How the master gives out the work: the paper's fixed groups, halved at
 * each path (section 4), or bands as tasks to whichever slaves are free
 * (par_dynamic.h). */
typedef enum { PAR_STATIC, PAR_DYNAMIC } par_schedule;

typedef struct {
  split_alloc alloc;   /* processor allocation: half (section 4), size (7.1) or
                          fit (size, capped by what the band can use: par_fit.h) */
  int min_diag;        /* d: at least d nodes of a diagonal per slave (7.2), >= 1 */
  int only_mu0;        /* stop after mu(0) (the section 7.2 experiment); the
                          result is then mu(0), not the optimum */
  int block;           /* k: run-boundary costs every k diagonals (par_block.h);
                          0 or 1: every diagonal, the paper's */
  par_schedule schedule;   /* PAR_STATIC (the paper's) or PAR_DYNAMIC */
  double book;         /* the price of one unit of the master's bookkeeping, in
                          node units (mp_compute units, c each): --master-c / c,
                          set by par_config_prices (par_config.h); 0: free */
  double table;        /* the price of one cell of a slave's weight table (a
                          vertical and a horizontal weight, m (n+1) cells a
                          pair, built where the slaves are few: par_slave_table),
                          in node units: --table-c / c; 0 (the default): the
                          build is not charged, as in the paper's figures */
  double back;         /* the price of one step of a slave's backtracking (Fig.
                          14: an edge bit looked up, the edge's weight computed
                          for the master), in node units: --back-c / c; 0 (the
                          default): not charged, as in the paper's figures.
                          Neither is counted in par_counts.units (nodes). */
} par_options;

const char *par_schedule_name(par_schedule s);   /* "static", "dynamic" */
int par_schedule_parse(const char *s, par_schedule *out);   /* 0, or -1 */

/* --- message packing: ints and doubles in order, native byte order ------- */

typedef struct {
  unsigned char *b;
  size_t len, cap;
} par_buf;

void par_buf_reset(par_buf *m);
void par_buf_free(par_buf *m);
void par_put_i32(par_buf *m, int32_t v);
void par_put_f64(par_buf *m, double v);
void par_put_i32s(par_buf *m, const int *v, int n);
void par_put_f64s(par_buf *m, const double *v, int n);

typedef struct {
  const unsigned char *p, *end;
} par_rd;

int32_t par_get_i32(par_rd *r);   /* a short message is a protocol bug: abort */
double par_get_f64(par_rd *r);
void par_get_i32s(par_rd *r, int *v, int n);
void par_get_f64s(par_rd *r, double *v, int n);

/* Send m to dst with tag, counting it under kind (kind < 0: not counted). */
int par_send(mp *self, par_counts *c, int kind, int dst, int tag, const par_buf *m);

/* Receive into *buf, made at least maxlen bytes first (every message of a
 * pair fits in par_maxlen(m, n); the POINTS header in 64). */
int par_recv(mp *self, int src, int tag, par_buf *buf, size_t maxlen, mp_status *st);

static inline size_t par_maxlen(int m, int n) { return 64 + 16 * ((size_t)m + n + 2); }

/* Charge units of work; counted in c->units. */
int par_compute(mp *self, par_counts *c, uint64_t units);

/* Return fail(ctx, rc, "call") from the enclosing function when call
 * returns rc < 0: the master's and the slaves' way out of a failed message
 * call, naming it (par_master_fail, par_slave_fail). */
#define PAR_TRY(fail, ctx, call)                                                \
  do {                                                                          \
    int rc_ = (call);                                                           \
    if (rc_ < 0) return fail(ctx, rc_, #call);                                  \
  } while (0)

#endif
