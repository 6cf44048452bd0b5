/* autobal/rotor.h: a rotor in a massive housing on visco-elastic supports with
 * one or two ball autobalancers (docs/rotor.md, equations (2.1)-(3.16)).
 *
 * Model.  An axisymmetric rotor (m_p, A_p, C_p) fixed in a housing (M_k, A_k)
 * on a left support in the plane z = -l_L and a right one in z = +l_R spins at
 * the constant speed omega, or with a prescribed speed Omega(t) (autobal_rotor_drive).  Small motions of the common centre of mass O:
 * x, y, z and the Resal angles alpha (about x), beta (about y); a body point at
 * axial coordinate p moves by (x + p beta, y - p alpha).  In each balancer
 * plane z = d_j: a static unbalance m_j0 at radius r_j0 and angle psi_j0
 * relative to the rotor, and n_j balls (point masses m_ji on tracks of radius
 * r_ji, viscous relative damping h_ji).  Gravity is neglected.
 *
 * Units: SI throughout (kg, m, s, rad, N/m, N s/m, N m/rad, ...), stated field
 * by field below.
 *
 * State vectors.  With N = total number of balls (plane 1's balls first, then
 * plane 2's), the FIXED-FRAME state (autobal_rotor_rhs) is
 *
 *   y = (x, y, alpha, beta, x', y', alpha', beta',
 *        phi_1 .. phi_N, phi_1' .. phi_N' [, z, z'] [, phi_0, Omega])   dimension 8 + 2N (+ 2) (+ 2)
 *
 * with phi the ABSOLUTE ball angles in the fixed axes (unwrapped, they grow like
 * omega t).  The ROTATING-FRAME state (autobal_rotor_rhs_rotating) is the same
 * with phi_k replaced by psi_k = phi_k - omega t and phi_k' by psi_k' = phi_k' - omega
 * (rotor coordinates stay in the fixed frame); with a drive, omega t is phi_0(t) and omega
 * is Omega(t) here and below.  Ball k of plane j has index
 * k = autobal_rotor_ball_index(r, j, i): angle y[8 + k], rate y[8 + N + k].
 * The rotor angle phi_0 and the spin speed Omega are state variables only with a MOTOR drive
 * (autobal_rotor_drive): then they are the last two entries, y[dim - 2] and y[dim - 1], in both
 * frames (the rotor angle is absolute: phi_0 measured in the fixed axes).
 * The unbalance of plane j is at phi_j0 = omega t + psi_j0.
 *
 * Two models (autobal_rotor_params.inertia):
 *  AUTOBAL_ROTOR_INERTIA_PAPER (default): the paper's simplification (2.2): the
 *    balls' and unbalances' masses do not enter M and A; the effective mass
 *    matrix of the rotor is diag(M, M, A, A) minus the balls' tangential part.
 *    It is derived from the kinetic energy
 *      T = 1/2 q'^T diag(M,M,A,A) q' + sum_i [ 1/2 m_i r_i^2 phi_i'^2 + m_i r_i phi_i' g_i . q' ]
 *    with g_i = (-sin phi_i, cos phi_i, -d cos phi_i, -d sin phi_i) (plus the same
 *    term of the unbalance with phi_0' = omega); results are meaningful to O(m/M).
 *  AUTOBAL_ROTOR_INERTIA_FULL: also keeps 1/2 m |v_D|^2 of every ball and of the
 *    unbalance (their full translational inertia), i.e. adds
 *    (m_0 + sum m_i) E^T E to the rotor's mass matrix, E = [[1,0,0,d],[0,1,-d,0]].
 *    The ball equations (3.4) are unchanged.
 *
 * Threads.  A handle owns a workspace used by the right-hand sides: do not
 * evaluate one handle from two threads at once; allocate one handle per thread
 * (cheap).  Two handles never interfere.  No allocation happens after
 * autobal_rotor_alloc(); the right-hand sides are O(N) per call.
 *
 * GSL: the library calls GSL only so that failures come back as statuses; a
 * host program should call gsl_set_error_handler_off() once.
 */
#ifndef AUTOBAL_ROTOR_H
#define AUTOBAL_ROTOR_H

#include <stddef.h>

#include "autobal/export.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* Largest number of balancer planes (the paper treats one or two; the code
 * loops over planes, so this is a sizing constant only). */
#define AUTOBAL_ROTOR_MAX_PLANES 2
/* Largest total number of balls over all planes. */
#define AUTOBAL_ROTOR_MAX_BALLS 1000000

/* Which support data are authoritative (autobal_rotor_params.input). */
typedef enum autobal_rotor_input {
  AUTOBAL_ROTOR_HARDWARE = 0, /* hw is used; the lumped coefficients are computed (2.7)-(2.11) */
  AUTOBAL_ROTOR_LUMPED = 1    /* lumped is used; of hw only l_L, l_R are read (for outputs) */
} autobal_rotor_input;

/* Inertia model (see the top of this header). */
typedef enum autobal_rotor_inertia {
  AUTOBAL_ROTOR_INERTIA_PAPER = 0,
  AUTOBAL_ROTOR_INERTIA_FULL = 1
} autobal_rotor_inertia;

/* Which state vector a function receives. */
typedef enum autobal_rotor_frame {
  AUTOBAL_ROTOR_FIXED = 0,   /* ball angles phi (absolute) */
  AUTOBAL_ROTOR_ROTATING = 1 /* ball angles psi = phi - omega t (relative to the rotor) */
} autobal_rotor_frame;

/* Hardware values (the paper's section 2).  Supports: left in z = -l_L, right in z = +l_R. */
typedef struct autobal_rotor_hardware {
  double M_k;  /* kg, housing mass, > 0 */
  double A_k;  /* kg m^2, housing transverse moment of inertia about O, > 0 */
  double m_p;  /* kg, rotor mass, > 0 */
  double A_p;  /* kg m^2, rotor transverse moment of inertia about O, > 0 */
  double C_p;  /* kg m^2, rotor polar moment of inertia, >= 0 */
  double l_L;  /* m, the left support is in the plane z = -l_L (finite; l_L + l_R > 0) */
  double l_R;  /* m, the right support is in the plane z = +l_R */
  double c_Lx, c_Ly, c_Lz; /* N/m, left support stiffnesses (x, y, axial), >= 0 */
  double c_Rx, c_Ry;       /* N/m, right support stiffnesses, >= 0 */
  double h_Lx, h_Ly, h_Lz; /* N s/m, left support viscosities, >= 0 */
  double h_Rx, h_Ry;       /* N s/m, right support viscosities, >= 0 */
} autobal_rotor_hardware;

/* Lumped coefficients (2.7), (2.9), (2.11). */
typedef struct autobal_rotor_lumped {
  double M;       /* kg, M = M_k + m_p, > 0 */
  double A;       /* kg m^2, A = A_k + A_p, > 0 */
  double C;       /* kg m^2, C = C_p, >= 0 */
  double c_x;     /* N/m,   c_Lx + c_Rx */
  double c_y;     /* N/m,   c_Ly + c_Ry */
  double c_z;     /* N/m,   c_Lz */
  double c_alpha; /* N m,   c_Ly l_L^2 + c_Ry l_R^2 */
  double c_beta;  /* N m,   c_Lx l_L^2 + c_Rx l_R^2 */
  double c_xbeta; /* N,     c_Lx l_L - c_Rx l_R */
  double c_yalpha;/* N,     c_Ly l_L - c_Ry l_R */
  double h_x, h_y, h_z;       /* N s/m, the same formulas with h_L., h_R. */
  double h_alpha, h_beta;     /* N m s */
  double h_xbeta, h_yalpha;   /* N s */
} autobal_rotor_lumped;
/* Validation of lumped values: M, A > 0; C >= 0; c_x, c_y, c_z, c_alpha,
 * c_beta >= 0 and the 2x2 blocks [[c_x, -c_xbeta], [-c_xbeta, c_beta]] and
 * [[c_y, c_yalpha], [c_yalpha, c_alpha]] positive semidefinite (same for h). */

/* One balancer plane: its unbalance and its balls.  The arrays are read
 * (copied) by autobal_rotor_alloc(); the caller keeps ownership. */
typedef struct autobal_rotor_plane {
  double d;                   /* m, signed axial coordinate of the plane, z = d (finite) */
  double m0;                  /* kg, unbalance mass m_j0, >= 0 */
  double r0;                  /* m, unbalance radius r_j0, >= 0 */
  double psi0;                /* rad, unbalance angle relative to the rotor axes (finite) */
  size_t n_balls;             /* number of balls n_j (0 allowed) */
  const double *ball_mass;    /* kg, m_ji > 0; n_balls entries (may be NULL if n_balls == 0) */
  const double *ball_radius;  /* m, track radius r_ji > 0 */
  const double *ball_damping; /* kg/s (N s/m), h_ji >= 0: force h_ji r_ji (phi_ji' - omega) */
  const double *ball_psi;     /* rad, initial angle relative to the rotor; NULL: all 0 */
  const double *ball_rate;    /* rad/s, initial relative rate psi_ji'; NULL: all 0 */
} autobal_rotor_plane;

/* Spin speed profile (autobal_rotor_drive.mode). */
typedef enum autobal_rotor_drive_mode {
  AUTOBAL_ROTOR_DRIVE_CONSTANT = 0, /* Omega(t) = omega (autobal_rotor_params.omega); the default */
  AUTOBAL_ROTOR_DRIVE_RAMP = 1,     /* omega_a for t <= t_a, linear to omega_b at t_b, omega_b after */
  AUTOBAL_ROTOR_DRIVE_TABLE = 2,    /* points (t_k, Omega_k), linear between, constant outside */
  AUTOBAL_ROTOR_DRIVE_MOTOR = 3     /* a motor of limited power: phi_0 and Omega are state variables */
} autobal_rotor_drive_mode;

/* A prescribed (kinematic) drive: the rotor angle phi_0(t) = integral_0^t Omega, so that
 * phi_0(0) = 0 (the unbalance of plane j sits at phi_0(t) + psi_j0).  Every constant omega of
 * the constant-speed model becomes Omega(t): the ball resistance acts on r (phi' - Omega), the
 * gyroscopic terms are C Omega alpha', C Omega beta', the unbalance gains the tangential
 * acceleration Omega' and the alpha equation the term C Omega' beta (the derivative of
 * C Omega beta, docs/rotor.md).  With a RAMP or TABLE drive autobal_rotor_params.omega is not
 * used by the right-hand sides, the initial state or the outputs (the stability analyses,
 * which need a constant speed, still read it).  Speeds may have either sign (the sense of
 * rotation) and may be 0. */
typedef struct autobal_rotor_drive {
  int mode;                    /* autobal_rotor_drive_mode */
  double omega_a, omega_b;     /* rad/s, RAMP: speeds before t_a and after t_b (finite) */
  double t_a, t_b;             /* s, RAMP: start and end of the ramp (finite, t_a < t_b) */
  size_t n_points;             /* TABLE: number of points, 1 .. AUTOBAL_ROTOR_DRIVE_MAX_POINTS */
  const double *table_t;       /* s, TABLE: strictly increasing finite times (copied by alloc) */
  const double *table_omega;   /* rad/s, TABLE: finite speeds (copied by alloc) */
  /* MOTOR (added in 0.2.0 at the end of the struct; a zeroed block is unused by the other modes).
   * The rotor angle phi_0 and the spin speed Omega = phi_0' become the LAST TWO entries of the
   * state (after the balls and after (z, z') when axial = 1), with the equation of
   * docs/device.md "(b) Motor" (derived in tools/derive/derive_rotor.py):
   *   (J + sum_j m_j0 r_j0^2) Omega' + C (alpha'' beta + alpha' beta')
   *     + sum_j m_j0 r_j0 (-u_jD'' sin th_j + v_jD'' cos th_j)
   *   = L(Omega) - k_r Omega + sum_ji h_ji r_ji^2 (phi_ji' - Omega),     th_j = phi_0 + psi_j0,
   * coupled to (3.2)/(3.4) with the unbalance's tangential acceleration m_j0 r_j0 Omega' and the
   * term C Omega' beta of the alpha equation.  Only the PAPER inertia model (the derivation's
   * truncation; FULL is refused with EINVAL).  Motor characteristic L(Omega): linear
   * L_0 (1 - Omega/omega_0) when n_torque == 0 (extrapolated linearly above omega_0 and below 0),
   * else the table (torque_omega[k], torque_L[k]), linear between the points and constant
   * outside them. */
  double J;                    /* kg m^2, MOTOR: spin inertia of the rotor and the motor's rotor, J >= C_p
                                * (lumped C), finite */
  double L_0;                  /* N m, MOTOR linear: starting torque L(0), > 0 (finite) */
  double omega_0;              /* rad/s, MOTOR linear: no-load speed, L(omega_0) = 0, > 0 (finite) */
  double k_r;                  /* N m s, MOTOR: resistance torque k_r Omega, >= 0 (finite) */
  double omega_start;          /* rad/s, MOTOR: Omega at the initial time (finite; default 0) */
  size_t n_torque;             /* MOTOR: 0 (linear characteristic) or the number of table points,
                                * 1 .. AUTOBAL_ROTOR_DRIVE_MAX_POINTS */
  const double *torque_omega;  /* rad/s, MOTOR table: strictly increasing finite speeds (copied) */
  const double *torque_L;      /* N m, MOTOR table: finite torques (copied); L(0) > 0 (the motor
                                * must be able to start) */
} autobal_rotor_drive;

/* Friction law of the balls (autobal_rotor_friction.law). */
typedef enum autobal_rotor_friction_law {
  AUTOBAL_ROTOR_FRICTION_NONE = 0,       /* frictionless balls: the right-hand sides of 0.2.0, bit for bit */
  AUTOBAL_ROTOR_FRICTION_EXACT = 1,      /* rolling resistance f N sgn(psi') and stiction mu N, switched at
                                          * events: every ball is in a MODE (autobal_rotor_ball_mode) */
  AUTOBAL_ROTOR_FRICTION_REGULARIZED = 2 /* rolling resistance f N tanh(psi'/u_eps), no modes, no stiction
                                          * beyond it (mu is not used) */
} autobal_rotor_friction_law;

/* Mode of a ball under the EXACT law. */
typedef enum autobal_rotor_ball_mode {
  AUTOBAL_ROTOR_BALL_SLIP_NEGATIVE = -1, /* slipping, the rolling resistance acts as for psi' < 0 */
  AUTOBAL_ROTOR_BALL_STUCK = 0,          /* stuck: a mass fixed to the rotor at its psi (psi' = 0) */
  AUTOBAL_ROTOR_BALL_SLIP_POSITIVE = 1   /* slipping, as for psi' > 0 */
} autobal_rotor_ball_mode;

/* Rolling resistance and stiction (docs/device.md section 3).  The normal force of the track on
 * ball i (inwards, N) is
 *   N_i = m_i [r_i phi_i'^2 - u_D'' cos phi_i - v_D'' sin phi_i]
 * (D's accelerations included: with friction the accelerations are solved with it).  A slipping
 * ball meets the tangential force f_i N_i against its relative motion: its equation (3.4) gains
 * + r_i f_i N_i sgn(psi_i') on the left (REGULARIZED: tanh(psi_i'/u_eps) instead of sgn; EXACT:
 * the sign of its mode), a MOTOR the reaction torque + r_i f_i N_i sgn(psi_i') on phi_0 (a
 * prescribed drive's torque takes it).  A STUCK ball (EXACT) is a mass fixed to the rotor at
 * phi_0 + psi_i: its own equation is dropped (psi_i'' = 0, psi_i' = 0: in the fixed frame
 * phi_i' = Omega and phi_i'' = Omega' whatever the state holds for phi_i'), it enters the rotor
 * equations like an unbalance, and with a MOTOR its m_i r_i^2 joins the spin inertia.  It stays
 * stuck while its holding force (the tangential force of the track on it)
 *   H_i = m_i [r_i Omega' - u_D'' sin phi_i + v_D'' cos phi_i]
 * satisfies |H_i| <= mu_i N_i.  The switching rules (autobal_rotor_friction_settle): a slipping
 * ball whose psi' reaches 0 sticks if then |H_i| <= mu_i N_i, else it slips on opposite to H_i; a
 * stuck ball with |H_i| > mu_i N_i slips opposite to H_i.  With friction on, a ball with
 * N_i <= 0 (it would leave its track) makes the right-hand sides fail.  Gravity is not in the
 * model yet (docs/device.md section 2): the forces above are written for g = 0.  The ball
 * arrays are copied by autobal_rotor_alloc; NULL means all 0. */
typedef struct autobal_rotor_friction {
  int law;                                        /* autobal_rotor_friction_law (0: NONE) */
  double u_eps;                                   /* rad/s, REGULARIZED: the speed of tanh(psi'/u_eps), > 0
                                                   * (finite); not read by the other laws */
  const double *ball_f[AUTOBAL_ROTOR_MAX_PLANES];  /* 1, rolling-resistance coefficient f_ji >= 0 of
                                                   * plane j's balls (n_balls entries; NULL: all 0) */
  const double *ball_mu[AUTOBAL_ROTOR_MAX_PLANES]; /* 1, static coefficient mu_ji >= f_ji (NULL: all
                                                   * equal to f) */
} autobal_rotor_friction;

/* Rolling inertia (docs/device.md section 3, "Rolling inertia").  With on = 1 every ball is a solid
 * sphere of radius rho_ji (m) whose centre runs on the track radius r_ji and which rolls without
 * sliding on the inside of the outer race (contact at r_ji + rho_ji).  It adds the rotational
 * kinetic energy T_rot = 1/5 m ((r + rho) Omega - r phi')^2: the ball equation (3.4) becomes
 *   7/5 m r^2 phi'' - 2/5 m r (r + rho) Omega' + h r^2 (phi' - Omega) = m r (u_D'' sin - v_D'' cos)
 * (rotating frame: 7/5 m r^2 psi'' + m r^2 (1 - 2 rho/(5 r)) Omega' + h r^2 psi' = ...), so the
 * relative inertia is 7/5 of the point mass's for every rho >= 0 (rho -> 0 is NOT the point mass:
 * that is on = 0); a MOTOR's phi_0 equation gains 2/5 m (r + rho) ((r + rho) Omega' - r phi''), a
 * stuck ball (friction EXACT) adds 2/5 m rho^2 to the spin inertia and -2/5 m rho Omega' to its
 * holding force.  The normal force keeps the point-mass formula (autobal_rotor_friction).  The
 * right-hand sides then take the friction path (a general 4x4 solve; with the law NONE f = 0, no
 * events).  The balanced states and the linear analyses (stability) do not include it: the
 * equilibria are the same, their stability is not (the CLI refuses rolling there). */
typedef struct autobal_rotor_rolling {
  int on;                                          /* 0 off (default), 1 on */
  const double *ball_rho[AUTOBAL_ROTOR_MAX_PLANES]; /* m, ball radius rho_ji >= 0 of plane j's balls
                                                    * (n_balls entries, copied; NULL: all 0) */
} autobal_rotor_rolling;

/* Ball size and contact (docs/device.md section 4).  With on = 1 ball i has the diameter delta_i
 * (m).  Balls on one TRACK (same plane, same track radius r, compared exactly) cannot overlap:
 * neighbours keep the angular distance of at least the gap angle
 *   gamma_ij = 2 asin((delta_i + delta_j) / (4 r))            (autobal_rotor_gap_angle);
 * balls on different tracks do not touch; a track whose balls all have delta = 0 has no contact.
 * The neighbours (pairs: the ball behind and the ball ahead in the positive sense) are fixed by
 * the cyclic order of the initial state (autobal_rotor_contact_order).  An IMPACT (the gap of a pair
 * reaching 0 while it closes) applies the generalized law with the model's mass matrix M (Newton's
 * restitution on the gap rate u = J v, J = -1 at the ball behind, +1 ahead):
 *   M dv = J^T Lambda,  J v+ = -e J v-,  Lambda = -(1 + e) u / G,  G = J M^-1 J^T,
 * the kinetic energy dropping by 1/2 (1 - e^2) u^2 / G (MOTOR; a prescribed drive adds the work of
 * its impulsive torque).  M^-1 J^T is computed as the response of the accelerations to a unit
 * generalized force pair on the two balls (friction off, every ball free).  RESTING contact: when
 * e |u| < v_rest the impact is plastic (u+ = 0) and the pair becomes a CLUSTER: the constraint
 * gap'' = 0 is imposed on the accelerations by the contact force lambda (N m, generalized, > 0
 * compressive), computed in every right-hand side; the pair separates when lambda falls to 0.
 * Several touching pairs may form chains (at most AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE clusters at
 * once; beyond that an impact keeps its restitution).  With contact on the right-hand sides take
 * the friction path.  With friction.law = EXACT: an impact's impulse sets its balls (and their
 * clusters) free, other stuck balls stay fixed; a cluster sticks as one; stuck balls in resting contact
 * form a chain held by stiction while its conditions hold (autobal_rotor_hybrid_settle, docs/device.md
 * "Stiction and contact"). */
#define AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE 16
typedef struct autobal_rotor_contact {
  int on;                                               /* 0 off (default), 1 on */
  double restitution;                                   /* 1, e in [0, 1] */
  double v_rest;                                        /* rad/s, resting-contact speed, >= 0 (0: 1e-3) */
  const double *ball_diameter[AUTOBAL_ROTOR_MAX_PLANES]; /* m, delta_ji >= 0 (n_balls entries, copied;
                                                         * NULL: all 0) */
} autobal_rotor_contact;

/* Largest number of points of a TABLE drive. */
#define AUTOBAL_ROTOR_DRIVE_MAX_POINTS 10000000

typedef struct autobal_rotor_params {
  int input;                  /* autobal_rotor_input */
  autobal_rotor_hardware hw;  /* used when input == AUTOBAL_ROTOR_HARDWARE */
  autobal_rotor_lumped lumped;/* used when input == AUTOBAL_ROTOR_LUMPED */
  int inertia;                /* autobal_rotor_inertia (default PAPER) */
  double omega;               /* rad/s, constant spin speed (finite; sign = sense of rotation) */
  int axial;                  /* 1: append (z, z') to the state, M z'' + h_z z' + c_z z = 0 (2.12) */
  size_t n_planes;            /* 1 .. AUTOBAL_ROTOR_MAX_PLANES */
  autobal_rotor_plane plane[AUTOBAL_ROTOR_MAX_PLANES];
  double q0[4];               /* initial x (m), y (m), alpha (rad), beta (rad); default 0 */
  double qd0[4];              /* initial rates, m/s and rad/s; default 0 */
  double z0, zd0;             /* initial axial displacement (m) and rate (m/s) */
  /* Prescribed spin speed Omega(t) (docs/rotor.md, "Prescribed spin speed"); added in 0.2.0 at
   * the end of the struct: a zeroed drive is AUTOBAL_ROTOR_DRIVE_CONSTANT, i.e. omega above. */
  autobal_rotor_drive drive;
  /* Gravity (docs/device.md section 2), added at the end of the struct: zeroed = off.  The weight
   * component g_s = g sin(shaft_angle) acts along -y of the fixed axes on rotor, housing, balls and
   * unbalance (the axial component is not modelled).  Used by the right-hand sides (transients)
   * with every drive: a prescribed speed carries the unbalance's weight, a MOTOR feels its torque
   * g_s sum_j m_j0 r_j0 cos(phi_0 + psi_j0) on phi_0.  The balanced states, the linear analyses
   * and the closed forms ignore it (the CLI refuses gravity for them).  CLI: [rotor] gravity,
   * shaft_angle, g. */
  int gravity;                /* 0 off (default), 1 on */
  double shaft_angle;         /* rad, angle of the shaft to the vertical, [0, pi] (pi/2: horizontal) */
  double g;                   /* m/s^2, gravitational acceleration, > 0 (default 9.80665) */
  /* Rolling resistance and stiction of the balls (docs/device.md section 3); added in 0.3.0 at
   * the end of the struct: a zeroed block is AUTOBAL_ROTOR_FRICTION_NONE (the model above). */
  autobal_rotor_friction friction;
  /* Rolling inertia of the balls (docs/device.md section 3, "Rolling inertia"); added in 0.3.0 at
   * the end of the struct: a zeroed block is off (point masses, the model above bit for bit). */
  autobal_rotor_rolling rolling;
  /* Ball size and contact (docs/device.md section 4); added in 0.3.0 at the end of the struct: a
   * zeroed block is off (balls pass through each other, the model above). */
  autobal_rotor_contact contact;
} autobal_rotor_params;

/* The default example (docs/rotor.md): M_k = 6, A_k = 0.12, m_p = 4, A_p = 0.04,
 * C_p = 0.03; l_L = 0.20, l_R = 0.15; c_Lx = c_Ly = 1e5, c_Rx = c_Ry = 1.5e5,
 * c_Lz = 2e5; h_Lx = h_Ly = 100, h_Rx = h_Ry = 150, h_Lz = 200; one plane
 * d = 0.10 with m0 = 0.02 at r0 = 0.1, psi0 = 0, two balls of 0.05 kg on
 * r = 0.1 with h = 0.1, starting at rest relative to the rotor at psi = 1.0 and
 * 2.5; omega = 500; hardware input; paper inertia; no axial motion.  The
 * lumped block is filled too (consistent with hw).  The ball arrays point to
 * static constant data (never written). */
AUTOBAL_API autobal_rotor_params autobal_rotor_params_default(void);

/* Lumped coefficients (2.7), (2.9), (2.11) from the hardware values.
 * Validates hw; returns AUTOBAL_SUCCESS or AUTOBAL_EINVAL (out untouched). */
AUTOBAL_API int autobal_rotor_lumped_from_hardware(const autobal_rotor_hardware *hw,
                                                   autobal_rotor_lumped *out, autobal_error *err);

/* Validate a parameter set.  Returns AUTOBAL_SUCCESS; AUTOBAL_WARNING (with a
 * message) when some plane's balls cannot cancel its unbalance (see
 * autobal_rotor_plane_can_balance); or AUTOBAL_EINVAL with a message naming the
 * parameter (e.g. "plane[0].ball_radius[1]"), its value and the allowed range.
 * In the PAPER inertia model the balls must also be light enough for the
 * effective mass matrix to stay positive definite in every configuration:
 * sum_j sum_i m_ji (1/M + d_j^2/A) < 1 (a sufficient condition; EINVAL otherwise).
 *
 * Gap between this check and the right-hand sides (PAPER model only).  Write
 * eps = 1 - sum_j sum_i m_ji g_j, g_j = 1/M + d_j^2/A.  The scaled mass matrix
 * D^-1/2 a D^-1/2 (D = diag(M, M, A, A)) has its smallest eigenvalue >= eps,
 * reached when a plane's balls lie on one line through the axis (all angles
 * equal modulo pi).  The right-hand sides refuse a matrix that is singular to
 * working precision: one plane, when det S <= 1e-13 (tr S)^2 for the 2x2
 * S = I + g C (about lambda_min(S) <= 1e-13, lambda_max(S) = 1 in that
 * configuration); two planes, when an L D L^T pivot is <= 1e-13 times its
 * diagonal entry (every pivot is >= eps times it).  So a parameter set with
 * 0 < eps <= about 1.2e-13 is accepted here, yet autobal_rotor_rhs and
 * autobal_rotor_rhs_rotating return GSL_EBADFUNC ("not positive definite") at
 * and near the collinear configurations: one plane, at all of them once
 * eps < 1e-13 (measured with one and two balls of the default plane); two
 * planes, only for smaller eps (below about 2.5e-14 for one ball in the
 * default plane and an empty second plane), because the pivot test is looser
 * than the eigenvalue bound.  For eps > 1.2e-13 the right-hand sides never
 * refuse on this account, but near those configurations the mass matrix has a
 * condition number up to 1/eps and the accelerations keep only about
 * 16 + log10(eps) significant digits (tests/test_rotor.c: 9e-8 relative
 * difference from a direct LU solve at eps = 1e-9).  The FULL inertia model
 * has no gap (its matrix is >= D).  The paper's simplification presumes light
 * balls, i.e. eps close to 1. */
AUTOBAL_API int autobal_rotor_params_check(const autobal_rotor_params *p, autobal_error *err);

/* Existence of a balanced configuration of one plane (3.14): balls with
 * a_i = m_i r_i can cancel s0 = m0 r0 iff
 *   max(0, 2 max_i a_i - sum_i a_i) <= s0 <= sum_i a_i
 * (relative slack 1e-12).  Returns 1 if they can, 0 otherwise (n = 0: s0 == 0). */
AUTOBAL_API int autobal_rotor_plane_can_balance(double s0, const double *a, size_t n);

/* Balanced angles of two balls (3.14), general masses: angles psi[0], psi[1]
 * relative to the rotor such that a1 e^{i psi1} + a2 e^{i psi2} = -s0 e^{i psi0}.
 * For a1 = a2 = a: psi_1,2 = psi0 + pi -/+ arccos(s0 / (2 a)).  For s0 = 0 and
 * a1 = a2 the pair psi0 + pi -/+ pi/2 is returned.  Angles are wrapped to
 * (-pi, pi].  Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL when no such pair exists
 * (message says why). */
AUTOBAL_API int autobal_rotor_balanced_angles_two(double s0, double a1, double a2, double psi0,
                                                  double psi[2], autobal_error *err);

/* ---- the model handle -------------------------------------------------- */
typedef struct autobal_rotor autobal_rotor;

/* Validate p (autobal_rotor_params_check) and build a handle owning copies of
 * the ball arrays, the lumped coefficients and a workspace.  Returns NULL on
 * failure (err: AUTOBAL_EINVAL or AUTOBAL_ENOMEM).  On success err (if not
 * NULL) holds AUTOBAL_SUCCESS or AUTOBAL_WARNING with the warning's message
 * (the handle is usable in both cases).  Free with autobal_rotor_free(). */
AUTOBAL_API autobal_rotor *autobal_rotor_alloc(const autobal_rotor_params *p, autobal_error *err);
/* NULL is allowed. */
AUTOBAL_API void autobal_rotor_free(autobal_rotor *r);
/* Last message recorded on the handle (alloc warning, rhs failure, ...); never
 * NULL ("rotor handle is NULL" for r == NULL); owned by the handle. */
AUTOBAL_API const char *autobal_rotor_errmsg(const autobal_rotor *r);

/* Getters: a NULL handle gives NULL (pointers), 0 (counts) or NAN (omega).
 * The parameters held by the handle (owned by it; its plane arrays and a TABLE
 * drive's arrays point into the handle; valid until autobal_rotor_free; omega
 * follows set_omega, which does not change a RAMP or TABLE drive). */
AUTOBAL_API const autobal_rotor_params *autobal_rotor_get_params(const autobal_rotor *r);
/* The lumped coefficients in use (computed from hw for HARDWARE input; owned
 * by the handle). */
AUTOBAL_API const autobal_rotor_lumped *autobal_rotor_get_lumped(const autobal_rotor *r);
/* State dimension 8 + 2N (+2 with axial motion) (+2 with a MOTOR drive: phi_0, Omega last). */
AUTOBAL_API size_t autobal_rotor_dim(const autobal_rotor *r);
AUTOBAL_API size_t autobal_rotor_n_planes(const autobal_rotor *r);
/* Number of balls of plane j (0 for j out of range), and total N. */
AUTOBAL_API size_t autobal_rotor_n_balls(const autobal_rotor *r, size_t plane);
AUTOBAL_API size_t autobal_rotor_n_balls_total(const autobal_rotor *r);
/* Global index k of ball i of plane j (angle at y[8 + k], rate at y[8 + N + k]);
 * (size_t)-1 if out of range. */
AUTOBAL_API size_t autobal_rotor_ball_index(const autobal_rotor *r, size_t plane, size_t i);
AUTOBAL_API double autobal_rotor_omega(const autobal_rotor *r);
/* The prescribed spin at time t (s): out[0] = Omega(t) (rad/s), out[1] = Omega'(t) (rad/s^2;
 * the right derivative at a corner of a ramp or table), out[2] = phi_0(t) = integral_0^t Omega
 * (rad; closed form, piecewise quadratic).  O(log n) for a table (binary search), O(1)
 * otherwise, no allocation.  The constant drive gives (omega, 0, omega t).  Returns
 * AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL r or out, t not finite; out untouched). */
AUTOBAL_API int autobal_rotor_drive_eval(const autobal_rotor *r, double t, double out[3]);
/* A MOTOR drive has no prescribed Omega(t): autobal_rotor_drive_eval returns AUTOBAL_EINVAL
 * for it (out untouched); use autobal_rotor_spin. */
/* The spin of the state y at time t, for every drive: out[0] = Omega (rad/s), out[1] = phi_0
 * (rad).  A prescribed drive (CONSTANT, RAMP, TABLE) gives autobal_rotor_drive_eval's Omega(t)
 * and phi_0(t) (y is not read and may be NULL); a MOTOR drive reads the state's last two
 * entries (y must hold autobal_rotor_dim values; the layout does not depend on the frame).
 * Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL r or out, t not finite, NULL y with a
 * motor; out untouched). */
AUTOBAL_API int autobal_rotor_spin(const autobal_rotor *r, double t, const double *y, double out[2]);
/* The motor characteristic L(Omega) (N m) of a MOTOR drive at the speed Omega (rad/s), without
 * the resistance k_r Omega.  NAN for a NULL handle, a drive that is not a motor, or a
 * non-finite Omega. */
AUTOBAL_API double autobal_rotor_motor_torque(const autobal_rotor *r, double Omega);
/* Largest |Omega(t)| over all t (rad/s): |omega| for the constant drive, else the largest
 * |speed| of the ramp or table.  MOTOR: the reference speed max(omega_0, |omega_start|)
 * (linear) or max(largest |torque_omega[k]|, |omega_start|) (table): not a bound of the
 * motion (the run-up usually stays below it), the speed the transient study samples at.
 * NAN for a NULL handle. */
AUTOBAL_API double autobal_rotor_drive_speed_max(const autobal_rotor *r);
/* Change the spin speed (rad/s, finite).  Returns AUTOBAL_SUCCESS, or
 * AUTOBAL_EINVAL for a non-finite omega (message on the handle; omega is
 * unchanged) or a NULL handle (no message). */
AUTOBAL_API int autobal_rotor_set_omega(autobal_rotor *r, double omega);

/* Initial state at time t0 from the parameters (q0, qd0, ball_psi, ball_rate,
 * z0, zd0) in the given frame: phi = phi_0(t0) + psi, phi' = Omega(t0) + psi'
 * (constant drive: omega t0 + psi, omega + psi'; MOTOR: phi_0(t0) = 0 and Omega(t0) =
 * drive.omega_start, written to the state's last two entries).
 * y has dim entries (dim must equal autobal_rotor_dim).  Returns
 * AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL r or y, a frame other than
 * AUTOBAL_ROTOR_FIXED/ROTATING, dim != autobal_rotor_dim, t0 not finite; y is
 * then untouched and no message is recorded on the handle). */
AUTOBAL_API int autobal_rotor_initial_state(const autobal_rotor *r, int frame, double t0, double *y,
                                            size_t dim);
/* Convert a state between frames at time t (psi = phi - phi_0(t),
 * psi' = phi' - Omega(t), a MOTOR's phi_0 and Omega read from the state; other entries copied).  in and out may alias.
 * Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL r, in or out, a frame other
 * than AUTOBAL_ROTOR_FIXED/ROTATING, dim != autobal_rotor_dim, t not finite;
 * out is then untouched and no message is recorded on the handle). */
AUTOBAL_API int autobal_rotor_convert_state(const autobal_rotor *r, int from_frame, int to_frame,
                                            double t, const double *in, double *out, size_t dim);

/* Right-hand side of (3.2)+(3.4) ((3.5)-(3.8) for two planes) in the fixed
 * frame, GSL signature; params = an autobal_rotor*.  The implicit system is
 * reduced exactly to a 4x4 symmetric positive definite system in (x'', y'',
 * alpha'', beta'') (see docs/rotor.md, "The exact O(n) acceleration solve"); one plane:
 * solved in closed form through the 2x2 system in (u_D'', v_D''), two planes:
 * by a 4x4 L D L^T factorization; then phi'' from (3.4).  O(N), no allocation.  Units: t in s, y in
 * the state layout of autobal_rotor_dim (SI), dydt per second.
 * Sines and cosines of the ball angles and of omega t come from a branch-free,
 * vectorized sin/cos (Cody-Waite reduction with a 152-bit pi/2, fdlibm's
 * kernels): within 1 ulp of the true values (measured max 0.79 ulp over 1e7
 * arguments, 0.5 ulp next to multiples of pi/2) for |angle| <= 2^21 rad
 * (about 2.1e6 rad; e.g. 70 min at 500 rad/s); libm's sin and cos for larger
 * and non-finite angles.  Results may therefore differ from an evaluation with
 * libm in the last bit or so; they do not depend on the CPU (AVX2 or not).
 * Return codes are GSL's, not autobal statuses, because this is the function
 * handed to an ODE driver (gsl_odeiv2_system.function, or
 * autobal_transient_system.rhs, which stops with AUTOBAL_ERHS on any non-zero
 * return): 0 (GSL_SUCCESS), or GSL_EBADFUNC (a positive GSL code) when the
 * effective mass matrix is not positive definite or the accelerations come out
 * non-finite (e.g. from a non-finite state).
 * Then the handle's message (autobal_rotor_errmsg) says at which t, recorded
 * with status AUTOBAL_ENUMERIC, and dydt is unspecified (the rows of the rotor
 * may have been written before a ball's acceleration overflowed).  rotor must be a
 * valid handle (not checked: no NULL test in the hot path).  Every call writes
 * the handle's workspace: one handle per thread (see Threads above). */
/* With a friction law other than NONE (autobal_rotor_friction) both right-hand sides take the
 * friction path: the normal forces enter the accelerations, the reduced 4x4 system is no longer
 * symmetric (one plane: 2x2 closed form, two planes: LU with partial pivoting; still O(N), no
 * allocation), stuck balls are masses fixed to the rotor, and a ball with N <= 0 also fails with
 * GSL_EBADFUNC (the message names the ball and t; dydt not written). */
AUTOBAL_API int autobal_rotor_rhs(double t, const double y[], double dydt[], void *rotor);
/* Returned by both right-hand sides (instead of GSL_EBADFUNC) when, with friction, a ball's
 * normal force is not positive: the state is outside the model (the ball would leave its
 * track; message on the handle).  Equal to AUTOBAL_TRANSIENT_RHS_REJECT of
 * autobal/transient.h: at a trial stage of a step the transient driver retries a shorter step,
 * at a state the integration has reached it stops with AUTOBAL_ERHS.  A GSL driver treats it as
 * a failure other than GSL_EBADFUNC, i.e. also retries with a smaller step. */
#define AUTOBAL_ROTOR_RHS_LEAVES_TRACK (-1000)

/* MOTOR drive (both right-hand sides): the system is linear in Omega' as well; the 4x4 solve
 * above is done for two right-hand sides (the terms without Omega' and those per unit Omega',
 * one factorization), and the phi_0 equation then gives Omega' from a scalar Schur complement
 * J + sum m_j0 r_j0^2 - g^T a^-1 g (g: the coupling column); a complement that is not
 * positive (relative to J + sum m_j0 r_j0^2, 1e-13) fails like a singular mass matrix.  Still
 * O(N), no allocation; the derivatives of phi_0 and Omega are the last two entries of dydt. */
/* The same motion with the balls in the rotating frame (3.9)-(3.13): ball
 * angles psi, (3.13) for the balls with the acceleration of D projected on the
 * rotor axes; rotor equations (3.2) in the fixed frame.  An independent second
 * implementation (the same GSL return codes and failure behaviour). */
AUTOBAL_API int autobal_rotor_rhs_rotating(double t, const double y[], double dydt[], void *rotor);

/* ---- friction (EXACT law): modes, forces, switching ----------------------- */
/* 1 when the handle's friction law is not NONE (the friction right-hand sides are in use). */
AUTOBAL_API int autobal_rotor_friction_on(const autobal_rotor *r);
/* Mode of ball k (state order, autobal_rotor_ball_index) under the EXACT law; after
 * autobal_rotor_alloc every ball slips in the sense of its initial rate (+1 for a rate of 0) until
 * autobal_rotor_friction_settle (with initial = 1) decides.  Other laws: the sign of psi' is not
 * held, the mode is reported as AUTOBAL_ROTOR_BALL_SLIP_POSITIVE.  get: the mode, or -2 for a NULL
 * handle or k out of range.  set: AUTOBAL_SUCCESS or AUTOBAL_EINVAL (bad k or mode, law not
 * EXACT).  Setting STUCK does not change the state: the caller sets psi_k' = 0 (the right-hand
 * sides treat a stuck ball as psi_k' = 0 anyway). */
AUTOBAL_API int autobal_rotor_ball_mode_get(const autobal_rotor *r, size_t k);
AUTOBAL_API int autobal_rotor_ball_mode_set(autobal_rotor *r, size_t k, int mode);
/* The normal forces N[k] (N) of all balls at the state y (frame) and time t, with the
 * accelerations of the current modes (stuck balls: phi' = Omega), n = total number of balls.
 * Works for every law (NONE: no friction terms in the accelerations).  Writes the handle's
 * workspace (one thread per handle).  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (bad arguments) or
 * AUTOBAL_ENUMERIC (the acceleration solve failed; message on the handle).  A non-positive N is
 * returned as it is (no error here). */
AUTOBAL_API int autobal_rotor_normal_forces(autobal_rotor *r, int frame, double t, const double *y,
                                            double *N, size_t n);
/* The holding forces H[k] (N) of the stuck balls (EXACT law), NAN for slipping balls (and for
 * every ball under the other laws); otherwise as autobal_rotor_normal_forces. */
AUTOBAL_API int autobal_rotor_holding_forces(autobal_rotor *r, int frame, double t, const double *y,
                                             double *H, size_t n);
/* The switching function of ball k (EXACT law), a transient-engine event function: slipping,
 * sgn(mode) psi_k' (> 0 while it slips, it falls through 0 when the ball stops); stuck,
 * |H_k| - mu_k N_k (<= 0 while it holds, it rises through 0 when the ball breaks free); with
 * contact, for stuck balls in resting contact (a chain), the first ball of the chain reports minus the
 * smallest margin of the chain's conditions (docs/device.md "Stiction and contact"), the others -1.  The
 * forces of all balls are computed once per (t, y) and cached on the handle (a copy of y is
 * compared), so calling it for every ball costs one solve when a ball is stuck.  NAN for bad
 * arguments or a failed solve. */
AUTOBAL_API double autobal_rotor_friction_switch(autobal_rotor *r, int frame, size_t k, double t,
                                                 const double *y);
/* Apply the switching rules (see autobal_rotor_friction) at (t, y), EXACT law: every slipping ball
 * with sgn(mode) psi' <= 0 (it has reached 0; with initial = 1 the modes are first set from the
 * sign of psi', and psi' = 0 counts as reached) is made stuck with psi' = 0 in y (fixed frame:
 * phi' = Omega); then, as long as
 * some stuck ball has |H| > mu N, the one with the largest excess (|H| - mu N) / N slips on
 * opposite to its H (a ball that had reached 0 gets its rate back: it slips on, reversed).
 * n_stick / n_slip (may be NULL) receive how many balls went from slipping to
 * stuck and from stuck (at entry) to slipping; the balls that reached psi' = 0 but could not
 * stick are counted in n_reverse (may be NULL).  Returns 1 when a mode or y changed, 0 when
 * nothing changed, or a negative status (AUTOBAL_EINVAL: bad arguments or law not EXACT; AUTOBAL_ENUMERIC: the solve failed or
 * a ball has N <= 0, message on the handle).  With contact on: a ball set free by an impact takes
 * its mode from the sign of psi'; a cluster with a stuck ball sticks as a whole; stuck chains are
 * checked as one body (slipping as a whole or coming apart); a mode and rate restored within the
 * call is no change.  Use autobal_rotor_hybrid_settle as the event reset with contact. */
AUTOBAL_API int autobal_rotor_friction_settle(autobal_rotor *r, int frame, double t, double *y,
                                              int initial, size_t *n_stick, size_t *n_slip,
                                              size_t *n_reverse);

/* ---- derived quantities ------------------------------------------------- */
/* Unbalance of plane j at time t (3.1), (3.10): s[0] = s_u, s[1] = s_v (fixed
 * axes), s[2] = s_xi, s[3] = s_eta (rotor axes), all kg m, including the
 * unbalance itself (phi_0 from autobal_rotor_spin).  Returns AUTOBAL_SUCCESS or AUTOBAL_EINVAL. */
AUTOBAL_API int autobal_rotor_plane_unbalance(const autobal_rotor *r, size_t plane, int frame,
                                              double t, const double *y, double s[4]);

/* "Time to balance" monitor: max over planes of |s_j| / s_ref,j with
 * s_ref,j = m_j0 r_j0 if positive, else sum_i m_ji r_ji, else 1 kg m.
 * Dimensionless; 0 on a balanced motion.  NAN for bad arguments. */
AUTOBAL_API double autobal_rotor_balance_monitor(const autobal_rotor *r, int frame, double t,
                                                 const double *y);

/* Number of derived outputs per sample and their layout (with gravity, x, y, alpha, beta in the
 * amplitudes below are measured from the static offset, autobal_rotor_static_offset):
 *   0 amp_G  |(x, y)|                                  m   at the centre of mass
 *   1 amp_L  |(x - l_L beta, y + l_L alpha)|           m   at the left support  (p = -l_L)
 *   2 amp_R  |(x + l_R beta, y - l_R alpha)|           m   at the right support (p = +l_R)
 *   then per plane j (7 entries, j = 1..n_planes):
 *     p<j>_s_u, p<j>_s_v, p<j>_s_xi, p<j>_s_eta  kg m   (3.1), (3.10)
 *     p<j>_s_abs   |s_j|                          kg m   residual unbalance
 *     p<j>_s_rel   |s_j| / s_ref,j                1      (see the monitor)
 *     p<j>_amp_D   |(x + d beta, y - d alpha)|    m      at the balancer plane
 *   then per ball (6 entries, in state order; names p<j>_b<i>_...):
 *     phi, phi_w   absolute angle, unwrapped and wrapped to (-pi, pi]   rad
 *     psi, psi_w   angle relative to the rotor, unwrapped and wrapped    rad
 *     phi_rate, psi_rate                                                 rad/s
 *   then, only with a RAMP or TABLE drive (1 entry):
 *     Omega        the prescribed spin speed Omega(t)                    rad/s
 *   or, only with a MOTOR drive (3 entries):
 *     Omega        the spin speed (the state's Omega)                    rad/s
 *     motor_torque the motor torque L(Omega) (without k_r Omega)         N m
 *     motor_power  L(Omega) Omega                                        W
 *   then, only with friction (law not NONE; added in 0.3.0), N entries and N entries:
 *     p<j>_b<i>_stuck   1 when the ball is stuck (EXACT law), else 0       1
 *     p<j>_b<i>_N       its normal force N (autobal_rotor_normal_forces)   N
 *   (all stuck flags first, then all normal forces, in state order; computing N writes the
 *   handle's workspace, as the right-hand sides do).
 * Programs should find these columns by name (autobal_rotor_output_name).
 * With LUMPED input and non-finite hw.l_L / hw.l_R, amp_L / amp_R are NAN.  The constant
 * drive keeps the layout of 0.1.0 (no Omega column). */
AUTOBAL_API size_t autobal_rotor_output_count(const autobal_rotor *r);
/* Fill out[0 .. n_out-1] (n_out must equal autobal_rotor_output_count) for
 * the state y (in the given frame) at time t.  Returns AUTOBAL_SUCCESS or
 * AUTOBAL_EINVAL. */
AUTOBAL_API int autobal_rotor_outputs(const autobal_rotor *r, int frame, double t, const double *y,
                                      double *out, size_t n_out);
/* The same outputs by the library's own sine, cosine and hypot instead of libm's (the transient
 * study with output = dense6, whose interpolated states are new in 0.2.0): sin and cos within
 * 1 ulp of libm's (fastmath.h's branch-free fdlibm kernels, libm above 2^21 rad), hypot as
 * sqrt(a^2 + b^2) below 1.5 ulp (libm's hypot for tiny, huge or non-finite arguments); the
 * other expressions, the layout and the checks as autobal_rotor_outputs. */
AUTOBAL_API int autobal_rotor_outputs_fast(const autobal_rotor *r, int frame, double t, const double *y,
                                           double *out, size_t n_out);
/* Name (written to buf, NUL-terminated, truncated to len) and unit (static
 * string; "1" for dimensionless) of output k.  Returns AUTOBAL_SUCCESS or
 * AUTOBAL_EINVAL (k out of range or buf NULL). */
AUTOBAL_API int autobal_rotor_output_name(const autobal_rotor *r, size_t k, char *buf, size_t len,
                                          const char **unit);

/* A balanced configuration of plane j (3.14): ball angles psi[0..n-1] relative
 * to the rotor, wrapped to (-pi, pi], with sum_i m_i r_i e^{i psi_i} =
 * -m0 r0 e^{i psi0}.  n = 1: psi0 + pi when m_1 r_1 = m0 r0; n = 2: the unique
 * pair of autobal_rotor_balanced_angles_two (ball 1 gets the "-" angle);
 * n >= 3 with identical a_i = m_i r_i: the symmetric fan psi_i = psi0 + pi +
 * (i - (n-1)/2) delta (i = 0..n-1) with delta in (0, 2 pi / n] solving
 * sum cos = s0 / a; n >= 3 otherwise: a member built ball by ball (each
 * remaining sub-chain keeps the remaining target inside its reachable annulus).
 * n must equal the plane's ball count.  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL
 * (bad arguments, or no balanced configuration exists; message in err, which may be NULL). */
AUTOBAL_API int autobal_rotor_balanced_angles(const autobal_rotor *r, size_t plane, double *psi,
                                              size_t n, autobal_error *err);

/* First time t[k] from which the sampled monitor values stay below
 * threshold to the end of the series (a post-processing helper for "time to
 * balance").  t are the sample times in whatever unit the caller uses (s for
 * the rotor model); the result is one of them, in the same unit, with no
 * interpolation between samples.  Returns NAN if t or monitor is NULL, n == 0,
 * or the last sample is not below threshold (NaN samples count as not below). */
AUTOBAL_API double autobal_rotor_time_to_balance(const double *t, const double *monitor, size_t n,
                                                 double threshold);

/* Gravity (docs/device.md section 2, "Static offset"): the static equilibrium of the linear part
 * under the weights, K q_s = -g_s (0, W, -D_m, 0) with W = M + all small masses (kg) and
 * D_m = sum_j d_j m_j (kg m): q_s = (x_s, y_s, alpha_s, beta_s) in m, m, rad, rad, x_s = beta_s = 0.
 * All zeros when p->gravity is 0 or g sin(shaft_angle) = 0.  Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL arguments, the
 * lumped coefficients of hardware input cannot be formed, or c_y c_alpha - c_yalpha^2 <= 0). */
AUTOBAL_API int autobal_rotor_static_offset(const autobal_rotor_params *p, double q_s[4]);

/* Gravity: g sin(shaft_angle) / (r Omega^2) (1) for the balls of `plane` at the speed omega (rad/s),
 * r the smallest ball track radius of the plane (the ball least easily carried round): below 1 the
 * centrifugal acceleration of a ball riding with the rotor exceeds the weight component at the top
 * of the track ("carried round"), above 1 the balls lie at the bottom.  NaN when p is NULL, gravity
 * is off, the plane does not exist or has no balls; 0 on a vertical shaft, +inf at omega = 0 otherwise. */
AUTOBAL_API double autobal_rotor_gravity_ratio(const autobal_rotor_params *p, size_t plane, double omega);

/* ---- ball size and contact (docs/device.md section 4; autobal_rotor_contact) ---------------------- */

/* The gap angle 2 asin((delta_i + delta_j) / (4 r)) (rad) of two balls on a track of radius r (m);
 * NAN when the arguments are negative or (delta_i + delta_j) > 4 r. */
AUTOBAL_API double autobal_rotor_gap_angle(double delta_i, double delta_j, double r);
/* Contact on (1) or off (0). */
AUTOBAL_API int autobal_rotor_contact_on(const autobal_rotor *r);
/* Number of neighbour pairs (0 without contact) and pair p's balls (state indices behind, ahead;
 * either may be NULL).  AUTOBAL_EINVAL when p is out of range. */
AUTOBAL_API size_t autobal_rotor_contact_n_pairs(const autobal_rotor *r);
AUTOBAL_API int autobal_rotor_contact_pair(const autobal_rotor *r, size_t p, size_t *behind, size_t *ahead);
/* Set the pairs from the cyclic order of the balls of every track in the state y (frame), clusters
 * cleared.  AUTOBAL_EINVAL, naming the balls, when two neighbours overlap (gap below -1e-12 rad);
 * autobal_rotor_alloc does it with the initial angles. */
AUTOBAL_API int autobal_rotor_contact_order(autobal_rotor *r, int frame, double t, const double *y);
/* The gap of pair p (rad; the angular distance minus the gap angle) in y. */
AUTOBAL_API double autobal_rotor_contact_gap(const autobal_rotor *r, size_t p, const double *y);
/* The event function of pair p (falls through 0): its gap plus 1e-12 rad, or for a cluster its contact force
 * lambda (N m) at (t, y) (NAN when the accelerations fail). */
AUTOBAL_API double autobal_rotor_contact_switch(autobal_rotor *r, int frame, size_t p, double t, const double *y);
/* Is pair p a cluster (1) or free (0)?  Set it (the caller keeps the gap at 0). */
AUTOBAL_API int autobal_rotor_contact_active(const autobal_rotor *r, size_t p);
AUTOBAL_API int autobal_rotor_contact_set_active(autobal_rotor *r, size_t p, int active);
/* Apply the impact law to the single pair p at (t, y) with restitution e (the velocities of y
 * changed in place; clusters held as constraints): optional outputs G (1/(kg m^2)), Lambda (N m s)
 * and u (rad/s, the gap rate before).  AUTOBAL_ENUMERIC when the accelerations fail or G <= 0. */
AUTOBAL_API int autobal_rotor_contact_impact(autobal_rotor *r, int frame, size_t p, double e, double t, double *y,
                                             double *G, double *Lambda, double *u);
/* The event reset of contact: clusters whose contact force is <= 0 are released; every free pair
 * with gap <= 1e-9 rad that closes (u < 0) is an impact (restitution e; plastic, and a cluster,
 * when e |u| < v_rest), repeated until no touching pair closes (chains); a pair so joined that is not
 * pressed (lambda <= 0) is released at once.  Gaps of the pairs that
 * touch are set to 0 exactly (the ball ahead moved by the tiny remaining gap or overlap).  Counts
 * added to the optional outputs.  Returns 1 when y or a cluster changed, 0 when nothing did, or a
 * negative status. */
AUTOBAL_API int autobal_rotor_contact_settle(autobal_rotor *r, int frame, double t, double *y, size_t *n_impacts,
                                             size_t *n_joins, size_t *n_releases);
/* The event reset of a run with the EXACT friction law and contact (docs/device.md, "Stiction and
 * contact"): autobal_rotor_contact_settle and autobal_rotor_friction_settle in turn until neither changes
 * anything.  With both: an impact's impulse sets free its balls and their clusters (stiction gives no
 * impulse), which then slip the way they move; the other stuck balls stay fixed to the rotor; balls in
 * resting contact move as one (a cluster with a stuck ball sticks); stuck balls in resting contact are a
 * chain held by stiction as one body while its conditions hold, else it slips as a whole or comes apart
 * where the balls pull away (counted as a release).  initial = 1 at the start of a run (the modes from
 * the sign of psi', touching balls at rest relative to each other join in resting contact).  With only
 * one of the two it calls that one's settle.  counts (required): sticks, slips, reversals, impacts,
 * joins, releases, added.  Returns 1 when y, a mode or a cluster changed, 0 when nothing did, or a
 * negative status (message on the handle). */
AUTOBAL_API int autobal_rotor_hybrid_settle(autobal_rotor *r, int frame, double t, double *y, int initial,
                                            size_t counts[6]);
/* Number of clusters (touching pairs held together). */
AUTOBAL_API size_t autobal_rotor_contact_n_active(const autobal_rotor *r);
/* Largest resultant m r of the balls of a plane the sizes allow (kg m): per track the resultant of
 * its balls packed at their gap angles in track order, summed over the tracks.  Two equal balls:
 * 2 m r cos(gamma/2).  Without contact: sum m r.  The balanced angles are out of reach when the
 * unbalance m0 r0 exceeds it (autobal_rotor_contact_reachable). */
AUTOBAL_API double autobal_rotor_contact_capacity(const autobal_rotor *r, size_t plane);
/* 1 when plane's unbalance m0 r0 <= autobal_rotor_contact_capacity (relative slack 1e-12), else 0. */
AUTOBAL_API int autobal_rotor_contact_reachable(const autobal_rotor *r, size_t plane);

/* ---- the rotor model's parameter fields --------------------------------------- */

/* One double field of autobal_rotor_hardware or autobal_rotor_lumped: the
 * `autobal` configuration section and key (the key is the field's name and the
 * name of the archive attribute), its SI unit (a UDUNITS-2 string) and where it
 * sits in its struct (offsetof).  The tables are static constant data owned by
 * the library, in the order the archive writes them. */
typedef struct autobal_rotor_field {
  const char *section; /* "rotor" or "supports" (hardware), "lumped" (lumped) */
  const char *name;    /* field name = configuration key = archive attribute, e.g. "c_Lx" */
  const char *unit;    /* SI unit, e.g. "N/m" */
  size_t offset;       /* byte offset of the double in its struct */
  const char *key;     /* "section.name", e.g. "supports.c_Lx": the name of the field as a
                          parameter of sweeps and maps (autobal_rotor_stab_param_from_name) */
} autobal_rotor_field;

/* The 17 fields of autobal_rotor_hardware (M_k, A_k, m_p, A_p, C_p in
 * [rotor]; l_L ... h_Ry in [supports]); *n (may be NULL) set to the count. */
AUTOBAL_API const autobal_rotor_field *autobal_rotor_hardware_fields(size_t *n);
/* The 17 fields of autobal_rotor_lumped ([lumped]); *n as above. */
AUTOBAL_API const autobal_rotor_field *autobal_rotor_lumped_fields(size_t *n);
/* The field `f` of the struct at `base` (an autobal_rotor_hardware for the
 * hardware table, an autobal_rotor_lumped for the lumped table). */
AUTOBAL_API double *autobal_rotor_field_ptr(void *base, const autobal_rotor_field *f);
AUTOBAL_API double autobal_rotor_field_get(const void *base, const autobal_rotor_field *f);

AUTOBAL_END_DECLS

#endif
