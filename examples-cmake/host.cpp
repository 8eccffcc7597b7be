// A C++ host of fc3d's native entry: a box on the ground (4 contacts) in block-sparse storage.
#include <fc3d.h>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  const int64_t nc = 4;
  // Four decoupled contacts, W_cc = diag(2, 1, 1), pushed in and sideways.
  std::vector<int64_t> row_ptr = {0, 1, 2, 3, 4}, col_idx = {0, 1, 2, 3};
  std::vector<double> blocks;
  for (int c = 0; c < nc; c++) blocks.insert(blocks.end(), {2, 0, 0, 0, 1, 0, 0, 0, 1});
  std::vector<double> q = {-1, 0.1, 0, -1, 3, 0, -1, 0, -0.2, -1, 0, 5}, mu(nc, 0.5), r(3 * nc, 0), u(3 * nc);
  Fc3dSettings* s = fc3d_settings_new(500);
  fc3d_settings_set_tolerance(s, 1e-12);
  Fc3dResult res;
  int info = fc3d_solve_blocks(nc, nc, row_ptr.data(), col_idx.data(), blocks.data(), q.data(), mu.data(),
                               r.data(), u.data(), s, &res);
  fc3d_settings_free(s);
  std::printf("fc3d %s: info %d, %lld sweeps, error %.2e\n", fc3d_version(), info, (long long)res.iterations,
              res.error);
  // Contact 1 slides: r_T = -mu r_N along u_T; contact 0 sticks.
  bool ok = info == 0 && std::fabs(r[0] - 0.5) < 1e-10 && std::fabs(r[4] + 0.25) < 1e-10 && std::fabs(u[1]) < 1e-10;
  if (!ok) std::fprintf(stderr, "wrong answer: %s\n", fc3d_last_error_message());
  return ok ? 0 : 1;
}
