/* help.h: configuration keys of each command, shown by `autobal CMD --help`. */
#ifndef AUTOBAL_APPS_HELP_H
#define AUTOBAL_APPS_HELP_H

#define HELP_PENDULUM_PARAMS                                                                      \
  "[pendulum] the two-pendulum autobalancer (spec pendulum.md), dimensionless form (2)-(3):\n"    \
  "  R_w   = 3.0    rotor speed omega/omega0, >= 0\n"                                             \
  "  R_m   = 0.1    mass ratio m/(M + 2m), in (0, 0.5)\n"                                         \
  "  H     = 0.1    external damping H2/(omega0 (M + 2m)), >= 0\n"                                \
  "  h     = 0.5    pendulum damping H1/(m l^2 omega0), >= 0\n"                                   \
  "  k     = 0.5    unbalance parameter sin^2(2 psi0), in [0, 1]   (or psi0 in rad, [0, pi/2))\n" \
  "or the physical form (SI; all eight keys, converted by (2)-(3); not mixed with the above):\n"   \
  "  M [kg]  e [m]  m [kg]  l [m]  c [N/m]  H1 [N m s]  H2 [N s/m]  omega [rad/s]\n"              \
  "  (requires M e < 2 m l)\n"

#define HELP_PENDULUM_ROOTS                                                                   \
  "Roots of the characteristic polynomial (6) (GSL complex polynomial solver), eigenvalues\n" \
  "of the 8x8 first-order matrix of (5) (GSL), their agreement, the Routh-Hurwitz verdict,\n" \
  "the stability margin (largest real part) and the sufficient conditions (7)-(9).\n\n"       \
  HELP_PENDULUM_PARAMS                                                                        \
  "\narchive: /pendulum (parameters as attributes), /pendulum/roots\n"

#define HELP_PENDULUM_CRITICAL                                                                  \
  "Critical speeds of the undamped balancer (H = h = 0) at the given R_m and k, located\n"      \
  "exactly from the discriminant of (10); the paper's closed forms and series (13)-(18) with\n" \
  "their errors; R_m^(1); critical-speed curves R_wj(R_m) for k = 0 and k = 1 (figure 2,\n"     \
  "regions A and B); and, when H or h > 0, the critical speeds of the damped system (6).\n\n"   \
  HELP_PENDULUM_PARAMS                                                                          \
  "\n[critical]\n"                                                                              \
  "  Rm_min = 0.001   Rm_max = 0.499   n_Rm = 499   R_m grid of the curves\n"                   \
  "  Rw_min = 0       Rw_max = 6       n_sweep = 3000   sweep of the damped search\n"           \
  "\narchive: /pendulum/critical, /pendulum/critical/curves\n"

#define HELP_PENDULUM_MAP                                                                      \
  "Stability map of the main motion (4) over an (R_m, R_w) grid: for one k, or for every\n"    \
  "unbalance (stable for all k of a set in [0, 1]).  Damped: Routh-Hurwitz sign test on (6);\n" \
  "undamped (H = h = 0): all roots of (10) real and <= 0.  OpenMP-parallel.\n\n"               \
  HELP_PENDULUM_PARAMS                                                                         \
  "\n[map]\n"                                                                                  \
  "  Rm_min = 0.005  Rm_max = 0.495  n_Rm = 200     R_m axis\n"                                \
  "  Rw_min = 0.05   Rw_max = 5      n_Rw = 200     R_w axis\n"                                \
  "  every_unbalance = false   true: stable for all k in {j/(n_k-1)}, j = 0..n_k-1\n"          \
  "  n_k = 65                  size of that k set (>= 2)\n"                                    \
  "  max_real = false          also store the largest real part of the roots (slower)\n"       \
  "  threads = 0               OpenMP threads (0: default)\n"                                  \
  "\narchive: /pendulum/map (verdict[R_m][R_w]: 1 stable, 0 marginal, -1 unstable)\n"

#define HELP_PENDULUM_TRANSIENT                                                                     \
  "Transient of the two-pendulum autobalancer: the nonlinear equations (1) in dimensionless time\n" \
  "tau = omega0 t, integrated with a GSL stepper and streamed to HDF5; derived quantities: shaft\n"  \
  "amplitude, residual unbalance of rotor plus pendulums (units of 2 m l), pendulum angles relative\n" \
  "to the balancing position, Jacobi integral; time to balance.\n\n" HELP_PENDULUM_PARAMS            \
  "\n[initial]   xi eta (units of l)  psi phi (rad)  xi_rate eta_rate psi_rate phi_rate   (all 0)\n" \
  "[transient] t_end = 300 (tau)   revs_out = 0.25 (or dt_out, tau)   stepper = rk8pd\n"           \
  "            rtol = 1e-10   atol = 1e-12   h_max = 0   max_steps = 1e8\n"                         \
  "            balance_tol = 1e-3 (units of 2 m l)   balance_revs = 20   stop_at_balance = false\n"   \
  "\narchive: /pendulum (parameters), /pendulum/transient (series over 'tau'), /pendulum/transient/solver\n"

#define HELP_ROTOR_PARAMS                                                                          \
  "[rotor]     M_k = 6  A_k = 0.12  m_p = 4  A_p = 0.04  C_p = 0.03   (kg, kg m^2)\n"                 \
  "            omega = 500 (rad/s)   inertia = paper|full   axial = false\n"                           \
  "[supports]  l_L = 0.20  l_R = 0.15 (m)   c_Lx c_Ly c_Lz c_Rx c_Ry (N/m)   h_Lx h_Ly h_Lz h_Rx h_Ry (N s/m)\n" \
  "            defaults: c_Lx = c_Ly = 1e5, c_Rx = c_Ry = 1.5e5, c_Lz = 2e5, h_L. = 100, h_R. = 150, h_Lz = 200\n" \
  "[lumped]    optional, replaces [supports]: M A C c_x c_y c_z c_alpha c_beta c_xbeta c_yalpha and h_ (all)\n" \
  "[initial]   x y (m)  alpha beta (rad)  x_rate y_rate (m/s)  alpha_rate beta_rate (rad/s)  z z_rate\n"      \
  "[plane1]    d = 0.10 (m)  m0 = 0.02 (kg)  r0 = 0.1 (m)  psi0 = 0 (rad, unbalance angle on the rotor)\n"   \
  "            ball_mass = 0.05, 0.05 (kg)  ball_radius = 0.1, 0.1 (m)  ball_damping = 0.1, 0.1 (kg/s)\n"    \
  "            ball_psi = 1.0, 2.5 (rad, initial angles relative to the rotor)  ball_rate = 0, 0 (rad/s)\n"   \
  "[plane2]    optional second balancer plane, same keys as [plane1]\n"

#define HELP_ROTOR_TRANSIENT                                                                       \
  "Transient of the rotor in a massive housing with ball autobalancers (spec rotor.md): the\n"     \
  "fixed-frame equations (3.2)+(3.4) (or the balls in the rotating frame, (3.13)), integrated\n"   \
  "with a GSL stepper, streamed to HDF5; summary: balanced or not, time to balance, residual\n"    \
  "unbalance and vibration before/after.\n\n" HELP_ROTOR_PARAMS                                    \
  "[transient] t_end = 20 (s)   revs_out = 0.25 (output every quarter revolution) or dt_out (s)\n" \
  "            stepper = rk8pd   rtol = 1e-10   atol = 1e-9   h_max = 0 (s, 0: none)   max_steps = 1e8\n" \
  "            frame = fixed|rotating   balance_tol = 0.01 (|s|/(m0 r0))   balance_revs = 50 (or balance_dwell, s)\n"    \
  "            stop_at_balance = false\n"                                                          \
  "\narchive: /rotor (parameters), /rotor/transient (time series over 'time'), /rotor/revolutions\n"

#define HELP_INFO                                                                                   \
  "A readable summary of any autobal archive: the command that wrote it, its status, provenance\n"   \
  "and configuration; the headline results (verdicts, critical speeds, stable intervals, time to\n" \
  "balance, residual unbalance); then every group with its attributes (parameters with units,\n"   \
  "solver settings and statistics) and datasets (dimensions, shape, type, units, long_name).\n"    \
  "--json prints the same as one JSON object (keys: file, root, command, status, headline[],\n"    \
  "groups[] with attributes {name: {value, units}} and datasets[] {name, path, shape, dims,\n"     \
  "dtype, coordinate, units, long_name, values (up to 64 elements)}).\n"                          \
  "Exit 4 (with the reason) when FILE.h5 is missing, not HDF5, truncated or not an autobal archive.\n"

#define HELP_RERUN                                                                                   \
  "Run again the command recorded in FILE.h5 (root attribute `command`) with the configuration\n"   \
  "recorded there (`effective_config`: every key the command read with the value it used, defaults\n" \
  "included; `input_config` for archives of older versions) and write NEW.h5.  With the same\n"     \
  "version of autobal every dataset is reproduced bit for bit (provenance such as `created` and\n"  \
  "wall times differ).\n"                                                                          \
  "Options: -o NEW.h5 (required, not FILE.h5 itself), --force, --json, --quiet.  --set is refused.\n"

#define HELP_PLOT                                                                                     \
  "Draw PNG pictures of an archive with matplotlib: runs `/usr/bin/python3 autobal_plot.py FILE.h5\n" \
  "-o DIR` (tools/ in the source tree, share/autobal/tools when installed; override with\n"          \
  "AUTOBAL_TOOLS_DIR and AUTOBAL_PYTHON).  The script reads only the archive and writes\n"             \
  "DIR/<stem>_<kind>.png (stem = FILE without .h5) for each group it knows: critical-speed curves\n" \
  "with regions A and B (figure 2), stability maps, roots, transients (displacement, residual\n"     \
  "unbalance on a log scale, ball/pendulum angles, time to balance).  -o DIR defaults to the current\n" \
  "directory; the names of the files written are printed.\n"

#define HELP_ROTOR_STAB_OPTS \
  "[stability] method = auto|poly|closed|full|floquet   tol = 1e-9   floquet_rtol = 1e-11   floquet_atol = 1e-13\n" \
  "            member1 = default|symmetric|free|given   member1_angles = (rad: balls 1..n-2 for free, all for given)\n" \
  "            member2, member2_angles (plane 2)\n"
#define HELP_ROTOR_STABILITY \
  "Stability of the balanced motion (3.14): the degree-12 polynomial Delta (GSL roots, Routh-Hurwitz), the closed\n" \
  "12x12 (16x16) matrix, the full model in rotating coordinates, Floquet multipliers (any supports); critical\n" \
  "speeds and the stable speed intervals.\n\n" HELP_ROTOR_PARAMS HELP_ROTOR_STAB_OPTS \
  "            critical_speeds = true  omega_min, omega_max (rad/s; default 5% of the 1st natural frequency .. 4x)\n" \
  "            n_omega = 400  xtol_rel = 1e-8\n" \
  "\narchive: /rotor (model), /rotor/stability (roots, eigenvalues, Floquet multipliers), /rotor/stability/critical\n"
#define HELP_ROTOR_SWEEP \
  "Stability margin along one parameter; every verdict change refined to xtol_rel; stable intervals.\n\n" \
  HELP_ROTOR_PARAMS HELP_ROTOR_STAB_OPTS \
  "[sweep] param = omega|ball_damping|ball_mass|stiffness_scale|damping_scale|unbalance_mass  min  max  n = 1000\n" \
  "        xtol_rel = 1e-8\n" \
  "\narchive: /rotor/sweep (margin and verdict over the parameter, critical_value, stable_lo/hi)\n"
#define HELP_ROTOR_MAP \
  "Two-parameter stability map, OpenMP-parallel (results independent of the thread count).\n\n" \
  HELP_ROTOR_PARAMS HELP_ROTOR_STAB_OPTS \
  "[map] param1 = omega  min1 max1 n1 = 120   param2 = ball_damping  min2 max2 n2 = 60   threads = 0\n" \
  "\narchive: /rotor/map (margin[param1][param2], verdict: 1 stable, 0 marginal, -1 unstable, -2 no balance)\n"
#define HELP_ROTOR_CAMPBELL \
  "Rotor-housing without balls: natural frequencies at rest (undamped, damped), Campbell diagram (C omega\n" \
  "gyroscopic), steady unbalance response, critical speeds (frequency = omega) and response peaks.\n\n" \
  HELP_ROTOR_PARAMS \
  "[campbell] omega_min = 0  omega_max  n = 401  n_resonance = 4000  xtol_rel = 1e-10\n" \
  "\narchive: /rotor/campbell\n"

#define HELP_ENSEMBLE_KEYS \
  "[ensemble] mode = grid|random\n" \
  "           param1 = NAME  min1 max1  n1 = 16   (grid axis; angles default to [-pi, pi])\n" \
  "           param2, min2, max2, n2   param3, min3, max3, n3   (optional; none to drop an axis)\n" \
  "           endpoint = (false when every parameter is an angle: n points over [min, max); else true)\n" \
  "           samples = 256  seed = 1   (random: member m, parameter j <- splitmix64 output m*nparam + j)\n" \
  "           series = (member numbers whose full time series is kept, e.g. 0, 17)\n" \
  "           threads = 0 (OpenMP threads per process; 0: OMP_NUM_THREADS or all cores)\n" \
  "           resume = false   (true: skip the members recorded in the journals FILE.h5.journal-*)\n" \
  "           max_members = 0  time_limit = 0 (s)   (stop after that many members / that wall time;\n" \
  "                                                  the archive is then incomplete: resume later)\n" \
  "Members run in parallel (OpenMP; with the AUTOBAL_MPI build also `mpirun -np N autobal ...`, members\n" \
  "dealt out cyclically over the ranks, rank 0 writes the archive).  The archive does not depend on the\n" \
  "number of threads or ranks.  A failed member is recorded (status < 0) and the others go on (exit 0).\n"
#define HELP_ROTOR_ENSEMBLE \
  "Many transients of the rotor (as `rotor transient`) over a grid or random samples of initial\n" \
  "conditions or parameters: per member balanced or not, time to balance, residual unbalance, amplitude,\n" \
  "final ball angles, solver status; the basin-of-attraction map and the probability of balancing.\n\n" \
  HELP_ROTOR_PARAMS \
  "[transient] as `rotor transient` (t_end = 20, rtol = 1e-10, atol = 1e-9, ...), but stop_at_balance = true by default\n" \
  HELP_ENSEMBLE_KEYS \
  "parameters: psi_K, rate_K (initial angle/rate of ball K relative to the rotor; K = 1..N, plane 1 first),\n" \
  "            omega, ball_damping (every ball), m0 (plane 1), x, y (initial displacement)\n" \
  "default: grid psi_1 x psi_2, 16 x 16 over [-pi, pi)\n" \
  "\narchive: /rotor (model), /rotor/ensemble (variables over the parameter axes, or over 'member' when\n" \
  "random; probability_balanced etc. as attributes), /rotor/ensemble/series/member_M, .../execution\n"
#define HELP_PENDULUM_ENSEMBLE \
  "Many transients of the two-pendulum autobalancer (as `pendulum transient`) over a grid or random\n" \
  "samples of initial conditions or parameters: per member balanced or not, time to balance, residual\n" \
  "unbalance, amplitude, final pendulum angles, solver status; basin map and probability of balancing.\n\n" \
  HELP_PENDULUM_PARAMS \
  "[initial]   xi eta psi phi xi_rate eta_rate psi_rate phi_rate   (all 0)\n" \
  "[transient] as `pendulum transient` (t_end = 300, ...), but stop_at_balance = true by default\n" \
  HELP_ENSEMBLE_KEYS \
  "parameters: xi, eta, psi, phi, xi_rate, eta_rate, psi_rate, phi_rate (initial state), R_w, R_m, H, h,\n" \
  "            psi0 or k\n" \
  "default: grid psi x phi, 16 x 16 over [-pi, pi)\n" \
  "\narchive: /pendulum (parameters), /pendulum/ensemble (as for the rotor)\n"

#endif
