/* farm.c -- a master-worker task farm: rank 0 hands out tasks, the workers
 * (ranks 1 .. P-1) do them and send back results, and the master gives the
 * next task to whichever worker answered first (a receive from any source).
 *
 *   cc farm.c $(pkg-config --cflags --libs tilesim) -o farm
 *   ./farm --procs 5 --net loggp -- 200 7
 *
 * Task i (i = 0 .. T-1, default T = 100) costs 1 + (i * 7) mod S units of
 * work (S = 1 gives equal tasks; default S = 7) and its result is i^2.
 * A worker charges the units with mp_compute and answers with the task's
 * number and result; the master adds the results and, when every task is
 * done, tells each worker to stop.  It prints the total (checked against
 * T(T - 1)(2T - 1) / 6) and the time.  On the simulator the order in which
 * results arrive is the earliest arrival first, ties to the lower rank: the
 * same on every run.
 *
 * With equal tasks (S = 1) of one unit, T = k W for W workers, on --net
 * ideal: the master's sends are instant, so every round of W tasks takes
 * 2 m + 24 per_byte + c (a task of 8 bytes out, its unit of work, a result
 * of 16 bytes back): the master prints k (2 m + 24 per_byte + c), and the
 * workers stop m + 8 per_byte later (the makespan). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <tilesim/tilesim.h>

typedef struct {
  int tasks, spread;
} farm_args;

enum { TAG_TASK = 1, TAG_RESULT = 2, TAG_STOP = 3 };

typedef struct {
  int64_t task, result;
} answer;

static void master(mp *self, const farm_args *a) {
  int workers = mp_size(self) - 1, next = 0, done = 0;
  int64_t total = 0, task;
  for (int w = 1; w <= workers && next < a->tasks; w++) {   /* one task each to start */
    task = next++;
    mp_send(self, w, TAG_TASK, &task, sizeof task);
  }
  while (done < a->tasks) {
    answer ans;
    mp_status st;
    mp_recv(self, MP_ANY, TAG_RESULT, &ans, sizeof ans, &st);   /* whoever is first */
    total += ans.result;
    done++;
    if (next < a->tasks) {
      task = next++;
      mp_send(self, st.source, TAG_TASK, &task, sizeof task);
    }
  }
  for (int w = 1; w <= workers; w++) mp_send(self, w, TAG_STOP, &task, sizeof task);
  int64_t t = a->tasks, expect = t * (t - 1) * (2 * t - 1) / 6;
  if (total != expect) mp_abort(self, 1, "farm: the total is wrong");
  printf("farm: %d tasks on %d workers: total %lld, checked\n", a->tasks, workers, (long long)total);
  char b[32];
  printf("farm: %s s\n", tilesim_fmt_double(mp_time(self), b, sizeof b));
}

static void worker(mp *self, const farm_args *a) {
  for (;;) {
    int64_t task;
    mp_status st;
    mp_recv(self, 0, MP_ANY, &task, sizeof task, &st);   /* a task, or stop */
    if (st.tag == TAG_STOP) return;
    mp_compute(self, 1 + (double)(task * 7 % a->spread));
    answer ans = {task, task * task};
    mp_send(self, 0, TAG_RESULT, &ans, sizeof ans);
  }
}

static void farm(mp *self, void *ud) {
  const farm_args *a = ud;
  if (mp_size(self) < 2) mp_abort(self, 1, "farm: a farm needs a master and at least one worker (--ranks 2)");
  if (mp_rank(self) == 0) master(self, a);
  else worker(self, a);
}

int main(int argc, char **argv) {
  tilesim_machine *m;
  int status = tilesim_args(&argc, &argv, &m);
  if (!m) return status;
  farm_args a = {100, 7};   /* after --: [TASKS [SPREAD]] */
  if (argc > 1) a.tasks = atoi(argv[1]);
  if (argc > 2) a.spread = atoi(argv[2]);
  if (argc > 3 || a.tasks < 1 || a.tasks > 1000000 || a.spread < 1) {
    fprintf(stderr, "farm: arguments after --: [TASKS [SPREAD]], TASKS from 1 to 10^6, SPREAD >= 1\n");
    tilesim_machine_free(m);
    return 2;
  }
  return tilesim_exec(m, 0, farm, &a);
}
