/* backend.h -- what a backend of mp.h (sim/, mp/threads.c, mp/mp_mpi.c)
 * fills in: its calls (mp_ops), the part of a rank's state every backend
 * shares (struct mp), and the way into a rank (mp_enter).  Private to mp/
 * and sim/ (tests/layers.txt): never installed, so that programs and the
 * layers above mp know a rank only through mp.h's functions. */
#ifndef MP_BACKEND_H
#define MP_BACKEND_H

#include <stddef.h>

#include "mp/mp.h"

typedef struct mp_ops {
  int (*send)(mp *, int dst, int tag, const void *buf, size_t len);
  int (*recv)(mp *, int src, int tag, void *buf, size_t cap, mp_status *st);
  int (*probe)(mp *, int src, int tag, mp_status *st);
  int (*compute)(mp *, double units);
  double (*time)(const mp *);
  int (*wait)(mp *, int src, int tag, mp_status *st);
  int (*busy)(mp *, double seconds);
  int (*sleep_for)(mp *, double seconds);   /* not "sleep": SimGrid's headers define that macro */
  void (*stop)(mp *, int code, const char *why);   /* mp_abort's effect on the run */
  void (*call)(mp *, const char *name, int begin); /* mp_call_begin/end, where traced */
  /* Messages without copies: NULL where the backend copies (mp.c then
   * does what the contract allows with send, wait and recv). */
  int (*send_ref)(mp *, int dst, int tag, const void *buf, size_t len, mp_ref **ref);
  void (*settle)(mp *, mp_ref *ref);
  int (*withdraw)(mp *, mp_ref *ref);
  int (*recv_msg)(mp *, int src, int tag, mp_msg **msg, mp_status *st);
  int (*msg_read)(mp *, mp_msg *msg, void *buf, size_t cap);
  int (*msg_gone)(mp *, const mp_msg *msg);
  mp_promise *(*promise)(mp *, int src, int tag, int mask, void *buf, size_t cap);
  int (*promise_drop)(mp *, mp_promise *p, int keep);

  /* One-sided transfers: NULL where time is the host's (mp.c then does
   * what the contract says for real backends). */
  double (*transfer)(mp *, int src, int dst, size_t len, double at);
  int (*notify)(mp *, int dst, int tag, double at);
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

#endif
