/*
 * The errata catalog: every known pbrt-v2 error that materia reproduces in
 * pbrt-v2 mode and fixes in corrected mode (conformance/ERRATA.md adds the
 * measured effect of each). Entries with bit 0 are fixed in both modes,
 * because pbrt-v2's behaviour there is NaN, Inf or memory corruption.
 */
#include <string.h>
#include "materia/mode.h"

static const mt_erratum errata[] = {
    {"scaled-pdf", MT_FIX_SCALED_PDF, "bxdf", "reflection.h ScaledBxDF",
     "ScaledBxDF does not override Pdf(), so BxDF::Pdf's cosine-hemisphere pdf is used for a "
     "mix's components while Sample_f samples (and reports the pdf of) the wrapped BxDF",
     "Pdf() of the wrapped BxDF; the scale affects f only"},
    {"microfacet-fresnel-cosine", MT_FIX_MICROFACET_FRESNEL, "bxdf",
     "reflection.cpp Microfacet::f",
     "Fresnel is evaluated at Dot(wi, wh) with wh = normalize(wo + wi), which is never "
     "negative: a dielectric is always seen from the eta_i side, even from below the surface",
     "the cosine with wh turned to the +z hemisphere, negative from inside (pbrt-v3)"},
    {"rho-world-space", MT_FIX_RHO_LOCAL, "bsdf", "reflection.cpp BSDF::rho",
     "BSDF::rho(wo) passes the world-space wo to BxDF::rho, which expects the local frame",
     "wo converted with WorldToLocal first"},
    {"anisotropic-normal", MT_FIX_ANISOTROPIC_NORMAL, "bxdf",
     "reflection.h Anisotropic::D, reflection.cpp Anisotropic::Pdf/Sample_f",
     "D and the pdf return 0 when wh is exactly the normal (sin^2 theta_h = 0), where the "
     "distribution has its maximum",
     "the limit value: D = sqrt((ex+2)(ey+2))/(2 pi), pdf from sqrt((ex+1)(ey+1))/(2 pi)"},
    {"glossy-sample-pdf", MT_FIX_GLOSSY_SAMPLE_PDF, "bxdf",
     "reflection.cpp Microfacet::Sample_f, FresnelBlend::Sample_f, BRDFToBTDF",
     "when the reflected direction lands in the other hemisphere, Sample_f returns f = 0 but "
     "keeps the distribution's non-zero pdf; BSDF::Sample_f carries on with it, so with "
     "translucent's transmission lobes the returned pdf is about twice Pdf()",
     "pdf 0 for such samples (the sample fails), consistent with Pdf()"},
    {"tangent-plane", MT_FIX_TANGENT_PLANE, "bsdf", "reflection.cpp BSDF::f, BSDF::Sample_f",
     "the reflection test Dot(wo, ng) * Dot(wi, ng) > 0 counts a direction exactly in the "
     "geometric tangent plane as transmission",
     "such directions carry no energy: f = 0 (a set of measure zero: no integral changes)"},
    {"bsdf-frame", MT_FIX_BSDF_FRAME, "bsdf", "reflection.cpp BSDF::BSDF",
     "the frame is sn = normalize(dpdu), tn = cross(nn, sn): when dpdu is not perpendicular "
     "to the shading normal the frame is not orthonormal, and local directions are not unit",
     "sn made perpendicular to nn (Gram-Schmidt) before tn = cross(nn, sn)"},
    {"dielectric-side", MT_FIX_DIELECTRIC_SIDE, "material",
     "plastic.cpp, uber.cpp, translucent.cpp",
     "the glossy coats build FresnelDielectric(1.5, 1) (or (index, 1)): the dielectric is "
     "seen from inside, with false total internal reflection; uber's specular lobes refract "
     "the opposite way to glass's",
     "FresnelDielectric(1, index)"},
    {"uber-opacity", MT_FIX_UBER_OPACITY, "material", "uber.cpp UberMaterial::GetBSDF",
     "opacity is clamped from below only, so opacity > 1 gives a negative transmission",
     "opacity clamped to [0, 1]"},
    {"loop-normals", MT_FIX_LOOP_NORMALS, "geometry", "loopsubdiv.cpp LoopSubdiv::Refine",
     "the vertices are pushed to their limit positions before Loop's tangent masks are applied "
     "to the one-ring, though the masks are meant for the control points; and across the "
     "boundary at vertices of four faces or more, Hoppe et al.'s mask does not belong to the "
     "rules pbrt-v2 subdivides with there: the limit normals are degrees off the limit "
     "surface's and change with nlevels (pbrt-v3 does the same)",
     "the masks applied to the control points; at boundary vertices of four faces or more the "
     "across tangent from the one-ring subdivided to its limit (the limit tangent for four and "
     "five faces; from six on the rules leave no single tangent plane and it is a choice)"},
    {"disk-partials", MT_FIX_DISK_PARTIALS, "geometry", "disk.cpp Disk::Intersect (992b6aa, 26fb330)",
     "dpdv = (x, y) (radius - innerradius) / rho is the derivative of the disk's (u, v) negated "
     "(dpdu = phimax (-y, x, 0) is right), so a hit's normal Normalize(Cross(dpdu, dpdv)) is -z "
     "while Disk::Sample gives +z: a disk light emits towards -z to the rays that hit it and "
     "towards +z to light sampling (the 2012 source had dpdu times phimax / 2 pi and dpdv = "
     "-(x, y) / (1 - v) (radius - innerradius) / radius, normal +z)",
     "pbrt-v3's dpdv = (x, y) (innerradius - radius) / rho: the normal +z for hits and samples"},
    {"normal-derivatives", MT_FIX_NORMAL_DERIVATIVES, "geometry",
     "sphere.cpp, cylinder.cpp Intersect; trianglemesh.cpp Triangle::GetShadingGeometry "
     "(397e01e: the primitive's transform, the shape's without instancing)",
     "dndu and dndv (of the object-space unit normal, or of the interpolated vertex normal "
     "before normalization) are carried to world space as normals: not the derivatives of the "
     "world unit normal unless the transform is rigid (half of them under Scale 2), nor negated "
     "with it under ReverseOrientation (pbrt-v3 does the same)",
     "the derivatives of the normal reported, (I - n n^T) A dN / |A N| with A the inverse "
     "transpose, negated with n"},
    {"triangle-facing", MT_FIX_TRIANGLE_FACING, "geometry",
     "trianglemesh.cpp Triangle::Intersect, Triangle::Sample, Triangle::GetShadingGeometry",
     "a hit's normal follows dpdu x dpdv, so it turns over with a mirrored uv map, and with "
     "degenerate uvs it is Cross(e2, e1), against the winding; Sample() negates the winding's "
     "normal under ReverseOrientation only, not under a mirroring transform as a hit's is (a "
     "mirrored mesh light emits one way to rays and the other to light sampling); with S and "
     "no N the shading normal, taken from the hit's, is flipped a second time",
     "pbrt-v3's rule (Triangle::Intersect; pbrt-v4's Triangle::Sample): the winding's normal, "
     "negated under ReverseOrientation xor a handedness change, for hits, samples and shading"},
    {"partial-sampling", MT_FIX_PARTIAL_SAMPLING, "geometry",
     "sphere.cpp Sphere::Sample, disk.cpp Disk::Sample",
     "the full sphere, or the full disk of the outer radius, is sampled whatever zmin, zmax, "
     "phimax and innerradius are, while Area() and Pdf() are the clipped shape's: samples on "
     "the missing part are dropped and the others carry the clipped shape's density (a "
     "hemisphere light gives half its light); a cone direction that misses a clipped sphere "
     "gets the ray's point of closest approach, whose normal at right angles to the ray passes "
     "the emission test about one time in two (pbrt-v3 samples full shapes too)",
     "uniform in area on the clipped shape; a cone direction that misses gives no sample"},
    {"quadric-scale", MT_FIX_QUADRIC_SCALE, "geometry",
     "shape.cpp Shape::Pdf with the quadrics' Area(); sphere.cpp Sphere::Sample(p), Pdf(p)",
     "quadrics measure Area() in object space, so Pdf = d^2 / (|cos| Area) is off by the "
     "transform's area scale (four times too high under Scale 2: the light four times too "
     "dark); the cone sampled from outside a sphere has the object-space radius about the "
     "world-space centre, and an ellipsoid is sampled as a sphere",
     "the world density 1 / (Area dA_world / dA_object) at the point; the cone with the world "
     "radius under a similarity, area sampling otherwise"},
    {"shapeset-hit", MT_FIX_SHAPESET_HIT, "geometry", "light.cpp ShapeSet::Sample, ShapeSet::Pdf; "
     "shape.cpp Shape::Pdf",
     "the sample stays where the chosen primitive's sampling put it (df276f5 removed the "
     "re-intersection, which in the 2012 source kept the last primitive the ray met), while "
     "the pdf of a direction adds the density of every primitive it meets: a sample on a "
     "primitive hidden behind another of the set is blocked by it, its density counted all the "
     "same (a closed mesh light seen from outside gives about half its light)",
     "the closest point of the set on the ray from p through the sample; the pdf of a "
     "direction sums over every point of the set along it"},
    {"triangle-hit-point", MT_FIX_TRIANGLE_HIT_POINT, "geometry", "trianglemesh.cpp Triangle::Intersect",
     "the hit point is ray(t) = o + t d, which float rounding puts up to about |t d| 2^-23 off "
     "the triangle's plane on either side: a 3D texture whose value changes across the plane "
     "(a 3D checkerboard on the floor z = 0) takes one side or the other at random",
     "the barycentric point b0 p0 + b1 p1 + b2 p2 (pbrt-v3), on the plane to within its "
     "rounding"},
    {"ortho-lens", MT_FIX_ORTHO_LENS, "camera",
     "orthographic.cpp OrthoCamera::GenerateRay, GenerateRayDifferential",
     "with lensradius > 0 every ray starts on the lens about the camera-space origin, "
     "ray->o = (lensU, lensV, 0), whatever the pixel, and aims at Pcamera + focalDistance z: "
     "a perspective projection from the origin that gives the orthographic image only in the "
     "plane of focus (elsewhere a point is drawn at its orthographic position times "
     "focalDistance / depth); the differentials (88cdb51) aim at Pcamera + dxCamera at depth "
     "focalDistance / d.z, d the main ray's direction, instead of in the plane of focus "
     "(pbrt-v3 and pbrt-v4 do the same)",
     "the lens about the pixel's point Pcamera, aimed at Pcamera + focalDistance z; the "
     "differentials the rays of the next pixels through the same lens point (the main ray "
     "moved by dxCamera, dyCamera)"},
    {"dipole-area", MT_FIX_DIPOLE_AREA, "integrator", "surfacepoints.cpp SurfacePointTask::Run",
     "every irradiance point is given the area pi (d/2)^2 of the disk of diameter "
     "minsampledistance, but a Poisson-disk set of minimum distance d covers only about half "
     "the surface with those disks: the areas sum to about half the surface's, and Mo, the "
     "dipole's multiple scattering, is about half what the points' irradiance gives",
     "each point gets the area per point of its neighbourhood, pi R^2 over the points within "
     "R = 3d of it (exact for the cap a ball cuts from a sphere or a plane)"},
    {"octree-cluster", MT_FIX_OCTREE_CLUSTER, "integrator",
     "dipolesubsurface.cpp SubsurfaceOctreeNode::InitHierarchy",
     "a node's irradiance is the plain mean of its children's (or of its points'), whatever "
     "area each holds, and its position the mean weighted by y(E) alone; the cluster's E times "
     "its summed area is not the sum of its points' E times area",
     "both means weighted by area: E is the area-weighted mean, the position weighted by "
     "area times y(E)"},
    {"fdr-range", MT_FIX_FDR_RANGE, "integrator", "reflection.h Fdr, dipolesubsurface.cpp",
     "the polynomial fit of the diffuse Fresnel reflectance is used for every eta: it is 0.0017 "
     "at eta 1 and exceeds 1 from eta 3.95 on (1.07 at 5), where A = (1 + Fdr) / (1 - Fdr) is "
     "negative and Fdt = 1 - Fdr < 0: the subsurface light turns negative",
     "the hemispherical integral of the dielectric Fresnel reflectance (Simpson's rule over "
     "the transmitted cosine), below 1 for every eta"},
    {"octree-coincident", 0, "integrator", "dipolesubsurface.cpp SubsurfaceOctreeNode::Insert",
     "a leaf holds 8 points and splits when a ninth arrives: more than 8 points at one "
     "position (a points file can hold them) split it without end, until the stack overflows",
     "below 40 levels a leaf keeps any number of points"},
    {"measured-empty", 0, "bxdf",
     "reflection.cpp IrregIsotropicBRDF::f",
     "f returns the clamped weighted sum of the samples divided by the sum of their weights "
     "exp(-100 d^2): 0/0 (NaN) when no sample lies within the last squared search radius "
     "(2.048), or when every weight underflows -- in float, each sample found is farther than "
     "d^2 = 1.04, as happens for 0.6% of direction pairs with the pbrt-v2 data files, all with "
     "wo and wi on opposite sides of the shading normal; materia returns 0 there in both "
     "modes. In double the weights do not underflow, so only the first case remains",
     "0 where no sample has weight"},
    {"measured-remap-symmetry", MT_FIX_MEASURED_SYMMETRY, "bxdf",
     "reflection.cpp BRDFRemap",
     "the azimuth difference phi_i - phi_o is folded into [0, pi] by adding 2 pi and then "
     "taking 2 pi minus the result, which rounds differently from the plain difference: in "
     "float BRDFRemap(wo, wi) and BRDFRemap(wi, wo) differ by an ulp on about a quarter of the "
     "pairs, and through the weights and the radius doubling the irregular measured BRDF is "
     "not reciprocal (f(wo, wi) != f(wi, wo) beyond 1e-6 on about 0.3% of pairs, by up to 2%)",
     "|phi_i - phi_o| folded once: the remap, and so f, is exactly symmetric"},
    {"trilinear-width", MT_FIX_TRILINEAR_WIDTH, "texture", "mipmap.h MIPMap::Lookup",
     "the isotropic (trilinear) lookup takes width = 2 max(|dst0|, |dst1|): twice the "
     "filter footprint, so trilinear textures are blurrier than EWA ones",
     "width = max(|dst0|, |dst1|)"},
    {"marble-index", MT_FIX_MARBLE_INDEX, "texture", "marble.h MarbleTexture::Evaluate",
     "t = 0.5 + 0.5 sin(...) reaches 1, and first = Floor2Int(t * NSEG) then reads c[first+3] "
     "one past the colour table",
     "first clamped to NSEG - 1 (as pbrt-v4)"},
    {"mapping-3d", MT_FIX_MAPPING_3D, "texture", "texture.h IdentityMapping3D, its creators",
     "the 3D mapping is built from the current transform (object to world) and applied to "
     "world points: `Scale 2 2 2` makes a 3D pattern finer, not larger",
     "the inverse (world to texture space), as for the 2D mappings"},
    {"checker-one-sided", MT_FIX_CHECKER_ONE_SIDED, "texture",
     "checkerboard.h Checkerboard2DTexture (closedform)",
     "the box filter's odd-check fraction along each axis is (BUMPINT(c + d) - BUMPINT(c - d)) "
     "/ 2d: with one width d = 0 and the footprint crossing an edge along the other axis it is "
     "0/0 (NaN), and with a width so small that c +- d rounds to c it is 0 instead of the "
     "check's parity (the wrong check's texture); materia returns, where pbrt-v2 gives NaN, "
     "the limit of its formula as that width tends to 0 (the zero-width axis point-sampled)",
     "an axis along which the footprint stays inside one check is point-sampled (its exact "
     "box average), the other integrated"},
    {"cylindrical-axis", MT_FIX_CYLINDRICAL_AXIS, "texture",
     "texture.h CylindricalMapping2D::cylinder",
     "normalizes the point's texture-space position (not its offset from the axis): the "
     "origin gives 0/0 and NaN (both modes: the zero vector is kept, u = 0.5 + "
     "atan2(0, 0)/2pi, v = 0); elsewhere on the axis u = (pi + atan2(+-0, +-0))/2pi is 0, "
     "0.5 or 1 by the signs of the zeros",
     "phi = 0 wherever x = y = 0: u = 0.5 on the whole axis"},
    {"dots-inside", MT_FIX_DOTS_INSIDE, "texture", "dots.h DotsTexture, dots.cpp",
     "the constructor takes (outsideDot, insideDot) but the creators pass the \"inside\" "
     "parameter first: \"inside\" is drawn around the dots and \"outside\" on them (the "
     "reference values show it)",
     "\"inside\" on the dots, \"outside\" around them"},
    {"exr-half", MT_FIX_EXR_HALF, "texture", "imageio.cpp ReadImageEXR",
     "reads R, G and B into a frame buffer of HALF slices, so OpenEXR converts float and uint "
     "channels to half (ImfConvert.cpp floatToHalf, uintToHalf: round to nearest even, "
     "relative change up to 2^-11; finite values beyond 65504 become infinite); materia "
     "saturates those at +-65504, the largest half, so that no infinity is made",
     "the stored precision (float and uint channels read exactly)"},
    {"exr-missing-channels", MT_FIX_EXR_MISSING_CHANNELS, "texture",
     "imageio.cpp ReadImageEXR",
     "reads through OpenEXR's RgbaInputFile (pbrt-v2 commit 4a851f4), which takes a Y channel "
     "for the whole image: a file with Y beside R, G and B reads gray Y, its colour ignored; a "
     "file with none of R, G, B and Y reads black (the 2012 source read R, G and B alone, so a "
     "Y-only file was black: the release reads it gray, and so do both modes)",
     "R, G and B when there are any, else Y as gray; a file with none of R, G, B and Y is an "
     "error"},
    {"pfm-rows", MT_FIX_PFM_ROWS, "texture", "imageio.cpp ReadImagePFM",
     "keeps the rows in file order, but PFM stores them bottom to top: the image is upside "
     "down relative to the same picture as EXR (row y of the texture is the file's row "
     "height - 1 - y); pbrt-v2's own PFM writer writes bottom to top, so reading its output "
     "back flips it",
     "the file's first row is the image's bottom row, as the format says"},
    {"exr-data-window", 0, "texture", "imageio.cpp ReadImageEXR",
     "fixed in pbrt-v2 as released (commit 4a851f4 offsets the frame buffer by the window's "
     "origin); the 2012 source's slices started at the pixel buffer, so a data window not at "
     "(0, 0) made OpenEXR write outside it",
     "the data window is read as the image wherever it lies (both modes, as the release)"},
    {"mix-overflow", 0, "material", "mixmat.cpp MixMaterial::GetBSDF",
     "a mix whose two materials add more than 8 BxDFs between them at a point writes past the "
     "BSDF's array (its Assert is compiled out in release builds)",
     "an error when the mix is created if its materials can add more than 8 at some point (a lobe "
     "that a constant black parameter leaves out everywhere does not count; both modes)"},
    {"specular-transmission-eta2", 0, "bxdf",
     "reflection.cpp SpecularTransmission::Sample_f",
     "the (eta_i/eta_t)^2 radiance scaling is commented out: the weight is (1 - F) T, the "
     "form for importance transport; for a closed object the factors cancel",
     "documented; both modes keep pbrt-v2's form, the MT_OPT_RADIANCE_TRANSMISSION option "
     "applies the scaling"},
    {"grazing-division", 0, "bxdf",
     "reflection.cpp SpecularReflection/SpecularTransmission::Sample_f, FrDiel",
     "divides by |cos theta_i| = 0 for an exactly grazing wo (Inf or NaN)",
     "f = 0 and pdf = 0 there (both modes)"},
    {"zero-dpdu", 0, "bsdf", "reflection.cpp BSDF::BSDF",
     "normalize(dpdu) with dpdu = 0 (a sphere's poles) is NaN and poisons the frame",
     "a frame from the shading normal alone (CoordinateSystem) in both modes"},
    {"spherical-origin", 0, "texture", "texture.cpp SphericalMapping2D::sphere",
     "normalizes the texture-space position: NaN at the origin",
     "the zero vector is kept (u = acos(0)/pi = 0.5, v = 0) in both modes"},
    {"noise-range", 0, "texture", "texture.cpp Noise, FBm, Turbulence",
     "Floor2Int overflows for coordinates beyond 2^31 (garbage lattice cells, Inf weights); "
     "a footprint whose squared length overflows gives -inf octaves and an infinite "
     "Turbulence",
     "lattice cells from an exact floor mod 256; the footprint's octave count at the largest "
     "finite length (both modes; identical to pbrt-v2 wherever it is finite)"},
    {"bump-degenerate", 0, "material", "material.cpp Material::Bump",
     "normalizes Cross(dpdu', dpdv') even when the bumped tangents are parallel (NaN normal)",
     "the unbumped shading geometry is kept where the bumped frame is degenerate (both modes)"},
};

const mt_erratum *mt_errata(int *count)
{
    if (count) *count = (int)(sizeof errata / sizeof errata[0]);
    return errata;
}

const char *mt_mode_name(mt_mode mode)
{
    mt_mode m = mode & ~MT_OPT_RADIANCE_TRANSMISSION;
    if (m == MT_MODE_PBRT_V2) return "pbrt-v2";
    if (m == MT_MODE_CORRECTED) return "corrected";
    return "custom";
}

int mt_mode_parse(const char *name, mt_mode *mode)
{
    if (!strcmp(name, "pbrt-v2")) {
        *mode = MT_MODE_PBRT_V2;
        return 0;
    }
    if (!strcmp(name, "corrected")) {
        *mode = MT_MODE_CORRECTED;
        return 0;
    }
    return -1;
}
