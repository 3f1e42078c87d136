/* Mass-spring fur strands, one per mesh vertex (Silva et al. §3.2.1,
 * Eq. 2-3; docs/dynamics.md). No GL here.
 *
 * Units. Positions and lengths are world units (the mesh's units times the
 * transform). External forces (pelt_forces: gravity, wind, gusts) are
 * accelerations in world units / s^2, so they do not depend on mass. The
 * spring and damping are forces divided by `mass`:
 *   a = g + wind + gust - (spring_k / mass) (p - p0) - (damping / mass) v
 * where p0 = p_root + L0 n is the rest tip. Damping is drag against still
 * air (world velocity), so a mesh moving at speed V sweeps its fur back by
 * about damping V / spring_k (a turntable shows fur lagging behind), and a
 * swinging tip settles. */
#ifndef PELT_STRAND_H
#define PELT_STRAND_H

#include "pelt/dynamics.h"
#include "pelt/mesh.h"

/* Strand parameters, fully resolved: the strands have no defaults of their
 * own. pelt_fur_desc's dynamics defaults (pelt__fur_desc_defaults in
 * core/fur/fur.c, stated in include/pelt/fur.h) are the one home. */
typedef struct pelt__strand_params {
    float length;   /* L0, world units, > 0 */
    float spring_k; /* spring constant, force per unit length, > 0 */
    float mass;     /* tip mass, > 0 */
    float damping;  /* drag force per unit velocity, >= 0 */
    uint32_t seed;  /* gust noise seed; 0 is a valid seed */
} pelt__strand_params;

/* Largest internal substep, and the most substeps one call takes; longer
 * calls use larger substeps (the spring-damper is integrated implicitly, so
 * any substep is stable). A dt above PELT__STRAND_MAX_DT is clamped to it. */
#define PELT__STRAND_MAX_SUBSTEP (1.0f / 240.0f)
#define PELT__STRAND_MAX_SUBSTEPS 16
#define PELT__STRAND_MAX_DT 1.0f

typedef struct pelt__strands pelt__strands;

/* One strand per vertex of `mesh`, all tips at rest, identity transform.
 * The mesh's positions and normals are copied, so the mesh need not outlive
 * the strands. All memory is allocated here; stepping allocates nothing.
 * PELT_ERR_INVALID_ARGUMENT when p is NULL or a parameter is out of its
 * range or not finite. Free with pelt__strands_destroy. */
pelt_status pelt__strands_create(const pelt_mesh *mesh, const pelt__strand_params *p,
                                 const pelt_allocator *alloc, pelt__strands **out, pelt_error *err);
void pelt__strands_destroy(pelt__strands *s);

size_t pelt__strands_count(const pelt__strands *s);

/* Threads for pelt__strands_step (core/base/workers.h), owned by the
 * caller and outliving the strands; NULL (the default) steps on the
 * caller's thread. The result is the same to the bit either way. */
struct pelt__workers;
void pelt__strands_set_workers(pelt__strands *s, struct pelt__workers *w);
pelt__strand_params pelt__strands_params(const pelt__strands *s);

/* Where the mesh is now: model matrix, column-major, mesh-local to world.
 * Takes effect at the next step: roots jump with the mesh, tips keep their
 * world position and lag. Returns false (and keeps the previous transform)
 * when the matrix has a non-finite entry or a singular 3x3 part. */
bool pelt__strands_set_transform(pelt__strands *s, const float model[16]);

/* Where each root is on a posed (skinned) mesh: mesh-local positions and
 * normals, 3 floats per vertex each. As a new transform, it takes effect
 * at the next step: roots move, tips keep their world position and lag.
 * Allocates nothing. */
void pelt__strands_set_pose(pelt__strands *s, const float *positions, const float *normals);

/* Advances every strand by dt seconds under `f` (NULL: pelt_forces_default)
 * at `time` seconds (the time the step starts; it drives the gusts). dt <= 0
 * or NaN does nothing; dt is clamped to PELT__STRAND_MAX_DT. Non-finite
 * force components count as 0 and huge ones are clamped. After every
 * substep each tip satisfies Silva Eq. 3. Allocates nothing. */
void pelt__strands_step(pelt__strands *s, float dt, const pelt_forces *f, float time);

/* The water each strand carries, count floats, 0 at creation: vertex i's
 * tip is 1 + load[i] times as heavy at the next step (load >= 0; the fur
 * writes it from the wetness mask, docs/dynamics.md). Gravity accelerates
 * it alike; the spring, the damping, the wind, gusts and blows, which are
 * forces per tip mass, accelerate it 1 + load[i] times less: it sags
 * 1 + load[i] times as far, bends as far in a steady wind and swings
 * slower. A strand with load 0 steps exactly as without. NULL for NULL
 * strands. */
float *pelt__strands_water_load(pelt__strands *s);

/* Tips to rest (p = p0) with zero velocity. */
void pelt__strands_reset(pelt__strands *s);

/* 3 floats per vertex: p - p_root in MESH-LOCAL coordinates (the inverse of
 * the transform's 3x3 part applied), ready to upload as a vertex attribute
 * for the Bezier of Silva Eq. 1. At rest it is L0 * n. Owned by s. */
const float *pelt__strands_tip_offsets(const pelt__strands *s);

/* Tip positions in world coordinates, one vertex at a time (for tests and
 * debug drawing). */
void pelt__strands_tip_world(const pelt__strands *s, size_t vertex, float out[3]);
void pelt__strands_root_world(const pelt__strands *s, size_t vertex, float out[3]);

/* The gust acceleration of pelt__strands_step at world position `pos` and
 * time `time`: seeded value noise, smooth in space and time, identical for
 * identical inputs. Zero when the wind or gust_strength is zero. */
void pelt__gust(const pelt_forces *f, uint32_t seed, const float pos[3], float time,
                float out[3]);

#endif
