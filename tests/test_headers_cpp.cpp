// test_headers_cpp.cpp: the public headers compile as C++11 (-std=c++11 -pedantic-errors -Wall
// -Wextra -Werror, see tests/CMakeLists.txt) and their extern "C" linkage is right: this program
// is LINKED against the C library and calls functions of every module, so a declaration that is
// not inside AUTOBAL_BEGIN_DECLS/AUTOBAL_END_DECLS would be looked up under its C++-mangled
// name and fail to link.  The answers are checked against closed forms.
#include <autobal.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

int failures = 0;

void check(const char *what, bool ok) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) failures++;
}

// y' = -y, y(0) = 1: y(t) = exp(-t).  The right-hand side is a C++ function with C++ linkage
// whose address is stored in the C struct (what a C++ host does).
int decay(double, const double y[], double dydt[], void *params) {
  const double rate = *static_cast<const double *>(params);
  dydt[0] = -rate * y[0];
  return 0;
}

struct Observer {
  std::vector<double> t, y;
};

int observe(double t, const double y[], void *user) {
  Observer *o = static_cast<Observer *>(user);
  o->t.push_back(t);
  o->y.push_back(y[0]);
  return 0;
}

}  // namespace

int main() {
  autobal_error err;
  autobal_error_clear(&err);

  check("autobal_strerror(AUTOBAL_EINVAL) non-empty", std::strlen(autobal_strerror(AUTOBAL_EINVAL)) > 0);
  check("autobal_version() == AUTOBAL_VERSION_STRING", std::strcmp(autobal_version(), AUTOBAL_VERSION_STRING) == 0);

  // pendulum: the leading coefficient of (6) is 1 - 2 R_m + k R_m^2 (pendulum.h)
  autobal_pendulum_params p;
  double coef[AUTOBAL_PENDULUM_NCOEF];
  int st = autobal_pendulum_params_from_k(3.0, 0.1, 0.1, 0.5, 0.5, &p, &err);
  if (st == AUTOBAL_SUCCESS) st = autobal_pendulum_char_poly(&p, coef, &err);
  check("pendulum: char poly built", st == AUTOBAL_SUCCESS);
  check("pendulum: leading coefficient 1 - 2 R_m + k R_m^2",
        std::fabs(coef[8] - (1.0 - 2.0 * 0.1 + 0.5 * 0.01)) < 1e-15);
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_result res;
  check("pendulum: analysis", ws && autobal_pendulum_analyze(ws, &p, &res) == AUTOBAL_SUCCESS);
  check("pendulum: roots and eigenvalues agree", ws && res.mismatch_rel < 1e-8);
  autobal_pendulum_workspace_free(ws);

  // transient driven from C++
  double rate = 0.5, y = 1.0, t_reached = 0.0;
  autobal_transient_options opt = autobal_transient_options_default();
  opt.dt_out = 1.0;
  autobal_transient *tr = autobal_transient_alloc(1, &opt, &err);
  check("transient: handle", tr != nullptr);
  if (tr) {
    Observer obs;
    autobal_transient_system sys = {decay, nullptr, 1, &rate};
    autobal_transient_set_observer(tr, observe, &obs);
    st = autobal_transient_run(tr, &sys, 0.0, 4.0, &y, &t_reached);
    check("transient: run", st == AUTOBAL_SUCCESS && t_reached == 4.0);
    check("transient: y(4) = exp(-2)", std::fabs(y - std::exp(-2.0)) < 1e-9);
    check("transient: observer at t = 0, 1, 2, 3, 4", obs.t.size() == 5 && obs.t[2] == 2.0);
    check("transient: y(2) = exp(-1)", obs.y.size() == 5 && std::fabs(obs.y[2] - std::exp(-1.0)) < 1e-9);
  }
  autobal_transient_free(tr);

  // rotor: two balls of equal a = m r cancel s0 at psi0 + pi -/+ arccos(s0 / (2 a)) (rotor.h)
  double psi[2];
  st = autobal_rotor_balanced_angles_two(0.002, 0.005, 0.005, 0.0, psi, &err);
  const double half = std::acos(0.002 / 0.01), pi = std::acos(-1.0);
  check("rotor: balanced angles of two balls",
        st == AUTOBAL_SUCCESS && std::fabs(std::fabs(psi[0]) - (pi - half)) < 1e-12 &&
            std::fabs(std::fabs(psi[1]) - (pi - half)) < 1e-12 && psi[0] * psi[1] < 0.0);
  autobal_rotor_params rp = autobal_rotor_params_default();
  autobal_rotor *rot = autobal_rotor_alloc(&rp, &err);
  check("rotor: default handle", rot != nullptr && autobal_rotor_dim(rot) == 12);
  autobal_rotor_free(rot);

  // archive: bad arguments come back as statuses (no HDF5 file is touched)
  autobal_archive *a = nullptr;
  check("archive: empty path rejected", autobal_archive_create("", 0, &a, &err) == AUTOBAL_EINVAL && a == nullptr);

  std::printf("%d failed\n", failures);
  // run-up: Omega 0 -> 200 rad/s over 2 s passes 100 rad/s at t = 1 s (runup.h)
  {
    const double rt[2] = {0.0, 2.0}, rw[2] = {0.0, 200.0}, wc = 100.0;
    autobal_runup_series rs;
    autobal_runup_buffers rb;
    autobal_runup_passage pass[2];
    autobal_runup_result rr;
    std::memset(&rs, 0, sizeof rs);
    std::memset(&rb, 0, sizeof rb);
    rs.n = 2;
    rs.t = rt;
    rs.omega = rw;
    rb.passages = pass;
    rb.passage_cap = 2;
    st = autobal_runup_analyze(&rs, &wc, 1, nullptr, &rb, &rr, &err);
    check("runup: one passage up at t = 1 s",
          st == AUTOBAL_SUCCESS && rr.n_passages == 1 && pass[0].direction == 1 && std::fabs(pass[0].t - 1.0) < 1e-15);
  }
  return failures;
}
