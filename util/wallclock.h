/* wallclock.h -- the host's monotonic clock, for reporting wall time only.
 * Simulated time never reads it. */
#ifndef WALLCLOCK_H
#define WALLCLOCK_H

double wallclock(void);   /* seconds since an arbitrary origin */

#endif
