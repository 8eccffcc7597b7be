/* Runs one case of a Siconos test collection in its own process (scripts/siconos-suite.sh).
   Linked with a collection's unmodified data_collection_*.c and test_*.c, Siconos' test
   utilities and either libsiconos_numerics or libfc3d.
     case_runner --list   one line per case: index, solver id, solver name, data file, and the
                          case's will_fail mark
     case_runner INDEX    runs that case with frictionContact_test_function (with
                          rollingFrictionContact_test_function when built with
                          -DCASE_RUNNER_ROLLING, the rolling collections, and with
                          globalFrictionContact_test_function when built with
                          -DCASE_RUNNER_GLOBAL, the global ones); exit 0 when it passes
   A collection whose driver (gfc3d_test_collection.c.in) sets will_fail marks after building the
   collection is built with -DCASE_RUNNER_MARKS="<file>": that file holds the driver's own lines
   setting them, extracted unmodified by scripts/siconos-suite.sh. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "SolverOptions.h"
#include "frictionContact_test_utils.h"
#include "test_utils.h"

int main(int argc, char **argv)
{
  const char **data = data_collection();
  int n_data = 0;
  while (strcmp(data[n_data], "---") != 0)
    n_data++;
  int n_tests = 0;
  TestCase *collection = build_test_collection(n_data, data, &n_tests);
#ifdef CASE_RUNNER_MARKS
#include CASE_RUNNER_MARKS
#endif
  int status = 0;
  if (argc == 2 && strcmp(argv[1], "--list") == 0) {
    for (int i = 0; i < n_tests; i++)
      printf("%d\t%d\t%s\t%s\t%d\n", i, collection[i].options->solverId,
             solver_options_id_to_name(collection[i].options->solverId), collection[i].filename,
             collection[i].will_fail);
  } else if (argc == 2) {
    char *end = NULL;
    long index = strtol(argv[1], &end, 10);
    if (*end != '\0' || index < 0 || index >= n_tests) {
      fprintf(stderr, "case_runner: no case %s (0..%d)\n", argv[1], n_tests - 1);
      status = 2;
    } else {
#if defined(CASE_RUNNER_ROLLING)
      int info = rollingFrictionContact_test_function(&collection[index]);
#elif defined(CASE_RUNNER_GLOBAL)
      int info = globalFrictionContact_test_function(&collection[index]);
#else
      int info = frictionContact_test_function(&collection[index]);
#endif
      printf("CASE %ld info %d residual %g iterations %d\n", index, info,
             collection[index].options->dparam[SICONOS_DPARAM_RESIDU],
             collection[index].options->iparam[SICONOS_IPARAM_ITER_DONE]);
      status = info == 0 ? 0 : 1;
    }
  } else {
    fprintf(stderr, "usage: %s --list | INDEX\n", argv[0]);
    status = 2;
  }
  free_test_collection(collection, n_tests);
  free(data);
  return status;
}
