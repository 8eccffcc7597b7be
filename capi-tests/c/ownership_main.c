/* Standalone driver of the C checks, linked against libfc3d.so by .ci/run and run under
 * valgrind: every create/free path of the C API must run clean. */
#include <stdio.h>

int capi_check_ownership(const char* data_dir, const char* scratch_dir);
int capi_check_bad_input(const char* data_dir);
int capi_check_options(void);
int capi_check_single_contacts(void);
int capi_check_callback(void);
int capi_check_nsgs_options(const char* data_dir);
int capi_check_vi_admm_single_contacts(void);
int capi_check_vi_admm_options(void);
int opt5_check_single_contacts_and_options(void);
int capi_check_newton_and_prox(void);
int capi_check_hostile_matrices(void);
int capi_check_problem_copy(const char* data_dir);
int capi_check_workspace(void);
int capi_check_global(const char* data_dir, const char* scratch_dir);

int main(int argc, char** argv) {
  const char* data = argc > 1 ? argv[1] : "../shared/data/siconos";
  const char* scratch = argc > 2 ? argv[2] : "/tmp";
  int failed = 0;
  failed += capi_check_options() != 0;
  failed += capi_check_single_contacts() != 0;
  failed += capi_check_bad_input(data) != 0;
  failed += capi_check_ownership(data, scratch) != 0;
  failed += capi_check_callback() != 0;
  failed += capi_check_nsgs_options(data) != 0;
  failed += capi_check_vi_admm_single_contacts() != 0;
  failed += capi_check_vi_admm_options() != 0;
  failed += opt5_check_single_contacts_and_options() != 0;
  failed += capi_check_newton_and_prox() != 0;
  failed += capi_check_hostile_matrices() != 0;
  failed += capi_check_problem_copy(data) != 0;
  failed += capi_check_workspace() != 0;
  failed += capi_check_global(data, scratch) != 0;
  printf("%d passed, %d failed\n", 14 - failed, failed);
  return failed != 0;
}
