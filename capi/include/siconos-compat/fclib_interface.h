/* fc3d compatibility header: stands in for Siconos Numerics 4.4's fclib_interface.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d.

   fc3d implements the two local-problem calls of Siconos' header (declared below and in fc3d.h):

     FrictionContactProblem* frictionContact_fclib_read(const char *path);
     int frictionContact_fclib_write(FrictionContactProblem* problem, char *title,
                                     char *description, char *mathInfo,
                                     const char *path, int ndof);

   and frictionContact_new_from_filename reads FCLIB .hdf5 files too. Unlike Siconos' header,
   these declarations do not depend on WITH_FCLIB: libfc3d always exports the two functions. When
   libfc3d was built without FCLIB support (cargo feature `fclib` of the fc3d crate, which needs
   libhdf5), frictionContact_fclib_read returns NULL and frictionContact_fclib_write returns 0
   with fc3d_last_error_code() = FC3D_ERR_IO, and fc3d_last_error_message() says so; nothing is
   written.

   Differences from Siconos 4.4:
   - frictionContact_fclib_write returns 1 on success and 0 on failure, as Siconos does, but never
     exits the process: the FC3D_ERR_* code of a failure is in fc3d_last_error_code(); the file is
     created or replaced, never left half-written.
   - A problem written by fc3d reads back bit for bit with W in the same storage (dense,
     sparse-block or sparse: the W group carries the attribute fc3d_storage, which other FCLIB
     readers ignore). Files from Siconos or FCLIB are read in sparse-block storage, as Siconos
     does; a file holding only a global problem is reduced to W = H^T M^-1 H, q = H^T M^-1 f + w.
   - title, description and mathInfo may be NULL (not written); ndof is written as the info
     attribute numberOfDegreeOfFreedom, as Siconos does.

   The global calls (declared in fc3d.h, with the same build-dependent behaviour):

     GlobalFrictionContactProblem* globalFrictionContact_fclib_read(const char *path);
     int globalFrictionContact_fclib_write(GlobalFrictionContactProblem* problem, char *title,
                                           char *description, char *mathInfo, const char *path);
     int globalRollingFrictionContact_fclib_write(GlobalRollingFrictionContactProblem* problem,
                                                  char *title, char *description,
                                                  char *mathInfo, const char *path);

   M and H of any storage are written as triplets (Siconos exits unless they are sparse with a
   triplet form); a global rolling problem is written as FCLIB's /fclib_global_rolling.

   Not implemented (they take FCLIB's own structs, which fc3d does not use): from_fclib_local,
   from_fclib_global, and frictionContact_fclib_write_guess. */
#ifndef FC3D_COMPAT_FCLIB_INTERFACE_H
#define FC3D_COMPAT_FCLIB_INTERFACE_H
#include <fc3d.h>
#include "NumericsFwd.h"

#if defined(__cplusplus)
extern "C" {
#endif

FrictionContactProblem *frictionContact_fclib_read(const char *path);

int frictionContact_fclib_write(FrictionContactProblem *problem,
                                char *title, char *description,
                                char *mathInfo,
                                const char *path, int ndof);

#if defined(__cplusplus)
}
#endif

#endif
