/* Welding: the one grouping of vertices that stand at the same point, so the
 * copies a uv seam or a patch border makes of one surface point share their
 * normal, tangent frame, strand and droplets (Lengyel et al. 2001 §2: shells
 * must not crack where vertices split). Used by mesh frames, the atlas's
 * direction field and surface droplets. GL-free. */
#ifndef PELT_BASE_WELD_H
#define PELT_BASE_WELD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define PELT__WELD_NONE UINT32_MAX

/* Groups `count` vertices by their key: the position (3 floats per vertex in
 * positions), followed by the normal (3 floats per vertex) when normals is
 * not NULL. Two keys are the same when every component compares equal as a
 * float: no tolerance, -0 and +0 are one value, a NaN equals nothing (its
 * vertex stays alone).
 *
 * Writes canon[i] = the smallest vertex index with the same key as i, so
 * canon[i] <= i, and canon[i] == i exactly for the first vertex of each
 * group. Expected time O(count) (a hash table of 2-4 slots per vertex,
 * allocated and freed here). Returns false when out of memory or when count
 * exceeds UINT32_MAX; canon is then unspecified. */
bool pelt__weld(const float *positions, const float *normals, size_t count, uint32_t *canon);

/* Dense welded ids from canon (as pelt__weld writes it): ids[i] in
 * [0, groups), numbered in the order of each group's smallest vertex.
 * Returns the number of groups. ids may be canon itself (rewritten in
 * place). */
size_t pelt__weld_ids(const uint32_t *canon, size_t count, uint32_t *ids);

/* Links the vertices of each group in ascending index order: next[i] = the
 * next larger vertex of i's group, or PELT__WELD_NONE after the last. A group
 * is walked from its canonical vertex c (canon[c] == c):
 *     for (uint32_t v = c; v != PELT__WELD_NONE; v = next[v]) ...
 * so sums over a group always run in the same order. */
void pelt__weld_chain(const uint32_t *canon, size_t count, uint32_t *next);

#endif
