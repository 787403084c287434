/* The footpoint solver backends shared by every closest-point module
 * (parametric curves and surfaces in footpoint.h, implicit surfaces in
 * implicit.h): the in-house Newton iteration (fast, allocation-free) and
 * Ceres Levenberg–Marquardt through src/solve/lsq.h (robust reference). */
#ifndef DFL_GEOM_FOOT_BACKEND_H
#define DFL_GEOM_FOOT_BACKEND_H

typedef enum dfl_foot_backend {
    DFL_FOOT_NEWTON = 0,
    DFL_FOOT_CERES = 1
} dfl_foot_backend;

#endif
