/* pelt — fur dynamics: forces on the mass-spring strands (Silva et al.
 * §3.2.1) and stepping them in time. */
#ifndef PELT_DYNAMICS_H
#define PELT_DYNAMICS_H

#include "pelt/base.h"
#include "pelt/fur.h"

#ifdef __cplusplus
extern "C" {
#endif

/* External forces, in world units. Start from pelt_forces_default(). */
typedef struct pelt_forces {
    float gravity[3];      /* acceleration, default (0, -9.81, 0) */
    float wind[3];         /* wind direction * strength (acceleration), default 0 */
    float gust_strength;   /* 0..: fraction of |wind| added as seeded noise, default 0.5 */
    float gust_scale;      /* spatial size of a gust in world units, default 0.5 */
    float gust_frequency;  /* gust changes per second, default 1.5 */
} pelt_forces;

pelt_forces pelt_forces_default(void);

#ifdef __cplusplus
}
#endif
#endif
