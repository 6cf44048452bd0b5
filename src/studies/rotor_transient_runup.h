/* rotor_transient_runup.h: the run-up part of the rotor transient study (private to
 * src/studies/).  With a drive other than constant the model's outputs have a column "Omega";
 * the study then keeps the columns the run-up analysis needs (t, Omega, amp_G, the balance
 * monitor max_j p<j>_s_rel, the balls' unwrapped p<j>_b<i>_psi) while it streams the series,
 * and after the run calls autobal_runup_analyze (include/autobal/runup.h) with the Campbell
 * crossings of the rotor-housing (autobal_rotor_resonance_speeds), fills the summary's run-up
 * fields and writes /rotor/runup.  Omega is read from the output column by name, so every drive
 * that writes that column is covered. */
#ifndef AUTOBAL_STUDIES_ROTOR_TRANSIENT_RUNUP_H
#define AUTOBAL_STUDIES_ROTOR_TRANSIENT_RUNUP_H

#include "autobal/study.h"

typedef struct study_runup study_runup;

/* A collector for the rotor r, or NULL in *out when r has no "Omega" output (the constant drive).
 * AUTOBAL_SUCCESS or AUTOBAL_ENOMEM (message in err). */
int study_runup_begin(const autobal_rotor *r, study_runup **out, autobal_error *err);
/* Keep one sample: t (s) and the outputs row of autobal_rotor_outputs.  NULL ru: nothing.
 * Memory grows by doubling; after a failed allocation the collector stops keeping samples and
 * study_runup_finish reports AUTOBAL_ENOMEM. */
void study_runup_sample(study_runup *ru, double t, const double *out);
/* Analyse what was kept, fill s's run-up fields (have_runup = 1) and, with an archive, write
 * /rotor/runup (the datasets over the time dimension only when series_rows, the rows of the
 * archived series, equals the samples kept).  NULL ru: nothing (AUTOBAL_SUCCESS).  Returns an autobal status with the
 * message in err. */
int study_runup_finish(study_runup *ru, const autobal_rotor *r, const autobal_study_rotor_transient_options *o,
                       autobal_archive *a, size_t series_rows, autobal_study_rotor_transient_summary *s,
                       autobal_error *err);
void study_runup_free(study_runup *ru);
/* Release the summary's run-up arrays (the pointers set to NULL). */
void study_runup_summary_free(autobal_study_rotor_transient_summary *s);

#endif
