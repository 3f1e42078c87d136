/* Default external forces for the strand dynamics (Silva et al. §3.2.1). */
#include "pelt/dynamics.h"

pelt_forces pelt_forces_default(void)
{
    pelt_forces f = {
        .gravity = {0.0f, -9.81f, 0.0f},
        .wind = {0.0f, 0.0f, 0.0f},
        .gust_strength = 0.5f,
        .gust_scale = 0.5f,
        .gust_frequency = 1.5f,
    };
    return f;
}
