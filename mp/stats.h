/* stats.h -- the figures of a run that every backend of mp.h counts (the
 * simulator, threads, MPI), as one struct.
 *
 * A backend's own statistics (sim_stats, mpt_stats, mpm_stats) begin with
 * them through MP_STATS_GROUP: each figure is a member of its own, by name
 * (st->messages), and all of them together are the member `run`, an
 * mp_stats, copied as one (the Linux kernel's struct_group does the
 * same).  Never installed. */
#ifndef MP_STATS_H
#define MP_STATS_H

/* The figures, in order. */
#define MP_STATS_FIELDS                                                       \
  int ranks;                /* ranks of the run */                            \
  long long messages;       /* messages sent */                               \
  long long received;       /* messages received */                           \
  long long bytes;          /* bytes sent */                                  \
  long long unread;         /* messages never received */                     \
  long long warnings;       /* warnings (truncations, unread messages) */     \
  long long errors;         /* errors (bad arguments, deadlock, ...) */       \
  int deadlock;             /* 1 if the run ended in a deadlock */            \
  int aborted, abort_code;  /* mp_abort: the first one's code (MPI: 0, 0) */  \
  double wall_s;            /* host seconds of the run (reporting only) */

typedef struct {
  MP_STATS_FIELDS
} mp_stats;

/* The first member of a backend's statistics: the figures by name, and
 * together as `run`. */
#define MP_STATS_GROUP   \
  union {                \
    mp_stats run;        \
    struct {             \
      MP_STATS_FIELDS    \
    };                   \
  }

#endif
