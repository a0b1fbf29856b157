/* bench_dicom.h -- ./bench --dicom: how fast an RT structure set is read. */
#ifndef BENCH_DICOM_H
#define BENCH_DICOM_H

/* The whole command line (argv[1] is "--dicom"); returns the exit status. */
int bench_dicom(int argc, char **argv);

#endif
