/* pendulum_critical.h: internal functions of pendulum_critical.c used by the maps
 * (pendulum_map.c), not installed.  Includes pendulum_verdict.h only. */
#ifndef AUTOBAL_PENDULUM_CRITICAL_H
#define AUTOBAL_PENDULUM_CRITICAL_H

#include "analysis/pendulum_verdict.h"

/* Context of the damped searches in R_w: the workspace and the other parameters of (6). */
typedef struct {
  autobal_pendulum_workspace *ws;
  double R_m, H, h, k, kc;
} autobal_pendulum_damped_ctx_;

/* max Re of the roots of (6) at R_w (deflated at k = 0); vctx: autobal_pendulum_damped_ctx_. */
int autobal_pendulum_damped_maxre_fn_(double R_w, void *vctx, double *fx);

#endif
