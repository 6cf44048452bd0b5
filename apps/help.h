/* help.h: the help texts: `autobal --help` (HELP_USAGE_*), `autobal MODEL --help` (HELP_MODEL_*)
 * and the configuration keys of each command, shown by `autobal CMD --help`.
 * Equation numbers refer to the model documentation in the repository: docs/pendulum.md for the
 * pendulum commands, docs/rotor.md for the rotor commands; units are described in docs/units.md.
 * Every text names the document it refers to, and none points outside the repository. */
#ifndef AUTOBAL_APPS_HELP_H
#define AUTOBAL_APPS_HELP_H

/* ---- autobal --help ------------------------------------------------------------------------- */
#define HELP_USAGE_HEAD                                                                          \
  "usage: autobal <model> <action> [CONFIG.ini] [options]\n"                                     \
  "       autobal info|rerun|plot FILE.h5 [options]\n"                                           \
  "       autobal help [<model> [<action>] | info|rerun|plot]\n"                                 \
  "       autobal --help | --version\n"                                                          \
  "\n"                                                                                           \
  "Dynamics of rotors with passive automatic balancers.  Every command runs on built-in\n"       \
  "defaults when no CONFIG is given; keys in CONFIG (INI) or --set override them.\n"             \
  "\n"                                                                                           \
  "commands:\n"
#define HELP_USAGE_TAIL                                                                                    \
  "\n"                                                                                                     \
  "options:\n"                                                                                             \
  "  -o, --output FILE.h5    write an HDF5 archive (written to a temporary name, renamed when done)\n"     \
  "  -f, --force             overwrite FILE.h5 if it exists\n"                                             \
  "  -s, --set SEC.KEY=VAL   override a configuration value (SECTION.KEY=VALUE; repeatable)\n"                       \
  "      --json              machine-readable summary on stdout (instead of the text summary)\n"           \
  "  -q, --quiet             no text summary\n"                                                            \
  "      --no-progress       no progress bar (none is drawn unless stderr is a terminal)\n"                \
  "  -h, --help              help; with a model: its actions; with a command: its configuration keys\n"    \
  "      --version           versions of autobal, GSL and HDF5\n"                                          \
  "\n"                                                                                                     \
  "exit codes:\n"                                                                                          \
  "  0 success   2 bad command line   3 bad configuration or parameter   4 file error\n"                   \
  "  5 numerical failure (partial results written)   6 interrupted (partial results written)\n"            \
  "  7 internal error\n"                                                                                   \
  "\n"                                                                                                     \
  "documentation (in the autobal source tree): docs/rotor.md (the rotor model and its equations),\n"       \
  "docs/pendulum.md (the two-pendulum model and its equations), docs/units.md (units), docs/guide.md (every\n" \
  "command with an example), docs/archive.md (the archive layout), docs/device.md (run-up, motor, gravity,\n" \
  "friction, contact), docs/embedding.md (the library in a C program)\n"

/* the "see also" line of every command */
#define HELP_DOCS_PENDULUM \
  "\ndocumentation: docs/pendulum.md (the model, its equations), docs/units.md (units), docs/guide.md (examples)\n"
#define HELP_DOCS_ROTOR \
  "\ndocumentation: docs/rotor.md (the model, its equations), docs/units.md (units), docs/guide.md (examples)\n"
#define HELP_DOCS_ARCHIVE                                                                          \
  "\ndocumentation: docs/archive.md (the archive layout), docs/rotor.md and docs/pendulum.md (what the\n" \
  "archives hold), docs/units.md (units)\n"

/* ---- autobal MODEL --help: the model in a few lines (then its actions and HELP_DOCS_*) -------- */
#define HELP_MODEL_PENDULUM                                                                         \
  "The planar two-pendulum autobalancer on a rigid rotor (mass M, eccentricity e) with an elastic\n" \
  "shaft: stability of the main (balanced) motion, critical speeds, stability maps, transients.\n"    \
  "Parameters in dimensionless form (R_w, R_m, H, h, k or psi0) or physical (SI) form.\n"
#define HELP_MODEL_ROTOR                                                                            \
  "A rigid rotor on elastic supports in a massive housing with one or two ball autobalancers:\n"    \
  "transients, stability of the balanced motion, sweeps, maps, Campbell diagram, ensembles.\n"      \
  "Parameters in SI units or with a unit (rpm, g mm, ...: docs/units.md), or a lumped coefficient set.\n"

/* ---- the pendulum commands ---------------------------------------------------------------------- */
#define HELP_PENDULUM_PARAMS                                                                         \
  "[pendulum] the two-pendulum autobalancer in dimensionless form, eqs. (2)-(3) in docs/pendulum.md:\n" \
  "  R_w   = 3.0    rotor speed omega/omega0, >= 0\n"                                                \
  "  R_m   = 0.1    mass ratio m/(M + 2m), in (0, 0.5)\n"                                            \
  "  H     = 0.1    external damping H2/(omega0 (M + 2m)), >= 0\n"                                   \
  "  h     = 0.5    pendulum damping H1/(m l^2 omega0), >= 0\n"                                      \
  "  k     = 0.5    unbalance parameter sin^2(2 psi0), in [0, 1]   (or psi0 in rad, [0, pi/2))\n"    \
  "or the physical form (SI; all eight keys, converted by eqs. (2)-(3) in docs/pendulum.md; not\n"   \
  "mixed with the above):\n"                                                                         \
  "  M [kg]  e [m]  m [kg]  l [m]  c [N/m]  H1 [N m s]  H2 [N s/m]  omega [rad/s]\n"                 \
  "  (requires M e < 2 m l)\n"

#define HELP_PENDULUM_ROOTS                                                                              \
  "Roots of the characteristic polynomial, eq. (6) in docs/pendulum.md (GSL complex polynomial\n"       \
  "solver), eigenvalues of the 8x8 first-order matrix of the linearization, eq. (5) in\n"               \
  "docs/pendulum.md (GSL), their agreement, the Routh-Hurwitz verdict (without damping, H = h = 0:\n"   \
  "the exact criterion of eq. (10) in docs/pendulum.md, roots on the imaginary axis and semisimple),\n" \
  "the stability margin (largest real part) and the sufficient conditions, eqs. (7)-(9) in\n"          \
  "docs/pendulum.md.\n\n"                                                                              \
  HELP_PENDULUM_PARAMS                                                                                   \
  "\narchive: /pendulum (parameters as attributes), /pendulum/roots\n" HELP_DOCS_PENDULUM

#define HELP_PENDULUM_CRITICAL                                                                          \
  "Critical speeds of the undamped balancer (H = h = 0) at the given R_m and k, located exactly from\n" \
  "the discriminant of eq. (10) in docs/pendulum.md; the closed forms and series, eqs. (13)-(18) in\n"  \
  "docs/pendulum.md, with their errors; R_m^(1); critical-speed curves R_wj(R_m) for k = 0 and k = 1\n" \
  "(regions A and B: docs/pendulum.md); and, when H or h > 0, the critical speeds of the damped\n"      \
  "system, eq. (6) in docs/pendulum.md.\n\n"                                                            \
  HELP_PENDULUM_PARAMS                                                                                  \
  "\n[critical]\n"                                                                                      \
  "  Rm_min = 0.001   Rm_max = 0.499   n_Rm = 499   R_m grid of the curves\n"                           \
  "  Rw_min = 0       Rw_max = 6       n_sweep = 3000   sweep of the damped search\n"                   \
  "\narchive: /pendulum/critical, /pendulum/critical/curves\n" HELP_DOCS_PENDULUM

#define HELP_PENDULUM_MAP                                                                                \
  "Stability map of the main motion, eq. (4) in docs/pendulum.md, over a grid of any two of the\n"      \
  "parameters R_w, R_m, H, h, k, psi0 and the ratio H/h (default (R_m, R_w)): for one k, or for every\n"  \
  "unbalance (stable for all k of a set in [0, 1]).  Damped: Routh-Hurwitz sign test on eq. (6) in\n"   \
  "docs/pendulum.md; undamped (H = h = 0): the exact criterion of eq. (10) in docs/pendulum.md as\n"   \
  "'pendulum roots' uses it (roots on the imaginary axis and semisimple), or with convention = paper\n" \
  "the first approximation (all roots x real and <= 0).  An undamped map carries the note on the\n"    \
  "small-damping limit (docs/pendulum.md).  OpenMP-parallel.\n\n"                                       \
  HELP_PENDULUM_PARAMS                                                                                   \
  "\n[map]\n"                                                                                            \
  "  param1 = R_m   param2 = R_w   the axes (rows, columns): R_w R_m H h k psi0 H/h, or with a\n"        \
  "      physical [pendulum] its keys M e m l c H1 H2 omega (ranges in their units, e.g. 500 rpm,\n"     \
  "      80 g; each point converted by eqs. (2)-(3) in docs/pendulum.md; not with a dimensionless\n"  \
  "      parameter it determines)\n"                                                                   \
  "  min1 max1 n1 log1, min2 max2 n2 log2   their ranges, points (<= 1e5), scale auto|log|linear\n"      \
  "      (defaults: R_w 0.05..5, R_m 0.005..0.495, H and h 1e-4..1 log, k 0..1, psi0 0..pi/4,\n"       \
  "       H/h 0.01..100 log; omega 0.05..5 omega0, e 0..(e at psi0 = pi/4), H1, H2 those of h, H,\n" \
  "       M m l c a quarter to four times their value, log; all inside the model's domain; 200 points)\n" \
  "  Rm_min = 0.005  Rm_max = 0.495  n_Rm = 200     the range of an R_m axis 1 (min1 ... take precedence)\n" \
  "  Rw_min = 0.05   Rw_max = 5      n_Rw = 200     the same for an R_w axis 2 (former keys)\n"          \
  "      H/h axis: H = (H/h) h with h held at pendulum.h (or h from the other axis);\n"              \
  "      with H on the other axis, h = H / (H/h)\n"                                                    \
  "  every_unbalance = false   true: stable for all k in {j/(n_k-1)}, j = 0..n_k-1 (not with a k axis)\n" \
  "  n_k = 65                  size of that k set (>= 2)\n"                                              \
  "  convention = exact        undamped verdict: exact (as pendulum roots) | paper\n"                   \
  "  max_real = false          also store the largest real part of the roots (slower)\n"                 \
  "  threads = 0               OpenMP threads (0: default)\n"                                            \
  "\narchive: /pendulum/map (verdict[axis1][axis2]: 1 stable, 0 marginal, -1 unstable; coordinates\n"    \
  "named after the parameters, H/h as H_over_h; attributes axis1, axis2, axis*_scale, note)\n"           \
  HELP_DOCS_PENDULUM

#define HELP_PENDULUM_SWEEP                                                                              \
  "Stability of the main motion, eq. (4) in docs/pendulum.md, along one parameter (R_w, R_m, H, h, k,\n" \
  "psi0, H/h, or a physical key such as omega in rpm), for one k or every unbalance, and its critical\n" \
  "values: every change of the verdict between neighbouring grid points, refined by bisection on the\n" \
  "verdict.  Verdicts as in 'pendulum map'.  A window narrower than the grid step can be missed\n"     \
  "(for the undamped system over R_w at one k, 'pendulum critical' is exact).\n\n"                     \
  HELP_PENDULUM_PARAMS                                                                                   \
  "\n[sweep]\n"                                                                                          \
  "  param = R_w         the swept parameter (or a physical key M e m l c H1 H2 omega, as in 'map')\n"  \
  "  min max            its range (defaults as in 'pendulum map')   n = 1000   log = auto|log|linear\n"  \
  "  every_unbalance = false   n_k = 65   xtol_rel = 1e-10   convention = exact|paper\n"                 \
  "\narchive: /pendulum/sweep (verdict over the parameter's coordinate; critical, critical_below,\n"     \
  "critical_above)\n" HELP_DOCS_PENDULUM

#define HELP_PENDULUM_TRANSIENT                                                                          \
  "Transient of the two-pendulum autobalancer: the nonlinear equations of motion, eq. (1) in\n"         \
  "docs/pendulum.md, in dimensionless time tau = omega0 t, integrated with a GSL stepper and streamed\n" \
  "to HDF5; derived quantities: shaft amplitude, residual unbalance of rotor plus pendulums (units of\n" \
  "2 m l), pendulum angles relative to the balancing position, Jacobi integral; time to balance.\n\n"    \
  HELP_PENDULUM_PARAMS                                                                                   \
  "\n[initial]   xi eta (units of l)  psi phi (rad)  xi_rate eta_rate psi_rate phi_rate   (all 0)\n"     \
  "[transient] t_end = 300 (tau)   revs_out = 0.25 (or dt_out, tau)   stepper = dop853\n"                \
  "            rtol = 1e-10   atol = 1e-12   h_max = 0   max_steps = 1e8\n"                               \
  "            output = dense6|dense|exact (stepper dop853: output and events on its continuous\n"        \
  "            extension, order 6 with no extra rhs | order 7 with 3 more rhs per step, or steps cut at\n" \
  "            the output times; the other steppers always cut; until 0.2.0: stepper = rk8pd)\n"           \
  "            balance_tol = 1e-3 (units of 2 m l)   balance_revs = 20   stop_at_balance = false\n"      \
  "\narchive: /pendulum (parameters), /pendulum/transient (series over 'tau'), /pendulum/transient/solver\n" \
  HELP_DOCS_PENDULUM

/* ---- the rotor commands ------------------------------------------------------------------------ */
#define HELP_ROTOR_PARAMS                                                                          \
  "[rotor]     M_k = 6  A_k = 0.12  m_p = 4  A_p = 0.04  C_p = 0.03   (kg, kg m^2)\n"                 \
  "            omega = 500 (rad/s)   inertia = paper|full   axial = false\n"                           \
  "            gravity = false   shaft_angle (with gravity: 0 vertical .. 90 deg horizontal .. 180 deg)\n" \
  "            g = 9.80665 (m/s^2)   (transients only: rotor stability/sweep/map/campbell refuse gravity)\n" \
  "[supports]  l_L = 0.20  l_R = 0.15 (m)   c_Lx c_Ly c_Lz c_Rx c_Ry (N/m)   h_Lx h_Ly h_Lz h_Rx h_Ry (N s/m)\n" \
  "            defaults: c_Lx = c_Ly = 1e5, c_Rx = c_Ry = 1.5e5, c_Lz = 2e5, h_L. = 100, h_R. = 150, h_Lz = 200\n" \
  "[lumped]    optional, replaces [supports]: M A C c_x c_y c_z c_alpha c_beta c_xbeta c_yalpha and h_ (all),\n" \
  "            the coefficients of eqs. (2.7)-(2.11) in docs/rotor.md\n"                               \
  "[initial]   x y (m)  alpha beta (rad)  x_rate y_rate (m/s)  alpha_rate beta_rate (rad/s)  z z_rate\n"      \
  "[plane1]    d = 0.10 (m)  m0 = 0.02 (kg)  r0 = 0.1 (m)  psi0 = 0 (rad, unbalance angle on the rotor)\n"   \
  "            ball_mass = 0.05, 0.05 (kg)  ball_radius = 0.1, 0.1 (m)  ball_damping = 0.1, 0.1 (kg/s)\n"    \
  "            ball_psi = 1.0, 2.5 (rad, initial angles relative to the rotor)  ball_rate = 0, 0 (rad/s)\n"   \
  "[plane2]    optional second balancer plane, same keys as [plane1]\n"

#define HELP_ROTOR_TRANSIENT                                                                          \
  "Transient of the rotor in a massive housing with ball autobalancers: the fixed-frame equations,\n" \
  "eqs. (3.2) and (3.4) in docs/rotor.md (with frame = rotating: the balls in the rotating frame,\n"  \
  "eq. (3.13) in docs/rotor.md), integrated with a GSL stepper, streamed to HDF5; summary: balanced\n" \
  "or not, time to balance, residual unbalance and vibration before/after.\n\n" HELP_ROTOR_PARAMS     \
  "[transient] t_end = 20 (s)   revs_out = 0.25 (output every quarter revolution) or dt_out (s)\n"    \
  "            stepper = dop853   rtol = 1e-10   atol = 1e-9   h_max = 0 (s, 0: none)   max_steps = 1e8\n" \
  "            output = dense6|dense|exact (stepper dop853: output and events on its continuous\n"        \
  "            extension, order 6 with no extra rhs | order 7 with 3 more rhs per step, or steps cut at\n" \
  "            the output times; the other steppers always cut; until 0.2.0: stepper = rk8pd)\n"           \
  "            frame = fixed|rotating   balance_tol = 0.01 (|s|/(m0 r0))   balance_revs = 50 (or balance_dwell, s)\n" \
  "            stop_at_balance = false\n"                                                             \
  "            capture_band = 0.05, capture_time = 2 (s): a capture near a resonance (run-up outputs, with a drive)\n" \
  "[drive]     spin speed: prescribed Omega(t), or a motor (optional; default mode = constant: rotor.omega)\n" \
  "            mode = ramp: omega_a, omega_b (rad/s, or e.g. rpm) before t_a and after t_b (s), linear between\n" \
  "            mode = table: table_t = t0, t1, ... (s, increasing)  table_omega = w0, w1, ... (rad/s each)\n" \
  "            linear between the points, constant outside; revolutions counted at the largest speed\n" \
  "            mode = motor: J (kg m^2, >= C_p)  L_0 (N m, > 0)  omega_0 (rad/s, > 0): L = L_0 (1 - Omega/omega_0)\n" \
  "            (or table_omega = speeds, increasing  table_torque = N m each)  k_r = 0 (N m s)  omega_start = 0\n" \
  "            (rad/s); revolutions counted at omega_0 (table: its largest speed)\n" \
  "[friction]  rolling resistance f N and stiction mu N of the balls (docs/device.md section 3; optional)\n" \
  "            law = none|exact|regularized  (exact: stick and slip switched at events; regularized:\n" \
  "            f N tanh(psi'/u_eps), no stiction)  u_eps (rad/s, > 0; regularized only)\n" \
  "            per plane in [plane1]/[plane2]: ball_f = 0 (>= 0, one value or one per ball)\n" \
  "            ball_mu = ball_f (>= ball_f, the static coefficient)\n" \
  "            ball_rho (m, >= 0; [plane1]/[plane2], one value or one per ball): the balls roll, solid\n" \
  "            spheres of that radius (relative inertia 7/5, docs/device.md section 3)\n" \
  "[contact]   ball size and impacts (docs/device.md section 4; on when [plane1]/[plane2] ball_diameter\n" \
  "            (m, >= 0, one value or one per ball) is given): restitution = 1 (in [0, 1])\n" \
  "            v_rest = 1e-3 rad/s (slower impacts join the pair in resting contact); with law = exact\n" \
  "            stuck balls pressed together hold as one body (docs/device.md \"Stiction and contact\")\n" \
  "[balance]   grade = G2.5 (optional; an ISO 21940-11 grade, G and mm/s): its permissible unbalance\n" \
  "            is reported and whether the run meets it (docs/units.md)\n" \
  "\narchive: /rotor (parameters), /rotor/transient (time series over 'time'; with a drive its\n"   \
  "attributes drive_* and the column Omega; with friction the columns p<j>_b<i>_stuck, p<j>_b<i>_N\n" \
  "and the attributes friction_*, p<j>_ball_time_stuck), /rotor/revolutions\n"                   \
  HELP_DOCS_ROTOR

#define HELP_ROTOR_STAB_OPTS \
  "[stability] method = auto|poly|closed|full|floquet   tol = 1e-9   floquet_rtol = 1e-11   floquet_atol = 1e-13\n" \
  "            member1 = default|symmetric|free|given   member1_angles = (rad: balls 1..n-2 for free, all for given)\n" \
  "            member2, member2_angles (plane 2)\n"
/* The parameters a sweep or a map varies (autobal_rotor_stab_param; the defaults of min and max
 * are param_default_lo/hi in apps/cmd_rotor_stability.c). */
#define HELP_ROTOR_STAB_AXES \
  "parameters (unit; what it changes; default min .. max):\n" \
  "  omega            rad/s  spin speed; 5% of the 1st natural frequency at rest .. 4x the larger of\n" \
  "                          the 4th one and |rotor.omega|\n" \
  "  ball_damping     kg/s   damping of every ball of every plane; 0 .. 10x plane1's first ball + 0.001\n" \
  "  ball_mass        kg     mass of every ball of every plane; 0.1x .. 4x plane1's first ball\n" \
  "  stiffness_scale  1      factor on every support stiffness; 0.25 .. 4\n" \
  "  damping_scale    1      factor on every support viscosity; 0 .. 4\n" \
  "  unbalance_mass   kg     unbalance mass m0 of every plane; 0 .. 4x plane1.m0 + 0.001\n" \
  "  anisotropy       1      y support stiffnesses = this x the x ones (c_Ly = a c_Lx, c_Ry = a c_Rx); v/4 .. 4v\n" \
  "  C_over_A         1      polar inertia C_p = this x (A_k + A_p); v/4 .. 4v\n" \
  "  any numeric key of the rotor's config, as section.key (v: its value; default v/4 .. 4v):\n" \
  "    rotor.M_k .. rotor.C_p, supports.l_L .. supports.h_Ry (hardware input; the names alone work too),\n" \
  "    lumped.M .. lumped.h_yalpha (lumped input),\n" \
  "    planeN.d (m; default the span of the supports), planeN.m0 (kg), planeN.r0 (m), planeN.psi0 (rad;\n" \
  "    -pi .. pi), planeN.unbalance (kg m or g mm: m0 = value / r0), planeN.ball_mass (kg),\n" \
  "    planeN.ball_radius (track radius, m or mm), planeN.ball_damping (kg/s): every ball of plane N\n" \
  "  (docs/rotor.md \"Sweeps and maps over any key\")\n"
#define HELP_ROTOR_STABILITY \
  "Stability of the balanced motion, eq. (3.14) in docs/rotor.md: the degree-12 polynomial Delta (GSL roots,\n" \
  "Routh-Hurwitz), the closed 12x12 (16x16) matrix, the full model in rotating coordinates, Floquet multipliers\n" \
  "(any supports); critical speeds and the stable speed intervals (eqs. (3.14)-(3.16) in docs/rotor.md).\n\n" \
  HELP_ROTOR_PARAMS HELP_ROTOR_STAB_OPTS \
  "            critical_speeds = true  omega_min, omega_max (rad/s; default 5% of the 1st natural frequency .. 4x)\n" \
  "            n_omega = 400  xtol_rel = 1e-8\n" \
  "            unbalance_min, unbalance_max (kg m or g mm): EVERY unbalance m0 r0 in the range (one plane, two\n" \
  "            or more balls): the critical unbalances at omega and the speeds stable for all of them (docs/rotor.md,\n" \
  "            \"Every unbalance\"); two planes of two balls: every relative phase and plane 1's whole range\n" \
  "            (exact), plane 2's m0 r0 over its range unbalance2_min, unbalance2_max (default: plane 1's) by a\n" \
  "            certified box search (exact where decided; else its n_unbalance grid values, sampled)\n" \
  "            n_unbalance = 9   unbalance2_boxes = 0 (budget; 0: 100000, -1: no search, grid only)\n" \
  "            unbalance_member = every|symmetric  (3 or more identical balls: which members; every: 3 to 10 balls)\n" \
  "            member_boxes = 0  (every, 4 to 10 balls: the search's box budget; 0: 4000000, else 1000 .. 1e9)\n" \
  "            hill_boxes = 0  (anisotropic supports, two balls: Hill's method, docs/rotor.md \"Anisotropic supports:\n" \
  "            Hill's method\"; box budget; 0: 20000, else 100 .. 1e8; at the budget undecided, never stable)\n" \
  "\narchive: /rotor (model), /rotor/stability (roots, eigenvalues, Floquet multipliers), /rotor/stability/critical,\n" \
  "         /rotor/stability/every_unbalance (and .../speeds, two planes .../phase)\n" \
  HELP_DOCS_ROTOR
#define HELP_ROTOR_SWEEP \
  "Stability margin of the balanced motion (eq. (3.14) in docs/rotor.md) along one parameter; every verdict\n" \
  "change refined to xtol_rel; stable intervals.\n\n" \
  HELP_ROTOR_PARAMS HELP_ROTOR_STAB_OPTS \
  "[sweep] param = omega   min  max  n = 1000   xtol_rel = 1e-8\n" \
  "        param: one of the parameters below; min, max in its unit\n\n" \
  HELP_ROTOR_STAB_AXES \
  "\narchive: /rotor/sweep (margin and verdict over the parameter, critical_value, stable_lo/hi)\n" \
  HELP_DOCS_ROTOR
#define HELP_ROTOR_MAP \
  "Two-parameter stability map of the balanced motion (eq. (3.14) in docs/rotor.md), OpenMP-parallel\n" \
  "(results independent of the thread count).\n\n" \
  HELP_ROTOR_PARAMS HELP_ROTOR_STAB_OPTS \
  "[map] param1 = omega         min1 max1  n1 = 120   (first axis)\n" \
  "      param2 = ball_damping  min2 max2  n2 = 60    (second axis)\n" \
  "      threads = 0 (OpenMP threads; 0: default)\n" \
  "      param1, param2: two different parameters below; min, max in their units\n" \
  "      unbalance_min, unbalance_max (kg m or g mm): each point's verdict for EVERY m0 r0 in the range\n" \
  "      (one plane, two or more balls; docs/rotor.md \"Every unbalance\"); unbalance_mass, plane1.m0 and\n" \
  "      plane1.unbalance are then no axes; unbalance_member = every|symmetric (3 or more balls),\n" \
  "      member_boxes = 0, hill_boxes = 0 (as in [stability]; anisotropic supports: -3 undecided points)\n\n" \
  HELP_ROTOR_STAB_AXES \
  "\narchive: /rotor/map (margin[param1][param2], verdict: 1 stable, 0 marginal, -1 unstable, -2 no balance,\n" \
  "         -3 undecided)\n" \
  HELP_DOCS_ROTOR
#define HELP_ROTOR_DESIGN \
  "Size a ball autobalancer (n identical balls in plane 1, two by default) for the machine of the config:\n" \
  "the designs whose balanced motion has every root Re lambda < -margin at every speed of the range and\n" \
  "for EVERY unbalance of the range, exact in the unbalance and the track radius, ranked by the robust\n" \
  "margin (n_balls_max >= 3 with every: the feasible ones by the margin their verdict covers);\n" \
  "the best re-checked by the every-unbalance analysis and printed as a runnable config.\n\n" \
  HELP_ROTOR_PARAMS \
  "[design] speed_min, speed_max (rad/s or rpm; required)  n_speed = 101  n_verify = 0 (4 (n_speed-1) + 1)\n" \
  "         unbalance_min, unbalance_max (kg m or g mm; required)  margin = 0.1 (1/s)\n" \
  "         ball_mass_min, ball_mass_max (kg or g; default 0.5x, 2x plane 1's)  n_ball_mass = 8\n" \
  "         track_radius_min, track_radius_max (m or mm; 0.5x, 1.5x)  n_track_radius = 24 (the map only)\n" \
  "         ball_damping_min, ball_damping_max (kg/s; 0.1x, 10x)  n_ball_damping = 8\n" \
  "         position_min, position_max (m; plane 1's d, fixed)  n_position = 1\n" \
  "         n_best = 10  n_starts = 3 (Nelder-Mead starts)  max_iter = 80  config_out = FILE (the best as .ini)\n" \
  "         a pair with min = max fixes that variable; one plane, inertia = paper\n" \
  "         anisotropic supports (one plane, two balls): every grid design SCREENED by Floquet (n_speed speeds x\n" \
  "         5 unbalances: sampled), the n_best by the screen's margin CERTIFIED by Hill's method with the margin\n" \
  "         at every re-check speed (n_verify = 0: n_speed; seconds per speed); only certified designs are\n" \
  "         feasible; no optimizer; keep the grids small (data/design_anisotropic.ini); hill_boxes = 0\n" \
  "         (each Hill verdict's budget: 0 = 20000, else [100, 1e8]; default [stability]'s)\n" \
  "         n_balls_min = 2, n_balls_max = 2 (identical balls per design; mass bounds per ball)\n" \
  "         total_ball_mass_max (kg or g; cap on n m)  unbalance_member = [stability]'s|every|symmetric (n >= 3:\n" \
  "         the search runs over the symmetric fan; every (3 to 10 balls): each ranked design then certified for\n" \
  "         every member at the re-check speeds, else not feasible)  member_boxes = 0 (4000000; [1000, 1e9])\n" \
  "         n_transient = 5 (best designs whose transients are run; 0 off)  rank_by = margin|time|p_balance\n" \
  "         n_start_angles = 3 (per ball)  n_transient_unbalances = 2  n_transient_speeds = 2  (grids, ends included)\n" \
  "         transient_t_end = 10 s (profile: its end + 10 s)  balance_tol = 0.01  balance_revs = 50  threads = 0\n" \
  "         planes = 1|2 (2: the same two-ball balancer in both planes of a two-plane config; every phase;\n" \
  "         unbalance2_min, unbalance2_max (plane 2; default plane 1's)  n_unbalance2 = 5 (plane 2's map grid)\n" \
  "         unbalance2_boxes = 0 (certification of the n_best: 0 = 100000 boxes, -1 none);\n" \
  "         n_transient and n_starts default to 0 there)\n" \
  "[drive]  mode = ramp|table (as `rotor transient`): the transients run the run-up profile from rest; the\n" \
  "         speed range is [design] balance_from (rpm or rad/s; required) .. the profile's top speed\n" \
  "\narchive: /rotor/design (feasible[ball_mass][ball_damping][plane_position][track_radius], radius windows,\n" \
  "ranked/ designs, best_config; with transients ranked/p_balance, time_to_balance_median, _worst (s));\n" \
  "with n_balls other than 2..2: n_balls, n_balls_N/feasible, radius windows per N, ranked/n_balls;\n" \
  "planes = 2: margin_map, ranked/certified_speeds, found_* (no radius windows);\n" \
  "anisotropic supports: feasible = the screen, ranked/hill_certified, hill_speeds, hill_found_* (no windows)\n" HELP_DOCS_ROTOR
#define HELP_ROTOR_CAMPBELL \
  "Rotor-housing without balls: natural frequencies at rest (undamped, damped), Campbell diagram (C omega\n" \
  "gyroscopic), steady unbalance response, critical speeds (frequency = omega) and response peaks.\n\n" \
  HELP_ROTOR_PARAMS \
  "[campbell] omega_min = 0  omega_max  n = 401  n_resonance = 4000  xtol_rel = 1e-10\n" \
  "\narchive: /rotor/campbell\n" HELP_DOCS_ROTOR

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
  "[ensemble] target_grade = G6.3 (or 6.3 mm/s)  target_unbalance = 50 g mm   (P(grade at the end <= target),\n" \
  "           P(residual unbalance <= target; two planes: each plane within half), Wilson 95% intervals)\n" \
  "           write_unbalance = false (true: per-member residual_unbalance_abs_final, balance_grade_final)\n" \
  "           attractors: each member classified over its final window (docs/guide.md, \"Attractors\"): balanced,\n" \
  "           heavy_side, fixed, circulating (frequency vs the natural frequency at its speed), periodic, irregular;\n" \
  "           attractor_window_revs = 100 (revolutions, (0, 1e6])  attractor_rest_tol = 0.05 rad ((0, pi])\n" \
  "           attractor_min_turns = 2 ([1, 1e9])  attractor_rate_tol = 0.02  attractor_envelope_tol = 0.05 ((0, 1))\n" \
  "           write_attractors = true (per-member attractor, circulation_frequency, natural_frequency)\n" \
  "[drive]    as `rotor transient` (mode = constant|ramp|table); with a ramp or table a member is balanced only\n" \
  "           when the dwell below balance_tol lies after the end of its ramp (t_b; a table's last time)\n" \
  "[friction] as `rotor transient` (law, u_eps; [plane1]/[plane2] ball_f, ball_mu); law = exact adds per member\n" \
  "           balls_stuck_final, time_stuck_max (s), friction_switches (write_unbalance = true: datasets)\n" \
  "[contact]  as `rotor transient` ([plane1]/[plane2] ball_diameter (m); restitution = 1, v_rest = 1e-3 rad/s):\n" \
  "           adds per member contact_impacts, contacts_final (pairs touching at the end); a member whose\n" \
  "           balls overlap at its initial angles fails (the warning names the balls), the others run\n" \
  "parameters: psi_K, rate_K (initial angle/rate of ball K relative to the rotor; K = 1..N, plane 1 first),\n" \
  "            omega (constant drive only), ball_damping (every ball), m0, psi0 (plane 1's unbalance mass and\n" \
  "            angle), x, y (initial displacement);\n" \
  "            with [drive] mode = ramp: ramp_rate (rad/s^2 > 0: t_b = t_a + |omega_b - omega_a| / ramp_rate),\n" \
  "            ramp_time (s > 0: t_b = t_a + ramp_time), omega_b (rad/s, the final speed);\n" \
  "            with a friction law: ball_f, ball_mu (every ball)\n" \
  "default: grid psi_1 x psi_2, 16 x 16 over [-pi, pi)\n" \
  "\narchive: /rotor (model), /rotor/ensemble (variables over the parameter axes, or over 'member' when\n" \
  "random; probability_balanced etc. as attributes), /rotor/ensemble/statistics/<quantity> (quantiles, mean,\n" \
  "targets of the residual unbalance and grade at the end), /rotor/ensemble/series/member_M, .../execution\n" \
  HELP_DOCS_ROTOR
#define HELP_PENDULUM_ENSEMBLE \
  "Many transients of the two-pendulum autobalancer (as `pendulum transient`) over a grid or random\n" \
  "samples of initial conditions or parameters: per member balanced or not, time to balance, residual\n" \
  "unbalance, amplitude, final pendulum angles, solver status; basin map and probability of balancing.\n\n" \
  HELP_PENDULUM_PARAMS \
  "[initial]   xi eta psi phi xi_rate eta_rate psi_rate phi_rate   (all 0)\n" \
  "[transient] as `pendulum transient` (t_end = 300, ...), but stop_at_balance = true by default\n" \
  HELP_ENSEMBLE_KEYS \
  "[ensemble] attractors: each member classified over its final window (docs/guide.md, \"Attractors\"), as for the\n" \
  "           rotor; the pendulums' directions from the shaft centre play the balls, their absolute rate\n" \
  "           (units of omega0) is compared with the shaft's natural frequency, sqrt(1 - H^2/4) (damped);\n" \
  "           the window (attractor_window_revs = 100 revolutions) must fit in\n" \
  "           t_end, or the member counts as irregular; the same keys attractor_* and write_attractors\n" \
  "parameters: xi, eta, psi, phi, xi_rate, eta_rate, psi_rate, phi_rate (initial state), R_w, R_m, H, h,\n" \
  "            psi0 or k\n" \
  "default: grid psi x phi, 16 x 16 over [-pi, pi)\n" \
  "\narchive: /pendulum (parameters), /pendulum/ensemble (as for the rotor)\n" HELP_DOCS_PENDULUM

/* ---- the commands on an archive ------------------------------------------------------------------ */
#define HELP_INFO                                                                                   \
  "A readable summary of any autobal archive: the command that wrote it, its status, provenance\n"   \
  "and configuration; the headline results (verdicts, critical speeds, stable intervals, time to\n" \
  "balance, residual unbalance); then every group with its attributes (parameters with units,\n"   \
  "solver settings and statistics) and datasets (dimensions, shape, type, units, long_name).\n"    \
  "--json prints the same as one JSON object (keys: file, root, command, status, headline[],\n"    \
  "groups[] with attributes {name: {value, units}} and datasets[] {name, path, shape, dims,\n"     \
  "dtype, coordinate, units, long_name, values (up to 64 elements)}).\n"                          \
  "Exit 4 (with the reason) when FILE.h5 is missing, not HDF5, truncated or not an autobal archive.\n" \
  HELP_DOCS_ARCHIVE

#define HELP_RERUN                                                                                   \
  "Run again the command recorded in FILE.h5 (root attribute `command`) with the configuration\n"   \
  "recorded there (`effective_config`: every key the command read with the value it used, defaults\n" \
  "included; `input_config` for archives of older versions) and write NEW.h5.  With the same\n"     \
  "version of autobal every dataset is reproduced bit for bit (provenance such as `created` and\n"  \
  "wall times differ).\n"                                                                          \
  "Options: -o NEW.h5 (required, not FILE.h5 itself), --force, --json, --quiet.  --set is refused.\n" \
  HELP_DOCS_ARCHIVE

#define HELP_PLOT                                                                                     \
  "Draw PNG pictures of an archive with matplotlib: runs `/usr/bin/python3 autobal_plot.py FILE.h5\n" \
  "-o DIR` (tools/ in the source tree, share/autobal/tools when installed; override with\n"          \
  "AUTOBAL_TOOLS_DIR and AUTOBAL_PYTHON).  The script reads only the archive and writes\n"             \
  "DIR/<stem>_<kind>.png (stem = FILE without .h5) for each group it knows: critical-speed curves\n" \
  "with regions A and B (docs/pendulum.md), stability maps, roots, transients (displacement,\n"      \
  "residual unbalance on a log scale, ball/pendulum angles, time to balance).  -o DIR defaults to\n" \
  "the current directory; the names of the files written are printed.\n" HELP_DOCS_ARCHIVE

#endif
