/* rotor_friction.h: the stick-slip switching of the rotor transient study (private to
 * src/studies/).  With the EXACT friction law (autobal_rotor_friction) every ball is stuck or
 * slipping; the switching functions of the model (autobal_rotor_friction_switch) become events of
 * the transient engine (one per ball, both directions), and the event reset applies the
 * switching rules (autobal_rotor_friction_settle) at the located event: all balls whose
 * condition holds there are settled together, and the integration restarts.  The collector
 * counts the switches and the time each ball spends stuck. */
#ifndef AUTOBAL_STUDIES_ROTOR_FRICTION_H
#define AUTOBAL_STUDIES_ROTOR_FRICTION_H

#include "autobal/archive.h"
#include "autobal/rotor.h"
#include "autobal/study.h"
#include "autobal/transient.h"

typedef struct study_friction study_friction;

/* For a rotor with the EXACT law: settle the modes at (t0, y) (autobal_rotor_friction_settle with
 * initial = 1: balls at psi' = 0 stick where they can; y may change), add one event per ball to tr
 * and install the reset.  *out = NULL (and nothing done) for the other laws.  Returns an autobal
 * status with the message in err. */
int study_friction_begin(autobal_rotor *rot, int frame, autobal_transient *tr, double t0, double *y,
                         study_friction **out, autobal_error *err);
/* After the run: close the stuck intervals at t_end and fill s's friction fields (have_friction,
 * the counts, the per-plane arrays: AUTOBAL_ENOMEM if they cannot be allocated).  A failure of the
 * switching during the run (a ball leaving its track) is returned here (AUTOBAL_ENUMERIC, the
 * rotor's message in err); NULL f: nothing (AUTOBAL_SUCCESS). */
int study_friction_finish(study_friction *f, double t_end, autobal_study_rotor_transient_summary *s,
                          autobal_error *err);
void study_friction_free(study_friction *f);
/* The friction inputs as attributes (group: the transient's; per plane /rotor/plane<j>: ball_f,
 * ball_mu) and the summary's friction results; nothing when the law is NONE.  An archive status. */
int study_friction_write_inputs(autobal_archive *a, const autobal_rotor *rot, const char *group);
int study_friction_write_summary(autobal_archive *a, const autobal_study_rotor_transient_summary *s,
                                 const char *group);
/* Contact (autobal_rotor_contact): one event per neighbour pair (autobal_rotor_contact_switch,
 * falling) and THE event reset of the run, which dispatches on the event index: contact events to
 * autobal_rotor_contact_settle, the others to the friction collector fric (may be NULL; its reset,
 * installed by study_friction_begin, is replaced by this one).  The pairs are set from (t0, y)
 * (overlap: AUTOBAL_EINVAL naming the balls).  *out = NULL (nothing done) without contact. */
typedef struct study_contact study_contact;
int study_contact_begin(autobal_rotor *rot, int frame, autobal_transient *tr, double t0, double *y,
                        study_friction *fric, study_contact **out, autobal_error *err);
/* After the run: s's contact fields (counts, clusters at the end, capacity, reachability); a failure
 * of the settling during the run is returned here.  NULL c: the fields of a rotor without contact. */
int study_contact_finish(study_contact *c, const autobal_rotor *rot, autobal_study_rotor_transient_summary *s,
                         autobal_error *err);
void study_contact_free(study_contact *c);
int study_contact_write_summary(autobal_archive *a, const autobal_study_rotor_transient_summary *s, const char *group);

/* Release the summary's friction arrays. */
void study_friction_summary_free(autobal_study_rotor_transient_summary *s);

#endif
