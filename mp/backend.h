/* backend.h -- what a backend of mp.h (sim/, mp/threads.c, mp/mp_mpi.c)
 * fills in: its calls (mp_ops), the part of a rank's state every backend
 * shares (struct mp), and the way into a rank (mp_enter); and the kit the
 * backends share: a run's errors and warnings (mp_log), the deadlock
 * report's words.  Private to mp/ and sim/ (tests/layers.txt): never
 * installed, so that programs and the layers above mp know a rank only
 * through mp.h's functions.
 *
 * mp.c checks every call's arguments before it calls the backend (the
 * ranks, the tags up to ops->tag_max, the buffers, the times), so a
 * backend's calls get valid ones; a bad one goes to ops->reject. */
#ifndef MP_BACKEND_H
#define MP_BACKEND_H

#include <stddef.h>
#include <stdio.h>

#include "mp/mp.h"
#include "mp/stats.h"
#include "util/errlog.h"

typedef struct mp_ops {
  int (*send)(mp *, int dst, int tag, const void *buf, size_t len);
  int (*recv)(mp *, int src, int tag, void *buf, size_t cap, mp_status *st);
  int (*probe)(mp *, int src, int tag, mp_status *st);
  int (*compute)(mp *, double units);
  double (*time)(const mp *);
  int (*wait)(mp *, int src, int tag, mp_status *st);
  int (*busy)(mp *, double seconds);
  int (*sleep_for)(mp *, double seconds);   /* not "sleep": SimGrid's headers define that macro */
  int (*yield)(mp *);                        /* mp_yield; NULL: nothing to do */
  void (*stop)(mp *, int code, const char *why);   /* mp_abort's effect on the run */
  void (*call)(mp *, const char *name, int begin); /* mp_call_begin/end, where traced */
  /* Messages without copies: NULL where the backend copies (mp.c then
   * does what the contract allows with send, wait and recv). */
  int (*send_ref)(mp *, int dst, int tag, const void *buf, size_t len, mp_ref **ref);
  void (*settle)(mp *, mp_ref *ref);
  int (*withdraw)(mp *, mp_ref *ref);
  int (*recv_msg)(mp *, int src, int tag, mp_msg **msg, mp_status *st);
  int (*recv_msg_into)(mp *, int src, int tag, int mask, int want, void *buf, size_t cap, mp_msg **msg,
                       mp_status *st);   /* NULL: recv_msg, then msg_read when it fits */
  int (*msg_read)(mp *, mp_msg *msg, void *buf, size_t cap);
  int (*msg_gone)(mp *, const mp_msg *msg);
  mp_promise *(*promise)(mp *, int src, int tag, int mask, void *buf, size_t cap);
  int (*promise_drop)(mp *, mp_promise *p, int keep);

  /* One-sided transfers: NULL where time is the host's (mp.c then does
   * what the contract says for real backends). */
  double (*transfer)(mp *, int src, int dst, size_t len, double at);
  int (*notify)(mp *, int dst, int tag, double at);

  /* A call with a bad argument, which mp.c found (why: "rank 3: mp_send
   * to rank 9, which does not exist (4 ranks)"): MP_ESTOPPED if the run
   * has stopped, else the run's error recorded (the run fails quoting
   * why) and code returned. */
  int (*reject)(mp *, int code, const char *why);
  int tag_max;        /* the largest tag (INT_MAX, or MPI's limit) */
  int sleep_bounded;  /* 1: mp_sleep takes 0 to 1e9 seconds (a real sleep) */
} mp_ops;

/* A backend's per-rank state begins with this struct.  The backend calls
 * the rank's main through mp_enter, which is where mp_exit returns to. */
struct mp {
  const mp_ops *ops;
  int rank, size;
  void *user;                 /* mp_user */
  mp_describe describe;       /* mp_label */
  void *describe_ud;
  void *exit_to;              /* mp_enter's jmp_buf while main runs */
  void *stack_lo;             /* the rank's own stack, where the backend knows it */
  size_t stack_size;          /* (the simulator's coroutines; else 0) */
  void *stack_guard;          /* a fault in [stack_guard, stack_lo) is its stack
                                 overflowing (the simulator's; else NULL) */
  int traced;                 /* the backend traces this rank's calls (ops->call) */
  int call_depth;             /* mp_call_begin's nesting, */
  const char *call_name;      /* and the outermost call's name */
  mp_progress progress;       /* mp_set_progress */
  void *progress_ud;
};

/* Run main(self, ud) until it returns or the rank calls mp_exit or
 * mp_abort; the backend sets the calling thread's mp_self first (and, on
 * a simulator, again at every switch, with mp_set_self). */
void mp_enter(mp *self, mp_main main, void *ud);
void mp_set_self(mp *self);

/* The label's words for a deadlock report: describe's, or NULL. */
const char *mp_label_text(const mp *self, char *buf, size_t len);

/* ==== the kit ============================================================= */

#if defined(__GNUC__)
#define MP_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define MP_PRINTF(a, b)
#endif

/* A run's errors and warnings, counted in *st's errors and warnings.  Not
 * locked: a backend whose ranks are threads holds its own lock around
 * these calls. */
typedef struct {
  const char *name;   /* "sim", "threads", "mpi": the warnings' prefix */
  FILE *warn;         /* warnings go here, "NAME: warning: TEXT"; NULL: quiet */
  mp_stats *st;
  errlog errs;        /* the errors quoted in the run's message (errlog.h) */
} mp_log;

/* An error of the run: counted, and quoted in its message (always: even
 * after ERRLOG_SHOWN others, as a deadlock report is). */
void mp_fail_text(mp_log *lg, const char *text, int always);
MP_PRINTF(2, 3) void mp_fail(mp_log *lg, const char *fmt, ...);

/* A warning: counted, and printed unless warn is NULL. */
MP_PRINTF(2, 3) void mp_warn(mp_log *lg, const char *fmt, ...);

/* The run's message: the quoted errors into err, 0 if there were none,
 * else -1 (errlog_report). */
int mp_log_report(const mp_log *lg, char *err, size_t errlen);
void mp_log_free(mp_log *lg);

/* The words of a source or tag in a report: "any" (v < 0) or the number,
 * in buf. */
const char *mp_peer_name(int v, char *buf, size_t len);

/* A deadlock report: HEAD, then for each blocked rank in rank order
 * " rank I waits in LABEL" (mp_label) or " rank I waits in recv(src=S,
 * tag=T)", ";"-separated, the first MP_DEADLOCK_SHOWN of them, then
 * "; and N more ranks". */
enum { MP_DEADLOCK_SHOWN = 16 };
typedef struct {
  char *text;         /* malloc'd */
  size_t cap, len;
  int blocked;
} mp_deadlock;
MP_PRINTF(2, 3) void mp_deadlock_begin(mp_deadlock *d, const char *head, ...);
void mp_deadlock_rank(mp_deadlock *d, const mp *rank, int wait_src, int wait_tag);
/* The text, complete (the caller frees it). */
char *mp_deadlock_end(mp_deadlock *d);

#endif
