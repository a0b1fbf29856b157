/* trace.c -- CSV and Chrome trace-event JSON writers for the simulator's timeline. */
#include "sim/trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

struct trace {
  FILE *csv, *json;
  int first;   /* no JSON event written yet (no comma before the next) */
  int netpid;  /* the network's pid: the number of processors */
  int netnamed;   /* its process_name is written */
  int count;   /* count the bytes (below) instead of writing */
  int ccsv, cjson;                  /* count mode: which of the two */
  unsigned long long ncsv, njson;   /* count mode: the bytes so far */
  trace *shadow;                    /* limited mode: counts every call, and */
  unsigned long long limit;         /* once its bytes pass the limit, */
  int over;                         /* writing stops (csv and json are dropped) */
};

trace *trace_new(FILE *csv, FILE *json) {
  if (!csv && !json) return NULL;
  trace *tr = xcalloc(1, sizeof *tr);
  tr->csv = csv;
  tr->json = json;
  tr->first = 1;
  return tr;
}

trace *trace_new_count(int csv, int json) {
  if (!csv && !json) return NULL;
  trace *tr = xcalloc(1, sizeof *tr);
  tr->count = 1;
  tr->ccsv = csv != 0;
  tr->cjson = json != 0;
  tr->first = 1;
  return tr;
}

trace *trace_new_limited(FILE *csv, FILE *json, unsigned long long limit) {
  trace *tr = trace_new(csv, json);
  if (!tr) return NULL;
  tr->shadow = trace_new_count(csv != NULL, json != NULL);
  tr->limit = limit;
  return tr;
}

int trace_over(const trace *tr) { return tr && tr->over; }

void trace_size(const trace *tr, unsigned long long *csv, unsigned long long *json) {
  if (tr && tr->shadow) tr = tr->shadow;
  *csv = tr && tr->count ? tr->ncsv : 0;
  *json = tr && tr->count ? tr->njson : 0;
}

void trace_free(trace *tr) {
  if (tr) trace_free(tr->shadow);
  free(tr);
}

/* Limited mode: the shadow has counted the call; 1 if nothing is to be
 * written (the bytes have passed the limit, now or before). */
static int past_limit(trace *tr) {
  if (tr->over) return 1;
  if (tr->shadow->ncsv + tr->shadow->njson <= tr->limit) return 0;
  tr->over = 1;
  tr->csv = tr->json = NULL;
  return 1;
}

/* At the top of every call that writes: the shadow counts it first. */
#define SHADOW(call)                                                           \
  do {                                                                         \
    if (tr->shadow) {                                                          \
      trace *real_ = tr;                                                       \
      tr = tr->shadow;                                                         \
      call;                                                                    \
      tr = real_;                                                              \
      if (past_limit(tr)) return;                                              \
    }                                                                          \
  } while (0)

/* ---- count mode: the length printf would give, by arithmetic ---------------
 * (the formats' lengths, kept beside the formats below; tests/test_trace.c
 * compares the counts with real traces byte for byte). */

static unsigned len_u(unsigned long long v) {
  unsigned n = 1;
  while (v >= 10) v /= 10, n++;
  return n;
}

static unsigned len_i(long long v) {
  return v < 0 ? 1 + len_u(0ULL - (unsigned long long)v) : len_u((unsigned long long)v);
}

/* "%.<prec>f" of a finite x. */
static unsigned len_f(double x, int prec) {
  static const double half[] = {0.5, 0.05, 0.005, 5e-4, 5e-5, 5e-6, 5e-7, 5e-8, 5e-9, 5e-10};
  unsigned n = signbit(x) ? 1 : 0;
  double r = fabs(x) + half[prec];
  unsigned digits = 1;
  if (r >= 1e18) digits = (unsigned)floor(log10(r)) + 1;
  else
    for (double p = 10; r >= p; p *= 10) digits++;
  return n + digits + 1 + (unsigned)prec;
}

static unsigned len_peer(int v) { return v < 0 ? 3 : len_i(v); }   /* "any" */
static unsigned len_jpeer(int v) { return v < 0 ? 5 : len_i(v); }  /* "\"any\"" */

/* jhead's bytes: the separator and the common fields. */
static unsigned long long len_jhead(trace *tr, const char *ph, const char *name, const char *cat,
                                    int proc, int rank, double t) {
  unsigned long long n = tr->first ? 1 : 2;
  tr->first = 0;
  n += strlen("{\"ph\":\"\",\"name\":\"\",\"cat\":\"\",\"pid\":,\"tid\":,\"ts\":");
  return n + strlen(ph) + strlen(name) + strlen(cat) + len_i(proc) + len_i(rank) + len_f(t * 1e6, 3);
}

/* Seconds to the microseconds of the JSON format. */
static double us(double s) { return s * 1e6; }

/* Start a JSON event: the separator, then the fields every event has. */
static void jhead(trace *tr, const char *ph, const char *name, const char *cat, int proc,
                  int rank, double t) {
  fputs(tr->first ? "\n" : ",\n", tr->json);
  tr->first = 0;
  fprintf(tr->json, "{\"ph\":\"%s\",\"name\":\"%s\",\"cat\":\"%s\",\"pid\":%d,\"tid\":%d,\"ts\":%.3f",
          ph, name, cat, proc, rank, us(t));
}

/* A source or tag for the CSV: "any" for -1. */
static void csv_peer(FILE *f, int v) {
  if (v < 0)
    fputs("any", f);
  else
    fprintf(f, "%d", v);
}

void trace_begin(trace *tr, int nranks, const int *place, int nprocs) {
  SHADOW(trace_begin(tr, nranks, place, nprocs));
  tr->netpid = nprocs;
  if (tr->count) {
    if (tr->ccsv) tr->ncsv += strlen("time,rank,proc,event,peer,tag,bytes,duration,msg,arrival\n");
    if (!tr->cjson) return;
    tr->njson += strlen("{\"displayTimeUnit\":\"ns\",\"traceEvents\":[");
    for (int p = 0; p < nprocs; p++) {
      tr->njson += (tr->first ? 1 : 2) + 4 * len_i(p) +
                   strlen("{\"ph\":\"M\",\"name\":\"process_name\",\"pid\":,\"args\":{\"name\":\"proc \"}},\n"
                          "{\"ph\":\"M\",\"name\":\"process_sort_index\",\"pid\":,\"args\":{\"sort_index\":}}");
      tr->first = 0;
    }
    for (int r = 0; r < nranks; r++)
      tr->njson += 2 * len_i(place[r]) + 4 * len_i(r) +
                   strlen(",\n{\"ph\":\"M\",\"name\":\"thread_name\",\"pid\":,\"tid\":,\"args\":{\"name\":\"rank \"}}"
                          ",\n{\"ph\":\"M\",\"name\":\"thread_sort_index\",\"pid\":,\"tid\":,\"args\":{\"sort_index\":}}");
    return;
  }
  if (tr->csv) fputs("time,rank,proc,event,peer,tag,bytes,duration,msg,arrival\n", tr->csv);
  if (!tr->json) return;
  fputs("{\"displayTimeUnit\":\"ns\",\"traceEvents\":[", tr->json);
  for (int p = 0; p < nprocs; p++) {
    fputs(tr->first ? "\n" : ",\n", tr->json);
    tr->first = 0;
    fprintf(tr->json,
            "{\"ph\":\"M\",\"name\":\"process_name\",\"pid\":%d,\"args\":{\"name\":\"proc %d\"}},\n"
            "{\"ph\":\"M\",\"name\":\"process_sort_index\",\"pid\":%d,\"args\":{\"sort_index\":%d}}",
            p, p, p, p);
  }
  for (int r = 0; r < nranks; r++) {
    fprintf(tr->json,
            ",\n{\"ph\":\"M\",\"name\":\"thread_name\",\"pid\":%d,\"tid\":%d,\"args\":{\"name\":\"rank %d\"}}"
            ",\n{\"ph\":\"M\",\"name\":\"thread_sort_index\",\"pid\":%d,\"tid\":%d,\"args\":{\"sort_index\":%d}}",
            place[r], r, r, place[r], r, r);
  }
}

void trace_span(trace *tr, const char *kind, int rank, int proc, double start, double dur,
                int peer, int tag) {
  SHADOW(trace_span(tr, kind, rank, proc, start, dur, peer, tag));
  int wait = strcmp(kind, "wait") == 0;
  if (tr->count) {
    size_t k = strlen(kind);
    if (tr->ccsv)   /* %.9f,%d,%d,%s, [peer,tag | ,] ,,%.9f,,\n */
      tr->ncsv += len_f(start, 9) + len_i(rank) + len_i(proc) + k + 4 +
                  (wait ? len_peer(peer) + 1 + len_peer(tag) : 1) + len_f(dur, 9) + 5;
    if (tr->cjson)
      tr->njson += len_jhead(tr, "X", kind, kind, proc, rank, start) + strlen(",\"dur\":") + len_f(dur * 1e6, 3) +
                   (wait ? strlen(",\"args\":{\"src\":,\"tag\":}") + len_jpeer(peer) + len_jpeer(tag) : 0) + 1;
    return;
  }
  if (tr->csv) {
    fprintf(tr->csv, "%.9f,%d,%d,%s,", start, rank, proc, kind);
    if (wait) {
      csv_peer(tr->csv, peer);
      fputc(',', tr->csv);
      csv_peer(tr->csv, tag);
    } else {
      fputc(',', tr->csv);
    }
    fprintf(tr->csv, ",,%.9f,,\n", dur);
  }
  if (tr->json) {
    jhead(tr, "X", kind, kind, proc, rank, start);
    fprintf(tr->json, ",\"dur\":%.3f", us(dur));
    if (wait) {
      fputs(",\"args\":{\"src\":", tr->json);
      if (peer < 0) fputs("\"any\"", tr->json); else fprintf(tr->json, "%d", peer);
      fputs(",\"tag\":", tr->json);
      if (tag < 0) fputs("\"any\"", tr->json); else fprintf(tr->json, "%d", tag);
      fputc('}', tr->json);
    }
    fputc('}', tr->json);
  }
}

void trace_send(trace *tr, int rank, int proc, double t, double dur, int dst, int tag,
                size_t len, uint64_t msg, double arrival) {
  SHADOW(trace_send(tr, rank, proc, t, dur, dst, tag, len, msg, arrival));
  if (tr->count) {
    if (tr->ccsv)   /* %.9f,%d,%d,send,%d,%d,%zu,%.9f,%llu,%.9f\n */
      tr->ncsv += len_f(t, 9) + len_i(rank) + len_i(proc) + len_i(dst) + len_i(tag) + len_u(len) +
                  len_f(dur, 9) + len_u(msg) + len_f(arrival, 9) + strlen(",,,send,,,,,,\n");
    if (tr->cjson)
      tr->njson += len_jhead(tr, "X", "send", "msg", proc, rank, t) +
                   strlen(",\"dur\":,\"args\":{\"dst\":,\"tag\":,\"bytes\":,\"msg\":,\"arrival_us\":}}") +
                   len_f(dur * 1e6, 3) + len_i(dst) + len_i(tag) + len_u(len) + len_u(msg) +
                   len_f(arrival * 1e6, 3) + len_jhead(tr, "s", "msg", "msg", proc, rank, t) +
                   strlen(",\"id\":}") + len_u(msg);
    return;
  }
  if (tr->csv)
    fprintf(tr->csv, "%.9f,%d,%d,send,%d,%d,%zu,%.9f,%llu,%.9f\n", t, rank, proc, dst, tag, len,
            dur, (unsigned long long)msg, arrival);
  if (tr->json) {
    jhead(tr, "X", "send", "msg", proc, rank, t);
    fprintf(tr->json,
            ",\"dur\":%.3f,\"args\":{\"dst\":%d,\"tag\":%d,\"bytes\":%zu,\"msg\":%llu,"
            "\"arrival_us\":%.3f}}",
            us(dur), dst, tag, len, (unsigned long long)msg, us(arrival));
    jhead(tr, "s", "msg", "msg", proc, rank, t);
    fprintf(tr->json, ",\"id\":%llu}", (unsigned long long)msg);
  }
}

/* The CSV row "T,A,B,KIND,C,TAG,LEN,DUR,MSG," of a receive or a link's
 * message: written, or its bytes counted. */
static void csv_msg(trace *tr, const char *kind, double t, int a, int b, int c, int tag, size_t len,
                    double dur, uint64_t msg) {
  if (tr->count) {
    if (tr->ccsv)
      tr->ncsv += len_f(t, 9) + len_i(a) + len_i(b) + strlen(kind) + len_i(c) + len_i(tag) + len_u(len) +
                  len_f(dur, 9) + len_u(msg) + strlen(",,,,,,,,,\n");
  } else if (tr->csv) {
    fprintf(tr->csv, "%.9f,%d,%d,%s,%d,%d,%zu,%.9f,%llu,\n", t, a, b, kind, c, tag, len, dur,
            (unsigned long long)msg);
  }
}

void trace_recv(trace *tr, int rank, int proc, double t, double dur, int src, int tag,
                size_t len, uint64_t msg) {
  SHADOW(trace_recv(tr, rank, proc, t, dur, src, tag, len, msg));
  csv_msg(tr, "recv", t, rank, proc, src, tag, len, dur, msg);
  if (tr->count) {
    if (tr->cjson)
      tr->njson += len_jhead(tr, "X", "recv", "msg", proc, rank, t) +
                   strlen(",\"dur\":,\"args\":{\"src\":,\"tag\":,\"bytes\":,\"msg\":}}") + len_f(dur * 1e6, 3) +
                   len_i(src) + len_i(tag) + len_u(len) + len_u(msg) +
                   len_jhead(tr, "f", "msg", "msg", proc, rank, t) + strlen(",\"bp\":\"e\",\"id\":}") + len_u(msg);
    return;
  }
  if (tr->json) {
    jhead(tr, "X", "recv", "msg", proc, rank, t);
    fprintf(tr->json, ",\"dur\":%.3f,\"args\":{\"src\":%d,\"tag\":%d,\"bytes\":%zu,\"msg\":%llu}}",
            us(dur), src, tag, len, (unsigned long long)msg);
    jhead(tr, "f", "msg", "msg", proc, rank, t);
    fprintf(tr->json, ",\"bp\":\"e\",\"id\":%llu}", (unsigned long long)msg);
  }
}

void trace_finish(trace *tr, int rank, int proc, double t) {
  SHADOW(trace_finish(tr, rank, proc, t));
  if (tr->count) {
    if (tr->ccsv) tr->ncsv += len_f(t, 9) + len_i(rank) + len_i(proc) + strlen(",,,finish,,,,,,\n");
    if (tr->cjson) tr->njson += len_jhead(tr, "i", "finish", "rank", proc, rank, t) + strlen(",\"s\":\"t\"}");
    return;
  }
  if (tr->csv) fprintf(tr->csv, "%.9f,%d,%d,finish,,,,,,\n", t, rank, proc);
  if (tr->json) {
    jhead(tr, "i", "finish", "rank", proc, rank, t);
    fputs(",\"s\":\"t\"}", tr->json);
  }
}

void trace_link_track(trace *tr, int link, const char *name) {
  SHADOW(trace_link_track(tr, link, name));
  if (tr->count) {
    if (!tr->cjson) return;
    if (!tr->netnamed) {
      tr->njson += (tr->first ? 1 : 2) + 3 * len_i(tr->netpid) +
                   strlen("{\"ph\":\"M\",\"name\":\"process_name\",\"pid\":,\"args\":{\"name\":\"network\"}},\n"
                          "{\"ph\":\"M\",\"name\":\"process_sort_index\",\"pid\":,\"args\":{\"sort_index\":}}");
      tr->first = 0;
      tr->netnamed = 1;
    }
    tr->njson += 2 * len_i(tr->netpid) + 3 * len_i(link) + strlen(name) +
                 strlen(",\n{\"ph\":\"M\",\"name\":\"thread_name\",\"pid\":,\"tid\":,\"args\":{\"name\":\"link \"}}"
                        ",\n{\"ph\":\"M\",\"name\":\"thread_sort_index\",\"pid\":,\"tid\":,\"args\":{\"sort_index\":}}");
    return;
  }
  if (!tr->json) return;
  if (!tr->netnamed) {
    fprintf(tr->json,
            "%s{\"ph\":\"M\",\"name\":\"process_name\",\"pid\":%d,\"args\":{\"name\":\"network\"}},\n"
            "{\"ph\":\"M\",\"name\":\"process_sort_index\",\"pid\":%d,\"args\":{\"sort_index\":%d}}",
            tr->first ? "\n" : ",\n", tr->netpid, tr->netpid, tr->netpid);
    tr->first = 0;
    tr->netnamed = 1;
  }
  fprintf(tr->json,
          ",\n{\"ph\":\"M\",\"name\":\"thread_name\",\"pid\":%d,\"tid\":%d,\"args\":{\"name\":\"link %s\"}}"
          ",\n{\"ph\":\"M\",\"name\":\"thread_sort_index\",\"pid\":%d,\"tid\":%d,\"args\":{\"sort_index\":%d}}",
          tr->netpid, link, name, tr->netpid, link, link);
}

void trace_link(trace *tr, int link, int rank, int dst, int tag, size_t len, uint64_t msg,
                double start, double dur) {
  SHADOW(trace_link(tr, link, rank, dst, tag, len, msg, start, dur));
  csv_msg(tr, "link", start, rank, link, dst, tag, len, dur, msg);
  if (tr->count) {
    if (tr->cjson)
      tr->njson += len_jhead(tr, "X", "msg", "link", tr->netpid, link, start) +
                   strlen(",\"dur\":,\"args\":{\"src\":,\"dst\":,\"tag\":,\"bytes\":,\"msg\":}}") +
                   len_f(dur * 1e6, 3) + len_i(rank) + len_i(dst) + len_i(tag) + len_u(len) + len_u(msg);
    return;
  }
  if (tr->json) {
    jhead(tr, "X", "msg", "link", tr->netpid, link, start);
    fprintf(tr->json, ",\"dur\":%.3f,\"args\":{\"src\":%d,\"dst\":%d,\"tag\":%d,\"bytes\":%zu,\"msg\":%llu}}",
            us(dur), rank, dst, tag, len, (unsigned long long)msg);
  }
}

int trace_end(trace *tr, char *err, size_t errlen) {
  int bad = 0;
  if (tr->shadow) {
    trace_end(tr->shadow, err, errlen);
    if (past_limit(tr)) return 0;
  }
  if (tr->count) {
    if (tr->cjson) tr->njson += strlen("\n]}\n");
    return 0;
  }
  if (tr->json) {
    fputs("\n]}\n", tr->json);
    if (fflush(tr->json) != 0 || ferror(tr->json)) bad |= 2;
  }
  if (tr->csv && (fflush(tr->csv) != 0 || ferror(tr->csv))) bad |= 1;
  if (bad) {
    snprintf(err, errlen, "cannot write the %s trace", bad == 3 ? "CSV and JSON" : bad == 1 ? "CSV" : "JSON");
    return -1;
  }
  return 0;
}

void trace_fmt_bytes(unsigned long long bytes, char *buf, size_t len) {
  static const char *const unit[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  double v = (double)bytes;
  int u = 0;
  while (v >= 1000 && u < 6) v /= 1000, u++;
  if (u == 0) snprintf(buf, len, "%llu bytes", bytes);
  else snprintf(buf, len, "%.*f %s", v < 10 ? 1 : 0, v, unit[u]);
}

int trace_over_limit(unsigned long long bytes, unsigned long long limit, char *err, size_t errlen) {
  if (bytes <= limit) return 0;
  static const char *const suffix[] = {"", "k", "M", "G", "T"};
  double unit = 1;
  int u = 0;
  while (u < 4 && (double)bytes >= unit * 1000) unit *= 1000, u++;
  char a[40], b[40];
  trace_fmt_bytes(bytes, a, sizeof a);
  trace_fmt_bytes(limit, b, sizeof b);
  snprintf(err, errlen,
           "the trace would take %s (%llu bytes), more than the limit of %s; "
           "--trace-limit %.0f%s (or none) writes it",
           a, bytes, b, ceil((double)bytes / unit), suffix[u]);
  return -1;
}
