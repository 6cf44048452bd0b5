/* autobal/design.h: sizing a ball autobalancer for a machine (`autobal rotor design`,
 * docs/rotor.md "Design").
 *
 * Given the machine (rotor, supports: autobal_rotor_params with one balancer plane of two balls),
 * an operating speed range [omega_min, omega_max], a range of unbalances m0 r0 in
 * [unbalance_min, unbalance_max] and a required margin delta (1/s), the search finds the balancers
 * (n identical balls, two by default (options.n_balls_min/max): ball mass m, track radius r, ball
 * damping h, and the axial position d of the plane, which in this one-plane model also holds the
 * unbalance) for which every root of the
 * balanced motion has Re lambda < -delta at every speed of the speed grid and for EVERY unbalance
 * of the range.  The verdict of a design is guaranteed in the unbalance and in the track radius
 * (autobal_rotor_stab_margin_ratio_set: the critical values, not samples; the radius enters only
 * through t = m0 r0 / (m r)), and sampled in the speed (n_omega points, re-checked on a finer grid)
 * and in m, h, d (a grid, then a simplex optimizer).
 *
 * Ranking: by the robust margin rho of a design, the largest delta for which it is feasible
 * (1/s; the slowest decay rate over the speed grid and every unbalance of the range), computed by
 * the exact test and bisection to about 1e-3 1/s.  Larger is better.  (Three or more balls with
 * unbalance_member EVERY: the feasible designs by the margin their verdict covers, see "Number of
 * balls" below.)
 *
 * Run-up profile: when p->drive is a RAMP or TABLE drive, the transients run that profile from
 * t = 0, and the operating speed range is [omega_min, the profile's top speed max |Omega|]:
 * omega_max may be NaN (then the top speed) or must equal it (AUTOBAL_EINVAL otherwise); the
 * stability analyses take constant speeds (the drive is dropped for them); the best config
 * carries the profile ([drive]).  A MOTOR drive: AUTOBAL_EUNSUPPORTED.
 *
 * Number of balls: options.n_balls_min .. n_balls_max identical balls (default 2 .. 2).  For n >= 3 the
 * search runs over the symmetric fan; with options.unbalance_member = EVERY (the default; n <= 10) each
 * re-checked n >= 3 design is then certified for EVERY balanced configuration (member) of every unbalance
 * of the range at every speed of the re-check grid (autobal_rotor_design.members_certified; a design not
 * certified is not feasible); with SYMMETRIC the verdict covers the symmetric fan only (it says so).
 * With EVERY and n_balls_max >= 3 the optimizer also starts from the best feasible cell of each n not among
 * the first n_starts cells, the ranked designs also include the best of each n not among the first n_best,
 * and after the certification the feasible designs come first, ranked by the margin their verdict covers:
 * rho for two balls (one member), min(rho, member_margin_certified) for three or more (rho is then the
 * symmetric fan's only); the designs that are not feasible keep their order after them.
 *
 * Two planes: options.planes = 2 (the same two-ball balancer in both planes of a two-plane machine;
 * see the options' last fields).
 *
 * Not covered (AUTOBAL_EUNSUPPORTED, the message names the key): two planes with planes = 1, balls that differ
 * within a design, the full inertia model, anisotropic supports, a motor drive, gravity.
 *
 * Units: SI inside (kg, m, kg/s, rad/s, 1/s, kg m).  Threads: none (one handle per call).  Errors
 * in err; the library never prints. */
#ifndef AUTOBAL_DESIGN_H
#define AUTOBAL_DESIGN_H

#include <stddef.h>

#include "autobal/archive.h"
#include "autobal/export.h"
#include "autobal/rotor.h"
#include "autobal/status.h"
#include "autobal/study.h"

AUTOBAL_BEGIN_DECLS

/* Options of `autobal rotor design` (section [design]).  A bound pair with min == max fixes that
 * variable (its grid then has one point).  NaN bounds take the defaults said. */
typedef struct autobal_study_rotor_design_options {
  double omega_min, omega_max;   /* rad/s, operating speeds, 0 < min < max (required)  (NaN, NaN) */
  size_t n_omega;                /* speeds of the search grid, [2, 1e5]                     (101) */
  size_t n_verify;               /* speeds of the re-check grid, [2, 1e6]; 0: 4 (n_omega-1) + 1 (0) */
  double unbalance_min, unbalance_max; /* kg m, 0 < min <= max (required)                (NaN, NaN) */
  double margin;                 /* 1/s, required decay rate delta >= 0                      (0.1) */
  double mass_min, mass_max;     /* kg, ball mass > 0; NaN: 0.5x and 2x the given ball's mass */
  size_t n_mass;                 /* geometric grid, [1, 1000]                                  (8) */
  double radius_min, radius_max; /* m, track radius > 0; NaN: 0.5x and 1.5x the given radius */
  size_t n_radius;               /* geometric grid of the map only (the search is exact in r) (24) */
  double damping_min, damping_max; /* kg/s, ball damping > 0; NaN: 0.1x and 10x the given one */
  size_t n_damping;              /* geometric grid, [1, 1000]                                  (8) */
  double position_min, position_max; /* m, plane position d; NaN: the given d (fixed)          */
  size_t n_position;             /* linear grid, [1, 1000] (1 if fixed)                        (1) */
  size_t n_best;                 /* ranked designs reported, [1, 1000]                        (10) */
  size_t n_starts;               /* optimizer starts (best grid designs), [0, 100]             (3) */
  size_t max_iter;               /* optimizer iterations per start, [1, 10000]                (80) */
  /* Transients of the best designs (docs/rotor.md "Design", "Ranking by transients"): for each of
   * the first n_transient ranked designs an ensemble (autobal_ensemble_rotor_member, grid) over the
   * start angles of the two balls (n_start each, ball 2 offset by half a step so that no member
   * starts with the balls together), the unbalances (n_transient_unbalances, linear from
   * unbalance_min to unbalance_max) and the speeds (n_transient_speeds, linear from omega_min to
   * omega_max; with a run-up profile (p->drive RAMP or TABLE) the profile from rest instead).
   * Each design gets P(balance), the median and the worst time to balance (autobal_rotor_design). */
  size_t n_transient;            /* designs run, [0, 1000]; 0: none (the fields stay NaN)     (0) */
  int rank_by;                   /* enum autobal_design_rank                  (AUTOBAL_DESIGN_RANK_MARGIN) */
  size_t n_start;                /* start angles per ball, [1, 64]                               (3) */
  size_t n_transient_unbalances; /* [1, 100] (1: unbalance_max)                                  (2) */
  size_t n_transient_speeds;     /* [1, 100] (1: omega_max); ignored with a run-up profile       (2) */
  double t_end;                  /* s, each transient, (0, 1e6]; NaN: 10 s after the profile's end (NaN) */
  double balance_tol;            /* residual unbalance of "balanced" (ensemble), (0, 1)       (0.01) */
  double balance_revs;           /* revolutions it must stay below, [0, 1e6]                    (50) */
  int threads;                   /* OpenMP threads of the ensembles, 0: the OpenMP default       (0) */
  autobal_study_progress_fn progress; /* fraction done; non-zero: cancel                  (NULL) */
  void *progress_user;                                                              /* (NULL) */
  /* The number of balls (added at the end; docs/rotor.md "Design", "Number of balls"): every n in
   * [n_balls_min, n_balls_max] is searched, n identical balls per design (0 is read as 2, so a
   * zeroed pair is today's two balls).  The ball mass bounds apply per ball; total_mass_max caps
   * the balls' total n m (NaN: no cap).  For n >= 3 the verdict covers the members of the family
   * named by unbalance_member (autobal_rotor_unbalance_member): SYMMETRIC, the symmetric fan (the search's
   * own verdict); EVERY, every member: the search over the fan, then the certification of the re-checked
   * n >= 3 designs (autobal_rotor_design.members_certified; n_balls_max <= 10 with EVERY). */
  size_t n_balls_min, n_balls_max; /* [2, AUTOBAL_DESIGN_MAX_BALLS], min <= max           (2, 2) */
  int unbalance_member;            /* for n >= 3                      (AUTOBAL_ROTOR_UNBALANCE_EVERY) */
  double total_mass_max;           /* kg, > 0 or NaN                                          (NaN) */
  /* Two planes (added at the end; docs/rotor.md "Design", "Two planes"): planes = 2 designs the same
   * balancer (two identical balls of mass m on radius r with damping h) in BOTH planes of a
   * two-plane machine (p->n_planes == 2; plane positions, unbalance radii from p), for every m0 r0
   * of plane 1 in [unbalance_min, unbalance_max], of plane 2 in [unbalance2_min, unbalance2_max] and
   * every relative phase.  Map: autobal_rotor_stab_every_unbalance2 without the box search at every
   * speed of the grid (exact in plane 1's unbalance and the phase, plane 2's unbalance on n_unbalance2
   * values); the first n_best stable cells by their sampled margin are then certified over plane 2's
   * whole range by the box search (budget unbalance2_boxes) at every speed of the grid, and get a
   * certified margin (autobal_rotor_design.margin_certified: bisection over
   * autobal_rotor_stab_every_unbalance2_shift), which decides feasibility where it is proven either
   * way (else the sampled margin does).  Transients (n_transient > 0) as for one plane, over the start
   * angles of all four balls (n_start^4) and both planes' unbalances (n_transient_unbalances each).  The
   * optimizer (n_starts, max_iter) over (m, h, r) on the sampled margin, its results certified like the
   * cells.  No position variable, n_balls 2 only. */
  size_t planes;                   /* 1 or 2; 0 is read as 1                                     (1) */
  double unbalance2_min, unbalance2_max; /* kg m, plane 2's range; NaN: plane 1's         (NaN, NaN) */
  size_t n_unbalance2;             /* plane-2 (and plane-1 cross-check) grid, [2, 100]            (5) */
  long unbalance2_boxes;           /* certification budget per side: 0 = 100000, -1 none, [1, 1e9] (0) */
  /* Every member (added at the end; one plane, n >= 3, unbalance_member EVERY): the box budget of the
   * enclosure of u over the members (4 to 10 balls; autobal_rotor_stab_options.member_boxes): 0 = 4000000,
   * else [1000, 1e9].                                                                               (0) */
  long member_boxes;
  /* Anisotropic supports (added at the end; one plane, two balls): the box budget of each Hill verdict of
   * the certification (autobal_rotor_stab_options.hill_boxes): 0 = 20000, else [100, 1e8].          (0) */
  long hill_boxes;
} autobal_study_rotor_design_options;

/* The largest number of balls a design may have. */
#define AUTOBAL_DESIGN_MAX_BALLS 16

AUTOBAL_API autobal_study_rotor_design_options autobal_study_rotor_design_options_default(void);

/* The ranking key (options.rank_by).  MARGIN: the robust margin rho, larger first (with EVERY and
 * n_balls_max >= 3: the covered margin, see "Number of balls" at the top).  P_BALANCE:
 * among the first n_transient designs, feasible ones first, then P(balance) larger first, then
 * the worst, then the median time to balance shorter first, then rho.  TIME: feasible first, then
 * the worst time to balance, then the median, shorter first, then P(balance), then rho.  The
 * designs after the first n_transient keep their order by rho (with every member for n >= 3: by the
 * covered margin, see "Number of balls" above). */
enum autobal_design_rank { AUTOBAL_DESIGN_RANK_MARGIN = 0, AUTOBAL_DESIGN_RANK_TIME = 1, AUTOBAL_DESIGN_RANK_P_BALANCE = 2 };

/* One design and its figures. */
typedef struct autobal_rotor_design {
  double mass;      /* kg, each ball */
  double radius;    /* m, track radius of every ball */
  double damping;   /* kg/s, h of each ball */
  double position;  /* m, plane position d */
  double margin;    /* 1/s, robust margin rho (see the top); -inf: unstable beyond the bisection's reach */
  int feasible;     /* 1: rho > the required margin (every speed of the grid, every unbalance), the
                       re-check passed and, n >= 3 with EVERY, members_certified = 1 */
  int source;       /* 0: a grid point of the map, 1: the optimizer */
  int recheck;      /* 1: the exact every-unbalance analysis (autobal_rotor_stab_every_unbalance_speeds)
                       finds it stable for every unbalance on the whole re-check speed grid, and the
                       margins it evaluates are all < -required margin; 0: it does not (then feasible
                       is set to 0 too); -1: not re-checked */
  double recheck_margin; /* 1/s, -(the largest margin the re-check evaluated): a sampled upper
                            estimate of rho on the finer speed grid */
  /* Transients (options.n_transient; NaN and 0 when not run).  A member's time to balance is the
   * ensemble's: the start of the stretch of balance_revs revolutions over which the residual
   * unbalance stays below balance_tol (not before the end of a run-up profile); +inf for a member
   * that does not balance within t_end.  A member counts as balanced when its attractor class is
   * AUTOBAL_ATTRACTOR_BALANCED. */
  double p_balance;     /* 1, balanced members / members */
  double ttb_median;    /* s, median time to balance over all members (+inf counts) */
  double ttb_worst;     /* s, largest time to balance (+inf when some member does not balance) */
  size_t n_runs, n_balanced; /* members run, members balanced */
  size_t n_balls;   /* identical balls of the design (added at the end; 0 is read as 2).  For n >= 3
                       margin and recheck_margin are also capped by h/m, the rate of the n - 2 ball
                       modes -h/m of the full system; they cover the symmetric fan (every member:
                       members_certified, member_margin_certified below) */
  /* Two planes (added at the end; 0 / NaN for one plane).  margin is then -(the largest margin the
     two-plane analysis evaluated over the speed grid): sampled.  recheck: the same analysis with the
     box search over plane 2's whole range at every grid speed (1 stable at all, 0 not, -1 not run) */
  size_t n_certified;   /* grid speeds where that verdict is certified over plane 2's range (exact_in_s2) */
  size_t n_certify_run; /* grid speeds it ran at (n_omega, fewer when it stopped at a speed not stable) */
  double found_omega, found_s[2], found_phase; /* rad/s, kg m, rad: a point not stable the search found (NaN) */
  size_t boxes;         /* boxes of the certification */
  /* Two planes, the certified margin (added at the end; NaN / 0 for one plane and when not run:
     options.unbalance2_boxes = -1, or recheck != 1).  Bisection in delta over
     autobal_rotor_stab_every_unbalance2_shift at every grid speed: margin_certified is the largest
     delta proven (every root Re lambda < -delta for every unbalance of both ranges and every phase at
     every grid speed), margin_upper the smallest delta at which a root at Re lambda >= -delta was
     found (or the sampled margin); they differ by at most about 1e-3 1/s when every step was decided
     (margin_decided 1).  margin_decided 0: some step stayed undecided (counted as not proven), so
     margin_certified is still proven but the bracket may be wider: report it as an estimate. */
  double margin_certified, margin_upper;
  int margin_decided;
  size_t margin_steps;  /* shifted verdicts evaluated (speeds x bisection steps) */
  /* Every member (added at the end; one plane, n >= 3 balls, options.unbalance_member EVERY; when not
     run see members_certified = 0 below).  At every speed of the re-check grid (n_verify): autobal_rotor_stab_every_unbalance with
     the member rule EVERY (the enclosure [u_min, u_max] of u = |Q|^2 / 4 over every member of every
     unbalance of the range; its verdict at members built in every sub-interval of u) and
     autobal_rotor_stab_margin_u_range over that enclosure with the required margin (every root
     Re lambda < -margin for every u of it), plus h/m > margin (the n - 2 ball modes).  members_certified:
     1 certified at every speed (then "every member"); -1 a violation found: a member not stable (the
     analysis's member) or, with the margin, a u of the members found (u_min_inner..u_max_inner) whose
     roots reach Re lambda >= -margin: member_found_omega (rad/s), member_found_u (kg^2), member_found_margin;
     -2 undecided at some speed (a u failing only in the enclosure's gap, or a sub-interval of u with no
     member; member_undecided speeds) and no violation; 0 not run (two balls: the member is unique;
     SYMMETRIC; two planes; recheck != 1; the counts are then 0 and the doubles NaN with one plane, every field 0 with two).  A design
     with -1 or -2 is not feasible. */
  int members_certified;
  size_t member_speeds;     /* re-check speeds evaluated by the certification (n_verify; fewer after a violation) */
  size_t member_undecided;  /* of them undecided */
  double member_undecided_omega[2]; /* rad/s, the first and the last undecided speed (NaN: none) */
  double member_found_omega; /* rad/s, speed of the violation (NaN: none) */
  double member_found_u;    /* kg^2, u of the violation (NaN: none) */
  double member_found_margin; /* 1/s, the margin of the member analysed there (NaN when found by the u test) */
  double member_margin;     /* 1/s, -(the largest margin of the members analysed over the speeds): sampled */
  double member_u[2];       /* kg^2, the enclosure of u over every member (the same at every speed) */
  long member_boxes;        /* boxes of the enclosure's search (4 to 10 balls) */
  int member_enclosure_complete; /* 1: the enclosure closed to its tolerance within the budget */
  /* members_certified = 1 only: the certified margin over every member, the largest delta (bisection to
     about 1e-3 (1 + delta) 1/s between the required margin and min(h/m, member_margin)) for which the
     margin test passes over the enclosure at every re-check speed: every root Re lambda < -delta for every
     member of every unbalance of the range there (proven).  It can be far below margin (rho: the fan's):
     members near the balls-on-one-line configurations decay slowly.  NaN otherwise. */
  double member_margin_certified; /* 1/s */
  int member_margin_decided;      /* 1: every step decided; 0: a step failed only in the enclosure's gap */
  size_t member_margin_steps;     /* bisection steps */
  /* Anisotropic supports (added at the end; one plane, two balls; docs/rotor.md "Design", "Anisotropic
     supports").  margin is then the Floquet screen's (sampled: -(the largest Floquet margin at the search
     grid's speeds and 5 unbalances)); the certification runs autobal_rotor_stab_every_unbalance_margin with
     the required margin at every speed of the re-check grid (n_verify).  hill_certified: 1 proven at every
     speed (then feasible = 1, recheck = 1); 0 a member whose Floquet margin is >= -margin found
     (hill_found_omega, hill_found_s); -1 undecided at hill_undecided speeds (the first: hill_found_omega;
     hill_found_s NaN), no violation; -2 not run.  Not feasible unless 1.  Zero for isotropic supports. */
  int hill_certified;
  size_t hill_speeds;       /* re-check speeds evaluated (fewer after a violation) */
  size_t hill_undecided;    /* of them undecided */
  double hill_found_omega;  /* rad/s */
  double hill_found_s;      /* kg m, the member's m0 r0 */
  long hill_boxes;          /* boxes of the Hill searches, all speeds */
} autobal_rotor_design;

/* Results.  Arrays owned by the summary (autobal_study_rotor_design_summary_free). */
typedef struct autobal_study_rotor_design_summary {
  size_t n_mass, n_damping, n_position, n_radius;
  double *mass, *damping, *position, *radius; /* the grids (kg, kg/s, m, m) */
  int *feasible;    /* [n_mass][n_damping][n_position][n_radius]: 1 feasible with the required margin
                       at every speed of the grid and every unbalance, 0 not, -1 the balls cannot
                       balance the largest unbalance (2 m r <= unbalance_max) */
  double *window_lo, *window_hi; /* [n_mass][n_damping][n_position] m: the widest interval of track
                       radii (within the bounds) where the design is feasible, exact in r (NaN: none) */
  size_t n_feasible;  /* feasible points of the map */
  size_t n_mass_done; /* rows of the map computed (n_mass, fewer after a cancellation) */
  size_t n_designs;   /* ranked designs (best first) */
  autobal_rotor_design *designs;
  char *best_config;  /* INI text of the best design (a runnable config: rotor, supports, plane1 with
                         the design's balls, omega = omega_max); NULL if there is no design */
  size_t ratio_sets;  /* exact every-unbalance tests (autobal_rotor_stab_margin_ratio_set) */
  size_t margin_evaluations; /* single-unbalance stability analyses (POLY) of the search and re-check */
  size_t optimizer_evaluations; /* objective evaluations of the simplex optimizer */
  size_t transients;  /* transient members run in all (options.n_transient) */
  int ranked;         /* 1: the ranking and the re-checks finished (0 after a cancellation: the
                         archive is then marked partial) */
  /* added at the end: the numbers of balls searched, n_balls_min .. n_balls_max.  The map's arrays
     have a leading dimension of n_n (feasible [n_n][n_mass][n_damping][n_position][n_radius],
     window_* [n_n][n_mass][n_damping][n_position]); n_mass_done counts the rows (n, ball mass) done,
     in that order */
  size_t n_n;
  int *n_balls;
  /* two planes (added at the end; 0 / NULL for one plane) */
  size_t planes;
  double *margin_map;  /* [n_mass][n_damping][n_position][n_radius] 1/s: -(the largest margin met over
                          the speed grid) where the two-plane grid+slice verdict is stable at every
                          grid speed, NaN elsewhere */
  size_t verdicts2;    /* two-plane every-unbalance verdicts (map and certification) */
  size_t n_undecided_cells; /* map cells the two-plane analysis could not decide (an error: -3) */
  /* anisotropic supports (added at the end): 1 when the search ran on them.  The map (feasible,
     n_feasible) is then the Floquet screen, SAMPLED (1: every sample of the search grid's speeds x 5
     unbalances decays faster than the margin), window_* are NaN, ratio_sets counts the Hill verdicts of the
     certification, margin_evaluations the Floquet analyses; the designs' verdicts: hill_certified */
  int aniso;
} autobal_study_rotor_design_summary;

/* Run the design search.  Map: for every (m, h, d) of the grids, the exact sets of normalized
 * unbalances t stable with the required margin at every speed of the grid are intersected; the
 * track radii r with [unbalance_min, unbalance_max] / (m r) inside one of its intervals form open
 * intervals, stored exactly (window_*) and sampled on the radius grid (feasible).  Ranking: every
 * map cell with a window contributes its design at the window's geometric middle; the best
 * n_starts are polished by the Nelder-Mead simplex (GSL gsl_multimin_fminimizer_nmsimplex2) on
 * -rho over the bounded box; the best n_best designs (distinct) are re-checked by the independent
 * every-unbalance analysis on the n_verify grid (n >= 3 with EVERY: also certified for every member,
 * with extra optimizer starts and ranked places per n and the ranking by the covered margin: "Number
 * of balls" at the top).  With an archive: /rotor (the machine) and
 * /rotor/design.  Returns AUTOBAL_SUCCESS (also when no design is feasible: n_designs counts the
 * ranked ones, feasible says which pass), AUTOBAL_EINVAL (options: the message names the field and
 * range), AUTOBAL_EUNSUPPORTED (the machine: message names the key), AUTOBAL_ENOMEM,
 * AUTOBAL_ENUMERIC, an archive status, AUTOBAL_ECANCELLED (progress asked to stop: the map rows
 * done are in the summary and, with an archive, written with partial = 1).  summary is zeroed
 * first; free it also after a failure. */
AUTOBAL_API int autobal_study_rotor_design(const autobal_rotor_params *p,
                                           const autobal_study_rotor_design_options *opt, autobal_archive *a,
                                           autobal_study_rotor_design_summary *summary, autobal_error *err);
AUTOBAL_API int autobal_study_rotor_design_write(autobal_archive *a, const autobal_rotor_params *p,
                                                 const autobal_study_rotor_design_options *opt,
                                                 const autobal_study_rotor_design_summary *summary);
AUTOBAL_API void autobal_study_rotor_design_summary_free(autobal_study_rotor_design_summary *summary);

/* The robust margin rho (1/s) of one design over the speed grid of opt (n_omega points in
 * [omega_min, omega_max]) and every unbalance in [unbalance_min, unbalance_max], by the exact test
 * and bisection (accuracy about 1e-3 (1 + |rho|) 1/s).  *rho = -INFINITY when the balls cannot
 * balance unbalance_max.  Statuses as above; AUTOBAL_EUNSUPPORTED for anisotropic supports (use
 * autobal_rotor_stab_every_unbalance_margin with the margin to check at each speed). */
AUTOBAL_API int autobal_study_rotor_design_margin(const autobal_rotor_params *p,
                                                  const autobal_study_rotor_design_options *opt,
                                                  const autobal_rotor_design *design, double *rho,
                                                  autobal_error *err);

/* The transients of one design (the ensembles of options.n_transient, see the options): fills
 * design->p_balance, ttb_median, ttb_worst, n_runs, n_balanced.  Needs the options' speed and
 * unbalance ranges (not n_transient).  Statuses as autobal_study_rotor_design. */
AUTOBAL_API int autobal_study_rotor_design_transients(const autobal_rotor_params *p,
                                                      const autobal_study_rotor_design_options *opt,
                                                      autobal_rotor_design *design, autobal_error *err);

/* The machine p with the design's balls (its n_balls balls m, r, h; plane 1 at d) as INI text (malloc'ed;
 * free()); for n >= 3 a comment says what the verdict covers (every member when members_certified = 1,
 * else the symmetric members only).  omega: the [rotor] omega written.  NULL when out of memory or p has no plane. */
AUTOBAL_API char *autobal_study_rotor_design_config(const autobal_rotor_params *p,
                                                    const autobal_rotor_design *design, double omega);

AUTOBAL_END_DECLS

#endif
