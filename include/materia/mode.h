/*
 * materia/mode.h -- the two modes: pbrt-v2 and corrected.
 *
 * pbrt-v2 mode (MT_MODE_PBRT_V2, the default) gives pbrt-v2's answer for the
 * same query, its known errors included -- except that materia never returns
 * NaN or Inf where pbrt-v2 would. Corrected mode fixes every erratum.
 *
 * A mode is a set of bits, one per erratum, so that the conformance suite can
 * measure the effect of each erratum on its own: MT_MODE_CORRECTED is the
 * union of every MT_FIX_* bit. MT_OPT_* bits are options outside both modes.
 * The catalog (mt_errata) describes each bit; conformance/ERRATA.md gives the
 * measured effects.
 */
#ifndef MATERIA_MODE_H
#define MATERIA_MODE_H

#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef unsigned mt_mode;

/* BxDF and BSDF layer */
#define MT_FIX_SCALED_PDF          (1u << 0)  /* ScaledBxDF::Pdf missing */
#define MT_FIX_MICROFACET_FRESNEL  (1u << 1)  /* Fresnel at the unsigned cosine */
#define MT_FIX_RHO_LOCAL           (1u << 2)  /* BSDF::rho given world directions */
#define MT_FIX_ANISOTROPIC_NORMAL  (1u << 3)  /* Anisotropic D = pdf = 0 at wh = n */
#define MT_FIX_GLOSSY_SAMPLE_PDF   (1u << 4)  /* non-zero pdf below the horizon */
#define MT_FIX_TANGENT_PLANE       (1u << 5)  /* grazing directions count as transmission */
#define MT_FIX_BSDF_FRAME          (1u << 6)  /* frame not orthonormal for oblique dpdu */
#define MT_FIX_MEASURED_SYMMETRY   (1u << 7)  /* BRDFRemap rounds (wo, wi) and (wi, wo) apart */
/* Material layer */
#define MT_FIX_DIELECTRIC_SIDE     (1u << 8)  /* FresnelDielectric(1.5, 1) in plastic & co */
#define MT_FIX_UBER_OPACITY        (1u << 9)  /* opacity > 1: negative transmission */
/* Geometry layer (the tracer's shapes) */
#define MT_FIX_LOOP_NORMALS        (1u << 10) /* limit normals from the pushed one-ring */
#define MT_FIX_DISK_PARTIALS       (1u << 11) /* disk dpdu * phimax/2pi; dpdv wrong with a hole */
#define MT_FIX_NORMAL_DERIVATIVES  (1u << 12) /* dndu, dndv not the derivatives of n */
#define MT_FIX_TRIANGLE_FACING     (1u << 13) /* triangle normal side: uvs, Sample, S only */
#define MT_FIX_PARTIAL_SAMPLING    (1u << 14) /* sphere/disk Sample ignore zmin/zmax/phimax/hole */
#define MT_FIX_QUADRIC_SCALE       (1u << 15) /* quadric area and cone radius in object space */
/* Texture layer */
#define MT_FIX_TRILINEAR_WIDTH     (1u << 16) /* trilinear MIP filter at twice the width */
#define MT_FIX_MARBLE_INDEX        (1u << 17) /* marble reads one past its table */
#define MT_FIX_MAPPING_3D          (1u << 18) /* 3D mapping applies the transform backwards */
#define MT_FIX_CHECKER_ONE_SIDED   (1u << 19) /* closed-form checkerboard 0/0 */
#define MT_FIX_CYLINDRICAL_AXIS    (1u << 20) /* cylindrical mapping NaN on its axis */
#define MT_FIX_DOTS_INSIDE         (1u << 21) /* dots: "inside" drawn outside the dots */
/* Image reading (pbrt-v2 ReadImage) */
#define MT_FIX_EXR_HALF            (1u << 22) /* EXR colour read through half */
#define MT_FIX_EXR_MISSING_CHANNELS (1u << 23) /* EXR: Y before R, G, B; none of them black */
#define MT_FIX_PFM_ROWS            (1u << 24) /* PFM rows kept in file order: upside down */
/* Geometry layer, continued */
#define MT_FIX_SHAPESET_HIT        (1u << 25) /* ShapeSet keeps the last hit; pdf counts one */
#define MT_FIX_TRIANGLE_HIT_POINT  (1u << 26) /* triangle hit point o + t d, off the plane */
/* The camera */
#define MT_FIX_ORTHO_LENS          (1u << 27) /* orthographic lens about the origin, not the pixel */
/* The dipole integrator (integrators/dipolesubsurface.cpp, renderers/surfacepoints.cpp) */
#define MT_FIX_DIPOLE_AREA         (1u << 29) /* each point given the disk pi (d/2)^2: half its area */
#define MT_FIX_OCTREE_CLUSTER      (1u << 30) /* cluster E the unweighted mean of its children's */
#define MT_FIX_FDR_RANGE           (1u << 31) /* Fdr's polynomial fit beyond its range: Fdr > 1 */

/* Options outside both modes. */
#define MT_OPT_RADIANCE_TRANSMISSION (1u << 28) /* scale specular transmission by (eta_t/eta_i)^2 */

#define MT_MODE_PBRT_V2   0u
#define MT_MODE_CORRECTED                                                                   \
    (MT_FIX_SCALED_PDF | MT_FIX_MICROFACET_FRESNEL | MT_FIX_RHO_LOCAL |                     \
     MT_FIX_ANISOTROPIC_NORMAL | MT_FIX_GLOSSY_SAMPLE_PDF | MT_FIX_TANGENT_PLANE |          \
     MT_FIX_BSDF_FRAME | MT_FIX_MEASURED_SYMMETRY | MT_FIX_DIELECTRIC_SIDE |                \
     MT_FIX_UBER_OPACITY | MT_FIX_TRILINEAR_WIDTH | MT_FIX_MARBLE_INDEX | MT_FIX_MAPPING_3D | \
     MT_FIX_CHECKER_ONE_SIDED | MT_FIX_CYLINDRICAL_AXIS | MT_FIX_DOTS_INSIDE |               \
     MT_FIX_EXR_HALF | MT_FIX_EXR_MISSING_CHANNELS | MT_FIX_PFM_ROWS |                      \
     MT_FIX_LOOP_NORMALS | MT_FIX_DISK_PARTIALS | MT_FIX_NORMAL_DERIVATIVES |                \
     MT_FIX_TRIANGLE_FACING | MT_FIX_PARTIAL_SAMPLING | MT_FIX_QUADRIC_SCALE |               \
     MT_FIX_SHAPESET_HIT | MT_FIX_TRIANGLE_HIT_POINT | MT_FIX_ORTHO_LENS |                   \
     MT_FIX_DIPOLE_AREA | MT_FIX_OCTREE_CLUSTER | MT_FIX_FDR_RANGE)

/* One entry of the errata catalog. bit is 0 for entries that materia fixes in
 * both modes (pbrt-v2 would produce NaN, Inf or memory corruption there). */
typedef struct mt_erratum {
    const char *id;          /* short name, e.g. "scaled-pdf" */
    mt_mode bit;             /* the MT_FIX_* bit, or 0 */
    const char *layer;       /* "bxdf", "bsdf", "material", "texture", "geometry", "camera",
                                "integrator" */
    const char *location;    /* where in pbrt-v2 */
    const char *behaviour;   /* what pbrt-v2 does */
    const char *correction;  /* what corrected mode does */
} mt_erratum;

/* The catalog; *count receives the number of entries. */
MT_API const mt_erratum *mt_errata(int *count);

/* "pbrt-v2" or "corrected" for the two modes, "custom" for other bit sets. */
MT_API const char *mt_mode_name(mt_mode mode);

/* Parses "pbrt-v2" or "corrected"; returns 0 on success, -1 otherwise. */
MT_API int mt_mode_parse(const char *name, mt_mode *mode);

#ifdef __cplusplus
}
#endif

#endif
