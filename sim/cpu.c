/* cpu.c -- the processor side of messages and computing (cpu.h). */
#include "sim/cpu.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void cpu_model_init(cpu_model *m) {
  memset(m, 0, sizeof *m);
  m->spin = 1e-3;
}

int cpu_model_on(const cpu_model *m) {
  return m->o_send > 0 || m->o_send_byte > 0 || m->o_recv > 0 || m->o_recv_byte > 0 || m->wake > 0 ||
         m->o_wake > 0 || m->slowdown > 0 || m->slowdown_spin > 0;
}

static const struct {
  const char *opt, *name;
  size_t off;
} fields[] = {
    {"--o-send", "o_send", offsetof(cpu_model, o_send)},
    {"--o-send-byte", "o_send_byte", offsetof(cpu_model, o_send_byte)},
    {"--o-recv", "o_recv", offsetof(cpu_model, o_recv)},
    {"--o-recv-byte", "o_recv_byte", offsetof(cpu_model, o_recv_byte)},
    {"--spin", "spin", offsetof(cpu_model, spin)},
    {"--wake", "wake", offsetof(cpu_model, wake)},
    {"--o-wake", "o_wake", offsetof(cpu_model, o_wake)},
    {"--slowdown", "slowdown", offsetof(cpu_model, slowdown)},
    {"--slowdown-spin", "slowdown_spin", offsetof(cpu_model, slowdown_spin)},
};

int cpu_model_check(const cpu_model *m, char *err, size_t errlen) {
  for (size_t i = 0; i < sizeof fields / sizeof *fields; i++) {
    double v = *(const double *)((const char *)m + fields[i].off);
    if (!(v >= 0) || isinf(v)) {
      snprintf(err, errlen, "sim: cost %s = %g: must be finite and >= 0", fields[i].name, v);
      return -1;
    }
  }
  return 0;
}

double *cpu_model_field(cpu_model *m, const char *opt) {
  for (size_t i = 0; i < sizeof fields / sizeof *fields; i++)
    if (strcmp(opt, fields[i].opt) == 0) return (double *)((char *)m + fields[i].off);
  return NULL;
}
