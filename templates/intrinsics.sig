# The intrinsics of the template dialect: one signature a line, RESULT NAME(PARAMETERS), then
# optional flags. A name may have several signatures (overloads); a call must match one exactly
# (no implicit conversion). In a line, F stands for one of real, real2, real3, real4, the same
# type at every place of that line. Flags: `derivative` (takes screen-space derivatives: the
# calling function is fragment-only), `resource NAME` (reads a resource the includer declares;
# see the target tables' "resources"). The names are HLSL's; each target table spells them.

# Component-wise arithmetic
F abs(F)
int abs(int)
F sign(F)
F min(F, F)
int min(int, int)
F max(F, F)
int max(int, int)
F clamp(F, F, F)
int clamp(int, int, int)
F saturate(F)
F lerp(F, F, F)
F step(F, F)
F smoothstep(F, F, F)
F floor(F)
F ceil(F)
F frac(F)
F round(F)
F trunc(F)

# Powers, exponentials, trigonometry
F sqrt(F)
F rsqrt(F)
F pow(F, F)
F exp(F)
F exp2(F)
F log(F)
F log2(F)
F sin(F)
F cos(F)
F tan(F)
F asin(F)
F acos(F)
F atan(F)
F atan2(F, F)

# Geometry
real dot(F, F)
real length(F)
real distance(F, F)
F normalize(F)
real3 cross(real3, real3)
F reflect(F, F)

# Screen-space derivatives (fragment stage)
F ddx(F) derivative
F ddy(F) derivative
F ddx_fine(F) derivative
F ddy_fine(F) derivative
F ddx_coarse(F) derivative
F ddy_coarse(F) derivative

# The glint dictionary (templates/glints/): a 1D array texture of RGBA densities, read at
# (u, layer) at an explicit MIP level (the templates pass integer levels only: the result then
# depends on no LOD the driver computes and on no blend between levels).
real4 glint_dictionary_lod(real, real, real) resource glint_dictionary
