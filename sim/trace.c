/* trace.c -- CSV and Chrome trace-event JSON writers for the simulator's timeline. */
#include "trace.h"

#include <stdlib.h>
#include <string.h>

#include "xmem.h"

struct trace {
  FILE *csv, *json;
  int first;   /* no JSON event written yet (no comma before the next) */
  int netpid;  /* the network's pid: the number of processors */
  int netnamed;   /* its process_name is written */
};

trace *trace_new(FILE *csv, FILE *json) {
  if (!csv && !json) return NULL;
  trace *tr = xcalloc(1, sizeof *tr);
  tr->csv = csv;
  tr->json = json;
  tr->first = 1;
  return tr;
}

void trace_free(trace *tr) { free(tr); }

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
  if (tr->csv) fputs("time,rank,proc,event,peer,tag,bytes,duration,msg,arrival\n", tr->csv);
  tr->netpid = nprocs;
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
  int wait = strcmp(kind, "wait") == 0;
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

void trace_recv(trace *tr, int rank, int proc, double t, double dur, int src, int tag,
                size_t len, uint64_t msg) {
  if (tr->csv)
    fprintf(tr->csv, "%.9f,%d,%d,recv,%d,%d,%zu,%.9f,%llu,\n", t, rank, proc, src, tag, len, dur,
            (unsigned long long)msg);
  if (tr->json) {
    jhead(tr, "X", "recv", "msg", proc, rank, t);
    fprintf(tr->json, ",\"dur\":%.3f,\"args\":{\"src\":%d,\"tag\":%d,\"bytes\":%zu,\"msg\":%llu}}",
            us(dur), src, tag, len, (unsigned long long)msg);
    jhead(tr, "f", "msg", "msg", proc, rank, t);
    fprintf(tr->json, ",\"bp\":\"e\",\"id\":%llu}", (unsigned long long)msg);
  }
}

void trace_finish(trace *tr, int rank, int proc, double t) {
  if (tr->csv) fprintf(tr->csv, "%.9f,%d,%d,finish,,,,,,\n", t, rank, proc);
  if (tr->json) {
    jhead(tr, "i", "finish", "rank", proc, rank, t);
    fputs(",\"s\":\"t\"}", tr->json);
  }
}

void trace_link_track(trace *tr, int link, const char *name) {
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
  if (tr->csv)
    fprintf(tr->csv, "%.9f,%d,%d,link,%d,%d,%zu,%.9f,%llu,\n", start, rank, link, dst, tag, len,
            dur, (unsigned long long)msg);
  if (tr->json) {
    jhead(tr, "X", "msg", "link", tr->netpid, link, start);
    fprintf(tr->json, ",\"dur\":%.3f,\"args\":{\"src\":%d,\"dst\":%d,\"tag\":%d,\"bytes\":%zu,\"msg\":%llu}}",
            us(dur), rank, dst, tag, len, (unsigned long long)msg);
  }
}

int trace_end(trace *tr, char *err, size_t errlen) {
  int bad = 0;
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
