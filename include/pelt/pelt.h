/* pelt — real-time dynamic shell fur. The umbrella header. */
#ifndef PELT_H
#define PELT_H

#include "pelt/animation.h"
#include "pelt/base.h"
#include "pelt/camera.h"
#include "pelt/compare.h"
#include "pelt/dynamics.h"
#include "pelt/fur.h"
#include "pelt/groom.h"
#include "pelt/headless.h"
#include "pelt/mesh.h"
#include "pelt/params.h"
#include "pelt/render.h"
#include "pelt/scene.h"
#include "pelt/scene_instance.h"
#include "pelt/shadow.h"
#include "pelt/wetness.h"

#define PELT_VERSION_STRING "0.1.0"

#endif
