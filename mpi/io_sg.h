/* io_sg.h -- SimGrid's file-system calls that SMPI programs make (simgrid/plugins/file_system.h:
 * sg_file_open, sg_file_close, sg_file_unlink, sg_file_get_name, sg_file_get_size), on the
 * machine's file systems (io_model.h), so that such programs load and run under tilesim-mpirun:
 * MPICH's test suite as SimGrid keeps it removes its files with them.
 *
 * A handle names a file by its path; opening does not make the file.  The handle is a plain
 * pointer (SimGrid's sg_file_t is one), freed by sg_file_close or sg_file_unlink.  The calls
 * cost no simulated time but sg_file_unlink's, a request of the file system as MPI_File_delete's. */
#ifndef TSMPI_IO_SG_H
#define TSMPI_IO_SG_H

typedef struct io_sg_file io_sg_file;

io_sg_file *sg_file_open(const char *fullpath, void *data);
void sg_file_close(io_sg_file *fd);
void sg_file_unlink(io_sg_file *fd);
const char *sg_file_get_name(const io_sg_file *fd);
unsigned long long sg_file_get_size(const io_sg_file *fd);

#endif
