/* Seeded value noise: smooth (C1) interpolation of hashed values on the
 * integer lattice, optionally tiling. The one noise of core/: the gusts
 * (core/fur/strand.c) and the colour patterns (core/fur/pattern.c). */
#ifndef PELT_NOISE_H
#define PELT_NOISE_H

#include "core/base/vec.h"

#include <stdint.h>

/* Noise coordinates are clamped to +-PELT__NOISE_MAX, so lattice cells fit
 * an int32 and a float coordinate still has a fraction. */
#define PELT__NOISE_MAX 1e6f

/* The lattice cell of coordinate x (its floor, into *cell) and the
 * smoothstep weight 3f^2 - 2f^3 of its fraction f: the weight the noise
 * blends neighbouring cells with. Callers blend noise slices with it too
 * (a fourth, integer axis made continuous: time in the gusts). */
float pelt__noise_cell(float x, int32_t *cell);

/* Value noise at the `dims` coordinates x (dims clamped to 1..3) on the lattice plane
 * `slice` of one further integer axis (a time step, an octave): three
 * channels in [-1, 1], each from 10 bits of the hash (pelt__hash_axis in
 * core/base/rng.h) of the seed, the slice and the lattice point, blended
 * with pelt__noise_cell weights along each axis. Identical inputs give
 * identical outputs. period > 0 tiles it: lattice coordinates wrap modulo
 * period on every axis of x, so the noise repeats every `period` units;
 * period <= 0 does not wrap. */
pelt_vec3 pelt__value_noise(uint32_t seed, int dims, const float *x, int32_t slice, int32_t period);

#endif
